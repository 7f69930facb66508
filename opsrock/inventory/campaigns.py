"""The inventory study's campaigns: every item on the floors it stands on, in every direction of the motions.

One campaign (a record :class:`~opsrock.campaign.scene.Scene`, run resumably by
:func:`opsrock.campaign.run_campaign` into ``store/<group>``) per :class:`Group`: the items that stand on the
same floors, under one direction, on the same support, with the same solver. An item runs only on its
floors, and every floor motion is shared by all the items of its group (a campaign costs a pool of worker
processes and a store whatever its size, so the groups are as few as the items allow):

* the scene's "ground records" are the user's floor motions of the group's floors and direction, as given,
  each named ``<record>.<floor>``; an item on the floor itself meets them unfiltered (the campaign's floor
  label ``ground``: the motion as given, whatever floor it was recorded on);
* an item on a support (a desk, a table, a shelf: :class:`opsrock.inventory.items.Support`) meets them through
  the support's linear oscillator: a one-storey shear building
  (:class:`opsrock.excitations.building.ShearBuilding` with one storey, period and damping the support's) *is*
  that single-degree-of-freedom oscillator, its floor 1 the support's top (floor label ``support.f1``);
* the items with friction run with the ``friction`` solver, the others with the design's no-slip solver.

Case ids, stable and readable: ``<item>-d<direction>/<record>.<floor>/<ground|support.f1>/l<k>`` inside the
group's folder ``d<direction>-<solver>[-T<period>z<damping>][-on-<floors>]`` (``-on-`` only for items on
some of the floors). The IDA levels are ``PFA / (g min(tan alpha, mu))`` (``pfa_onset``) of the motion the item meets; the demands of
the fits are the *floor's* (the scale factor times the floor motion's PFA and PFV,
:mod:`opsrock.inventory.fits`), so that an item on a desk has its fragility in the floor demand pelicun
assesses.

The floor-motion measures (:func:`opsrock.intensity.records.motion_measures`) of every motion are computed
once (:func:`floor_demands`, cached in the store for a resumed study: :func:`cached_demands`) and handed to
each unfiltered group's campaign through its floor-motion cache (:func:`seed_motions`), so no campaign
computes them again.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import pickle
import time
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Iterator

import numpy as np
import pandas as pd

from opsrock.errors import InputError
from opsrock.inventory.friction import FrictionDistribution
from opsrock.inventory.items import DIRECTIONS, Item, Support
from opsrock.inventory.motions import MotionSet

#: Label of the one-storey building that stands for a support (its top is the floor label ``support.f1``).
SUPPORT_NAME: str = "support"

#: Cases per batch sent to a worker by a planar campaign: a case takes about a millisecond, and every batch
#: costs a round trip and a store commit (measured on FEMA P-58's nine: 16 -> 256 cut the solve phase of 25,344
#: cases from 18.7 to 15.6 s on a loaded 2-core machine). A campaign in plan (a case takes 0.1 to
#: several seconds) lets the campaign engine size its batches, a few per worker
#: (:func:`opsrock.campaign.executors.batch_size`): 256 cases in one batch kept a worker alone on a whole
#: round item's campaign while the other waited.
BATCH: int = 256

#: Columns of a campaign's ``cases.csv`` the study reads (and :data:`OPTIONAL_CASE_COLUMNS` where written).
CASE_COLUMNS: tuple[str, ...] = ("case_id", "block", "record", "level", "level_value", "scale", "status",
                                 "reason", "overturned")

#: Columns the study reads where the scene's solver writes them (registry ``result_columns``): ``slide_max`` (m)
#: where friction is modelled (NaN otherwise); a box in plan's ``azimuth`` (deg), ``tilt_max`` (rad) and
#: ``overturned_over``.
OPTIONAL_CASE_COLUMNS: tuple[str, ...] = ("slide_max", "azimuth", "tilt_max", "overturned_over")


@dataclass(frozen=True)
class Group:
    """The items of one campaign: those that stand on one floor, under one direction, on one support, with
    one solver.

    Parameters
    ----------
    floors : tuple of str
        The floors its items stand on, as the motions name them.
    all_floors : bool
        Whether they are all the floors of the motions.
    direction : str
        ``"1"`` or ``"2"``.
    support : Support or None
        The support the items stand on; None: the floor itself.
    solver : str
        The solver of its cases.
    """

    floors: tuple[str, ...]
    all_floors: bool
    direction: str
    support: Support | None
    solver: str

    @property
    def name(self) -> str:
        """Folder of the campaign: ``d<direction>-<solver>[-T<period>z<damping>][-on-<floors>]``."""
        from opsrock.excitations.records import safe_name

        tail = "" if self.support is None else "-" + _number(f"T{self.support.period:g}z{self.support.damping:g}")
        on = "" if self.all_floors else "-on-" + "_".join(safe_name(f) for f in self.floors)
        return f"d{self.direction}-{self.solver}{tail}{on}"


def _number(text: str) -> str:
    return text.replace(".", "p")


@dataclass(frozen=True)
class GroupScene:
    """One group's campaign scene and what its blocks stand for.

    Parameters
    ----------
    group : Group
        The group.
    scene : Scene
        Its record scene (:class:`opsrock.campaign.scene.Scene`).
    blocks : dict of str to str
        Block name -> item id.
    records : dict of str to (str, str)
        Record name in the scene (``<record>.<floor>``, safe in case ids) -> the record and the floor as the
        motions name them.
    """

    group: Group
    scene: Any
    blocks: dict[str, str]
    records: dict[str, tuple[str, str]]


def block_name(item_id: str, direction: str) -> str:
    """The campaign's block label of an item in a direction: ``<item>-d<direction>``."""
    return f"{item_id}-d{direction}"


#: IDA levels (PFA / (g tan alpha), per item): 16 from 1.1 to 9, where the pilot on the FEMA P695
#: far-field set had 4 % of the no-slip cases overturned at 1.2 and 99 % at 7.4, on every floor.
DEFAULT_LEVELS: tuple[float, ...] = tuple(float(x) for x in np.geomspace(1.1, 9.0, 16))


def item_block_spec(item: Item, direction: str, name: str, seed: int = 0, solver: str | None = None) -> Any:
    """The campaign entry (:class:`~opsrock.campaign.scene.BlockSpec`) of ``item``: the one place an item
    becomes a block spec, planar or a box in plan as the solver declares (registry ``plan``, ``restitution``).

    Parameters
    ----------
    item : Item
        The inventory row (SI: m, kg).
    direction : str
        ``"1"``: the block's base is the item's ``width``; ``"2"``: its ``depth`` (m). A box in plan takes
        ``"1"`` (its width along direction 1 at azimuth 0, its ``depth`` across).
    name : str
        The entry's name (first part of its case ids; letters, digits, ``_ . -``).
    seed : int
        Seed of friction drawn per case (with each case id), within ``LIMITS["seed"]``.
    solver : str or None
        The solver the entry is for (None: a planar one that takes any restitution). One that models Housner's
        impact only gives the entry its declared restitution (``e_R``) and refuses an item that gives its own
        ``restitution``; one in plan gives it the item's ``depth``.

    Returns
    -------
    BlockSpec
        The planar block of :meth:`~opsrock.inventory.items.Item.planar_block` (base, height, mass, the item's
        own restitution ``e`` if given, else the project's ``0.95 e_R``), its friction fixed or drawn per case
        from ``seed`` and the case id (``friction_distribution``), its mass distribution where given.
    """
    from opsrock.campaign.scene import BlockSpec
    from opsrock.solvers.registry import METHODS

    entry = METHODS[solver] if solver is not None else None
    factor = entry.default_restitution_factor if entry is not None else None
    if factor is not None and item.restitution is not None:
        raise InputError(f"item {item.id!r} gives restitution = {item.restitution!r}; solver {solver!r} reproduces "
                         "Housner's impact only (e = e_R): leave its restitution blank", argument="inventory")
    block = item.planar_block(direction, *(() if factor is None else (factor,)))
    law = item.friction
    extra: dict[str, Any] = {k: v for k, v in item.mass_distribution().items()
                             if v is not None}  # only when given (or a cylinder's): a homogeneous entry as ever
    if law is not None and not law.fixed:
        extra["friction_distribution"] = FrictionDistribution(law, seed)
    reason = f"{item.description} (inventory item {item.id}, direction {direction})"
    if entry is not None and entry.plan and "depth" in entry.block_needs:
        extra["depth"] = item.depth
        reason = f"{item.description} (inventory item {item.id}, in three dimensions)"
    return BlockSpec(name=name, width=block.width, height=block.height, reason=reason, mass=block.mass,
                     restitution_factor=block.restitution_factor, restitution=block.restitution,
                     friction=block.friction, friction_kinetic=block.friction_kinetic if law is not None else None,
                     **extra)


def groups_of(items: tuple[Item, ...], motions: MotionSet, solver: str,
              friction_solver: str) -> dict[Group, list[Item]]:
    """The groups of the study and their items, in inventory order: each item on its floors (all the
    motions' floors when it names none), in each direction of the motions."""
    floors = motions.floors
    out: dict[Group, list[Item]] = {}
    for item in items:
        bad = [f for f in item.floors if f not in floors]
        if bad:
            raise InputError(f"item {item.id!r} stands on floors {bad!r} that the motions do not have "
                             f"(they have {', '.join(floors)})", argument="inventory")
        own = tuple(f for f in floors if f in item.floors) if item.floors else floors
        for direction in motions.directions:
            g = Group(own, own == floors, direction, item.support,
                      friction_solver if item.friction is not None else solver)
            out.setdefault(g, []).append(item)
    names = [g.name for g in out]
    if len(set(names)) != len(names):
        raise InputError(f"two floors of the motions give the same folder name: {sorted(names)!r}; rename one",
                         argument="motions")
    return out


def group_scenes(groups: dict[Group, list[Item]], motions: MotionSet, intensity: Any,
                 seed: int = 0) -> list[GroupScene]:
    """One record scene per group (see the module docstring).

    Parameters
    ----------
    groups : dict
        :func:`groups_of`.
    motions : MotionSet
        The floor motions (m/s²).
    intensity : Intensity
        The intensity axis (:class:`opsrock.campaign.records.Intensity`): IDA levels or a cloud.
    seed : int
        Seed of friction drawn per case.
    """
    from opsrock.campaign.records import Floor, RecordSet
    from opsrock.campaign.scene import Scene
    from opsrock.excitations.building import ShearBuilding
    from opsrock.excitations.records import check_sampling

    names = _motion_names(motions)
    out = []
    for g, items in groups.items():
        grounds = tuple(m.motion.with_name(names[(m.record, m.floor)]) for m in motions.motions
                        if m.floor in g.floors and m.direction == g.direction)
        floor = Floor(None, 0) if g.support is None else Floor(
            ShearBuilding(SUPPORT_NAME, g.support.period, 1, g.support.damping), 1)
        records = RecordSet(grounds=grounds, floors=(floor,), source=motions.source, intensity=intensity)
        blocks = tuple(item_block_spec(it, g.direction, block_name(it.id, g.direction), seed, g.solver) for it in items)
        for b in blocks:
            for rec in grounds:
                try:
                    check_sampling(rec, b.block)
                except ValueError as exc:
                    raise InputError(str(exc), argument="motions") from None
        scene = Scene(name=f"inventory-{g.name}", path="", blocks=blocks, grid=None, solver=g.solver, records=records)
        out.append(GroupScene(g, scene, {b.name: it.id for b, it in zip(blocks, items)},
                              {v: k for k, v in names.items()}))
    return out


def _motion_names(motions: MotionSet) -> dict[tuple[str, str], str]:
    """``(record, floor)`` -> ``<record>.<floor>``, usable in case ids (:func:`opsrock.excitations.records.safe_name`)."""
    from opsrock.excitations.records import safe_name

    names = {(m.record, m.floor): f"{safe_name(m.record)}.{safe_name(m.floor)}" for m in motions.motions}
    if len(set(names.values())) != len(names):
        raise InputError("two (record, floor) pairs of the motions give the same name in case ids "
                         "(<record>.<floor>, characters outside A-Z a-z 0-9 _ . - replaced): rename one",
                         argument="motions")
    return names


class _Measures:
    """Task state of :func:`floor_demands`: task ``(lo, hi)`` measures motions ``lo`` to ``hi - 1``."""

    def __init__(self, records: list) -> None:
        self.records = records

    def run(self, lo: int, hi: int) -> list:
        from opsrock.intensity.records import motion_measures

        return [dataclasses.asdict(motion_measures(r)) for r in self.records[lo:hi]]


def floor_demands(motions: MotionSet, workers: int | None = 1) -> pd.DataFrame:
    """Every motion's demands, computed once: one row per (record, floor, direction) with the fields of
    :class:`opsrock.intensity.records.MotionMeasures` (``pfa`` m/s², ``pfv`` m/s, ``pfd`` m, ``mean_period``
    and ``predominant_period`` s), in ``workers`` processes (about 0.1-0.3 s a motion: the spectrum of the
    predominant period)."""
    from opsrock._pool import TaskPool

    n = len(motions.motions)
    workers = max(1, workers or 1)
    size = max(1, math.ceil(n / (4 * workers)))
    tasks = [(lo, min(n, lo + size)) for lo in range(0, n, size)]
    state = _Measures([m.motion for m in motions.motions])
    with TaskPool(state, tasks, workers if n >= 8 else 1) as pool:
        measured = [row for chunk in pool.results() for row in chunk]
    return pd.DataFrame([{"record": m.record, "floor": m.floor, "direction": m.direction, **meas}
                         for m, meas in zip(motions.motions, measured)])


#: The motions' demands, cached in the store (keyed by the motions' digest): a resumed study does not measure
#: them again.
DEMANDS_FILE: str = "floor_demands.pickle"


def motions_digest(motions: MotionSet) -> str:
    """A digest of every motion: record, floor, direction, time step and samples."""
    import hashlib

    h = hashlib.sha256()
    for m in motions.motions:
        h.update(f"{m.record}|{m.floor}|{m.direction}|{m.motion.dt!r}|".encode())
        h.update(np.ascontiguousarray(m.motion.values).tobytes())
    return h.hexdigest()


def cached_demands(motions: MotionSet, store: Path, workers: int | None = 1) -> pd.DataFrame:
    """:func:`floor_demands`, read from ``store``'s cache (:data:`DEMANDS_FILE`) when it was written for these
    motions, else computed and cached (atomically)."""
    from opsrock._files import atomic_write

    digest, cache = motions_digest(motions), store / DEMANDS_FILE
    try:
        with open(cache, "rb") as fh:
            saved = pickle.load(fh)
        if saved.get("digest") == digest:
            return saved["table"]
    except (OSError, EOFError, pickle.UnpicklingError, AttributeError, KeyError, TypeError, ValueError):
        pass
    table = floor_demands(motions, workers)
    store.mkdir(parents=True, exist_ok=True)
    atomic_write(cache, lambda fh: pickle.dump({"digest": digest, "table": table}, fh), binary=True)
    return table


def seed_motions(gs: GroupScene, folder: Path, demands: pd.DataFrame) -> bool:
    """Give an unfiltered group's campaign the floor motions and their measures (:func:`floor_demands`)
    through its floor-motion cache (:data:`opsrock.campaign.motions.MOTIONS_FILE`), so that it computes
    none; a group on a support computes its filtered motions itself, and a group in both directions at once (a
    box in plan, direction ``"12"``) its motion pairs. Returns whether it seeded."""
    from opsrock._files import atomic_write
    from opsrock.campaign.motions import MOTIONS_FILE
    from opsrock.intensity.records import MotionMeasures

    if gs.group.support is not None or gs.group.direction not in DIRECTIONS or (folder / MOTIONS_FILE).exists():
        return False
    d = demands[demands["direction"] == gs.group.direction].set_index(["record", "floor"])
    keys = [f.name for f in dataclasses.fields(MotionMeasures)]
    results = []
    for ground, _building, _floors in gs.scene.records.motion_items():
        row = d.loc[gs.records[ground.name]]
        results.append([(np.asarray(ground.values), MotionMeasures(**{k: float(row[k]) for k in keys}))])
    folder.mkdir(parents=True, exist_ok=True)
    atomic_write(folder / MOTIONS_FILE, lambda fh: pickle.dump({"digest": gs.scene.digest(), "results": results}, fh),
                 binary=True)
    return True


@contextmanager
def study_pool(scenes: list, workers: int | None, case_timeout: float | None = None) -> Iterator[tuple[Any, float]]:
    """One pool of worker processes for all of a study's campaigns: ``(pool, budget)``.

    Every solver the ``scenes`` (:class:`~opsrock.campaign.scene.Scene`) use is compiled here once (announced
    when the cache is cold) and loaded by each worker before it takes a case, so that no case's budget pays for a
    compile; ``budget`` is the case budget (s) of ``case_timeout`` (:func:`opsrock.campaign.run.case_budget`; None:
    the scenes' default), the pool's hard limit per case too. The study's one campaign runner (:func:`run_campaigns`) runs every
    configuration's campaigns on it.

    Parameters
    ----------
    scenes : list of Scene
        The campaigns' scenes.
    workers : int or None
        Processes (None: every core).
    case_timeout : float or None
        Wall-clock budget of one case (s).
    """
    from opsrock.campaign.executors import LocalPool
    from opsrock.campaign.run import case_budget
    from opsrock.solvers import warm_up

    solvers = tuple(sorted({scene.solver for scene in scenes}))
    for solver in solvers:
        warm_up(solver)
    budget = case_budget(scenes[0], case_timeout) if scenes else None
    with LocalPool(workers, warm=solvers, item_timeout=budget) as pool:
        yield pool, budget


@dataclass(frozen=True)
class CampaignJob:
    """One campaign of a study as the study's one runner (:func:`run_campaigns`) takes it, whatever configuration
    built it (the inventory's groups, FEMA P-58's variants, the directionality study's record pairs).

    Parameters
    ----------
    name : str
        Its folder in the store.
    scene : Scene
        Its scene (:class:`~opsrock.campaign.scene.Scene`).
    read : callable
        ``read(cases_csv) -> DataFrame``: the study's rows of its ``cases.csv`` (path, str).
    cases : list or None
        The scene's cases when the configuration built them (their floor motions computed already); None: the
        engine builds them from the scene.
    seed : callable or None
        ``seed(folder) -> bool``: give the campaign its floor motions before it runs, so it computes none
        (returns whether it did); None: it computes its own.
    """

    name: str
    scene: Any
    read: Callable[[str], pd.DataFrame]
    cases: list | None = None
    seed: Callable[[Path], bool] | None = None


@dataclass(frozen=True)
class StudyOptions:
    """How a contents study runs (:func:`opsrock.run_study`, :func:`opsrock.inventory.run.run_design`), its
    campaigns included (:func:`run_campaigns`), whatever it computes.

    Parameters
    ----------
    workers : int or None
        Processes (None: every core).
    progress : bool
        Progress on stderr.
    force : bool
        Delete stored results of other settings in the campaigns' folders instead of refusing them.
    store_dir : str, Path or None
        Where the campaigns keep their stores (None: the study's ``out_dir/campaigns``).
    case_timeout : float or None
        Wall-clock budget of one case (s); None: the campaigns' default (300 s). Cases stored as timed out are
        computed again (:func:`run_campaigns`).
    """

    workers: int | None = None
    progress: bool = True
    force: bool = False
    store_dir: str | Path | None = None
    case_timeout: float | None = None


@dataclass(frozen=True)
class CampaignRun:
    """What one campaign of :func:`run_campaigns` did: its folder name, its cases, those computed now, those stored as
    timed out that were computed again, its wall time (s) and whether its floor motions were seeded."""

    name: str
    n_cases: int
    n_computed: int
    n_retried: int
    seconds: float
    seeded: bool


def run_campaigns(jobs: list[CampaignJob], store: Path,
                  how: StudyOptions) -> tuple[pd.DataFrame, tuple[CampaignRun, ...]]:
    """Run (or resume) every campaign of a study into ``store/<name>``, in order, on one pool of worker processes
    (:func:`study_pool`): the one campaign runner of every configuration of the study.

    A campaign in plan (registry ``plan``) lets the engine size its batches; a planar one sends :data:`BATCH`
    cases per batch. A case stored as failed on its case budget (reason ``"timeout..."``: a machine's load or a
    cold compile as much as the case) is computed again on a resume, within ``how.case_timeout`` (s; default the
    campaigns' :data:`opsrock.campaign.timeout.DEFAULT_CASE_TIMEOUT`); every other failure is a result and stays.

    Returns
    -------
    cases : DataFrame
        Every campaign's rows (each job's ``read``), joined in order.
    runs : tuple of CampaignRun
        What each campaign did.
    """
    from opsrock.campaign.run import Execution, Stage
    from opsrock.campaign.store import STORE_FILE, ResultStore
    from opsrock.solvers.registry import METHODS as SOLVERS

    frames, runs = [], []
    with study_pool([j.scene for j in jobs], how.workers, how.case_timeout) as (pool, budget):
        for job in jobs:
            t0, folder, retried = time.perf_counter(), store / job.name, 0
            if not how.force and (folder / STORE_FILE).is_file():
                with ResultStore(folder / STORE_FILE) as stored:
                    retried = stored.forget_timeouts()
            seeded = bool(job.seed(folder)) if job.seed is not None else False
            batch = None if SOLVERS[job.scene.solver].plan else BATCH
            execution = Execution(how.workers, pool, how.force, how.progress, batch, budget)
            summary, _ = Stage(execution)(job.scene, folder, cases=job.cases)
            frames.append(job.read(summary.cases_csv))
            runs.append(CampaignRun(job.name, summary.n_cases, summary.n_computed, retried,
                                    time.perf_counter() - t0, seeded))
    return pd.concat(frames, ignore_index=True), tuple(runs)


def group_jobs(scenes: list[GroupScene], demands: pd.DataFrame) -> list[CampaignJob]:
    """The inventory study's campaigns as :class:`CampaignJob`: each group's into its folder
    (:attr:`Group.name`), an unfiltered group's seeded with the motions' measures (:func:`seed_motions`)."""
    return [CampaignJob(gs.group.name, gs.scene, functools.partial(_read_cases, gs=gs),
                        seed=functools.partial(_seed, gs, demands)) for gs in scenes]


def _seed(gs: GroupScene, demands: pd.DataFrame, folder: Path) -> bool:
    return seed_motions(gs, folder, demands)


def _read_cases(path: str, gs: GroupScene) -> pd.DataFrame:
    from opsrock.campaign.cases import read_cases

    extra = [c for c in OPTIONAL_CASE_COLUMNS if c in gs.scene.columns]  # as the scene's solver declares
    df = read_cases(path, usecols=list(CASE_COLUMNS) + extra)
    if "slide_max" not in extra:
        df["slide_max"] = math.nan
    df["item"] = df["block"].map(gs.blocks)
    source = df["record"].map(gs.records)
    df["record"], df["floor"] = [r for r, _ in source], [f for _, f in source]
    df["direction"], df["group"] = gs.group.direction, gs.group.name
    return df


__all__ = ["BATCH", "CASE_COLUMNS", "CampaignJob", "CampaignRun", "DEFAULT_LEVELS", "DEMANDS_FILE", "Group",
           "GroupScene", "OPTIONAL_CASE_COLUMNS", "SUPPORT_NAME", "StudyOptions", "block_name", "cached_demands",
           "floor_demands", "group_jobs", "group_scenes", "groups_of", "item_block_spec", "motions_digest",
           "run_campaigns", "seed_motions", "study_pool"]
