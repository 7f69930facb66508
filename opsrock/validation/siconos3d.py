"""The rigid box of ``rigid3d`` in Siconos (tools/siconos_block3d.py): the case file the Siconos model reads.

Unfinished (issue 33): this module writes the cases (frames and conventions opsrock's: the floor accelerations in
the block frame from :meth:`PlanMotion.components` on a time grid, the inertia from
:func:`opsrock.solvers.rigid3d.solver.box_properties`); the comparison with ``rigid3d`` and the registration as a
validation case are still to come (validation/siconos3d/README.md).

``python -m opsrock.validation.siconos3d OUT.npz`` writes the smoke cases ``make test-siconos`` runs.
"""

from __future__ import annotations

import json
import math
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from opsrock.block import Block
from opsrock.constants import G
from opsrock.excitations import OneSinePulse, Pulse
from opsrock.excitations.plan import PlanMotion
from opsrock.solvers.rigid3d.solver import box_properties

#: Sample step of a pulse in the case file (s): linear interpolation of a 2 Hz sine at this step errs by
#: ``(omega dt)² / 8`` ~ 1e-5 relative.
PULSE_DT = 2.5e-4
#: Free motion after the excitation (s), in Siconos.
TAIL = 3.0


@dataclass(frozen=True)
class Case:
    """One case: a block (with depth; ``restitution_factor = 1``) and a floor motion in plan."""

    label: str
    block: Block
    motion: PlanMotion


def smoke_cases() -> list[Case]:
    """A slender box under a one-sine pulse along its width and along 30 deg, with infinite and finite friction."""
    out = []
    for mu in (None, 0.5):
        block = Block(0.4, 1.6, depth=0.6, restitution_factor=1.0, friction=mu)
        for phi in (0.0, 30.0):
            pulse = OneSinePulse(0.5 * G, 2.0 * math.pi * 2.0)
            out.append(Case(f"one-sine 0.5 g 2 Hz phi {phi:g} mu {mu}", block, PlanMotion.along(pulse, phi)))
    return out


def _samples(motion: PlanMotion) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
    """``(dt, a_x, a_y, a_v)`` of a motion on its time grid (s, m/s²)."""
    first = motion.first
    dt = PULSE_DT if isinstance(first, Pulse) else first.dt
    n = int(round(motion.duration / dt)) + 1
    t = np.arange(n) * dt
    ax, ay = motion.components(t)
    vertical = motion.vertical
    if vertical is None:
        av = np.zeros(n)
    elif np.ndim(vertical) == 0:
        av = np.full(n, float(vertical))
    else:
        av = np.zeros(n)
        av[:min(n, len(vertical))] = np.asarray(vertical, dtype=float)[:n]
    return dt, np.asarray(ax, dtype=float), np.asarray(ay, dtype=float), av


def write_cases(path: str | Path, cases: list[Case]) -> Path:
    """Write ``cases`` as the .npz the Siconos model reads (tools/siconos_block3d.py's docstring); return the path."""
    meta, ax, ay, av, start = [], [], [], [], 0
    for i, case in enumerate(cases):
        dt, x, y, v = _samples(case.motion)
        b = case.block
        meta.append({"index": i, "label": case.label, "b": b.b, "d": b.d, "h": b.h_cm,
                     "inertia": list(box_properties(b).inertia), "mu": b.friction, "dt": dt, "start": start,
                     "n": int(x.size), "tail": TAIL})
        ax.append(x)
        ay.append(y)
        av.append(v)
        start += x.size
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    np.savez(path, meta=json.dumps(meta), ax=np.concatenate(ax), ay=np.concatenate(ay), av=np.concatenate(av))
    return path


__all__ = ["Case", "smoke_cases", "write_cases"]

if __name__ == "__main__":
    print(write_cases(sys.argv[1], smoke_cases()))
