"""Scenes: which blocks meet which pulses (``[grid]``) or floor motions (``[records]``,
:mod:`opsrock.campaign.records`), read from TOML and validated first.

A *scene* (``models/scenes/*.toml``) names a blocks file (``models/blocks.toml``), a grid of
dimensionless pulse ratios, the solver and its settings, and the PFV convention of the
intensity measures. :func:`load_scene` checks everything before anything runs: unknown keys,
missing fields, wrong types, non-positive or non-finite numbers, empty grids and unknown
solvers or solver settings all raise :class:`SceneError`, whose message names the file, the
field as a dotted path (``grid.pfa_ratio.num``) and the offending value.

Scene file layout (see ``models/README.md``)::

    name = "paper"                      # optional, default: file stem
    description = "..."                 # optional
    blocks = "../blocks.toml"           # required, relative to the scene file
    select = ["bookcase", "wardrobe"]   # optional subset of the blocks file, in this order
    pfv_convention = "amplitude"        # optional, "amplitude" (default) or "peak"

    [solver]                            # optional, default name "opensees"
    name = "opensees"
    [solver.settings]                   # optional keyword settings of that solver's solve()
    dt = 1e-4

    [pulse]                             # optional, default shape "one-sine"
    shape = "one-sine"                  # rectangular, half-sine, one-sine, one-cosine, ricker

    [grid.freq_ratio]                   # omega_p / p (IM1): start/stop/num ...
    start = 0.5
    stop = 10.0
    num = 10
    [grid.pfa_ratio]                    # PFA / (g tan alpha) (IM2): ... or an explicit list
    values = [1.0, 2.0, 5.0]

Blocks file layout: an array of tables ``[[block]]`` with ``name``, ``width`` (2b, m),
``height`` (2h, m), ``reason`` (one line), and optionally ``mass`` (kg) and either
``restitution_factor`` (``e / e_R``) or ``restitution`` (``e`` itself).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import re
import tomllib
from dataclasses import dataclass, field
from numbers import Real
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping

import numpy as np

from opsrock.block import Block
from opsrock.constants import DEFAULT_RESTITUTION_FACTOR
from opsrock.errors import MISSING, SceneError, UnknownSettingError
from opsrock.excitations import PFV_CONVENTIONS, PULSE_SHAPES, Pulse, pulse_class
from opsrock.solvers import SOLVERS, check_settings

if TYPE_CHECKING:
    from opsrock.campaign.records import RecordSet

#: Version of the scene format; bump when the meaning of a scene file changes.
SCENE_FORMAT: int = 1

#: Solver used when a scene has no ``[solver]`` table: the paper's OpenSees SDOF model.
DEFAULT_SOLVER: str = "opensees"

#: Largest number of values on one grid axis: a guard against a typo (``num = 1000000``)
#: that would otherwise allocate and queue an absurd campaign; 10 000 x 10 000 pulses per
#: block is already far beyond any overturning spectrum.
MAX_AXIS_POINTS: int = 10_000

#: Largest number of cases in one scene (blocks x grid). A campaign keeps every case (block, pulse,
#: id) in memory and one store row per case: about 1 KB each, so 250,000 cases are a few hundred MB.
#: Dense spectra beyond that go through :func:`opsrock.solvers.housner_fast.solve_pulses`, which
#: streams arrays instead of case objects.
MAX_CASES: int = 250_000

#: Block names become part of case ids (``bookcase/f03/a07``) and file names: keep them plain.
_NAME_PATTERN = re.compile(r"^[A-Za-z0-9_.-]+$")

_SCENE_KEYS = {"name", "description", "blocks", "select", "pfv_convention", "solver", "grid", "records", "pulse"}
_SOLVER_KEYS = {"name", "settings", "case_timeout"}
_GRID_AXES = ("freq_ratio", "pfa_ratio")
_BLOCK_KEYS = {"name", "width", "height", "reason", "mass", "restitution_factor", "restitution"}




# --- data classes ----------------------------------------------------------------------------
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
    """

    name: str
    width: float
    height: float
    reason: str = ""
    mass: float = 1.0
    restitution_factor: float = DEFAULT_RESTITUTION_FACTOR
    restitution: float | None = None

    @property
    def block(self) -> Block:
        """The :class:`~opsrock.block.Block` this entry describes."""
        return Block(
            width=self.width,
            height=self.height,
            mass=self.mass,
            restitution_factor=self.restitution_factor,
            name=self.name,
            restitution=self.restitution,
        )


@dataclass(frozen=True)
class Grid:
    """The pulse grid, in the dimensionless ratios of the overturning spectrum.

    Parameters
    ----------
    freq_ratio : tuple of float
        ``omega_p / p`` values (dimensionless, IM1), > 0, in run order.
    pfa_ratio : tuple of float
        ``PFA / (g tan alpha)`` values (dimensionless, IM2), > 0, in run order.
    shape : str
        Pulse shape, a key of :data:`opsrock.excitations.PULSE_SHAPES` (``[pulse] shape``).
    """

    freq_ratio: tuple[float, ...]
    pfa_ratio: tuple[float, ...]
    shape: str = "one-sine"

    @property
    def size(self) -> int:
        """Number of pulses per block."""
        return len(self.freq_ratio) * len(self.pfa_ratio)


@dataclass(frozen=True)
class Case:
    """One block under one pulse: the unit of work of a campaign.

    Parameters
    ----------
    case_id : str
        Stable id ``"<block>/f<i>/a<j>"``: ``i`` (``j``) is the 1-based index into the
        grid's ``freq_ratio`` (``pfa_ratio``) values, zero-padded to at least two digits.
    block : Block
        The block.
    pulse : Pulse
        The pulse (the scene's shape), ``PFA = pfa_ratio g tan(alpha)``, ``omega_p = freq_ratio p``.
    freq_ratio : float
        ``omega_p / p`` (dimensionless).
    pfa_ratio : float
        ``PFA / (g tan alpha)`` (dimensionless).
    """

    case_id: str
    block: Block
    pulse: Pulse
    freq_ratio: float
    pfa_ratio: float

    @property
    def excitation(self) -> Pulse:
        """What the solver gets: the pulse."""
        return self.pulse


@dataclass(frozen=True)
class Scene:
    """A validated scene: blocks x pulse grid, with the solver and its settings.

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
        Keyword settings passed to that solver (JSON-serialisable scalars and lists).
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
        The ``[records]`` table of a record scene (:mod:`opsrock.campaign.records`), or None.
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

    @property
    def n_cases(self) -> int:
        """Number of cases: ``len(blocks) * grid.size``, or blocks x floor motions x levels."""
        if self.records is not None:
            return len(self.blocks) * self.records.n_per_block
        return len(self.blocks) * self.grid.size

    def cases(self, motions: Mapping | None = None) -> list:
        """All cases in a deterministic order.

        Pulse scene: :class:`Case` by block (file order), then freq_ratio, then pfa_ratio.
        Record scene: :class:`~opsrock.campaign.records.RecordCase` by block, record, floor, level;
        ``motions`` are the floor motions (:func:`opsrock.campaign.records.assemble_motions`),
        computed here, in this process, when omitted.
        """
        if self.records is not None:
            from opsrock.campaign.records import (
                assemble_motions,
                compute_motions,
                motion_items,
                record_cases,
            )

            if motions is None:
                items = motion_items(self.records)
                motions = assemble_motions(self.records, items, compute_motions(items))
            return record_cases(self.blocks, self.records, motions)
        nf, na = len(self.grid.freq_ratio), len(self.grid.pfa_ratio)
        wf, wa = max(2, len(str(nf))), max(2, len(str(na)))
        out = []
        for spec in self.blocks:
            block = spec.block
            for i, fr in enumerate(self.grid.freq_ratio, start=1):
                for j, ar in enumerate(self.grid.pfa_ratio, start=1):
                    out.append(
                        Case(
                            case_id=f"{spec.name}/f{i:0{wf}d}/a{j:0{wa}d}",
                            block=block,
                            pulse=pulse_class(self.grid.shape).from_ratios(block, pfa_ratio=ar, freq_ratio=fr),
                            freq_ratio=fr,
                            pfa_ratio=ar,
                        )
                    )
        return out

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
        settings = _check_solver(self.path or "<scene>", "solver", solver, dict(settings))
        return dataclasses.replace(self, solver=solver, solver_settings=settings)

    def fingerprint(self) -> dict[str, Any]:
        """Everything that determines the results, as plain JSON data (see :meth:`digest`).

        The scene's name, description and file paths are left out: renaming a scene or moving
        its files does not change its results.
        """
        return {
            "scene_format": SCENE_FORMAT,
            "solver": self.solver,
            "solver_settings": _canonical(self.solver_settings),
            "pfv_convention": self.pfv_convention,
            # a directly set restitution (and a pulse shape other than the paper's) enter only when
            # used, so the digests of existing scenes, and the stores that resume from them, stay valid
            "blocks": [
                [b.name, b.width, b.height, b.mass, b.restitution_factor]
                + ([b.restitution] if b.restitution is not None else []) for b in self.blocks
            ],
            **({"freq_ratio": list(self.grid.freq_ratio), "pfa_ratio": list(self.grid.pfa_ratio)}
               if self.grid is not None else {"records": self.records.fingerprint()}),
            **({"pulse_shape": self.grid.shape} if self.grid is not None and self.grid.shape != "one-sine" else {}),
        }

    def digest(self) -> str:
        """SHA-256 (hex) of :meth:`fingerprint` as canonical JSON: equal digests, equal results."""
        text = json.dumps(self.fingerprint(), sort_keys=True, separators=(",", ":"), allow_nan=False)
        return hashlib.sha256(text.encode()).hexdigest()


# --- loading ------------------------------------------------------------------------------------
def load_blocks(path: str | Path) -> tuple[BlockSpec, ...]:
    """Read and validate a blocks file.

    Parameters
    ----------
    path : str or Path
        TOML file with an array of tables ``[[block]]`` (see the module docstring).

    Returns
    -------
    tuple of BlockSpec
        In file order.

    Raises
    ------
    SceneError
        On any invalid content; the message names the file, the field and the value.
    """
    path = Path(path)
    data = _read_toml(path)
    _check_keys(path, "", data, allowed={"block"}, required={"block"})
    entries = data["block"]
    if not isinstance(entries, list) or not entries:
        raise SceneError(path, "block", entries, "must be a non-empty array of tables [[block]]")
    specs: list[BlockSpec] = []
    seen: dict[str, int] = {}
    for k, entry in enumerate(entries):
        where = f"block[{k}]"
        if not isinstance(entry, dict):
            raise SceneError(path, where, entry, "must be a table")
        _check_keys(path, where, entry, allowed=_BLOCK_KEYS, required={"name", "width", "height"})
        name = _string(path, f"{where}.name", entry["name"])
        if not _NAME_PATTERN.match(name):
            raise SceneError(path, f"{where}.name", name, "must use only letters, digits, '_', '.', '-'")
        if name in seen:
            raise SceneError(path, f"{where}.name", name, f"duplicates block[{seen[name]}].name")
        seen[name] = k
        spec = BlockSpec(
            name=name,
            width=_positive(path, f"{where}.width", entry["width"]),
            height=_positive(path, f"{where}.height", entry["height"]),
            reason=_string(path, f"{where}.reason", entry.get("reason", ""), allow_empty=True),
            mass=_positive(path, f"{where}.mass", entry.get("mass", 1.0)),
            restitution_factor=_positive(
                path, f"{where}.restitution_factor", entry.get("restitution_factor", DEFAULT_RESTITUTION_FACTOR)
            ),
            restitution=_positive(path, f"{where}.restitution", entry["restitution"]) if "restitution" in entry else None,
        )
        try:  # the Block's own physical checks (restitution in (0, 1], e_R > 0)
            spec.block
        except (TypeError, ValueError) as exc:
            raise SceneError(path, where, {"width": spec.width, "height": spec.height}, str(exc)) from None
        specs.append(spec)
    return tuple(specs)


def scene_path(scene: str | Path) -> Path:
    """The file of ``scene``: a path as given, or a shipped scene's file when ``scene`` is a bare name
    (no folder, no ``.toml``) that is not a file here."""
    path = Path(scene)
    if not path.exists() and path.suffix == "" and path.name == str(scene):
        from opsrock.data import scene_file, scene_names

        if str(scene) in scene_names():
            return scene_file(str(scene))
    return path


def load_scene(path: str | Path) -> Scene:
    """Read and validate a scene file and the blocks file it names.

    Parameters
    ----------
    path : str or Path
        Scene TOML file (see the module docstring), or the name of a scene shipped with opsrock
        (:func:`opsrock.data.scene_names`: ``"paper"``, ``"tiny"``, ...).

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        On any invalid content of the scene or its blocks file; the message names the file,
        the dotted field and the value.
    """
    path = scene_path(path)
    data = _read_toml(path)
    _check_keys(path, "", data, allowed=_SCENE_KEYS, required={"blocks"})
    if ("grid" in data) == ("records" in data):
        raise SceneError(path, "grid", "<both>" if "grid" in data else "<missing>",
                         "a scene needs exactly one of [grid] (pulses) or [records] (floor motions)")

    name = _string(path, "name", data.get("name", path.stem))
    description = _string(path, "description", data.get("description", ""), allow_empty=True)
    pfv = data.get("pfv_convention", "amplitude")
    if pfv not in PFV_CONVENTIONS:
        raise SceneError(path, "pfv_convention", pfv, f"must be one of {', '.join(map(repr, PFV_CONVENTIONS))}")

    blocks_ref = _string(path, "blocks", data["blocks"])
    blocks_path = (path.parent / blocks_ref).resolve()
    if not blocks_path.is_file():
        raise SceneError(path, "blocks", blocks_ref, f"no such file ({blocks_path})")
    blocks = load_blocks(blocks_path)
    if "select" in data:
        blocks = _select(path, data["select"], blocks)

    grid, records = None, None
    if "grid" in data:
        grid = _grid(path, data["grid"], blocks, _pulse_shape(path, data.get("pulse", {})))
        if pfv == "peak" and grid.shape != "one-sine":
            # IM3/IM8 under "peak" use the one-sine pulse's peak velocity 2 PFA / omega_p
            raise SceneError(path, "pfv_convention", pfv, f"'peak' is defined for the one-sine pulse only, "
                             f"not for [pulse] shape = {grid.shape!r}; use 'amplitude' (PFA / omega_p)")
    elif "pulse" in data:
        raise SceneError(path, "pulse", data["pulse"], "[pulse] goes with [grid] (pulses), not with [records]")
    else:
        records = _records(path, data["records"], blocks)

    solver_raw = data.get("solver", {})
    if not isinstance(solver_raw, dict):
        raise SceneError(path, "solver", solver_raw, "must be a table [solver] with name and optional settings")
    _check_keys(path, "solver", solver_raw, allowed=_SOLVER_KEYS, required=set())
    solver = solver_raw.get("name", DEFAULT_SOLVER)
    settings = solver_raw.get("settings", {})
    if not isinstance(settings, dict):
        raise SceneError(path, "solver.settings", settings, "must be a table [solver.settings]")
    settings = _check_solver(path, "solver", solver, settings)
    case_timeout = solver_raw.get("case_timeout")
    if case_timeout is not None:
        if isinstance(case_timeout, bool) or not isinstance(case_timeout, Real) or not (
            math.isfinite(case_timeout) and case_timeout > 0
        ):
            raise SceneError(path, "solver.case_timeout", case_timeout, "must be a positive number of seconds")
        case_timeout = float(case_timeout)

    return Scene(
        name=name,
        path=str(path),
        blocks=blocks,
        grid=grid,
        solver=solver,
        solver_settings=settings,
        pfv_convention=pfv,
        description=description,
        blocks_path=str(blocks_path),
        case_timeout=case_timeout,
        records=records,
    )


def _pulse_shape(path: Path, pulse_raw: Any) -> str:
    if not isinstance(pulse_raw, dict):
        raise SceneError(path, "pulse", pulse_raw, "must be a table [pulse] with shape")
    _check_keys(path, "pulse", pulse_raw, allowed={"shape"}, required=set())
    shape = pulse_raw.get("shape", "one-sine")
    if shape not in PULSE_SHAPES:
        raise SceneError(path, "pulse.shape", shape, f"must be one of {', '.join(map(repr, PULSE_SHAPES))}")
    return shape


def _grid(path: Path, grid_raw: Any, blocks: tuple[BlockSpec, ...], shape: str = "one-sine") -> Grid:
    if not isinstance(grid_raw, dict):
        raise SceneError(path, "grid", grid_raw, "must be a table with [grid.freq_ratio] and [grid.pfa_ratio]")
    _check_keys(path, "grid", grid_raw, allowed=set(_GRID_AXES), required=set(_GRID_AXES))
    grid = Grid(**{axis: _axis(path, f"grid.{axis}", grid_raw[axis]) for axis in _GRID_AXES}, shape=shape)
    if len(blocks) * grid.size > MAX_CASES:
        raise SceneError(path, "grid", f"<{len(blocks)} blocks x {grid.size} pulses = {len(blocks) * grid.size} cases>",
                         f"must give <= {MAX_CASES} cases in all (MAX_CASES); split the scene")
    _check_pulses(path, blocks, grid)
    return grid


def _records(path: Path, raw: Any, blocks: tuple[BlockSpec, ...]) -> "RecordSet":
    from opsrock.campaign.records import RecordSceneError, parse_records

    try:
        records = parse_records(path, raw, [b.block for b in blocks])
    except RecordSceneError as exc:
        raise SceneError(path, exc.field, exc.value, exc.problem) from None
    n = len(blocks) * records.n_per_block
    if n > MAX_CASES:
        raise SceneError(path, "records", f"<{n} cases>", f"must give <= {MAX_CASES} cases in all (MAX_CASES); split the scene")
    return records


# --- helpers ------------------------------------------------------------------------------------
def _read_toml(path: Path) -> dict:
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except FileNotFoundError:
        raise SceneError(path, "(file)", str(path), "no such file") from None
    except IsADirectoryError:
        raise SceneError(path, "(file)", str(path), "is a directory, not a TOML file") from None
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(path, "(file)", str(path), f"not valid TOML: {exc}") from None
    except UnicodeDecodeError as exc:
        raise SceneError(path, "(file)", str(path), f"not UTF-8 text: {exc}") from None
    except OSError as exc:  # unreadable (permissions), a FIFO gone wrong, an I/O error
        raise SceneError(path, "(file)", str(path), f"cannot be read: {exc.strerror or exc}") from None


def _dotted(prefix: str, key: str) -> str:
    return f"{prefix}.{key}" if prefix else key


def _check_keys(path: Path, prefix: str, table: dict, *, allowed: set[str], required: set[str]) -> None:
    for key in table:
        if key not in allowed:
            raise SceneError(
                path, _dotted(prefix, key), table[key], f"unknown key (allowed: {', '.join(sorted(allowed))})"
            )
    for key in sorted(required):
        if key not in table:
            raise SceneError(path, _dotted(prefix, key), MISSING, "required field is missing")


def _string(path: Path, where: str, value: Any, *, allow_empty: bool = False) -> str:
    if not isinstance(value, str):
        raise SceneError(path, where, value, f"must be a string, not {type(value).__name__}")
    if not allow_empty and not value.strip():
        raise SceneError(path, where, value, "must not be empty")
    return value


def _positive(path: Path, where: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, Real):
        raise SceneError(path, where, value, f"must be a number, not {type(value).__name__}")
    v = float(value)
    if not math.isfinite(v):
        raise SceneError(path, where, value, "must be finite")
    if v <= 0.0:
        raise SceneError(path, where, value, "must be positive")
    return v


def _axis(path: Path, where: str, raw: Any) -> tuple[float, ...]:
    """One grid axis: ``{start, stop, num}`` (``num >= 2`` equal steps) or ``{values}``."""
    if not isinstance(raw, dict):
        raise SceneError(path, where, raw, "must be a table with start/stop/num or values")
    if "values" in raw:
        _check_keys(path, where, raw, allowed={"values"}, required={"values"})
        values = raw["values"]
        if not isinstance(values, list):
            raise SceneError(path, f"{where}.values", values, "must be an array of numbers")
        if not values:
            raise SceneError(path, f"{where}.values", values, "must not be empty")
        if len(values) > MAX_AXIS_POINTS:
            raise SceneError(path, f"{where}.values", f"<{len(values)} values>", f"must hold <= {MAX_AXIS_POINTS}")
        out = tuple(_positive(path, f"{where}.values[{k}]", v) for k, v in enumerate(values))
        if len(set(out)) != len(out):
            raise SceneError(path, f"{where}.values", values, "must not repeat a value")
        return out
    _check_keys(path, where, raw, allowed={"start", "stop", "num"}, required={"start", "stop", "num"})
    start = _positive(path, f"{where}.start", raw["start"])
    stop = _positive(path, f"{where}.stop", raw["stop"])
    num = raw["num"]
    if isinstance(num, bool) or not isinstance(num, int):
        raise SceneError(path, f"{where}.num", num, f"must be an integer, not {type(num).__name__}")
    if num < 2:
        raise SceneError(path, f"{where}.num", num, "must be >= 2 (use values = [x] for a single value)")
    if num > MAX_AXIS_POINTS:
        raise SceneError(path, f"{where}.num", num, f"must be <= {MAX_AXIS_POINTS} (MAX_AXIS_POINTS)")
    if not stop > start:
        raise SceneError(path, f"{where}.stop", raw["stop"], f"must exceed start = {raw['start']!r}")
    # float() of each numpy value: plain Python floats, identical on every run and platform.
    return tuple(float(v) for v in np.linspace(start, stop, num))


def _check_pulses(path: Path, blocks: tuple[BlockSpec, ...], grid: Grid) -> None:
    """Every pulse of the grid must be a valid pulse (finite, positive PFA and omega_p).

    ``PFA`` and ``omega_p`` grow with their ratios, so the extreme ratios of each axis decide.
    """
    for spec in blocks:
        block = spec.block
        for axis in _GRID_AXES:
            values = getattr(grid, axis)
            for ratio in (min(values), max(values)):
                # PFA depends only on pfa_ratio and omega_p only on freq_ratio: hold the other at 1.
                other = {a: 1.0 for a in _GRID_AXES if a != axis}
                try:
                    pulse_class(grid.shape).from_ratios(block, **{axis: ratio}, **other)
                except (TypeError, ValueError) as exc:
                    raise SceneError(
                        path, f"grid.{axis}", ratio, f"gives no valid pulse for block {spec.name!r}: {exc}"
                    ) from None


def _select(path: Path, select: Any, blocks: tuple[BlockSpec, ...]) -> tuple[BlockSpec, ...]:
    if not isinstance(select, list) or not select:
        raise SceneError(path, "select", select, "must be a non-empty array of block names")
    by_name = {b.name: b for b in blocks}
    out = []
    for k, name in enumerate(select):
        if not isinstance(name, str):
            raise SceneError(path, f"select[{k}]", name, f"must be a block name (string), not {type(name).__name__}")
        if name not in by_name:
            raise SceneError(
                path, f"select[{k}]", name, f"no such block in the blocks file (has: {', '.join(by_name)})"
            )
        if select.index(name) != k:
            raise SceneError(path, f"select[{k}]", name, "named twice")
        out.append(by_name[name])
    return tuple(out)


def _canonical(value: Any) -> Any:
    """Settings as plain JSON data (dicts with sorted keys, lists, str, bool, int, float)."""
    if isinstance(value, Mapping):
        return {str(k): _canonical(value[k]) for k in sorted(value)}
    if isinstance(value, (list, tuple)):
        return [_canonical(v) for v in value]
    return value


def _check_setting_value(path: Path | str, where: str, value: Any) -> None:
    if isinstance(value, (bool, int, str)):
        return
    if isinstance(value, float):
        if not math.isfinite(value):
            raise SceneError(path, where, value, "must be finite")
        return
    if isinstance(value, list):
        for k, v in enumerate(value):
            _check_setting_value(path, f"{where}[{k}]", v)
        return
    raise SceneError(path, where, value, f"must be a number, string, boolean or array, not {type(value).__name__}")


def _check_solver(path: Path | str, where: str, solver: Any, settings: dict) -> dict:
    if solver not in SOLVERS:
        raise SceneError(path, f"{where}.name", solver, f"unknown solver (known: {', '.join(SOLVERS)})")
    for key, value in settings.items():
        if isinstance(value, dict):
            for sub, v in value.items():
                _check_setting_value(path, f"{where}.settings.{key}.{sub}", v)
        else:
            _check_setting_value(path, f"{where}.settings.{key}", value)
    try:
        check_settings(solver, settings)
    except ImportError as exc:
        raise SceneError(path, f"{where}.name", solver, f"solver cannot be loaded: {exc}") from None
    except UnknownSettingError as exc:
        raise SceneError(path, f"{where}.settings.{exc.key}", settings[exc.key], exc.args[0]) from None
    except (TypeError, ValueError) as exc:
        # The settings classes name the field first ("delta must lie in ..."): point at it.
        key = next((k for k in settings if str(exc).startswith(f"{k} ")), None)
        field_, value = (f"{where}.settings.{key}", settings[key]) if key else (f"{where}.settings", dict(settings))
        raise SceneError(path, field_, value, f"refused by solver {solver!r}: {exc}") from None
    return dict(settings)


__all__ = [
    "DEFAULT_SOLVER",
    "MAX_AXIS_POINTS",
    "MAX_CASES",
    "BlockSpec",
    "Case",
    "Grid",
    "Scene",
    "SceneError",
    "load_blocks",
    "load_scene",
]
