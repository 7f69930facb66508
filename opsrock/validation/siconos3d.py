"""The rigid box of ``rigid3d`` in Siconos (opsrock/data/siconos/siconos_block3d.py): the cases and the case file the Siconos
model reads.

Frames and conventions are opsrock's: the floor accelerations in the block frame from
:meth:`PlanMotion.components` on a time grid, the inertia from :func:`opsrock.solvers.rigid3d.solver.box_properties`.
The case set (:func:`all_cases`, 208 cases; :func:`quick_cases`, every tenth) is built from opsrock objects: one-sine
pulses along plan directions 0-90 deg around the uplift threshold in that direction, and FEMA P695 far-field
record pairs as ``PlanMotion(first, second, azimuth)``, with and without vertical motion. The comparison with
``rigid3d`` is :mod:`opsrock.validation.siconos3d_compare` (validation/siconos3d/README.md).

``python -m opsrock.validation.siconos3d OUT.npz [smoke|quick|all]`` writes a case file (default: the smoke cases).
"""

from __future__ import annotations

import dataclasses
import json
import math
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from opsrock.block import Block
from opsrock.constants import G
from opsrock.excitations import OneSinePulse, Pulse, Record, library
from opsrock.excitations.plan import PlanMotion
from opsrock.excitations.vertical import with_vertical
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


#: The two boxes (width, height, depth in m): slender (b/h = 0.25, d/h = 0.375) and squat (b/h = 0.5, d/h = 0.75).
BOXES: tuple[tuple[str, float, float, float], ...] = (("slender", 0.4, 1.6, 0.6), ("squat", 0.6, 1.2, 0.9))
#: Plan directions of the pulses (deg from the width axis).
DIRECTIONS: tuple[float, ...] = (0.0, 30.0, 45.0, 60.0, 90.0)
#: Pulse amplitudes as multiples of the uplift threshold in the pulse's direction.
AMPLITUDES: tuple[float, ...] = (1.2, 1.8, 2.6)
#: Pulse frequencies as multiples of the box's frequency parameter ``p = sqrt(3 g / (4 R))``.
FREQUENCY_RATIOS: tuple[float, ...] = (3.0, 5.0)
#: Constant vertical floor acceleration of the vertical pulse group (m/s², positive up).
PULSE_VERTICAL = -0.15 * G
#: FEMA P695 far-field recordings used (the first component's index in the set: pairs (k, k + 1)).
RECORD_PAIRS: tuple[int, ...] = (0, 4, 8, 12, 16, 20, 24, 28)
#: Block azimuths of the record pairs (deg).
RECORD_AZIMUTHS: tuple[float, ...] = (0.0, 30.0, 60.0)
#: Strong part of a record kept (s): from ``RECORD_LEAD`` before its peak, ``RECORD_WINDOW`` long.
RECORD_LEAD, RECORD_WINDOW = 4.0, 10.0
#: Ratio of the synthetic vertical to the recording's other horizontal component (as opsrock.excitations.vertical).
RECORD_VERTICAL = 0.5


def uplift_threshold(block: Block, phi: float) -> float:
    """Uplift threshold of ``block`` along plan direction ``phi`` (m/s²): ``g/h min(b/|cos phi|, d/|sin phi|)``."""
    c, s = abs(math.cos(math.radians(phi))), abs(math.sin(math.radians(phi)))
    return G / block.h_cm * min(block.b / c if c > 1e-12 else math.inf, block.d / s if s > 1e-12 else math.inf)


def _box(shape: tuple[str, float, float, float], mu: float | None) -> Block:
    return Block(shape[1], shape[2], depth=shape[3], restitution_factor=1.0, friction=mu)


def pulse_cases() -> list[Case]:
    """One-sine pulses: both boxes, every direction, amplitude and frequency ratio, mu None and 0.5 (no vertical);
    the same at the middle frequency ratio 4 with a constant vertical ``PULSE_VERTICAL`` and mu 0.3 (slender) or
    None (squat); and both boxes at 0.85 of the threshold (no uplift expected)."""
    out = []
    groups = [(FREQUENCY_RATIOS, AMPLITUDES, (None, 0.5), 0.0), ((4.0,), AMPLITUDES, ("v",), PULSE_VERTICAL),
              ((4.0,), (0.85,), (None,), 0.0)]
    for ratios, amps, mus, av in groups:
        for shape in BOXES:
            for mu in mus:
                mu = (0.3 if shape[0] == "slender" else None) if mu == "v" else mu
                block = _box(shape, mu)
                p = math.sqrt(3.0 * G / (4.0 * math.hypot(block.b, block.h_cm)))
                for phi in DIRECTIONS:
                    for k in amps:
                        for r in ratios:
                            pulse = OneSinePulse(k * uplift_threshold(block, phi), r * p, vertical=av)
                            out.append(Case(f"pulse {shape[0]} phi {phi:g} a/a_up {k:g} w/p {r:g} mu {mu} "
                                            f"av {av / G:g}g", block, PlanMotion.along(pulse, phi)))
    return out


def _strong_part(record: Record, peak_time: float) -> Record:
    """``record`` from ``RECORD_LEAD`` before ``peak_time`` for ``RECORD_WINDOW`` (s)."""
    i0 = max(0, int(round((peak_time - RECORD_LEAD) / record.dt)))
    i1 = min(record.values.size, i0 + int(round(RECORD_WINDOW / record.dt)))
    vertical = None if record.vertical is None else record.vertical[i0:i1]
    return dataclasses.replace(record, values=record.values[i0:i1], vertical=vertical)


def record_cases() -> list[Case]:
    """FEMA P695 far-field pairs on the slender box: both components (scaled by one factor that brings the first
    to 2 or 3 times the box's uplift threshold along its width), cut to their strong part, at ``RECORD_AZIMUTHS``;
    mu None without vertical, mu 0.5 with the synthetic vertical."""
    refs = [e.reference for e in library.entries("far-field")]
    out = []
    for n, k in enumerate(RECORD_PAIRS):
        first, second = library.load(refs[k]), library.load(refs[k + 1])
        factor = (2.0 + n % 2) * G * 0.25 / first.pfa
        first, second = first.scaled(factor), second.scaled(factor)
        peak = float(np.argmax(np.abs(first.values))) * first.dt
        for with_v, mu in ((False, None), (True, 0.5)):
            a = with_vertical(first, second, RECORD_VERTICAL) if with_v else first
            a, b2 = _strong_part(a, peak), _strong_part(second, peak)
            block = _box(BOXES[0], mu)
            for az in RECORD_AZIMUTHS:
                out.append(Case(f"record {first.name} x{factor:.4g} az {az:g} mu {mu} vertical {with_v}", block,
                                PlanMotion(a, b2, az)))
    return out


def all_cases() -> list[Case]:
    """The full case set (:func:`pulse_cases` then :func:`record_cases`), deterministic."""
    return pulse_cases() + record_cases()


def quick_cases() -> list[Case]:
    """Every tenth case of :func:`all_cases` (the quick form of ``make test-siconos``)."""
    return all_cases()[::10]


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


def _vertical_after(motion: PlanMotion) -> float:
    """Vertical floor acceleration after the motion's samples (m/s²): a pulse's constant ``vertical`` acts over the
    whole run (:class:`opsrock.excitations.Pulse`), a record's vertical samples end with it."""
    vertical = motion.vertical
    return float(vertical) if vertical is not None and np.ndim(vertical) == 0 else 0.0


def box_geometry(block: Block) -> dict:
    """The box's fields of a case file: half-width ``b``, half-depth ``d``, centre-of-mass height ``h`` (m) and the
    principal inertia per unit mass (m², :func:`box_properties`)."""
    return {"b": block.b, "d": block.d, "h": block.h_cm, "inertia": list(box_properties(block).inertia)}


def write_cases(path: str | Path, cases: list[Case], geometry: Callable[[Block], dict] = box_geometry) -> Path:
    """Write ``cases`` as the .npz the Siconos model reads (opsrock/data/siconos/siconos_block3d.py's docstring), each
    block's fields from ``geometry`` (the box's by default); return the path."""
    meta, ax, ay, av, start = [], [], [], [], 0
    for i, case in enumerate(cases):
        dt, x, y, v = _samples(case.motion)
        meta.append({"index": i, "label": case.label, **geometry(case.block), "mu": case.block.friction, "dt": dt,
                     "start": start, "n": int(x.size), "tail": TAIL, "av_tail": _vertical_after(case.motion)})
        ax.append(x)
        ay.append(y)
        av.append(v)
        start += x.size
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    np.savez(path, meta=json.dumps(meta), ax=np.concatenate(ax), ay=np.concatenate(ay), av=np.concatenate(av))
    return path


__all__ = ["BOXES", "Case", "all_cases", "box_geometry", "pulse_cases",
           "quick_cases", "record_cases", "smoke_cases", "uplift_threshold", "write_cases"]

if __name__ == "__main__":
    _SETS = {"smoke": smoke_cases, "quick": quick_cases, "all": all_cases}
    print(write_cases(sys.argv[1], _SETS[sys.argv[2] if len(sys.argv) > 2 else "smoke"]()))
