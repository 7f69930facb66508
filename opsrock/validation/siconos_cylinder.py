"""``cylinder3d`` against the same cylinder in Siconos (opsrock/data/siconos/siconos_cylinder3d.py): validation case
``siconos_cylinder`` (validation/siconos_cylinder/README.md, issue 45), the cylinder's counterpart of ``siconos3d``.

The cases (:func:`all_cases`, 32, deterministic; :func:`quick_cases`, every fifth): one-sine pulses on two
homogeneous cylinders above the uplift threshold ``g r / h``, with infinite friction along a rim point of the Siconos
model's 16 and with finite friction half-way between two; and FEMA P695 far-field record pairs (both components), with
infinite friction at azimuth 0 and finite at 30 deg. The comparison (the join, the amplitude test, the classes of a
verdict difference, the targets) is :mod:`opsrock.validation.siconos3d_compare`'s, with ``cylinder3d`` in
``rigid3d``'s place.

Run: ``python -m opsrock.validation.siconos_cylinder --help``.
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import json
import math
import sys
import time
from dataclasses import dataclass
from importlib.resources import as_file, files
from pathlib import Path

import numpy as np

from opsrock.constants import G
from opsrock.excitations import OneSinePulse, library
from opsrock.excitations.plan import PlanMotion
from opsrock.solvers import simulate
from opsrock.solvers.cylinder3d import cylinder_block, cylinder_properties
from opsrock.validation import siconos3d as box_cases
from opsrock.validation import siconos3d_compare as cmp
from opsrock.validation.siconos3d import Case

#: The Siconos model of the cylinder (package data, beside the box's, whose helpers it imports).
SICONOS_MODEL = files("opsrock.data").joinpath("siconos", "siconos_cylinder3d.py")
#: The two homogeneous cylinders (name, diameter, height in m): slender (r/h = 0.25) and squat (r/h = 0.5).
CYLINDERS: tuple[tuple[str, float, float], ...] = (("slender", 0.4, 1.6), ("squat", 0.6, 1.2))
#: Plan directions of the pulses (deg): on one of the Siconos model's 16 rim points, and half-way between two.
DIRECTIONS: tuple[float, ...] = (0.0, 11.25)
#: Pulse amplitudes as multiples of the uplift threshold ``g r / h`` (above the 16-gon's 0.981 of it).
AMPLITUDES: tuple[float, ...] = (1.3, 1.8, 2.6)
#: Pulse frequencies as multiples of the cylinder's ``p`` (rocking in a vertical plane through its axis).
FREQUENCY_RATIOS: tuple[float, ...] = (3.0, 5.0)
#: FEMA P695 far-field recordings used (the first component's index in the set: pairs (k, k + 1)).
RECORD_PAIRS: tuple[int, ...] = (0, 8, 16, 24)
#: Azimuths of the record pairs (deg).
RECORD_AZIMUTHS: tuple[float, ...] = (0.0, 30.0)
#: Cases of the quick form: every ``QUICK_EVERY``-th.
QUICK_EVERY = 5


def _cylinder(shape: tuple[str, float, float], mu: float | None):
    return cylinder_block(shape[1], shape[2], friction=mu)


def pulse_cases() -> list[Case]:
    """One-sine pulses: both cylinders, every amplitude and frequency ratio, with infinite friction along
    ``DIRECTIONS[0]`` and with mu 0.5 along ``DIRECTIONS[1]`` (the Siconos model costs about 2 ms a step: the
    directions and frictions are paired, not crossed)."""
    out = []
    for shape in CYLINDERS:
        for mu, phi in zip((None, 0.5), DIRECTIONS):
            block = _cylinder(shape, mu)
            cyl = cylinder_properties(block)
            for k in AMPLITUDES:
                for ratio in FREQUENCY_RATIOS:
                    pulse = OneSinePulse(k * G * cyl.r / cyl.h, ratio * cyl.p)
                    out.append(Case(f"pulse {shape[0]} phi {phi:g} a/a_up {k:g} w/p {ratio:g} mu {mu}", block,
                                    PlanMotion.along(pulse, phi)))
    return out


def record_cases() -> list[Case]:
    """FEMA P695 far-field pairs on the slender cylinder: both components scaled by one factor that brings the
    first to 2 or 3 times the uplift threshold ``g r / h``, cut to their strong part (as siconos3d's), at
    ``RECORD_AZIMUTHS[0]`` with mu None and ``RECORD_AZIMUTHS[1]`` with mu 0.5 (no vertical)."""
    refs = [e.reference for e in library.entries("far-field")]
    out = []
    for n, k in enumerate(RECORD_PAIRS):
        first, second = library.load(refs[k]), library.load(refs[k + 1])
        shape = CYLINDERS[0]
        factor = (2.0 + n % 2) * G * (0.5 * shape[1]) / (0.5 * shape[2]) / first.pfa
        first, second = first.scaled(factor), second.scaled(factor)
        peak = float(np.argmax(np.abs(first.values))) * first.dt
        a, b = box_cases._strong_part(first, peak), box_cases._strong_part(second, peak)
        for mu, az in zip((None, 0.5), RECORD_AZIMUTHS):
            out.append(Case(f"record {first.name} x{factor:.4g} az {az:g} mu {mu}", _cylinder(shape, mu),
                            PlanMotion(a, b, az)))
    return out


def all_cases() -> list[Case]:
    """The full case set (:func:`pulse_cases` then :func:`record_cases`), deterministic: 24 + 8 cases."""
    return pulse_cases() + record_cases()


def quick_cases() -> list[Case]:
    """Every ``QUICK_EVERY``-th case of :func:`all_cases` (7 cases: 5 pulses, 2 records)."""
    return all_cases()[::QUICK_EVERY]


def cylinder_geometry(block) -> dict:
    """The cylinder's fields of a case file: radius ``r``, centre-of-mass height ``h`` (m) and the inertia per unit
    mass ``(i_h, i_h, i_z)`` (m²) as cylinder3d reads them (:func:`cylinder_properties`)."""
    cyl = cylinder_properties(block)
    return {"r": cyl.r, "h": cyl.h, "inertia": [cyl.i_h, cyl.i_h, cyl.i_z]}


def write_cases(path: str | Path, cases: list[Case]) -> Path:
    """Write ``cases`` as the .npz the Siconos model reads (siconos_cylinder3d.py's docstring); return the path."""
    return box_cases.write_cases(path, cases, cylinder_geometry)


@dataclass(frozen=True)
class CylinderRun(cmp.Rigid3DRun):
    """``cylinder3d`` on one case and its amplitude test: the fields of :class:`.siconos3d_compare.Rigid3DRun`,
    which the comparison reads (``alpha = atan(r / h)``)."""


def run_cylinder(case: Case) -> CylinderRun:
    """``cylinder3d`` on ``case`` and at :data:`.siconos3d_compare.AMPLITUDE_FACTORS` of its amplitude."""
    t0 = time.perf_counter()
    r = simulate(case.block, case.motion, solver="cylinder3d")
    wall = time.perf_counter() - t0
    scaled = [simulate(case.block, case.motion.scaled(f), solver="cylinder3d", record=False)
              for f in cmp.AMPLITUDE_FACTORS]
    done = {s.overturned for s in (r, *scaled) if s.status == "ok"}
    plan = r.plan
    return CylinderRun(bool(r.overturned), float(r.theta_max), float(plan.slide_max if plan else math.nan),
                       float(r.alpha), float(r.time[-1]) if r.time.size else 0.0,
                       float(plan.time_flight if plan else 0.0), r.status, len(done) > 1, wall, r.reason)


def cylinder_runs(cases: list[Case], path: Path, reuse: bool) -> dict[int, CylinderRun]:
    """:func:`run_cylinder` on every case, kept in ``path`` (JSON) and read back from it if ``reuse``."""
    if reuse and path.exists():
        return {int(k): CylinderRun(**v) for k, v in json.loads(path.read_text()).items()}
    out = {i: run_cylinder(c) for i, c in enumerate(cases)}
    path.write_text(json.dumps({i: dataclasses.asdict(r) for i, r in out.items()}))
    return out


def run_siconos(python: str, cases_npz: Path, out_csv: Path, indices: list[int], *, step: float = cmp.STEP,
                jobs: int = 1) -> Path:
    """The Siconos cylinder on ``indices`` of ``cases_npz`` in ``jobs`` processes; writes ``out_csv``."""
    with as_file(SICONOS_MODEL) as tool:
        return cmp._run_parts(python, tool, cases_npz, out_csv, indices, step, jobs)


def compare(cases: list[Case], work: Path, python: str, *, jobs: int, reuse: bool) -> list[cmp.Row]:
    """Both solvers on ``cases`` (raw results kept in ``work``), joined and classified as siconos3d's; the verdict
    differences the amplitude test does not explain rerun in Siconos at half its step."""
    work.mkdir(parents=True, exist_ok=True)
    npz, sic_csv = work / "cases.npz", work / "siconos.csv"
    if not (reuse and npz.exists() and sic_csv.exists()):
        write_cases(npz, cases)
        run_siconos(python, npz, sic_csv, list(range(len(cases))), jobs=jobs)
    mine = cylinder_runs(cases, work / "cylinder3d.json", reuse)
    siconos = cmp.read_siconos(sic_csv, cmp.STEP)
    rows = cmp.join(cases, mine, siconos)
    redo = [r.index for r in rows if r.difference and not r.ill_conditioned]
    if redo:
        half = work / "siconos_half.csv"
        if not (reuse and half.exists()):
            run_siconos(python, npz, half, redo, step=cmp.HALF_STEP, jobs=jobs)
        rows = cmp.join(cases, mine, siconos, {i: s["overturned"] for i, s in cmp.read_siconos(half, cmp.HALF_STEP)
                                               .items()})
    return rows


def write_tables(rows: list[cmp.Row], summary: cmp.Agreement, out: Path) -> None:
    """cases.csv (siconos3d's columns, ``rigid3d`` read ``cylinder3d``) and summary.csv in ``out``."""
    out.mkdir(parents=True, exist_ok=True)
    columns = [c.replace("rigid3d", "cylinder3d") for c in cmp.COLUMNS]
    with open(out / "cases.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(columns)
        w.writerows([cmp.row_values(r)[c] for c in cmp.COLUMNS] for r in rows)
    fields = {k: v for k, v in dataclasses.asdict(summary).items() if k != "classes"}
    fields.update({f"differences {c}": n for c, n in summary.classes.items()})
    with open(out / "summary.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(("quantity", "value"))
        w.writerows((k, repr(v) if isinstance(v, float) else v) for k, v in fields.items())


def main(argv: list[str] | None = None) -> int:
    """``python -m opsrock.validation.siconos_cylinder``: run, compare, write, print; 1 if below the targets."""
    p = argparse.ArgumentParser(prog="python -m opsrock.validation.siconos_cylinder",
                                description=__doc__.split("\n")[0])
    p.add_argument("--quick", action="store_true", help=f"every {QUICK_EVERY}th case")
    p.add_argument("--work", type=Path, help="folder of the raw runs (default .siconos-venv/cylinder-full|quick)")
    p.add_argument("--out", type=Path, help="write cases.csv and summary.csv here")
    p.add_argument("--siconos-python", default=".siconos-venv/bin/python", help="the Python that has siconos")
    p.add_argument("--jobs", type=int, default=2, choices=(1, 2, 3, 4), help="Siconos processes (default 2)")
    p.add_argument("--reuse", action="store_true", help="reuse the raw results already in --work")
    a = p.parse_args(argv)
    cases = quick_cases() if a.quick else all_cases()
    work = a.work or Path(".siconos-venv") / ("cylinder-quick" if a.quick else "cylinder-full")
    rows = compare(cases, work, a.siconos_python, jobs=a.jobs, reuse=a.reuse)
    summary = cmp.summarize(rows)
    print(cmp.format_table(summary).replace("rigid3d", "cylinder3d"))
    if a.out is not None:
        write_tables(rows, summary, a.out)
    return 0 if summary.passed else 1


__all__ = ["CYLINDERS", "CylinderRun", "all_cases", "compare", "quick_cases", "record_cases", "pulse_cases",
           "run_cylinder", "write_cases"]

if __name__ == "__main__":
    sys.exit(main())
