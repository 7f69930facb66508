"""The directionality study: contents under both horizontal floor components, in three dimensions, beside the
planar analysis along the weaker axis and pelicun's non-directional factor 1.2 (``opsrock contents --model both``, alias ``opsrock directionality``).

What it computes (docs/guide/directionality.md):

* the items: FEMA P-58's nine unanchored items (:func:`opsrock.inventory.items.shipped_inventory`
  ``"fema-p58-nine"``) and the example office inventory (``"example"``), each a box of base ``width x depth``
  (:attr:`opsrock.block.Block.depth`) with the item's mass distribution and friction (a friction drawn from a
  distribution at its median), Housner's restitution (``rigid3d`` models Housner's impact only, so the planar
  runs use it too); an item on a support (a desk) meets the floor motion through the support's oscillator in
  both directions;
* the motions: the FEMA P695 far-field records through the shipped shear building
  (:func:`opsrock.inventory.sources.building_motions`), each recording's two components filtered as two
  directions of one floor motion (:func:`opsrock.inventory.motions.paired_motions`), named by the first
  component's record name;
* the cases: each item on each floor under each record pair at each plan orientation ``azimuth`` (deg, from
  motion direction 1 to the item's width axis) and each IDA level, solved in three dimensions (``rigid3d``,
  both components) and in the plane of the weaker axis (``housner_fast``, or ``friction`` for an item with
  friction) under the component along that axis; the scale factor of a record pair is the same for both
  components and for both models: ``level x g min(tan alpha, mu) / max(PFA_1, PFA_2)`` of the weaker axis;
* the campaigns: one per (model, solver), run by the campaign engine (:class:`opsrock.campaign.run.Stage`:
  resumable, parallel, with progress) into ``store/<campaign>``;
* the tables (:mod:`opsrock.inventory.directionality.summary`) and the report and figures
  (:mod:`opsrock.inventory.directionality.report`), which compute nothing.

``solver3d`` is the study's three-dimensional solver (``rigid3d``); a planar solver named there runs the
three-dimensional cases in the plane of the weaker axis instead (the plumbing of the study, for its tests).
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

import numpy as np
import pandas as pd

from opsrock.inventory.directionality import summary
from opsrock.inventory.directionality.cases import study_campaigns, study_motions
from opsrock.inventory.directionality.columns import write_directionality_table
from opsrock.inventory.directionality.report import write_figures, write_report
from opsrock.campaign.cases import read_cases
from opsrock.errors import InputError
from opsrock.inventory.items import shipped_inventory
from opsrock.inventory.outputs import Written
from opsrock.inventory.stages import Route
from opsrock.limits import int_at_least
from opsrock.solvers.registry import METHODS, plan_solver

#: The record pairs of the full study, by their first component's name (FEMA P695 far-field): twelve of the 22, of
#: 20 to 44 s, one or two per event, chosen to fit the cost budget of 15 minutes on 2 cores
#: (docs/guide/directionality.md).
DEFAULT_PAIRS: tuple[str, ...] = ("NORTHR_MUL009", "NORTHR_LOS000", "KOBE_NIS000", "KOBE_SHI000", "LANDERS_YER270",
                                  "CAPEMEND_RIO270", "SUPERST_B-POE270", "SFERN_PEL090", "KOCAELI_DZC180",
                                  "FRIULI_A-TMZ000", "LOMAP_G03000", "IMPVALL_H-E11140")

#: The items of the full study: empty, every item of the shipped inventories (:data:`INVENTORIES`): FEMA P-58's nine
#: and the example's four boxes (its low cabinet, server rack and printer with friction, its bookcase without; its
#: round item is left out, :func:`round_items`).
DEFAULT_ITEMS: tuple[str, ...] = ()

#: Plan orientations of the full study (deg): 0 to 90 in steps of 22.5 (a box is symmetric about its axes).
DEFAULT_AZIMUTHS: tuple[float, ...] = (0.0, 22.5, 45.0, 67.5, 90.0)

#: IDA levels of ``max(PFA_1, PFA_2) / (g min(tan alpha, mu))`` of the weaker axis (dimensionless).
#: Four, from 1.1 to 4: in a pilot (two pairs, the roof) 17 % of the cases overturned at 1.2 and 92-100 % at 3.2.
DEFAULT_LEVELS: tuple[float, ...] = tuple(float(x) for x in np.geomspace(1.1, 4.0, 4))

#: The shipped inventories of the study.
INVENTORIES: tuple[str, ...] = ("fema-p58-nine", "example")

#: The models of a case: three dimensions, and the plane of the weaker axis.
MODELS: tuple[str, ...] = ("3d", "planar")

#: Files the study writes into its folder (besides ``figures/``), by table, each with a ``Units`` row after its
#: header (:mod:`opsrock.inventory.directionality.columns`).
TABLES: dict[str, str] = {k: f"{k}.csv" for k in ("directionality", "fits", "mechanisms", "cost", "demands", "map")}

#: Every output the study owns in its folder (globs relative to it; :func:`opsrock._files.staged_folder`).
OUTPUTS: tuple[str, ...] = ("report.md", "*.csv", "figures/*.png")


@dataclass(frozen=True)
class DirectionalityDesign:
    """What the study covers.

    Parameters
    ----------
    period : float
        First period ``T_1`` of the shipped linear shear building (s).
    storeys : int
        Its storeys.
    damping : float
        Its modal damping ratio (dimensionless).
    floors : tuple
        Floors: ``"ground"``, numbers 1..storeys and/or ``"roof"``.
    record_set : str
        Library record set (``fema-p695:far-field``).
    pairs : tuple of str
        The record pairs, by their first component's name (empty: every pair of the set).
    azimuths : tuple of float
        Plan orientations (deg, in [0, 90]: from motion direction 1 to the item's width axis).
    levels : tuple of float
        IDA levels of ``max(PFA_1, PFA_2) / (g min(tan alpha, mu))`` of the weaker axis (dimensionless).
    items : tuple of str
        Item ids of the shipped inventories (:data:`INVENTORIES`) (empty: all of them; default
        :data:`DEFAULT_ITEMS`).
    solver3d : str
        Solver of the three-dimensional cases (``rigid3d``; a planar solver: the plumbing only).
    tolerance : float
        Planar analysis suffices where the three-dimensional median lies within this fraction of the planar
        one (dimensionless).
    n_boot : int
        Record-bootstrap resamples of each fit.
    seed : int
        Seed of the resamples.
    settings3d : Mapping
        Settings of ``solver3d`` (its ``solve()`` keywords). Default ``{"tail": "peak", "record": False}``: a case
        ends once its verdict and peak tilt are final (the fragility needs no more), as the planar ``housner_fast``
        does, and keeps no time history (a campaign stores none: the stored rows are the same to the last bit, and a
        3-D case costs 2-6 % less, issue 43).
    """

    period: float = 1.0
    storeys: int = 8
    damping: float = 0.05
    floors: tuple = ("ground", "roof")
    record_set: str = "fema-p695:far-field"
    pairs: tuple[str, ...] = DEFAULT_PAIRS
    azimuths: tuple[float, ...] = DEFAULT_AZIMUTHS
    levels: tuple[float, ...] = DEFAULT_LEVELS
    items: tuple[str, ...] = DEFAULT_ITEMS
    solver3d: str = field(default_factory=plan_solver)
    tolerance: float = 0.10
    n_boot: int = 40
    seed: int = 0
    settings3d: Mapping[str, Any] = field(default_factory=lambda: {"tail": "peak", "record": False})

    def __post_init__(self) -> None:

        for name, low, high in (("azimuths", 0.0, 90.0), ("levels", 0.0, math.inf)):
            values = getattr(self, name)
            if not values or any(isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x)
                                 or not (low <= x <= high) or (name == "levels" and x <= 0) for x in values):
                raise InputError(f"{name} must be numbers in [{low:g}, {high:g}]" + (" (positive)" if name == "levels"
                                 else " deg") + f", got {values!r}", argument=name)
            if len(set(values)) != len(values):
                raise InputError(f"{name} name a value twice: {values!r}", argument=name)
            object.__setattr__(self, name, tuple(float(x) for x in values))
        if self.solver3d not in METHODS or (METHODS[self.solver3d].friction and not METHODS[self.solver3d].plan):
            raise InputError(f"solver3d must be {plan_solver()} or a no-slip planar solver, got {self.solver3d!r}",
                             argument="solver3d")
        if isinstance(self.tolerance, bool) or not isinstance(self.tolerance, (int, float)) or not 0 < self.tolerance < 1:
            raise InputError(f"tolerance must lie in (0, 1), got {self.tolerance!r}", argument="tolerance")
        int_at_least("n_boot", self.n_boot, 0)
        int_at_least("seed", self.seed, 0)
        object.__setattr__(self, "settings3d", dict(self.settings3d))

    @property
    def in_plan(self) -> bool:
        """Whether ``solver3d`` solves motion in plan (``rigid3d``); False: the plumbing stand-in."""

        return METHODS[self.solver3d].plan


#: Records of the quick study (``--quick``): two pairs.
QUICK_PAIRS: tuple[str, ...] = ("NORTHR_MUL009", "KOBE_NIS000")

#: Items of the quick study: FEMA's five-shelf bookcase and the example's bookcase loaded low (same base).
QUICK_ITEMS: tuple[str, ...] = ("E.20.22.105a", "bookcase")


def quick(design: DirectionalityDesign) -> DirectionalityDesign:
    """A small copy of ``design`` for tests and CI (under a minute): the roof, two record pairs, two
    orientations, three levels, two items (:data:`QUICK_ITEMS`), 10 resamples."""
    return dataclasses.replace(design, floors=("roof",), pairs=QUICK_PAIRS, azimuths=(0.0, 45.0),
                               levels=(1.3, 2.2, 3.6), items=QUICK_ITEMS, n_boot=min(design.n_boot, 10))


@dataclass(frozen=True)
class StudyItem:
    """One item of the study, its blocks and where it stands.

    Parameters
    ----------
    id : str
        The item's id.
    inventory : str
        The shipped inventory it comes from.
    description : str
        What it is.
    block3d : Block
        The box: ``width`` along its x axis, ``depth`` along y (m), Housner's restitution.
    planar : Block
        The planar block of the weaker axis (its base the smaller of width and depth, m).
    weak : str
        The weaker axis: ``"x"`` (the width) or ``"y"`` (the depth).
    support : Support or None
        The support the item stands on (:class:`opsrock.inventory.items.Support`); None: the floor.
    fema_id : str
        FEMA P-58's ID, or ``""``.
    """

    id: str
    inventory: str
    description: str
    block3d: Any
    planar: Any
    weak: str
    support: Any
    fema_id: str = ""

    @property
    def b_over_h(self) -> float:
        """Slenderness of the weaker axis, ``tan alpha = b / h_cm`` (dimensionless)."""
        return float(self.planar.tan_alpha)


def round_items() -> tuple[str, ...]:
    """The shipped inventories' items with a round base (``shape`` ``cylinder``), which the study leaves out: it
    turns a box in plan, and a cylinder has no orientation to turn (the contents study solves it in three
    dimensions with its own solver: ``opsrock contents --inventory FILE --motions FILE --model 3d``)."""
    return tuple(item.id for name in INVENTORIES for item in shipped_inventory(name).items if item.shape != "box")


def left_out(design: DirectionalityDesign) -> tuple[str, ...]:
    """The round items the study leaves out, for its report: every shipped one (:func:`round_items`) unless the
    design names its items (a named round item is refused, :func:`study_items`)."""
    return () if design.items else round_items()


def study_items(design: DirectionalityDesign) -> tuple[StudyItem, ...]:
    """The study's items from the shipped inventories (:data:`INVENTORIES`), in inventory order, boxes only
    (:func:`round_items`)."""
    rounds = set(round_items()) if design.items else set()
    named_round = [i for i in design.items if i in rounds]
    if named_round:
        raise InputError(f"items {named_round!r} have a round base: the directionality study turns boxes in plan, and a "
                         "cylinder has no orientation to turn; its 3-D fragility is the contents study's (opsrock "
                         "contents --inventory FILE --motions FILE --model 3d)", argument="items")
    out = []
    for name in INVENTORIES:
        for item in shipped_inventory(name).items:
            if (design.items and item.id not in design.items) or item.shape != "box":
                continue
            weak = "1" if item.width <= item.depth else "2"
            housner = {"restitution": None, "restitution_factor": 1.0}
            block = dataclasses.replace(item.planar_block("1", 1.0), depth=item.depth, **housner)
            planar = dataclasses.replace(item.planar_block(weak, 1.0), **housner)
            out.append(StudyItem(item.id, name, item.description, block, planar, "x" if weak == "1" else "y",
                                 item.support, item.fema_id))
    missing = [i for i in design.items if i not in {it.id for it in out}]
    if missing or len(set(design.items)) != len(design.items):
        bad = missing or [design.items]
        raise InputError(f"items {bad!r} are not (each once) among the shipped inventories' ({', '.join(INVENTORIES)})",
                         argument="items")
    return tuple(out)


def _motions(a: Any) -> Any:
    """The floor motions of every record pair in both directions (:func:`study_motions`)."""
    a.say(f"floor motions of {len(a.design.pairs) or 'every'} record pair(s) in both directions")
    return study_motions(a.design, a.scenes, a.options.workers)


def _jobs(a: Any) -> list:
    """Both models' campaigns (:func:`opsrock.inventory.directionality.cases.study_campaigns`), each with the cases
    it built, as the study's one runner takes them (:class:`opsrock.inventory.campaigns.CampaignJob`): their
    ``cases.csv`` with ``campaign`` and ``solver_name`` (the campaign's solver)."""
    from opsrock.inventory.campaigns import CampaignJob

    return [CampaignJob(c.name, c.scene, functools.partial(_read, campaign=c.name, solver=c.scene.solver),
                        cases=c.cases) for c in study_campaigns(a.design, a.scenes, a.demands)]


def _read(path: str, campaign: str, solver: str) -> pd.DataFrame:
    return read_cases(path).assign(campaign=campaign, solver_name=solver)


def _fit(a: Any) -> dict[str, pd.DataFrame]:
    """The fits of both models and the tables computed from them
    (:func:`opsrock.inventory.directionality.summary.study_tables`)."""
    fits = summary.fit_table(a.cases, a.design, a.options.workers or 1)
    return summary.study_tables(fits, a.cases, a.demands.demands, a.design, a.scenes)


def _write(a: Any, stage: Path) -> Written:
    """The tables (CSV, full precision, each with its units row), the figures and the report into the staging
    folder ``stage``; the 3-D over planar medians per item and floor (``directionality.csv``) among the tables."""
    t0 = time.perf_counter()
    paths = {k: write_directionality_table(df, stage / TABLES[k]) for k, df in a.tables.items()}
    figures = write_figures(a.tables, stage / "figures", a.design.tolerance)
    a.timings["outputs_s"] = time.perf_counter() - t0
    a.timings["total_s"] = time.perf_counter() - a.t_start
    head = summary.headline(a.tables, a.cases, {**a.timings, "motions_s": a.timings.get("demands_s", 0.0),
                                                "n_computed": a.n_computed})
    report = write_report(stage / "report.md", summary.report_inputs(a.design, a.tables, head, figures,
                                                                             left_out(a.design)))
    return Written(paths, report, {}, tuple(figures), head)


#: Both models side by side (:class:`opsrock.inventory.stages.Route`): the same items under the same record pairs,
#: in three dimensions (both components at once) and in the plane of the weaker axis, and the 3-D over planar
#: medians per item and floor.
BOTH: Route = Route("both", study_items, _fit, _write, OUTPUTS, demands=_motions, jobs=_jobs)


__all__ = ["BOTH", "DEFAULT_AZIMUTHS", "DEFAULT_ITEMS", "DEFAULT_LEVELS", "DEFAULT_PAIRS", "QUICK_ITEMS", "INVENTORIES",
           "MODELS", "OUTPUTS", "QUICK_PAIRS", "TABLES", "DirectionalityDesign", "StudyItem", "left_out", "quick", "round_items",
           "study_items"]
