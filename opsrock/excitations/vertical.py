"""Vertical floor motion beside a horizontal record: from a second record, or synthetic.

A block feels ``g + a_v(t)`` (docs/friction.md). The FEMA P695 record sets hold two horizontal
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
"""

from __future__ import annotations

import numpy as np

from opsrock.errors import InputError
from opsrock.excitations import library
from opsrock.excitations.records import Record

#: Vertical-to-horizontal ratio of a synthetic vertical motion (dimensionless).
VERTICAL_TO_HORIZONTAL: float = 2.0 / 3.0

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


__all__ = ["VERTICAL_SOURCES", "VERTICAL_TO_HORIZONTAL", "on_grid", "padded", "partner", "synthetic_vertical",
           "with_vertical"]
