"""The directionality study's motions, cases and campaigns (:mod:`opsrock.inventory.directionality.study`).

* :func:`study_motions`: the shipped building's floor motions of each record pair in both directions
  (:func:`opsrock.inventory.sources.building_motions`, paired by :func:`opsrock.inventory.motions.paired_motions`),
  the same through each item support's oscillator, and the demands of each pair and floor (:data:`DEMAND_COLUMNS`);
* :class:`PlanCase`: one item under one pair on one floor at one orientation and level, in three dimensions
  (a :class:`~opsrock.excitations.plan.PlanMotion` of both components) or in the plane of the weaker axis (the
  component along it);
* :class:`PlanScene`: the campaign scene of a set of such cases; the engine (:class:`opsrock.campaign.run.Stage`)
  runs the cases it is given, and the scene's digest holds everything that decides them (the records' samples,
  the blocks with their depth, the orientations, the levels and the scaling rule, the supports).

Case ids: ``<item>/<pair>/<floor>/a<azimuth>/l<k>``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np
import pandas as pd

from opsrock._pool import TaskPool
from opsrock.campaign.cases import CONTACT_COLUMNS, PLAN_COLUMNS, RESULT_COLUMNS, units_of
from opsrock.campaign.records import Floor, Intensity, RecordSet
from opsrock.campaign.scene import BlockSpec, Scene
from opsrock.constants import G
from opsrock.errors import InputError, OpsrockError
from opsrock.excitations import library
from opsrock.excitations.building import ShearBuilding, floor_motions
from opsrock.excitations.plan import PlanMotion
from opsrock.excitations.records import Record
from opsrock.intensity.records import velocity_displacement
from opsrock.inventory.motions import FloorMotion, MotionSet, paired_motions
from opsrock.inventory.sources import BuildingSource, building_motions
from opsrock.limits import LIMITS

#: The demands of a record pair on a floor, unscaled: peak floor accelerations of each direction (m/s²), peak
#: floor velocities of each direction, the larger of the two, and the non-directional value, the peak of the
#: horizontal velocity vector's length (m/s).
DEMAND_COLUMNS: tuple[str, ...] = ("record", "floor", "pfa_1", "pfa_2", "pfv_1", "pfv_2", "pfv_max", "pfv_nd")

#: The scene's columns of a case (m/s², m/s; ``azimuth`` deg; ``b_over_h`` the weaker axis's ``tan alpha``).
SCENE_COLUMNS: tuple[str, ...] = (
    "case_id", "block", "item", "model", "record", "floor", "azimuth", "level", "level_value", "scale", "b_over_h",
    "pfa", "pfv_1", "pfv_2", "pfv_max", "pfv_nd", "pfv_weak",
)  # fmt: skip

#: The units of the scene's columns that a campaign's own scenes do not have (the others':
#: :data:`opsrock.campaign.cases.UNITS`), as the units row of its ``cases.csv`` writes them.
SCENE_UNITS: dict[str, str] = {"item": "", "model": "", "b_over_h": "-", "pfv_1": "m/s", "pfv_2": "m/s",
                               "pfv_max": "m/s", "pfv_nd": "m/s", "pfv_weak": "m/s"}

#: Columns of a campaign's ``cases.csv``: the scene's, then what the solver stored (the contact and plan columns
#: a solver fills: :data:`opsrock.campaign.cases.CONTACT_COLUMNS`, :data:`~opsrock.campaign.cases.PLAN_COLUMNS`;
#: the scene's own of those, the block's friction, depth and azimuth, are in the scene's columns or its plan).
CASE_COLUMNS: tuple[str, ...] = (*SCENE_COLUMNS, *RESULT_COLUMNS,
                                 *(c for c in CONTACT_COLUMNS if c not in ("friction", "friction_kinetic",
                                                                           "pfa_vertical")),
                                 *(c for c in PLAN_COLUMNS if c not in ("depth", "azimuth", "record2")))


@dataclass(frozen=True)
class StudyMotions:
    """The floor motions of the study.

    Parameters
    ----------
    pairs : tuple of MotionPair
        Each record pair on each floor (:class:`opsrock.inventory.motions.MotionPair`, m/s²).
    demands : DataFrame
        One row per pair and floor, :data:`DEMAND_COLUMNS`.
    velocities : dict
        ``(record, floor)`` -> ``(v_1, v_2)``, the floor velocities of both directions (m/s, baseline-corrected,
        padded with zeros to one length).
    supported : dict
        ``(record, floor, period, damping)`` -> the two directions through a support's oscillator (m/s²).
    source : str
        Where the motions come from.
    """

    pairs: tuple[Any, ...]
    demands: pd.DataFrame = field(repr=False)
    velocities: dict = field(repr=False)
    supported: dict = field(repr=False)
    source: str = ""


def _padded(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    n = max(a.size, b.size)
    return np.pad(a, (0, n - a.size)), np.pad(b, (0, n - b.size))


class _Support:
    """Task state of :func:`study_motions`: task ``(k,)`` filters motion ``k`` through its support."""

    def __init__(self, work: list) -> None:
        self.work = work

    def run(self, k: int) -> Record:

        record, period, damping = self.work[k]
        return floor_motions(record, ShearBuilding("support", period, 1, damping), [1])[0]


def _pair_names(design: Any) -> dict[str, tuple[str, str]]:
    """First component's name -> the names of the pair's two components, for the design's pairs."""

    try:
        set_name, _ = library.parse_reference(design.record_set)
        entries = library.entries(set_name)
    except OpsrockError as exc:
        raise InputError(f"record_set {design.record_set!r}: {exc}", argument="record_set") from None
    events: dict[int, dict[str, str]] = {}
    for e in entries:
        events.setdefault(e.event_id, {})[e.component] = e.name
    pairs = {c["a"]: (c["a"], c["b"]) for c in events.values() if set(c) == {"a", "b"}}
    missing = [p for p in design.pairs if p not in pairs]
    if missing or len(set(design.pairs)) != len(design.pairs):
        raise InputError(f"pairs {missing or list(design.pairs)!r}: each must be named once, by the first component "
                         f"of a pair of {design.record_set}", argument="pairs")
    return {p: pairs[p] for p in (design.pairs or tuple(pairs))}


def study_motions(design: Any, items: tuple, workers: int | None) -> StudyMotions:
    """The floor motions of the study's pairs in both directions, through the supports of ``items``, with their
    demands (see :class:`StudyMotions`)."""

    names = _pair_names(design)
    direction = {c: (pair, str(k + 1)) for pair, comps in names.items() for k, c in enumerate(comps)}
    source = BuildingSource(design.period, design.storeys, design.damping, tuple(design.floors), design.record_set,
                            tuple(c for comps in names.values() for c in comps))
    built = building_motions(source, workers)
    relabelled = MotionSet(tuple(FloorMotion(direction[m.record][0], m.floor, direction[m.record][1], m.motion)
                                 for m in built.motions), built.source, storeys=built.storeys)
    pairs = paired_motions(relabelled)
    supports = sorted({(it.support.period, it.support.damping) for it in items if it.support is not None})
    work = [(m.motion, t, z) for t, z in supports for p in pairs for m in (p.first, p.second)]
    with TaskPool(_Support(work), [(k,) for k in range(len(work))], workers or 1) as pool:
        filtered = pool.results()
    supported = {(p.record, p.floor, t, z): (filtered[2 * k], filtered[2 * k + 1])
                 for k, ((t, z), p) in enumerate((s, p) for s in supports for p in pairs)}
    rows, velocities = [], {}
    for p in pairs:
        rows.append(_demands(p, velocities))
    return StudyMotions(pairs, pd.DataFrame(rows, columns=list(DEMAND_COLUMNS)), velocities, supported,
                        relabelled.source)


def _demands(pair: Any, velocities: dict) -> dict[str, Any]:
    """The demands of one pair on one floor (:data:`DEMAND_COLUMNS`); its velocities stored in ``velocities``."""

    v1, v2 = _padded(velocity_displacement(pair.first.motion)[0], velocity_displacement(pair.second.motion)[0])
    velocities[(pair.record, pair.floor)] = (v1, v2)
    pfv_1, pfv_2 = float(np.max(np.abs(v1))), float(np.max(np.abs(v2)))
    return {"record": pair.record, "floor": pair.floor, "pfa_1": pair.first.motion.pfa, "pfa_2": pair.second.motion.pfa,
            "pfv_1": pfv_1, "pfv_2": pfv_2, "pfv_max": max(pfv_1, pfv_2), "pfv_nd": float(np.max(np.hypot(v1, v2)))}


def weak_cosines(weak: str, azimuth: float) -> tuple[float, float]:
    """``(c_1, c_2)``: the weaker axis's component of the floor motion is ``c_1 a_1 + c_2 a_2`` at ``azimuth``
    (deg; :class:`~opsrock.excitations.plan.PlanMotion`'s frames: ``a_x = a_1 cos + a_2 sin``, ``a_y = -a_1 sin +
    a_2 cos``)."""
    c, s = math.cos(math.radians(azimuth)), math.sin(math.radians(azimuth))
    return (c, s) if weak == "x" else (-s, c)


@dataclass(frozen=True)
class PlanCase:
    """One item under one record pair on one floor, at one orientation and level.

    Parameters
    ----------
    case_id : str
        ``<item>/<pair>/<floor>/a<azimuth>/l<k>``.
    block : Block
        The box (three dimensions) or the weaker axis's planar block.
    first : Record
        Direction 1 of the motion the item meets (m/s², unscaled); in the plane: the weaker axis's component.
    second : Record or None
        Direction 2 (m/s², unscaled); None in the plane.
    azimuth : float
        The orientation (deg).
    scale : float
        Factor on both directions (dimensionless).
    columns : Mapping
        The scene's columns of the case (:data:`SCENE_COLUMNS`).
    problem : str
        Non-empty if the case cannot be run (a scale factor outside its limits): stored failed with it.
    """

    case_id: str
    block: Any
    first: Record = field(repr=False)
    second: Record | None = field(repr=False)
    azimuth: float
    scale: float
    columns: Mapping[str, Any] = field(repr=False)
    problem: str = ""

    @property
    def excitation(self) -> Any:
        """The scaled floor motion: a :class:`~opsrock.excitations.plan.PlanMotion` of both directions, or the
        weaker axis's component in the plane (m/s²)."""

        if self.second is None:
            return self.first.scaled(self.scale)
        return PlanMotion(self.first.scaled(self.scale), self.second.scaled(self.scale), self.azimuth)

    def row(self) -> dict[str, Any]:
        """The scene's columns of ``cases.csv``."""
        return dict(self.columns)


@dataclass(frozen=True)
class PlanScene(Scene):
    """A record scene whose cases are :class:`PlanCase` (built by :func:`study_campaigns`, given to the engine).

    Parameters
    ----------
    plan : Mapping
        What decides the cases beyond the records, blocks, solver and levels of :class:`Scene` (JSON data): the
        model, the blocks' depths, the orientations, the scaling rule, the pairs, the supports.
    case_count : int
        Its cases.
    """

    plan: Mapping[str, Any] = field(default_factory=dict)
    case_count: int = 0

    @property
    def columns(self) -> tuple[str, ...]:
        """:data:`CASE_COLUMNS`."""
        return CASE_COLUMNS

    @property
    def units(self) -> list[str]:
        """The units row of its ``cases.csv``: the campaign's units, and :data:`SCENE_UNITS`."""
        return units_of(self.columns, self.measure, SCENE_UNITS)

    @property
    def n_cases(self) -> int:
        """:attr:`case_count`."""
        return self.case_count

    def fingerprint(self) -> dict[str, Any]:
        """:meth:`Scene.fingerprint` with :attr:`plan`."""
        return {**super().fingerprint(), "plan": self.plan}


@dataclass(frozen=True)
class Campaign:
    """One campaign of the study: its folder name, scene and cases (in order)."""

    name: str
    scene: PlanScene
    cases: list = field(repr=False)


def _solver(model: str, item: Any, design: Any) -> str:
    """The solver of ``item``'s cases of ``model``: the design's ``solver3d`` in three dimensions (or, for the
    plumbing, the planar one), in the plane the registry's planar solver for a base that slips or not
    (:func:`opsrock.solvers.registry.planar_solver`)."""
    from opsrock.solvers.registry import planar_solver

    planar = planar_solver(item.planar.friction is not None)
    if model == "3d":
        return design.solver3d if design.in_plan else (planar if item.planar.friction is not None else design.solver3d)
    return planar


def study_campaigns(design: Any, items: tuple, motions: StudyMotions) -> list[Campaign]:
    """The campaigns of the study, one per model, solver and item (a study of other items reuses the stores of
    the items it shares), each case once, ordered by pair and floor (so a batch sent to a worker carries few
    records)."""

    groups: dict[tuple[str, str, str], list] = {}
    projected: dict = {}
    demands = motions.demands.set_index(["record", "floor"])
    for pair in motions.pairs:
        d = demands.loc[(pair.record, pair.floor)]
        for item in items:
            for model in ("3d", "planar"):
                solver = _solver(model, item, design)
                three_d = model == "3d" and design.in_plan
                groups.setdefault((model, solver, item.id), []).extend(
                    _cases(design, item, pair, d, motions, projected, three_d, model))
    out = []
    for (model, solver, _), cases in groups.items():
        names = list(dict.fromkeys(c.columns["item"] for c in cases))
        by_id = {it.id: it for it in items}
        blocks = tuple(_spec(by_id[n], model, design.in_plan, BlockSpec) for n in names)
        grounds = tuple({id(r): r for c in cases for r in (c.first, c.second) if r is not None}.values())
        records = RecordSet(grounds=grounds, floors=(Floor(None, 0),), source=motions.source,
                            intensity=Intensity("ida", "pfa_onset", design.levels))
        plan = {"model": model, "azimuths": list(design.azimuths), "in_plan": model == "3d" and design.in_plan,
                "scaling": "level x g min(tan alpha, mu) of the weaker axis / max(PFA_1, PFA_2)",
                "depths": {n: by_id[n].block3d.depth for n in names},
                "supports": {n: None if by_id[n].support is None else [by_id[n].support.period,
                                                                       by_id[n].support.damping] for n in names}}
        settings = design.settings3d if solver == design.solver3d and model == "3d" else {}
        scene = PlanScene(name=f"directionality-{model}-{solver}", path="", blocks=blocks, grid=None, solver=solver,
                          solver_settings=settings, records=records, plan=plan, case_count=len(cases))
        out.append(Campaign(f"{model}-{solver}-{names[0]}", scene, cases))
    return out


def _spec(item: Any, model: str, in_plan: bool, spec_class: type) -> Any:
    """The scene's entry of ``item`` (with its depth in three dimensions; its support is in the scene's plan)."""
    b = item.block3d if model == "3d" and in_plan else item.planar
    return spec_class(name=item.id, width=b.width, height=b.height, depth=b.depth, reason=item.description, mass=b.mass,
                      restitution_factor=1.0, friction=b.friction, friction_kinetic=b.friction_kinetic if b.friction
                      is not None else None, cm_height=b.h_cm if b.h_cm != b.h else None,
                      radius_of_gyration=b.r_gyration if not math.isclose(b.r_gyration, _homogeneous_r(b)) else None)


def _homogeneous_r(b: Any) -> float:
    return math.sqrt((b.width ** 2 + b.height ** 2) / 12.0)


def _motion_of(item: Any, pair: Any, motions: StudyMotions) -> tuple[Record, Record]:
    """The two directions of the motion ``item`` meets (through its support, if any), m/s²."""
    if item.support is None:
        return pair.first.motion, pair.second.motion
    return motions.supported[(pair.record, pair.floor, item.support.period, item.support.damping)]


def _projection(item: Any, pair: Any, azimuth: float, motions: StudyMotions, projected: dict) -> tuple[Record, float]:
    """The weaker axis's component of the motion ``item`` meets at ``azimuth`` (m/s², shared among cases) and
    the peak floor velocity along that axis (m/s)."""
    key = (pair.record, pair.floor, item.weak, azimuth, None if item.support is None else
           (item.support.period, item.support.damping))
    if key not in projected:
        c1, c2 = weak_cosines(item.weak, azimuth)
        a1, a2 = _motion_of(item, pair, motions)
        x1, x2 = _padded(np.asarray(a1.values), np.asarray(a2.values))
        v1, v2 = motions.velocities[(pair.record, pair.floor)]
        record = Record(dt=a1.dt, values=c1 * x1 + c2 * x2, name=f"{pair.record}.{pair.floor}.{item.weak}{azimuth:g}",
                        info=a1.info, units="m/s2")
        projected[key] = (record, float(np.max(np.abs(c1 * v1 + c2 * v2))))
    return projected[key]


def _cases(design: Any, item: Any, pair: Any, d: pd.Series, motions: StudyMotions, projected: dict, three_d: bool,
           model: str) -> list[PlanCase]:
    """The cases of ``item`` under ``pair`` in ``model``: every orientation and level."""

    lim = LIMITS["scale"]
    pfa_max = max(float(d["pfa_1"]), float(d["pfa_2"]))
    a1, a2 = _motion_of(item, pair, motions)
    block = item.block3d if three_d else item.planar
    out = []
    for azimuth in design.azimuths:
        planar, pfv_weak = _projection(item, pair, azimuth, motions, projected)
        for k, level in enumerate(design.levels, start=1):
            scale = level * item.planar.onset_acceleration / pfa_max
            problem = "" if lim.low <= scale <= lim.high else (
                f"scale factor {scale:.4g} to reach level {level:g} is outside [{lim.low:g}, {lim.high:g}] (the "
                f"larger component's PFA is {pfa_max / G:.4g} g)")
            case_id = f"{item.id}/{pair.record}/{pair.floor}/a{azimuth:g}/l{k:02d}"
            cols = {"case_id": case_id, "block": item.id, "item": item.id, "model": model, "record": pair.record,
                    "floor": pair.floor, "azimuth": azimuth, "level": k, "level_value": level, "scale": scale,
                    "b_over_h": item.b_over_h, "pfa": scale * pfa_max,
                    **{c: scale * float(d[c]) for c in ("pfv_1", "pfv_2", "pfv_max", "pfv_nd")},
                    "pfv_weak": scale * pfv_weak}
            first, second = (a1, a2) if three_d else (planar, None)
            out.append(PlanCase(case_id, block, first, second, azimuth, scale, cols, problem))
    return out


__all__ = ["CASE_COLUMNS", "DEMAND_COLUMNS", "SCENE_COLUMNS", "Campaign", "PlanCase", "PlanScene", "StudyMotions",
           "study_campaigns", "study_motions", "weak_cosines"]
