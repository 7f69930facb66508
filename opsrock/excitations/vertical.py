"""Vertical floor motion beside a horizontal record: from a second record, or synthetic.

A block feels ``g + a_v(t)`` (docs/guide/friction.md). The FEMA P695 record sets hold two horizontal
components per recording and no vertical one; where a recorded vertical motion is not at hand, opsrock
builds a synthetic one from the recording's *other* horizontal component, scaled by
:data:`VERTICAL_TO_HORIZONTAL`:

* the ratio 2/3 is the vertical-to-horizontal ratio of design spectra long used in practice (Newmark and
  Hall's rule of thumb); measured ratios are larger near the source and at short periods and smaller
  elsewhere, so the synthetic motion is a plausible vertical intensity, not a prediction of one;
* the orthogonal component carries the event's duration and time of arrival without repeating the
  horizontal motion the block already feels; its frequency content is a horizontal one (real vertical
  motions are richer at high frequency).

Inside a building the vertical motion of every floor is taken as the ground's: buildings are axially
stiff (vertical periods of a few hundredths of a second), so their floors follow the ground vertically.

A floor's downward acceleration beyond ``g`` (``a_v < -g``: the block leaves the floor) lasts a fraction
of a second in the strongest recorded motions (a vertical half-cycle of a few hundredths to a tenth of a
second); :func:`check_free_fall` refuses a vertical motion that keeps it up longer than
:data:`MAX_FREE_FALL` (a floor falling faster than gravity for 1 s would drop more than 4.9 m).
"""

from __future__ import annotations

import math

import numpy as np

from opsrock.constants import G
from opsrock.errors import InputError
from opsrock.excitations import library
from opsrock.excitations.records import Record

#: Vertical-to-horizontal ratio of a synthetic vertical motion (dimensionless).
VERTICAL_TO_HORIZONTAL: float = 2.0 / 3.0

#: Longest stretch (s) a floor may accelerate downward faster than gravity (``a_v < -g``) on end.
MAX_FREE_FALL: float = 1.0

#: What a record's vertical motion can come from (scene key ``[records] vertical``).
VERTICAL_SOURCES: tuple[str, ...] = ("none", "synthetic")


def on_grid(record: Record, source: Record) -> np.ndarray:
    """``source``'s samples at ``record``'s sample times (m/s²): linear interpolation, zero beyond its end."""
    return np.interp(record.time, source.time, source.values, left=0.0, right=0.0)


def with_vertical(record: Record, vertical: Record, factor: float = 1.0) -> Record:
    """``record`` with the vertical motion ``factor`` x ``vertical`` (m/s², resampled to its times).

    Parameters
    ----------
    record : Record
        The horizontal motion.
    vertical : Record
        The vertical motion (its own sampling; cut or padded with zeros to ``record``'s duration).
    factor : float
        Factor on ``vertical`` (dimensionless).
    """
    return record.with_vertical(factor * on_grid(record, vertical))


def padded(vertical: np.ndarray | None, n: int) -> np.ndarray | None:
    """Vertical samples cut or padded with zeros to ``n`` samples of the same interval (a floor motion is
    the ground record followed by the building's free vibration, when the ground no longer moves)."""
    if vertical is None:
        return None
    out = np.zeros(n)
    m = min(n, vertical.size)
    out[:m] = vertical[:m]
    return out


def longest_free_fall(record: Record) -> tuple[float, float]:
    """``(duration, start)`` (s) of the longest stretch in which ``record``'s floor accelerates downward faster
    than gravity (``a_v < -g``, the samples read piecewise linear); ``(0, nan)`` if none or no vertical."""
    if record.vertical is None:
        return 0.0, math.nan
    below = np.concatenate(([False], record.vertical < -G, [False]))
    edges = np.flatnonzero(np.diff(below.astype(np.int8)))
    if edges.size == 0:
        return 0.0, math.nan
    v, dt, n = record.vertical, record.dt, record.vertical.size
    starts, ends = edges[::2], edges[1::2]  # samples [start, end) are below -g; the crossings in between
    before, after = np.maximum(starts - 1, 0), np.minimum(ends, n - 1)  # the neighbours above -g, if any
    with np.errstate(divide="ignore", invalid="ignore"):  # the branches np.where discards divide by zero
        t0 = np.where(starts > 0, (before + (v[before] + G) / (v[before] - v[starts])) * dt, 0.0)
        t1 = np.where(ends < n, (ends - 1 + (v[ends - 1] + G) / (v[ends - 1] - v[after])) * dt, (n - 1) * dt)
    k = int(np.argmax(t1 - t0))
    return float(t1[k] - t0[k]), float(t0[k])


def check_free_fall(record: Record) -> None:
    """Refuse a vertical floor motion no floor makes: downward acceleration beyond ``g`` for longer than
    :data:`MAX_FREE_FALL` on end.

    Raises
    ------
    InputError
        Naming ``vertical``, the record, the stretch and the likely cause.
    """
    duration, start = longest_free_fall(record)
    if duration > MAX_FREE_FALL:
        raise InputError(f"vertical: the floor of record {record.name or '<unnamed>'} accelerates downward faster "
                         f"than g (a_v < -g) for {duration:.4g} s on end from t = {start:.4g} s; no floor does that "
                         f"for more than {MAX_FREE_FALL:g} s (it would drop more than {G * MAX_FREE_FALL ** 2 / 2:.3g} "
                         "m): likely a vertical record in the wrong units or scaled far beyond any recorded motion",
                         argument="vertical")
    gap = gap_at_end(record)
    if gap > 0.0:
        raise InputError(f"vertical: the floor of record {record.name or '<unnamed>'} falls away from the block (a_v "
                         f"down to {float(np.min(record.vertical)) / G:.3g} g from t = {start:.4g} s) and is still "
                         f"{gap:.3g} m below it when the record ends: the block would fly free for longer than the "
                         "record, which no floor does; likely a vertical record in the wrong units or sign, or scaled "
                         "far beyond any recorded motion", argument="vertical")


def gap_at_end(record: Record) -> float:
    """How far (m) the floor of ``record`` is still below a block that left it at the first ``a_v < -g`` when the
    record ends (0: the block landed before, or never left). In flight the gap grows as ``gap'' = -(g + a_v)``
    from rest (trapezoidal sums over the samples): a floor that keeps falling faster than the block has no
    recorded counterpart (issue 46: 32.47 s of flight reported in a 9.99-s record)."""
    if record.vertical is None or not np.any(record.vertical < -G):
        return 0.0
    rel = -(G + np.asarray(record.vertical, dtype=float))
    k0 = int(np.flatnonzero(rel > 0.0)[0])
    v = np.concatenate(([0.0], np.cumsum(0.5 * (rel[k0:-1] + rel[k0 + 1:]) * record.dt)))
    gap = np.concatenate(([0.0], np.cumsum(0.5 * (v[:-1] + v[1:]) * record.dt)))
    return 0.0 if np.any(gap[1:] <= 0.0) else float(gap[-1])


def partner(ref: str) -> str:
    """The library reference of the other horizontal component of the recording ``ref`` belongs to.

    The FEMA P695 sets list each recording's two horizontal components one after the other.

    Raises
    ------
    InputError
        If the neighbour is not the same event and station (the set is not in pairs there).
    """
    e = library.entry(ref)
    entries = library.entries(e.set_name)
    k = next(i for i, x in enumerate(entries) if x.name == e.name)
    other = entries[k ^ 1] if (k ^ 1) < len(entries) else None
    if other is None or (other.info.event, other.info.station) != (e.info.event, e.info.station):
        raise InputError(f"record {ref}: no second horizontal component of the same recording in set {e.set_name}")
    return other.reference


def synthetic_vertical(ref: str, ratio: float = VERTICAL_TO_HORIZONTAL) -> Record:
    """The library record ``ref`` with a synthetic vertical motion: ``ratio`` x its recording's other
    horizontal component (m/s²)."""
    return with_vertical(library.load(ref), library.load(partner(ref)), ratio)


__all__ = ["MAX_FREE_FALL", "VERTICAL_SOURCES", "VERTICAL_TO_HORIZONTAL", "check_free_fall", "gap_at_end",
           "longest_free_fall",
           "on_grid", "padded", "partner", "synthetic_vertical", "with_vertical"]
