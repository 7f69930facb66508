"""The floor motions of a record scene: every ground record through every building, computed once.

One work item per (ground record, building) computes all the building's floors of interest from one
analysis (:func:`compute_motions`, run by the campaign's executor); the results are cached in the
campaign's folder (:data:`MOTIONS_FILE`, keyed by the scene's digest) so a resumed campaign does not
filter them again, and assembled into :class:`Motion` objects the cases share.
"""

from __future__ import annotations

import math
import pickle
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import numpy as np

from opsrock._files import atomic_write
from opsrock.excitations.building import ShearBuilding, floor_motions, floor_record
from opsrock.excitations.records import Record
from opsrock.intensity.records import MotionMeasures, motion_measures

#: Floor label of an unfiltered ground motion.
GROUND: str = "ground"

#: Floor motions of a record scene, cached in its output folder (computed once, reused on resume).
MOTIONS_FILE: str = "floor_motions.pickle"


@dataclass(frozen=True)
class Motion:
    """A floor motion (unscaled) with its measures, shared by the cases that use it."""

    record: Record = field(repr=False)
    measures: MotionMeasures
    floor: str
    ground: str
    #: First period (s) of the building the motion was filtered through; NaN on the ground.
    building_period: float = math.nan


#: One item of work: a ground record, the building it goes through (None: the ground itself) and the
#: building's floors of interest (1-based).
Item = tuple[Record, "ShearBuilding | None", tuple[int, ...]]


def compute_motions(items: list[Item]) -> list[Any]:
    """Floor motions and their measures for a batch of items.

    Runs in a worker. Returns, per item, a list of ``(values, MotionMeasures)`` per floor, or the
    error text if the building analysis failed (never raises).
    """
    out: list[Any] = []
    for ground, building, floors in items:
        try:
            recs = [ground] if building is None else floor_motions(ground, building, list(floors))
            out.append([(np.asarray(r.values), motion_measures(r)) for r in recs])
        except Exception as exc:  # noqa: BLE001  (reported per case, never hidden)
            out.append(f"{type(exc).__name__}: {exc}")
    return out


def motion_items(grounds, floors) -> list[Item]:
    """One item per (ground record, building): all floors of a building from one analysis.

    Parameters
    ----------
    grounds : sequence of Record
        The ground records.
    floors : sequence of Floor
        The floor motion sources (:class:`opsrock.campaign.records.Floor`).
    """
    by_building: dict[str | None, tuple[ShearBuilding | None, list[int]]] = {}
    for f in floors:
        key = None if f.building is None else f.building.name
        by_building.setdefault(key, (f.building, []))[1].append(f.floor)
    return [(g, b, tuple(fls)) for g in grounds for b, fls in by_building.values()]


def assemble_motions(items: list[Item], results: list[Any]) -> dict[tuple[str, str], Motion | str]:
    """``{(record name, floor label): Motion or error text}`` from :func:`compute_motions` output."""
    motions: dict[tuple[str, str], Motion | str] = {}
    for (ground, building, floors), res in zip(items, results):
        labels = [GROUND] if building is None else [building.floor_label(f) for f in floors]
        for j, label in enumerate(labels):
            if isinstance(res, str):
                motions[(ground.name, label)] = res
                continue
            values, measures = res[j]
            rec = floor_record(ground, values, label)  # the ground itself too, labelled as its floor
            motions[(ground.name, label)] = Motion(record=rec, measures=measures, floor=label, ground=ground.name,
                                                   building_period=math.nan if building is None else building.period)
    return motions


def cached_motions(folder: Path, digest: str, items: list[Item],
                   compute: Callable[[list[Item]], list[Any]]) -> dict[tuple[str, str], Motion | str]:
    """The motions of ``items``: from ``folder``'s cache when it was written for ``digest``, else
    ``compute(items)`` (the executor's work), then cached (atomically)."""
    cache = Path(folder) / MOTIONS_FILE
    try:
        with open(cache, "rb") as fh:
            saved = pickle.load(fh)
        if saved.get("digest") == digest and len(saved["results"]) == len(items):
            return assemble_motions(items, saved["results"])
    except (OSError, EOFError, pickle.UnpicklingError, AttributeError, KeyError, TypeError, ValueError):
        pass
    results = compute(items)
    atomic_write(cache, lambda fh: pickle.dump({"digest": digest, "results": results}, fh), binary=True)
    return assemble_motions(items, results)


__all__ = ["GROUND", "MOTIONS_FILE", "Motion", "assemble_motions", "cached_motions", "compute_motions",
           "motion_items"]
