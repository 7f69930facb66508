"""The cost of an inventory study (issue 32): 20 items on 3 floors under 44 motions each at 16 IDA levels
(42,240 cases) with the default solver (``housner_fast``), fits and pelicun files included, timed in one run.

    python tools/inventory_cost.py [--out DIR] [--workers 2] [--records 44] [--items 20] [--n-boot 100]

The motions: the FEMA P-695 far-field set (44 records) filtered through the shipped shear building
(T1 = 1 s, 8 storeys, 5 %; floors 1, 4 and 8: :func:`opsrock.inventory.sources.building_motions`), made
first and not timed (they are the study's input). The inventory: 20 synthetic homogeneous blocks, widths
0.30-0.80 m and heights 1.0-2.2 m (b/h from 0.14 to 0.8), one of each on every floor. The study runs into a
fresh folder (``--out``, default a temporary one) and its wall time is printed with the study's own timings,
its CPU time (this process and its finished workers) and the load average (the machine may be shared: the
wall time on two idle cores is about the CPU time over two, plus the serial parts).
"""

from __future__ import annotations

import argparse
import json
import resource
import tempfile
import time
from pathlib import Path

import numpy as np

from opsrock.inventory.items import Inventory, Item
from opsrock.inventory.sources import BuildingSource, building_motions
from opsrock.inventory.run import StudyOptions, run_design
from opsrock.inventory.study import InventoryDesign


def synthetic_inventory(n: int) -> Inventory:
    """``n`` homogeneous blocks, widths 0.30-0.80 m and heights 1.0-2.2 m, depth 0.5 m (m)."""
    widths = np.linspace(0.30, 0.80, n)
    heights = np.linspace(1.0, 2.2, n)[::-1] if n > 1 else np.array([1.6])
    items = tuple(Item(f"item{k:02d}", f"synthetic block {w:.2f} x {h:.2f} m", float(w), 0.5, float(h), quantity=2.0)
                  for k, (w, h) in enumerate(zip(widths, np.roll(heights, n // 3))))
    return Inventory(items, "synthetic")


def _cpu() -> float:
    """CPU seconds (user + system) of this process and of its finished worker processes."""
    me, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", type=Path, help="study folder (default: a temporary folder)")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--records", type=int, default=44, help="records of the far-field set (default all 44)")
    ap.add_argument("--items", type=int, default=20)
    ap.add_argument("--n-boot", type=int, default=100)
    args = ap.parse_args(argv)
    from opsrock.excitations import library

    names = tuple(e.name for e in library.entries("far-field"))[: args.records]
    t0 = time.perf_counter()
    motions = building_motions(BuildingSource(period=1.0, storeys=8, floors=(1, 4, 8), names=names), args.workers)
    t_motions = time.perf_counter() - t0
    design = InventoryDesign(synthetic_inventory(args.items), motions, n_boot=args.n_boot)
    out = args.out or Path(tempfile.mkdtemp(prefix="inventory-cost-"))
    t0, cpu0 = time.perf_counter(), _cpu()
    study = run_design(design, out, StudyOptions(workers=args.workers, progress=True))
    wall, cpu = time.perf_counter() - t0, _cpu() - cpu0
    print(json.dumps({"cases": study.n_cases, "computed": study.n_computed, "failed": study.n_failed,
                      "items": args.items, "floors": len(motions.floors), "records": len(motions.records),
                      "levels": len(design.levels), "workers": args.workers, "motions_s": round(t_motions, 1),
                      "study_wall_s": round(wall, 1), "study_cpu_s": round(cpu, 1),
                      "load_average": [round(x, 1) for x in __import__("os").getloadavg()], **{k: round(v, 1) for k, v in study.timings.items()},
                      "out": str(out)}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
