"""Scenes: which blocks meet which pulses (``[grid]``, :mod:`~opsrock.campaign.grid`) or floor motions
(``[records]``, :mod:`~opsrock.campaign.records`), read from TOML and validated first.

A *scene* names a blocks file, a design (a pulse grid or a record set), the solver and its settings,
and the PFV convention of the intensity measures. :func:`load_scene` checks everything before anything
runs (:class:`~opsrock.campaign.toml.TomlFile`): unknown keys, missing fields, wrong types,
non-positive or non-finite numbers, empty grids and unknown solvers or solver settings all raise
:class:`~opsrock.errors.SceneError`, whose message names the file, the field as a dotted path
(``grid.pfa_ratio.num``) and the offending value. The scenes shipped with opsrock are named without a
path (:mod:`opsrock.data`: ``paper``, ``tiny``, ...).

Scene file layout (see ``docs/guide/scenes.md``)::

    name = "paper"                      # optional, default: file stem
    description = "..."                 # optional
    blocks = "../blocks.toml"           # required, relative to the scene file, or a shipped library's name
    select = ["bookcase", "wardrobe"]   # optional subset of the blocks file, in this order
    pfv_convention = "amplitude"        # optional, "amplitude" (default) or "peak"
    accept_implausible = false          # optional: true runs blocks and record files beyond the
                                        # plausibility bounds (opsrock.limits.PLAUSIBLE)

    [solver]                            # optional, default name "opensees"; "auto": picked from [needs]
    name = "opensees"
    case_timeout = 300                  # optional wall-clock budget of one case (s)
    [solver.settings]                   # optional keyword settings of that solver's solve()
    step = 1e-4

    [needs]                             # optional (opsrock.campaign.needs): what is asked
    answer = "verdicts"                 # verdicts | theta_max | histories | hysteresis
    tolerance = 0.01                    # alpha
    model = "either"                    # rigid | sdof | either

    [pulse] and [grid] (a pulse scene), or [records] (a record scene)

Blocks file layout: an array of tables ``[[block]]`` with ``name``, ``width`` (2b, m),
``height`` (2h, m), ``reason`` (one line), and optionally ``mass`` (kg), either
``restitution_factor`` (``e / e_R``, or a distribution of it sampled per case) or ``restitution`` (``e``
itself, or a named law: :mod:`opsrock.restitution`), and ``friction`` (the static
Coulomb coefficient on the floor) with ``friction_kinetic``; a block with friction needs a solver of
the ``friction`` model. ``cm_height`` (m above the base) and ``radius_of_gyration`` (m, about the centre of
mass) describe a mass distribution other than a homogeneous block's (:class:`~opsrock.block.Block`); such a
block needs a solver that models it (registry: ``mass_distribution``). ``depth`` (m, the base's full depth
across ``width``) makes it a box in three dimensions, for a solver in plan (registry ``plan``: ``rigid3d``); a
planar solver ignores it.

Three dimensions: a scene whose design turns a block in plan (``[pulse] azimuth`` or ``[records] azimuth``
other than multiples of 360 deg) or gives a second horizontal component (``[records] second``) needs a solver
in plan and every block's ``depth``; ``[solver] name = "auto"`` then picks ``rigid3d`` (the only one), whose
``cases.csv`` adds :data:`~opsrock.campaign.cases.PLAN_COLUMNS`.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping

from opsrock.block import Block
from opsrock.campaign.cases import CONTACT_COLUMNS, PLAN_COLUMNS, units_of
from opsrock.campaign.grid import Grid, parse_grid
from opsrock.campaign.needs import HISTORY_ANSWERS, Choice, Needs, check, choose
from opsrock.campaign.toml import MAX_AXIS_POINTS, TomlFile, canonical
from opsrock.constants import DEFAULT_RESTITUTION_FACTOR
from opsrock.errors import ModelNotSupported, OpsrockError, SceneError, UnknownSettingError
from opsrock.excitations import PFV_CONVENTIONS, pulse_class
from opsrock.excitations.base import has_vertical
from opsrock.excitations.plan import PlanMotion
from opsrock.limits import ACCEPT_KEY, ACCEPT_OPTION, check_plausible_sizes
from opsrock.restitution import RestitutionDistribution, distribution_from_table, law_factor
from opsrock.solvers import check_settings
from opsrock.solvers.registry import METHODS, capabilities, check_model, reference_sdof_solver, solver_names

if TYPE_CHECKING:
    from opsrock.campaign.records import RecordSet
    from opsrock.inventory.friction import FrictionDistribution

#: Version of the scene format; bump when the meaning of a scene file changes.
SCENE_FORMAT: int = 1

#: Solver used when a scene has no ``[solver]`` table: the paper's OpenSees SDOF model.
DEFAULT_SOLVER: str = reference_sdof_solver()

#: ``[solver] name`` that picks the solver from ``[needs]`` (:mod:`opsrock.campaign.needs`).
AUTO: str = "auto"

#: Largest number of cases in one scene (blocks x design). A campaign keeps every case (block, motion,
#: id) in memory and one store row per case: about 1 KB each, so 250,000 cases are a few hundred MB.
#: Dense spectra beyond that go through :func:`opsrock.solvers.housner_fast.solve_pulses`, which
#: streams arrays instead of case objects.
MAX_CASES: int = 250_000

_SCENE_KEYS = {"name", "description", "blocks", "select", "pfv_convention", "solver", "grid", "records", "pulse",
               "needs", "accept_implausible"}
_NEEDS_KEYS = {"answer", "tolerance", "model"}
_SOLVER_KEYS = {"name", "settings", "case_timeout"}
_BLOCK_KEYS = {"name", "width", "height", "reason", "mass", "restitution_factor", "restitution", "friction",
               "friction_kinetic", "cm_height", "radius_of_gyration", "depth"}


@dataclass(frozen=True)
class BlockSpec:
    """One entry of a blocks file.

    Parameters
    ----------
    name : str
        Unique label (letters, digits, ``_``, ``.``, ``-``); first part of every case id.
    width : float
        Full base width ``2b`` (m).
    height : float
        Full height ``2h`` (m).
    reason : str
        One line saying what real object the block stands for.
    mass : float
        Mass (kg); rocking does not depend on it.
    restitution_factor : float
        ``e / e_R`` (dimensionless).
    restitution : float or None
        ``e`` itself (dimensionless, in (0, 1]), instead of ``restitution_factor``; None if not set.
    friction : float or None
        Static Coulomb friction coefficient on the floor (dimensionless); None: the base never slips.
    friction_kinetic : float or None
        Kinetic coefficient (dimensionless, <= ``friction``); None: equal to ``friction``.
    restitution_distribution : RestitutionDistribution or None
        A distribution of ``e / e_R`` drawn once per case (:meth:`block_for`); ``restitution_factor`` is
        then its mean. None: the factor is fixed.
    cm_height : float or None
        Height of the centre of mass above the base (m); None: mid-height (a homogeneous block).
    radius_of_gyration : float or None
        Radius of gyration about the centre of mass (m); None: a homogeneous block's.
    friction_distribution : FrictionDistribution or None
        A distribution of the friction coefficients drawn once per case (:meth:`block_for`,
        :mod:`opsrock.inventory.friction`); ``friction`` and ``friction_kinetic`` are then its median's. None:
        the friction is fixed.
    depth : float or None
        Full depth ``2d`` of the base (m), across ``width``; None: a planar block.
    """

    name: str
    width: float
    height: float
    reason: str = ""
    mass: float = 1.0
    restitution_factor: float = DEFAULT_RESTITUTION_FACTOR
    restitution: float | None = None
    friction: float | None = None
    friction_kinetic: float | None = None
    restitution_distribution: RestitutionDistribution | None = None
    cm_height: float | None = None
    radius_of_gyration: float | None = None
    friction_distribution: FrictionDistribution | None = None
    depth: float | None = None

    @property
    def block(self) -> Block:
        """The :class:`~opsrock.block.Block` this entry describes (with the mean factor of a distribution)."""
        return Block(width=self.width, height=self.height, mass=self.mass, restitution_factor=self.restitution_factor,
                     name=self.name, restitution=self.restitution, friction=self.friction,
                     friction_kinetic=self.friction_kinetic, cm_height=self.cm_height,
                     radius_of_gyration=self.radius_of_gyration, depth=self.depth)

    def block_for(self, case_id: str) -> Block:
        """The block of case ``case_id``: :attr:`block`, with its own draws of the friction coefficients and of
        the restitution factor when the entry has distributions of them."""
        block = self.block
        if self.friction_distribution is not None:
            mu, mu_k = self.friction_distribution.sample(case_id)
            block = dataclasses.replace(block, friction=mu, friction_kinetic=mu_k)
        if self.restitution_distribution is None:
            return block
        return dataclasses.replace(block, restitution_factor=self.restitution_distribution.sample(case_id, block.e_R))


@dataclass(frozen=True)
class Scene:
    """A validated scene: blocks x a design (pulse grid or record set), with the solver and its settings.

    The solver and its settings are checked once, when the scene is made (:func:`load_scene`,
    :meth:`with_solver`, or in code): a bad name or value raises :class:`~opsrock.errors.SceneError`.

    Parameters
    ----------
    name : str
        Scene label.
    path : str
        File the scene was read from (empty if built in code).
    blocks : tuple of BlockSpec
        Blocks, in run order.
    grid : Grid or None
        Pulse ratios (a pulse scene), or None (a record scene).
    solver : str
        Solver name, one of :data:`opsrock.solvers.SOLVERS`.
    solver_settings : dict
        Keyword settings of that solver (JSON-serialisable scalars, lists and tables, as in TOML).
    pfv_convention : str
        PFV convention of IM3 and IM8, one of :data:`opsrock.excitations.PFV_CONVENTIONS`.
    description : str
        Free text.
    blocks_path : str
        The blocks file the blocks came from (empty if built in code).
    case_timeout : float or None
        Wall-clock budget of one case (s), ``[solver] case_timeout``; None: the campaign's
        default (:data:`opsrock.campaign.timeout.DEFAULT_CASE_TIMEOUT`). Not part of the digest: it
        decides how long a stuck case may run, not what a finished case computes.
    records : RecordSet or None
        The ``[records]`` table of a record scene, or None.
    needs : Needs or None
        What the scene asks for (``[needs]``, :mod:`opsrock.campaign.needs`); None: not stated.
    choice : Choice or None
        The solver chosen for, or checked against, ``needs`` and why (for the manifest); None without needs.
    """

    name: str
    path: str
    blocks: tuple[BlockSpec, ...]
    grid: Grid | None
    solver: str = DEFAULT_SOLVER
    solver_settings: Mapping[str, Any] = field(default_factory=dict)
    pfv_convention: str = "amplitude"
    description: str = ""
    blocks_path: str = ""
    case_timeout: float | None = None
    records: RecordSet | None = None
    needs: Needs | None = None
    choice: Choice | None = None

    def __post_init__(self) -> None:
        if (self.grid is None) == (self.records is None):
            raise SceneError(self.path or "<scene>", "grid", "<both>" if self.grid is not None else "<missing>",
                             "a scene needs exactly one of [grid] (pulses) or [records] (floor motions)")
        object.__setattr__(self, "solver_settings", _check_solver(TomlFile(self.path or "<scene>"), self.solver,
                                                                  dict(self.solver_settings)))
        self._refuse_unmodelled()

    def _refuse_unmodelled(self) -> None:
        """Refuse now what the solver does not model, as its registry entry declares it
        (:func:`opsrock.solvers.registry.capabilities`), so that no case is stored failed for it later.

        Every need a scene can have, in one place: the time histories its ``[needs] answer`` asks for;
        ``end_time`` (a span of free rocking) in its settings, with a solver that takes it only without a
        floor motion; a vertical floor motion (``[records] vertical``); and for each block a restitution
        drawn per case, then what :func:`~opsrock.solvers.registry.check_model` refuses for ``simulate`` too
        (a base that slips, a restitution other than Housner's) under the scene's floor motion. Free rocking
        (no floor motion) is no need of a scene: every case moves the floor.
        """
        where, solver, caps = self.path or "<scene>", self.solver, capabilities(self.solver)
        if self.needs is not None and self.needs.answer in HISTORY_ANSWERS and not caps["histories"]:
            raise SceneError(where, "needs.answer", self.needs.answer, f"solver {solver!r} returns no time "
                             f"histories (registry: histories = False); use one of {_having('histories')}")
        end_time = self.solver_settings.get("end_time")
        if end_time is not None and not caps["end_time_under_motion"]:
            raise SceneError(where, "solver.settings.end_time", end_time, f"solver {solver!r} takes end_time only "
                             "for free rocking (no floor motion), and every case of a scene moves the floor: drop it")
        motion = self._floor_motion()
        if has_vertical(motion) and not caps["vertical"]:
            shown = self.records.vertical if self.records.vertical != "none" else f"<in record {motion.name}>"
            raise SceneError(where, "records.vertical", shown, f"solver {solver!r} takes "
                             f"horizontal floor motion only (registry: vertical = False); use one of "
                             f"{_having('vertical')}, or drop the vertical motion")
        for spec in self.blocks:
            if "depth" in caps["block_needs"] and spec.depth is None:
                raise SceneError(where, "solver.name", solver, f"solver {solver!r} models a box in three dimensions "
                                 f"and block {spec.name!r} has no depth: give it depth (m) in the blocks file")
            if spec.restitution_distribution is not None and not caps["restitution"]:
                raise SceneError(where, "solver.name", solver, f"block {spec.name!r} draws its restitution_factor "
                                 f"from a distribution, and solver {solver!r} reproduces Housner's impact only "
                                 f"(registry: restitution = False); use one of {_having('restitution')}")
            try:
                check_model(solver, spec.block, motion if motion is not None else self._pulse(spec))
            except ModelNotSupported as exc:
                raise SceneError(where, "solver.name", solver, str(exc)) from None

    def _floor_motion(self) -> Any:
        """A ground record of a record scene, one with a vertical motion if any has one, in plan when the scene
        is (:attr:`in_plan`); None for a pulse scene."""
        if self.records is None:
            return None
        return self._in_plan_if_turned(next((r for r in self.records.grounds if has_vertical(r)),
                                            self.records.grounds[0]))

    def _pulse(self, spec: BlockSpec) -> Any:
        """The first pulse of the grid for ``spec``'s block (a pulse has no vertical motion), in plan when the
        scene is (:attr:`in_plan`)."""
        return self._in_plan_if_turned(pulse_class(self.grid.shape).from_ratios(
            spec.block, freq_ratio=self.grid.freq_ratio[0], pfa_ratio=self.grid.pfa_ratio[0]))

    def _in_plan_if_turned(self, motion: Any) -> Any:
        """``motion`` as a :class:`PlanMotion` turned by the scene's first azimuth that turns the block (or with
        a second component), for the registry's checks; as it is in a planar scene."""
        if not self.in_plan:
            return motion
        turned = next((z for z in self.design.azimuth if z % 360.0 != 0.0), 0.0)
        second = self.records.seconds[0] if self.records is not None and self.records.seconds else None
        return PlanMotion(motion, second, turned)

    @property
    def in_plan(self) -> bool:
        """True if the scene needs three dimensions: its design turns a block in plan (an azimuth not a multiple
        of 360 deg) or gives a second horizontal component."""
        return needs_plan(self.design)

    @property
    def design(self) -> Grid | RecordSet:
        """What the blocks meet: the pulse grid or the record set."""
        return self.grid if self.grid is not None else self.records

    @property
    def columns(self) -> tuple[str, ...]:
        """Columns of the scene's ``cases.csv``: the design's, then the result columns its solver declares
        (registry ``result_columns``: :data:`opsrock.campaign.cases.CONTACT_COLUMNS`,
        :data:`opsrock.campaign.cases.PLAN_COLUMNS`)."""
        groups = {"contact": CONTACT_COLUMNS, "plan": PLAN_COLUMNS}
        return (*self.design.columns, *(c for g in METHODS.get(self.solver).result_columns for c in groups[g]))

    @property
    def units(self) -> list[str]:
        """The units row of the scene's ``cases.csv`` (:func:`opsrock.campaign.cases.units_of`), column by column."""
        return units_of(self.columns, self.measure)

    @property
    def measure(self) -> str:
        """The intensity measure of a record scene's levels (:data:`opsrock.campaign.records.MEASURES`; the unit of
        ``cases.csv``'s ``level_value``); ``""`` for a pulse scene or a cloud."""
        return "" if self.records is None else self.records.intensity.measure

    @property
    def n_cases(self) -> int:
        """Number of cases: blocks x pulses, or blocks x floor motions x levels."""
        return len(self.blocks) * self.design.n_per_block

    def cases(self, motions: Mapping | None = None) -> list:
        """All cases in a deterministic order.

        Pulse scene: :class:`~opsrock.campaign.cases.PulseCase` by block (file order), then freq_ratio,
        then pfa_ratio. Record scene: :class:`~opsrock.campaign.cases.RecordCase` by block, record, floor,
        level; ``motions`` are the floor motions (:func:`opsrock.campaign.motions.assemble_motions`),
        computed here, in this process, when omitted.
        """
        if self.grid is not None:
            return self.grid.cases(self.blocks, self.pfv_convention)
        if motions is None:
            from opsrock.campaign.motions import assemble_motions, compute_motions

            items = self.records.motion_items()
            motions = assemble_motions(items, compute_motions(items))
        return self.records.cases(self.blocks, motions)

    def with_solver(self, solver: str, settings: Mapping[str, Any] | None = None) -> "Scene":
        """A copy run by another solver.

        Parameters
        ----------
        solver : str
            One of :data:`opsrock.solvers.SOLVERS`.
        settings : dict, optional
            Its settings. When omitted, the scene's settings are kept if ``solver`` is the
            scene's own solver, and dropped (solver defaults) otherwise: settings belong to
            the solver they were written for.
        """
        if settings is None:
            settings = dict(self.solver_settings) if solver == self.solver else {}
        choice = self.choice
        if self.needs is not None:  # the scene's needs hold for any solver it is run with
            friction = any(b.friction is not None for b in self.blocks) or any(
                r.vertical is not None for r in (self.records.grounds if self.records else ()))
            choice = check(solver, self.needs, friction=friction, plan=self.in_plan)
        return dataclasses.replace(self, solver=solver, solver_settings=dict(settings), choice=choice)

    def fingerprint(self) -> dict[str, Any]:
        """Everything that determines the results, as plain JSON data (see :meth:`digest`).

        The scene's name, description and file paths are left out: renaming a scene or moving
        its files does not change its results.
        """
        return {
            "scene_format": SCENE_FORMAT,
            "solver": self.solver,
            "solver_settings": canonical(self.solver_settings),
            "pfv_convention": self.pfv_convention,
            # a directly set restitution enters only when used, so the digests of existing scenes, and
            # the stores that resume from them, stay valid
            "blocks": [
                [b.name, b.width, b.height, b.mass, b.restitution_factor]
                + ([b.restitution] if b.restitution is not None else [])
                + ([{"friction": b.friction, "friction_kinetic": b.friction_kinetic}] if b.friction is not None else [])
                + ([{"restitution": b.restitution_distribution.fingerprint()}] if b.restitution_distribution else [])
                + ([{"cm_height": b.cm_height, "radius_of_gyration": b.radius_of_gyration}]
                   if (b.cm_height, b.radius_of_gyration) != (None, None) else [])
                + ([{"friction_distribution": b.friction_distribution.fingerprint()}] if b.friction_distribution
                   else [])
                + ([{"depth": b.depth}] if b.depth is not None else [])
                for b in self.blocks
            ],
            **self.design.fingerprint(),
        }

    def digest(self) -> str:
        """SHA-256 (hex) of :meth:`fingerprint` as canonical JSON: equal digests, equal results."""
        text = json.dumps(self.fingerprint(), sort_keys=True, separators=(",", ":"), allow_nan=False)
        return hashlib.sha256(text.encode()).hexdigest()


def needs_plan(design: Any) -> bool:
    """True if a scene's design (:class:`Grid` or :class:`RecordSet`) needs three dimensions: an azimuth that
    turns the block in plan (not a multiple of 360 deg), or a second horizontal component."""
    return any(z % 360.0 != 0.0 for z in design.azimuth) or bool(getattr(design, "second", ""))


def _having(capability: str) -> str:
    """The solvers that declare ``capability``, quoted, for a message."""
    return ", ".join(map(repr, solver_names(**{capability: True})))


# --- loading ------------------------------------------------------------------------------------
def load_blocks(path: str | Path, *, confirm: bool = False) -> tuple[BlockSpec, ...]:
    """Read and validate a blocks file.

    Parameters
    ----------
    path : str or Path
        TOML file with an array of tables ``[[block]]`` (see the module docstring).
    confirm : bool
        True: a block larger than ``PLAUSIBLE["block_size"]`` (10 m) is accepted; otherwise it is refused
        as a likely unit mistake (:func:`opsrock.limits.check_plausible`).

    Returns
    -------
    tuple of BlockSpec
        In file order.

    Raises
    ------
    SceneError
        On any invalid content; the message names the file, the field and the value.
    ImplausibleInputError
        For a block larger than 10 m, unless ``confirm``.
    """
    f = TomlFile(path)
    data = f.read()
    f.keys("", data, allowed={"block"}, required={"block"})
    entries = data["block"]
    if not isinstance(entries, list) or not entries:
        raise f.error("block", entries, "must be a non-empty array of tables [[block]]")
    specs: list[BlockSpec] = []
    seen: dict[str, int] = {}
    for k, entry in enumerate(entries):
        where = f"block[{k}]"
        spec = _block_spec(f, where, f.table(where, entry, "a table"))
        if spec.name in seen:
            raise f.error(f"{where}.name", spec.name, f"duplicates block[{seen[spec.name]}].name")
        sizes = {f"{f.path}: {where}.width": spec.width, f"{f.path}: {where}.height": spec.height,
                 **({f"{f.path}: {where}.depth": spec.depth} if spec.depth is not None else {})}
        check_plausible_sizes(sizes, option=f"{ACCEPT_KEY} in the scene (or {ACCEPT_OPTION})", confirm=confirm)
        seen[spec.name] = k
        specs.append(spec)
    return tuple(specs)


def _restitution(f: TomlFile, where: str, entry: dict) -> tuple[float, float | None, RestitutionDistribution | None]:
    """``(restitution_factor, restitution, distribution)`` of a blocks-file entry: a number, a named law
    (``restitution = "housner"``), or a distribution table (``restitution_factor = {...}``)."""
    factor, e, dist = DEFAULT_RESTITUTION_FACTOR, None, None
    raw_f, raw_e = entry.get("restitution_factor"), entry.get("restitution")
    if raw_f is not None and raw_e is not None:
        raise f.error(f"{where}.restitution", raw_e, "give restitution or restitution_factor, not both")
    try:
        if isinstance(raw_e, str):
            factor = law_factor(raw_e)
        elif raw_e is not None:
            e = f.positive(f"{where}.restitution", raw_e)
        if isinstance(raw_f, dict):
            dist = distribution_from_table(raw_f)
            factor = dist.mean
        elif raw_f is not None:
            factor = f.positive(f"{where}.restitution_factor", raw_f)
    except OpsrockError as exc:
        key = "restitution" if raw_e is not None else "restitution_factor"
        raise f.error(f"{where}.{key}", entry[key], str(exc)) from None
    return factor, e, dist


def _block_spec(f: TomlFile, where: str, entry: dict) -> BlockSpec:
    f.keys(where, entry, allowed=_BLOCK_KEYS, required={"name", "width", "height"})
    factor, e, dist = _restitution(f, where, entry)
    spec = BlockSpec(
        name=f.name(f"{where}.name", entry["name"]),
        width=f.positive(f"{where}.width", entry["width"]),
        height=f.positive(f"{where}.height", entry["height"]),
        reason=f.string(f"{where}.reason", entry.get("reason", ""), allow_empty=True),
        mass=f.positive(f"{where}.mass", entry.get("mass", 1.0)),
        restitution_factor=factor,
        restitution=e,
        restitution_distribution=dist,
        friction=f.number(f"{where}.friction", entry["friction"]) if "friction" in entry else None,
        friction_kinetic=(f.number(f"{where}.friction_kinetic", entry["friction_kinetic"])
                          if "friction_kinetic" in entry else None),
        cm_height=f.number(f"{where}.cm_height", entry["cm_height"]) if "cm_height" in entry else None,
        radius_of_gyration=(f.number(f"{where}.radius_of_gyration", entry["radius_of_gyration"])
                            if "radius_of_gyration" in entry else None),
        depth=f.number(f"{where}.depth", entry["depth"]) if "depth" in entry else None,
    )
    try:  # the Block's own physical checks (restitution in (0, 1], friction ranges, mass distribution)
        spec.block
    except OpsrockError as exc:
        key = next((k for k in ("friction_kinetic", "friction", "cm_height", "radius_of_gyration", "depth")
                    if str(exc).startswith(k) and k in entry), None)
        if key:
            raise f.error(f"{where}.{key}", entry[key], str(exc)) from None
        raise f.error(where, {"width": spec.width, "height": spec.height}, str(exc)) from None
    return spec


def scene_path(scene: str | Path) -> Path:
    """The file of ``scene``: a path as given, or a shipped scene's file when ``scene`` is a bare name
    (no folder, no ``.toml``) that is not a file here."""
    path = Path(scene)
    if not path.exists() and path.suffix == "" and path.name == str(scene):
        from opsrock.data import scene_file, scene_names

        if str(scene) in scene_names():
            return scene_file(str(scene))
    return path


def load_scene(path: str | Path, *, accept_implausible: bool = False) -> Scene:
    """Read and validate a scene file and the blocks file it names.

    Parameters
    ----------
    path : str or Path
        Scene TOML file (see the module docstring), or the name of a scene shipped with opsrock
        (:func:`opsrock.data.scene_names`: ``"paper"``, ``"tiny"``, ...).
    accept_implausible : bool
        True (or ``accept_implausible = true`` in the scene): blocks larger than 10 m and record files whose
        PFA exceeds 10 g are run; otherwise they are refused as likely unit mistakes
        (:data:`opsrock.limits.PLAUSIBLE`).

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        On any invalid content of the scene or its blocks file; the message names the file,
        the dotted field and the value.
    ImplausibleInputError
        For a block or a record file beyond the plausibility bounds, unless confirmed.
    """
    f = TomlFile(scene_path(path))
    data = f.read()
    f.keys("", data, allowed=_SCENE_KEYS, required={"blocks"})
    if ("grid" in data) == ("records" in data):
        raise f.error("grid", "<both>" if "grid" in data else "<missing>",
                      "a scene needs exactly one of [grid] (pulses) or [records] (floor motions)")
    pfv = data.get("pfv_convention", "amplitude")
    if pfv not in PFV_CONVENTIONS:
        raise f.error("pfv_convention", pfv, f"must be one of {', '.join(map(repr, PFV_CONVENTIONS))}")
    confirm = f.boolean("accept_implausible", data.get("accept_implausible", False)) or accept_implausible
    blocks, blocks_path = _blocks(f, data, confirm)
    grid, records = _design(f, data, blocks, pfv, confirm)
    solver, settings, case_timeout = _solver(f, data.get("solver", {}))
    n_cases = len(blocks) * (grid if grid is not None else records).n_per_block
    needs, choice = _needs(f, data, solver, blocks, (grid, records), n_cases)
    if choice is not None:
        solver = choice.solver
    return Scene(name=f.string("name", data.get("name", f.path.stem)), path=str(f.path), blocks=blocks,
                 grid=grid, solver=solver, solver_settings=settings, pfv_convention=pfv,
                 description=f.string("description", data.get("description", ""), allow_empty=True),
                 blocks_path=str(blocks_path), case_timeout=case_timeout, records=records, needs=needs, choice=choice)


def _needs(f: TomlFile, data: dict, solver: str, blocks, designs: tuple, n_cases: int) -> tuple[Needs | None,
                                                                                              Choice | None]:
    """``[needs]`` and the solver it picks (``solver = "auto"``: ``rigid3d`` when the design needs three
    dimensions, :func:`needs_plan`) or checks (a named solver)."""
    grid, records = designs
    plan = needs_plan(grid if grid is not None else records)
    raw = data.get("needs")
    if raw is None and solver != AUTO:
        return None, None
    raw = f.table("needs", raw if raw is not None else {}, "a table [needs]")
    f.keys("needs", raw, allowed=_NEEDS_KEYS)
    friction = any(b.friction is not None for b in blocks) or any(r.vertical is not None for r in
                                                                    (records.grounds if records else ()))
    try:
        needs = Needs(**raw)
        choice = (choose(needs, friction=friction, n_cases=n_cases, plan=plan) if solver == AUTO
                  else check(solver, needs, friction=friction, plan=plan))
    except OpsrockError as exc:
        key = next((k for k in raw if str(exc).startswith(f"needs.{k}")), None)
        raise f.error(f"needs.{key}" if key else "needs", raw.get(key, dict(raw)) if key else dict(raw),
                      str(exc)) from None
    return needs, choice


def _blocks(f: TomlFile, data: dict, confirm: bool) -> tuple[tuple[BlockSpec, ...], Path]:
    """The scene's blocks: its blocks file (blocks beyond 10 m refused unless ``confirm``), and the ``select``
    subset of it."""
    blocks_ref = f.string("blocks", data["blocks"])
    from opsrock.data import block_library, block_library_names

    if blocks_ref in block_library_names():  # a shipped library, named without a path
        blocks = load_blocks(block_library(blocks_ref))
        return (_select(f, data["select"], blocks) if "select" in data else blocks), block_library(blocks_ref)
    try:
        blocks_path = (f.path.parent / blocks_ref).resolve()
        is_file = blocks_path.is_file()
    except (RuntimeError, OSError) as exc:  # a symlink loop (RuntimeError before Python 3.13), a name too long
        raise f.error("blocks", blocks_ref, f"cannot be resolved: {exc}") from None
    if not is_file:
        raise f.error("blocks", blocks_ref, f"no such file ({blocks_path})")
    blocks = load_blocks(blocks_path, confirm=confirm)
    if "select" in data:
        blocks = _select(f, data["select"], blocks)
    return blocks, blocks_path


def _design(f: TomlFile, data: dict, blocks: tuple[BlockSpec, ...], pfv: str,
            confirm: bool) -> tuple[Grid | None, RecordSet | None]:
    """The pulse grid or the record set (record files beyond 10 g refused unless ``confirm``), within
    :data:`MAX_CASES` cases in all."""
    grid = records = None
    if "grid" in data:
        grid = parse_grid(f, data["grid"], data.get("pulse", {}), blocks)
        if pfv == "peak" and grid.shape != "one-sine":
            # IM3/IM8 under "peak" use the one-sine pulse's peak velocity 2 PFA / omega_p
            raise f.error("pfv_convention", pfv, f"'peak' is defined for the one-sine pulse only, "
                          f"not for [pulse] shape = {grid.shape!r}; use 'amplitude' (PFA / omega_p)")
    elif "pulse" in data:
        raise f.error("pulse", data["pulse"], "[pulse] goes with [grid] (pulses), not with [records]")
    else:
        from opsrock.campaign.records import parse_records  # floor motions need scipy: only for record scenes

        records = parse_records(f, data["records"], [b.block for b in blocks], confirm=confirm)
    design, kind = (grid, "grid") if grid is not None else (records, "records")
    n = len(blocks) * design.n_per_block
    if n > MAX_CASES:
        raise f.error(kind, f"<{len(blocks)} blocks x {design.n_per_block} per block = {n} cases>",
                      f"must give <= {MAX_CASES} cases in all (MAX_CASES); split the scene")
    return grid, records


def _solver(f: TomlFile, raw: Any) -> tuple[str, dict, float | None]:
    """``[solver]``: the name, the settings table (checked when the scene is made) and the case budget."""
    f.table("solver", raw, "a table [solver] with name and optional settings")
    f.keys("solver", raw, allowed=_SOLVER_KEYS)
    settings = f.table("solver.settings", raw.get("settings", {}), "a table [solver.settings]")
    if raw.get("name") == AUTO and settings:
        raise f.error("solver.settings", settings, "'auto' picks the solver and its settings; give no settings")
    case_timeout = raw.get("case_timeout")
    if case_timeout is not None:
        case_timeout = f.positive("solver.case_timeout", case_timeout)
    return raw.get("name", DEFAULT_SOLVER), settings, case_timeout


def _select(f: TomlFile, select: Any, blocks: tuple[BlockSpec, ...]) -> tuple[BlockSpec, ...]:
    if not isinstance(select, list) or not select:
        raise f.error("select", select, "must be a non-empty array of block names")
    by_name = {b.name: b for b in blocks}
    out = []
    for k, name in enumerate(select):
        if not isinstance(name, str):
            raise f.error(f"select[{k}]", name, f"must be a block name (string), not {type(name).__name__}")
        if name not in by_name:
            raise f.error(f"select[{k}]", name, f"no such block in the blocks file (has: {', '.join(by_name)})")
        if select.index(name) != k:
            raise f.error(f"select[{k}]", name, "named twice")
        out.append(by_name[name])
    return tuple(out)


def _check_solver(f: TomlFile, solver: Any, settings: dict) -> dict:
    """The solver's name and settings, checked once: the settings object the solver would run with is
    built (:func:`opsrock.solvers.check_settings`), so a bad name or value is refused now."""
    if solver == AUTO:
        raise f.error("solver.name", solver, "'auto' is resolved from [needs] when the scene loads")
    if METHODS.get(solver) is None:
        raise f.error("solver.name", solver, f"unknown solver (known: {', '.join(solver_names())})")
    for key, value in settings.items():
        f.setting(f"solver.settings.{key}", value)
    try:
        check_settings(solver, settings)
    except ImportError as exc:
        raise f.error("solver.name", solver, f"solver cannot be loaded: {exc}") from None
    except UnknownSettingError as exc:
        raise f.error(f"solver.settings.{exc.key}", settings[exc.key], str(exc)) from None
    except OpsrockError as exc:
        # The settings classes name the field first ("delta must lie in ..."): point at it.
        key = next((k for k in settings if str(exc).startswith(f"{k} ")), None)
        where, value = (f"solver.settings.{key}", settings[key]) if key else ("solver.settings", dict(settings))
        raise f.error(where, value, f"refused by solver {solver!r}: {exc}") from None
    return dict(settings)


__all__ = ["BlockSpec", "DEFAULT_SOLVER", "MAX_AXIS_POINTS", "MAX_CASES", "Scene", "SceneError", "load_blocks",
           "load_scene", "needs_plan", "scene_path"]
