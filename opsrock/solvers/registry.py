"""The solver registry: every solver by name, with what it models declared (as OpenQuake's ground-motion
models declare their inputs), and the checks that read those declarations.

A solver package is imported when first used (OpenSeesPy and numba are costly to import), so an entry
names its module and settings class instead of holding them.
"""

from __future__ import annotations

import dataclasses
import importlib
from dataclasses import dataclass
from typing import Any

from opsrock.block import Block
from opsrock.errors import InputError, ModelNotSupported
from opsrock.limits import one_of

#: The models a solver may solve (:attr:`SolverInfo.model`).
MODELS: tuple[str, ...] = ("rigid", "sdof", "friction", "rigid3d", "cylinder3d")

#: The models by meaning, for the code that chooses a solver by what it models (never by its name): the rigid
#: body (Eq. 1-3), the paper's equivalent SDOF model with its spring and damper (Eq. 5-8), the planar rigid block
#: on a base that slips, the box in plan, the cylinder in plan.
RIGID_MODEL, SDOF_MODEL, FRICTION_MODEL, BOX3D_MODEL, CYLINDER3D_MODEL = MODELS

#: The bases a solver models (:attr:`SolverInfo.base`): a rectangular ``box`` (corners) or a ``round`` one (a rim).
BASES: tuple[str, ...] = ("box", "round")

#: Groups of result columns a solver may write beyond every solver's (:attr:`SolverInfo.result_columns`):
#: ``contact`` (the base's friction and what it did, :data:`opsrock.campaign.cases.CONTACT_COLUMNS`) and
#: ``plan`` (a box in plan, :data:`opsrock.campaign.cases.PLAN_COLUMNS`).
RESULT_COLUMN_GROUPS: tuple[str, ...] = ("contact", "plan")

#: What a solver may need of each block of a scene (:attr:`SolverInfo.block_needs`): ``depth`` (m).
BLOCK_NEEDS: tuple[str, ...] = ("depth",)

#: What a solver takes as excitation (:attr:`SolverInfo.excitations`): any :class:`Excitation`, or the
#: analytic pulses of ``PULSE_SHAPES`` and records only (the compiled kernels).
EXCITATION_KINDS: tuple[str, ...] = ("any", "pulses_records")


@dataclass(frozen=True)
class SolverInfo:
    """One entry of the registry: where the solver lives and what it models.

    Parameters
    ----------
    name : str
        The solver's name (``--solver``, ``[solver] name``).
    module : str
        Package whose ``solve`` runs it.
    settings : str
        ``"module:Class"`` of its frozen settings dataclass.
    model : str
        What it solves, one of :data:`MODELS`: ``"rigid"`` (the rigid-body equation, Eq. 1-3),
        ``"sdof"`` (the paper's equivalent SDOF model, Eq. 5-8) or ``"friction"`` (the rigid block with
        Coulomb friction under horizontal and vertical floor motion, docs/guide/friction.md) or ``"rigid3d"`` (the
        rigid box on four base corners with isotropic Coulomb friction under two horizontal components and
        a vertical one, docs/guide/three-dimensions.md) or ``"cylinder3d"`` (the rigid cylinder on its circular base,
        the same floor and friction, :mod:`opsrock.solvers.cylinder3d`).
    friction : bool
        Models a base that slips (``Block.friction``); False: a block with friction is refused.
    vertical : bool
        Models vertical floor motion; False: an excitation with a vertical component is refused.
    free_rocking : bool
        Takes ``excitation=None`` (a still floor) with a start state ``theta0``, ``theta_dot0``.
    end_time_under_motion : bool
        Takes the setting ``end_time`` (a hard end of the run, s) under a floor motion; False: only with
        ``excitation=None``, as the span of free rocking (a campaign, whose cases all move the floor, refuses it).
    histories : bool
        Returns time histories (``time``, ``theta``, ``theta_dot``) when ``record`` is True.
    mass_distribution : bool
        Models a block whose mass is not distributed as a homogeneous block's (``Block.cm_height``,
        ``Block.radius_of_gyration``: its ``R``, ``alpha``, ``p``, ``I_O`` and ``e_R`` from them); False: such a
        block is refused.
    flat_landing : bool
        Models an impact that leaves no rotation (``e = 0``: a block with ``e_R <= 0``, :attr:`Block.lands_flat`,
        which lands flat); False: such a block is refused (the SDOF model's damper keeps ``e²`` of the energy per
        passage through its band, and no finite damper keeps none).
    restitution : bool
        Takes any restitution of the block (``restitution``, ``restitution_factor``, so the campaign's
        restitution laws and distributions); False: Housner's ``e_H`` only (the restitution it models: a block
        built for it takes ``restitution_factor = 1``, :attr:`default_restitution_factor`).
    excitations : str
        What it takes as excitation, one of :data:`EXCITATION_KINDS`.
    plan : bool
        Models motion in plan: takes a :class:`~opsrock.excitations.plan.PlanMotion` with a second horizontal
        component or a block turned in plan (``azimuth``), and a block's ``depth``; False: planar motion along
        the block's width only (a :class:`PlanMotion` that is not planar is refused).
    result_columns : tuple of str
        The groups of :data:`RESULT_COLUMN_GROUPS` its cases write beyond every solver's columns (a campaign's
        ``cases.csv`` has them).
    block_needs : tuple of str
        What it needs of each block of a scene, among :data:`BLOCK_NEEDS` (a block without it is refused).
    compiled : bool
        Runs a numba kernel (compiled once and cached on first use).
    needs_opensees : bool
        Needs OpenSeesPy (and its system BLAS), loaded when first used.
    base : str
        The block's base it models, one of :data:`BASES`: ``"box"`` (a rectangle, rocking on its edges and
        corners) or ``"round"`` (a circle, rocking on its rim: an item whose ``shape`` is a cylinder).
    """

    name: str
    module: str
    settings: str
    model: str
    friction: bool = False
    vertical: bool = False
    free_rocking: bool = True
    end_time_under_motion: bool = True
    histories: bool = True
    mass_distribution: bool = False
    flat_landing: bool = True
    restitution: bool = True
    excitations: str = "any"
    plan: bool = False
    result_columns: tuple[str, ...] = ()
    block_needs: tuple[str, ...] = ()
    compiled: bool = False
    needs_opensees: bool = False
    base: str = "box"

    def __post_init__(self) -> None:
        one_of("model", self.model, MODELS)
        one_of("base", self.base, BASES)
        one_of("excitations", self.excitations, EXCITATION_KINDS)
        for group in self.result_columns:
            one_of("result_columns", group, RESULT_COLUMN_GROUPS)
        for need in self.block_needs:
            one_of("block_needs", need, BLOCK_NEEDS)

    @property
    def default_restitution_factor(self) -> float | None:
        """The ``restitution_factor`` a block built for this solver takes when none is given (dimensionless):
        1 (Housner's ``e_R``) for a solver that models no other restitution; None: the block's own default."""
        return None if self.restitution else 1.0

    def load(self):
        """The solver package."""
        return importlib.import_module(self.module)

    def settings_class(self) -> type:
        """The solver's settings dataclass."""
        module, _, attr = self.settings.partition(":")
        return getattr(importlib.import_module(module), attr)

    def capabilities(self) -> dict[str, Any]:
        """The declarations (every field but where the solver lives), by name."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)
                if f.name not in ("name", "module", "settings")}


def _entry(name: str, settings: str, model: str, **declared: Any) -> SolverInfo:
    return SolverInfo(name, f"opsrock.solvers.{name}", f"opsrock.solvers.{name}.settings:{settings}", model, **declared)


#: The registry: every solver by name (as scipy's ``solve_ivp`` keeps its ``METHODS``).
METHODS: dict[str, SolverInfo] = {
    "opensees": _entry("opensees", "OpenSeesSettings", "sdof", needs_opensees=True, mass_distribution=True,
                       flat_landing=False),
    "sdof": _entry("sdof", "SDOFSettings", "sdof", mass_distribution=True, flat_landing=False),
    "housner": _entry("housner", "HousnerSettings", "rigid", mass_distribution=True),
    "housner_fast": _entry("housner_fast", "HousnerFastSettings", "rigid", excitations="pulses_records",
                           compiled=True, end_time_under_motion=False, mass_distribution=True),
    "friction": _entry("friction", "FrictionSettings", "friction", friction=True, vertical=True, mass_distribution=True,
                       excitations="pulses_records", compiled=True, end_time_under_motion=False,
                       result_columns=("contact",)),
    "moreau_jean": _entry("moreau_jean", "MoreauJeanSettings", "friction", friction=True, vertical=True,
                          restitution=False, mass_distribution=True, excitations="pulses_records", compiled=True,
                          end_time_under_motion=False, result_columns=("contact",)),
    "rigid3d": _entry("rigid3d", "Rigid3DSettings", "rigid3d", friction=True, vertical=True, restitution=False,
                      mass_distribution=True, excitations="pulses_records", plan=True, compiled=True,
                      end_time_under_motion=False, result_columns=("contact", "plan"), block_needs=("depth",)),
    "cylinder3d": _entry("cylinder3d", "Cylinder3DSettings", "cylinder3d", friction=True, vertical=True,
                         restitution=False, mass_distribution=True, excitations="pulses_records", plan=True,
                         compiled=True, end_time_under_motion=False, result_columns=("contact", "plan"),
                         base="round"),
}

#: Solver names accepted by :func:`opsrock.solvers.simulate` and the command line.
SOLVERS: tuple[str, ...] = tuple(METHODS)


def info(name: str) -> SolverInfo:
    """The registry entry of the solver ``name`` (one of :data:`SOLVERS`)."""
    return METHODS[one_of("solver", name, SOLVERS)]


def capabilities(name: str) -> dict[str, Any]:
    """What the solver ``name`` models and needs (:class:`SolverInfo`'s declarations)."""
    return info(name).capabilities()


def solver_names(**declared: Any) -> tuple[str, ...]:
    """The registered solvers whose declarations match every ``declared`` one, in registry order
    (``solver_names(friction=True)``, ``solver_names(model="sdof", compiled=False)``).

    Raises
    ------
    InputError
        A declaration :class:`SolverInfo` does not have.
    """
    known = SolverInfo.__dataclass_fields__.keys() - {"name", "module", "settings"}
    unknown = sorted(set(declared) - known)
    if unknown:
        raise InputError(f"unknown solver capability {unknown[0]!r}; known: {', '.join(sorted(known))}")
    return tuple(n for n, e in METHODS.items() if all(getattr(e, k) == v for k, v in declared.items()))


def plan_solver() -> str:
    """The box solver in plan (the first that declares ``plan`` and a ``box`` base): the one a scene in three
    dimensions takes."""
    return solver_names(plan=True, base="box")[0]


def round_solver() -> str:
    """The solver in plan of a round base (the first that declares ``plan`` and a ``round`` base): the one an item
    whose ``shape`` is a cylinder takes in three dimensions."""
    return solver_names(plan=True, base="round")[0]


def reference_sdof_solver() -> str:
    """The paper's own solver of its SDOF model (the first of :data:`SDOF_MODEL` that needs OpenSeesPy): a scene's
    default and the expensive solver a multi-fidelity campaign runs by default."""
    return solver_names(model=SDOF_MODEL, needs_opensees=True)[0]


def screen_solver() -> str:
    """The cheapest rigid-body solver (the first compiled one of :data:`RIGID_MODEL`): the screen of a
    multi-fidelity campaign."""
    return solver_names(model=RIGID_MODEL, compiled=True)[0]


def planar_solver(friction: bool) -> str:
    """The first compiled planar solver that takes any restitution and models a slipping base (``friction``
    True) or a base that never slips (False): the one a study solves planar items with by default."""
    return solver_names(plan=False, compiled=True, restitution=True, friction=friction)[0]


def check_model(name: str, block: Block, excitation: object) -> None:
    """Refuse what the solver ``name`` does not model, as its registry entry declares it: a block whose
    base slips, a mass distribution other than a homogeneous block's, a block that lands flat (``e = 0``), a
    vertical floor motion, free rocking
    (``excitation=None``), a restitution other than Housner's.

    Raises
    ------
    ModelNotSupported
        Naming the solver and what it cannot model.
    """
    from opsrock.excitations.base import has_vertical  # numpy: not loaded for the command line's parser

    entry = info(name)
    if block.slips and not entry.friction:
        raise ModelNotSupported(
            f"solver {name!r} models no-slip rocking; block {block.name or '<unnamed>'} has friction = "
            f"{block.friction!r}: use solver {_alternative('friction')} (or drop friction)")
    if not block.homogeneous and not entry.mass_distribution:
        raise ModelNotSupported(
            f"solver {name!r} models a homogeneous block only; block {block.name or '<unnamed>'} has cm_height = "
            f"{block.cm_height!r}, radius_of_gyration = {block.radius_of_gyration!r}: use solver "
            f"{_mass_alternative(block)} (or drop cm_height and radius_of_gyration)", argument="solver")
    if block.e == 0.0 and not entry.flat_landing:
        raise ModelNotSupported(
            f"solver {name!r} models an impact by a damper that keeps e² of the energy; block "
            f"{block.name or '<unnamed>'} ({block.width:g} x {block.height:g} m) has e_R = {block.e_R:.4f} <= 0 and "
            f"lands flat (e = 0): use solver {_alternative('flat_landing')}, or give its restitution", argument="solver")
    if block.lands_flat and block.restitution is not None and entry.model == "friction":
        raise ModelNotSupported(
            f"solver {name!r}: block {block.name or '<unnamed>'} has e_R = {block.e_R:.4f} <= 0, so its corner "
            f"impulses land it flat (e = 0); restitution = {block.restitution!r} has no rebound to scale: drop "
            "restitution", argument="restitution")
    if excitation is not None and has_vertical(excitation) and not entry.vertical:
        raise ModelNotSupported(
            f"solver {name!r} takes horizontal floor motion only; the excitation has a vertical component: "
            f"use solver {_alternative('vertical')} (or drop the vertical motion)")
    if _in_plan(excitation) and not entry.plan:
        raise ModelNotSupported(
            f"solver {name!r} is planar (one horizontal component along the block's width); the excitation has "
            f"a second horizontal component or turns the block in plan: use solver {_alternative('plan')}",
            argument="solver")
    if excitation is None and not entry.free_rocking:
        raise ModelNotSupported(f"solver {name!r} does not model free rocking (excitation None)")
    if not entry.restitution and (block.restitution is not None or block.restitution_factor != 1.0):
        given = (f"restitution = {block.restitution!r}" if block.restitution is not None
                 else f"restitution_factor = {block.restitution_factor!r}")
        raise ModelNotSupported(
            f"solver {name!r} reproduces Housner's impact (e = e_H = {block.e_R:.6g}) and no other: block "
            f"{block.name or '<unnamed>'} has {given}; build it with restitution_factor=1.0 and no restitution")


def _in_plan(excitation: object) -> bool:
    """True if ``excitation`` is a :class:`~opsrock.excitations.plan.PlanMotion` that is not planar."""
    return getattr(excitation, "planar", True) is False


def _mass_alternative(block: Block) -> str:
    """The first solver that models ``block``'s mass distribution (and its friction, if any), quoted."""
    wanted = {"mass_distribution": True, **({"friction": True} if block.slips else {})}
    return repr(solver_names(**wanted)[0])


def _alternative(capability: str) -> str:
    """The first solver that has ``capability``, quoted, for a message."""
    return repr(solver_names(**{capability: True})[0])


__all__ = ["BASES", "BLOCK_NEEDS", "BOX3D_MODEL", "CYLINDER3D_MODEL", "EXCITATION_KINDS", "FRICTION_MODEL", "METHODS",
           "MODELS", "RESULT_COLUMN_GROUPS", "RIGID_MODEL", "SDOF_MODEL", "SOLVERS", "SolverInfo", "capabilities",
           "check_model", "info", "plan_solver", "planar_solver", "reference_sdof_solver", "round_solver",
           "screen_solver", "solver_names"]
