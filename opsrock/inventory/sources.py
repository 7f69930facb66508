"""Sources of floor motions besides the user's manifest: the shipped shear building.

:func:`building_motions` filters a library record set through a linear shear building
(:class:`opsrock.excitations.building.ShearBuilding`, as ``opsrock contents`` does) and returns the floors'
absolute accelerations as a :class:`~opsrock.inventory.motions.MotionSet`: one motion per library record
(each recorded component its own record) and floor, direction ``"1"``. Floors are labelled ``ground`` and
the floor numbers ``"1"`` .. ``"<storeys>"`` (the roof is the top number), so that pelicun's locations
follow (:func:`opsrock.inventory.pelicun.floor_numbers`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from opsrock.errors import InputError
from opsrock.inventory.motions import FloorMotion, MotionSet


@dataclass(frozen=True)
class BuildingSource:
    """The shipped building route's inputs.

    Parameters
    ----------
    period : float
        First period ``T_1`` (s).
    storeys : int
        Storeys.
    damping : float
        Modal damping ratio (dimensionless).
    floors : tuple
        ``"ground"``, floor numbers 1..storeys and/or ``"roof"``.
    record_set : str
        Library record set (``fema-p695:far-field``).
    names : tuple of str
        A subset of its records (empty: all).
    """

    period: float = 1.0
    storeys: int = 8
    damping: float = 0.05
    floors: tuple = ("ground", "roof")
    record_set: str = "fema-p695:far-field"
    names: tuple[str, ...] = ()


class _Filter:
    """Task state of :func:`building_motions`: task ``(k,)`` filters ground record ``k`` through the building."""

    def __init__(self, grounds, building, numbers) -> None:
        self.grounds, self.building, self.numbers = grounds, building, numbers

    def run(self, k: int) -> list:
        from opsrock.excitations.building import floor_motions

        g = self.grounds[k]
        suspended = [n for n in self.numbers if n > 0]
        filtered = dict(zip(suspended, floor_motions(g, self.building, suspended))) if suspended else {}
        return [g if n == 0 else filtered[n] for n in self.numbers]


#: Records of a quick study on the shipped building (six of the FEMA P695 far-field set).
QUICK_RECORDS: tuple[str, ...] = ("NORTHR_MUL009", "NORTHR_LOS000", "DUZCE_BOL000", "HECTOR_HEC000",
                                  "KOBE_NIS000", "LANDERS_YER270")


def floor_numbers(building: Any, floors: tuple) -> tuple[int, ...]:
    """``floors`` of ``building`` (a :class:`~opsrock.excitations.building.ShearBuilding`) as numbers: 0 the
    ground, ``storeys`` the roof; each ``"ground"``, a floor 1..storeys or ``"roof"``, at least one, each floor
    once, else :class:`InputError` naming ``floors``."""
    from opsrock.errors import OpsrockError

    if not floors:
        raise InputError("floors must name at least one floor ('ground', a number or 'roof')", argument="floors")
    numbers = []
    for f in floors:
        try:
            numbers.append(0 if f == "ground" else building.floor_index(f))
        except OpsrockError:
            raise InputError(f"floors: {f!r} is not 'ground', 'roof' or a floor 1..{building.storeys}",
                             argument="floors") from None
    if len(set(numbers)) != len(floors):
        raise InputError(f"floors name the same floor twice: {tuple(floors)!r}", argument="floors")
    return tuple(numbers)


def building_motions(source: BuildingSource, workers: int | None = None) -> MotionSet:
    """The floor motions (m/s²) of ``source``'s building under its record set, as a motion set.

    Parameters
    ----------
    source : BuildingSource
        The building (period s, storeys, damping), its floors, the record set and records.
    workers : int or None
        Processes for the building analyses (OpenSeesPy; about a second per record); None or 1: this one.
    """
    from opsrock._pool import TaskPool
    from opsrock.excitations.building import ShearBuilding

    building = ShearBuilding("building", source.period, source.storeys, source.damping)  # checks each, by name
    numbers = floor_numbers(building, source.floors)
    grounds = _grounds(source)
    state = _Filter(grounds, building, numbers)
    tasks = [(k,) for k in range(len(grounds))]
    with TaskPool(state, tasks, workers or 1) as pool:
        results = pool.results()
    motions = tuple(FloorMotion(g.name, "ground" if n == 0 else str(n), "1", rec)
                    for g, recs in zip(grounds, results) for n, rec in zip(numbers, recs))
    return MotionSet(motions, f"{source.record_set} through a shear building T1 = {source.period:g} s, "
                              f"{source.storeys} storeys, damping {source.damping:g}", storeys=source.storeys)


def _grounds(source: BuildingSource) -> tuple:
    from opsrock.errors import OpsrockError
    from opsrock.excitations import library

    if len(set(source.names)) != len(source.names):
        raise InputError(f"records name a record twice: {list(source.names)!r}", argument="records")
    try:
        set_name, one = library.parse_reference(source.record_set)
    except OpsrockError as exc:
        raise InputError(f"record_set {source.record_set!r}: {exc}", argument="record_set") from None
    if one is not None:
        raise InputError(f"record_set {source.record_set!r} names one record; give a set and records for a subset",
                         argument="record_set")
    entries = [e for e in library.entries(set_name) if not source.names or e.name in source.names]
    missing = sorted(set(source.names) - {e.name for e in entries})
    if missing:
        raise InputError(f"records {missing!r} are not in {source.record_set}", argument="records")
    return tuple(library.load(e.reference) for e in entries)


__all__ = ["QUICK_RECORDS", "BuildingSource", "building_motions", "floor_numbers"]
