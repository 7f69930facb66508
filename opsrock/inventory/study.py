"""The user's inventory on the user's floor motions: :class:`InventoryDesign` and the planar route :data:`PLANAR`
(``opsrock contents --inventory FILE --motions FILE --out DIR``; run by :func:`opsrock.inventory.run.run_design`).

Every item runs on the floors it stands on, in every direction of the motions (direction ``"1"``: its
``width`` along the motion; ``"2"``: its ``depth``), through its support's oscillator if it stands on one
(:mod:`opsrock.inventory.campaigns`): by IDA (``method="ida"``: each motion scaled to the levels of
``PFA / (g tan alpha)`` of the item) or as recorded (``method="cloud"``: one case per motion, fitted as a
cloud). Each item's fragility per floor and direction, overturning and (where friction is modelled)
sliding beyond ``slide_distance``, in the floor's PFV and PFA (:mod:`opsrock.inventory.fits`); the expected
number overturned under the motions as recorded; and a pelicun folder (:mod:`opsrock.inventory.pelicun`).

Outputs (in ``out_dir``, written together through a staging folder: a failed or interrupted run changes
nothing): ``fits.csv`` (:data:`opsrock.inventory.fits.FIT_COLUMNS`), ``demands.csv`` (each motion's
:class:`~opsrock.intensity.records.MotionMeasures`, pfa m/s², pfv m/s, pfd m, periods s), ``expected.csv``,
``pelicun/`` and ``report.md``. The campaigns keep their stores in ``out_dir/campaigns/<group>`` (or
``store_dir``): a second run computes only what is missing.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from opsrock.inventory.campaigns import DEFAULT_LEVELS
from opsrock.errors import InputError
from opsrock.inventory.items import Inventory
from opsrock.inventory.motions import MotionSet
from opsrock.inventory.outputs import OUTPUTS, TABLES, InventoryStudy, study_tables, write_outputs
from opsrock.inventory.stages import Route
from opsrock.inventory.three_d import DEFAULT_AZIMUTHS, check_azimuths
from opsrock.solvers.registry import planar_solver

#: Intensity methods: IDA on the given motions, or the motions as given (a cloud).
METHODS: tuple[str, ...] = ("ida", "cloud")

#: Default PFV levels (m/s) and PFA levels (g) at which the report tabulates P(overturning).
DEFAULT_DEMAND_LEVELS_PFV: tuple[float, ...] = (0.25, 0.5, 1.0)
DEFAULT_DEMAND_LEVELS_PFA: tuple[float, ...] = (0.25, 0.5, 1.0)

#: Sliding beyond this distance (m) is counted where friction is modelled.
DEFAULT_SLIDE_DISTANCE: float = 0.05



def _positive(name: str, values: tuple, what: str) -> tuple[float, ...]:
    if not values or any(isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x) or x <= 0
                         for x in values):
        raise InputError(f"{name} must be positive numbers ({what}), got {values!r}", argument=name)
    return tuple(float(x) for x in values)


@dataclass(frozen=True)
class InventoryDesign:
    """The study of one inventory on one set of floor motions.

    Parameters
    ----------
    inventory : Inventory
        The items (SI: m, kg).
    motions : MotionSet
        The floor motions (m/s²), per record, floor and direction.
    method : str
        ``"ida"``: each motion scaled to ``levels``; ``"cloud"``: the motions as given (one case each).
    levels : tuple of float
        IDA levels of ``PFA / (g min(tan alpha, mu))`` (dimensionless, per item: over the floor acceleration at
        which it first moves, slip or uplift; ``PFA / (g tan alpha)`` without friction); not used by a cloud.
    n_boot : int
        Record-bootstrap resamples of each fit (0: no intervals).
    seed : int
        Seed of the resamples (and of friction drawn per case).
    demand_levels_pfv : tuple of float
        PFV values (m/s) at which the report tabulates P(overturning).
    demand_levels_pfa : tuple of float
        PFA values (g) at which the report tabulates P(overturning).
    slide_distance : float
        Sliding beyond it (m) is an outcome where friction is modelled.
    solver : str
        Solver of the items without friction (no slip; default the registry's,
        :func:`~opsrock.solvers.registry.planar_solver`); a solver in plan (registry ``plan``): every item a box in
        three dimensions under both directions at once (:mod:`opsrock.inventory.three_d`).
    friction_solver : str
        Solver of the items with friction (a solver of the ``friction`` model; default the registry's,
        :func:`~opsrock.solvers.registry.planar_solver`).
    accept_implausible : bool
        Run a block larger than :data:`opsrock.limits.PLAUSIBLE` or a motion beyond its PFA bound anyway.
    azimuths : tuple of float
        With a solver in plan: the items' azimuths in plan (deg, from direction 1 to an item's width),
        pooled in each fit (:data:`opsrock.inventory.three_d.DEFAULT_AZIMUTHS`); unused by the planar route.
    side_by_side : bool
        Also every item a box in three dimensions (the registry's solver in plan, at ``azimuths``), and the two
        models' medians side by side (:mod:`opsrock.inventory.side_by_side`); ``solver`` stays the planar one.
    """

    inventory: Inventory
    motions: MotionSet = field(repr=False)
    method: str = "ida"
    levels: tuple[float, ...] = DEFAULT_LEVELS
    n_boot: int = 100
    seed: int = 0
    demand_levels_pfv: tuple[float, ...] = DEFAULT_DEMAND_LEVELS_PFV
    demand_levels_pfa: tuple[float, ...] = DEFAULT_DEMAND_LEVELS_PFA
    slide_distance: float = DEFAULT_SLIDE_DISTANCE
    solver: str = field(default_factory=lambda: planar_solver(False))
    friction_solver: str = field(default_factory=lambda: planar_solver(True))
    accept_implausible: bool = False
    azimuths: tuple[float, ...] = DEFAULT_AZIMUTHS
    side_by_side: bool = False

    def __post_init__(self) -> None:
        from opsrock.limits import int_at_least

        if self.method not in METHODS:
            raise InputError(f"method must be one of {', '.join(METHODS)}, got {self.method!r}", argument="method")
        object.__setattr__(self, "levels", _positive("levels", tuple(self.levels), "PFA / g min(tan alpha, mu)"))
        object.__setattr__(self, "demand_levels_pfv", _positive("demand_levels_pfv", tuple(self.demand_levels_pfv), "m/s"))
        object.__setattr__(self, "demand_levels_pfa", _positive("demand_levels_pfa", tuple(self.demand_levels_pfa), "g"))
        _positive("slide_distance", (self.slide_distance,), "m")
        int_at_least("n_boot", self.n_boot, 0)
        int_at_least("seed", self.seed, 0)
        object.__setattr__(self, "azimuths", check_azimuths(self.azimuths))
        self._check_solvers()
        self._check_inputs()

    def _check_solvers(self) -> None:
        from opsrock.solvers.registry import METHODS as SOLVERS

        for name, slips in (("solver", False), ("friction_solver", True)):
            value = getattr(self, name)
            info = SOLVERS.get(value) if isinstance(value, str) else None
            planar_slip = info is not None and info.friction and not info.plan  # the planar block whose base slips
            if info is None or planar_slip != slips:
                kind = "of the friction model" if slips else "without friction (no slip)"
                raise InputError(f"{name} must name a solver {kind}, got {value!r}", argument=name)
        if not isinstance(self.side_by_side, bool):
            raise InputError(f"side_by_side must be True or False, got {self.side_by_side!r}", argument="side_by_side")
        if self.side_by_side and SOLVERS[self.solver].plan:
            raise InputError(f"side_by_side runs solver {self.solver!r} as the planar model beside the solver in "
                             "plan: give a planar solver", argument="solver")

    def _check_inputs(self) -> None:
        from opsrock.limits import check_plausible

        if not self.inventory.items:
            raise InputError(f"the inventory {self.inventory.source} has no items", argument="inventory")
        ids = [it.id for it in self.inventory.items]
        if len(set(ids)) != len(ids):
            raise InputError(f"the inventory names an item twice: {sorted(i for i in set(ids) if ids.count(i) > 1)!r}",
                             argument="inventory")
        if not self.motions.motions:
            raise InputError(f"the motions {self.motions.source} hold no motion", argument="motions")
        option = "accept_implausible=True"
        for it in self.inventory.items:
            for dim in ("width", "depth", "height"):
                check_plausible("block_size", getattr(it, dim), what=f"item {it.id}: {dim}", option=option,
                                confirm=self.accept_implausible)
        for m in self.motions.motions:
            check_plausible("pfa", float(np.max(np.abs(m.motion.values))), what=f"motion {m.record} floor {m.floor} "
                            f"direction {m.direction}: PFA", option=option, confirm=self.accept_implausible)

    @property
    def intensity(self) -> Any:
        """The campaigns' intensity axis (:class:`opsrock.campaign.records.Intensity`)."""
        from opsrock.campaign.records import Intensity

        if self.method == "cloud":
            return Intensity("cloud", "", (1.0,))
        return Intensity("ida", "pfa_onset", self.levels)


def quick(design: InventoryDesign) -> InventoryDesign:
    """A small copy of ``design`` for checks: eight IDA levels (1.1 to 9), at most 20 resamples."""
    return dataclasses.replace(design, n_boot=min(design.n_boot, 20),
                               levels=tuple(float(x) for x in np.geomspace(1.1, 9.0, 8)))


def inventory_design(inventory: str | Path | None, motions: str | Path | None, source: Any, settings: dict[str, Any],
                     *, quick_run: bool = False, workers: int | None = None) -> InventoryDesign:
    """The design of ``opsrock contents --inventory FILE --motions FILE``, every input read and checked.

    Parameters
    ----------
    inventory : str, Path or None
        An inventory file (:func:`opsrock.inventory.items.read_inventory`); None: FEMA P-58's nine
        (:func:`opsrock.inventory.items.shipped_inventory`).
    motions : str, Path or None
        A motions manifest (:func:`opsrock.inventory.motions.read_motions`); None: the shipped shear building's
        floor motions (:func:`opsrock.inventory.sources.building_motions` of ``source``).
    source : BuildingSource
        The building, floors and records when ``motions`` is None (:class:`opsrock.inventory.sources.BuildingSource`).
    settings : dict
        The other fields of :class:`InventoryDesign` (``method``, ``levels``, ``n_boot``, ...).
    quick_run : bool
        :func:`quick`; on the building's motions also the quick records of the contents study (unless named).
    workers : int or None
        Processes of the building analyses.
    """
    from opsrock.inventory.items import read_inventory, shipped_inventory
    from opsrock.inventory.motions import read_motions
    from opsrock.inventory.sources import QUICK_RECORDS, building_motions

    confirm = bool(settings.get("accept_implausible", False))
    inv = shipped_inventory("fema-p58-nine") if inventory is None else read_inventory(inventory, confirm=confirm)
    if motions is not None:
        ms = read_motions(motions, confirm=confirm)
    else:
        if quick_run and not source.names:
            source = dataclasses.replace(source, names=QUICK_RECORDS)
        ms = building_motions(source, workers)
    design = InventoryDesign(inv, ms, **settings)
    return quick(design) if quick_run else design


def _planar_scenes(design: InventoryDesign) -> list:
    """One campaign per group of items on the same floors, direction, support and solver."""
    from opsrock.inventory.campaigns import group_scenes, groups_of

    groups = groups_of(design.inventory.items, design.motions, design.solver, design.friction_solver)
    return group_scenes(groups, design.motions, design.intensity, design.seed)


#: The planar route: each item along each direction of the motions, its own campaign per group.
PLANAR: Route = Route("planar", _planar_scenes, lambda a: study_tables(a, a.cases), write_outputs, OUTPUTS)

__all__ = ["DEFAULT_DEMAND_LEVELS_PFA", "DEFAULT_DEMAND_LEVELS_PFV", "DEFAULT_SLIDE_DISTANCE", "METHODS", "OUTPUTS",
           "PLANAR", "TABLES", "InventoryDesign", "InventoryStudy", "inventory_design", "quick"]
