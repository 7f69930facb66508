"""The user's floor motions: a manifest CSV with the columns ``record, floor, direction, file, units, dt``
(``dt`` where the file does not give it; ``file`` relative to the manifest), listing floor acceleration
histories in any format :func:`opsrock.excitations.readers.read_record` reads. Each motion is checked
for plausibility (:data:`opsrock.limits.PLAUSIBLE`) unless confirmed.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from opsrock.excitations.records import Record


@dataclass(frozen=True)
class FloorMotion:
    """One floor acceleration history of the user's building.

    Parameters
    ----------
    record : str
        The ground-motion record (event) it comes from: the unit a record bootstrap resamples.
    floor : str
        The floor's label as the manifest gives it (``"1"``, ``"roof"``, ``"L3"``).
    direction : str
        ``"1"`` or ``"2"``: the horizontal direction (``Item.width`` lies along 1, ``depth`` along 2).
    motion : Record
        The acceleration history (m/s²).
    """

    record: str
    floor: str
    direction: str
    motion: Record = field(repr=False)


@dataclass(frozen=True)
class MotionSet:
    """Every floor motion of a manifest (or of the shipped shear building), each (record, floor, direction)
    once.

    Parameters
    ----------
    motions : tuple of FloorMotion
        In manifest order.
    source : str
        The manifest read, or a description of the building filter.
    """

    motions: tuple[FloorMotion, ...]
    source: str

    @property
    def floors(self) -> tuple[str, ...]:
        """The floors, in first-seen order."""
        return tuple(dict.fromkeys(m.floor for m in self.motions))

    @property
    def directions(self) -> tuple[str, ...]:
        """The directions, in first-seen order."""
        return tuple(dict.fromkeys(m.direction for m in self.motions))

    @property
    def records(self) -> tuple[str, ...]:
        """The records, in first-seen order."""
        return tuple(dict.fromkeys(m.record for m in self.motions))


def read_motions(path: str | Path, *, confirm: bool = False) -> MotionSet:
    """Read a motions manifest; a motion whose PFA exceeds :data:`opsrock.limits.PLAUSIBLE` is refused with
    its likely unit unless ``confirm``. Raises :class:`opsrock.errors.InputError` naming the manifest line."""
    raise NotImplementedError


__all__ = ["FloorMotion", "MotionSet", "read_motions"]
