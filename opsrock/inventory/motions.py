"""The user's floor motions: a manifest CSV with the columns ``record, floor, direction, file, units, dt`` and
optionally ``column`` and ``location`` (``dt`` where the file does not give it; ``file`` relative to the
manifest), listing floor acceleration
histories in any format :func:`opsrock.excitations.readers.read_record` reads. Each motion is checked
for plausibility (:data:`opsrock.limits.PLAUSIBLE`) unless confirmed.

The manifest is read like an inventory (:func:`opsrock.inventory.readers.read_csv_rows`: a header row, ``#``
comments, blank lines, spaces trimmed, UTF-8 with or without a byte-order mark). Per row:

``record``
    The ground-motion record (event) the floor motion comes from: the unit a record bootstrap resamples
    (letters, digits, ``_ . -``).
``floor``
    The floor's label, as the inventory's ``floor`` column names it (letters, digits, ``_ . -``).
``direction``
    ``1`` or ``2``: the horizontal direction (an item's ``width`` lies along 1, its ``depth`` along 2). Name
    X and Y as 1 and 2: the manifest says which is which, not a convention of opsrock's.
``file``
    The record file, relative to the manifest's folder (or absolute): ``.AT2`` (PEER NGA, its units in its
    header), or text/CSV of one column (accelerations) or two (time, acceleration).
``units``
    ``g``, ``m/s2`` or ``cm/s2`` (:data:`opsrock.excitations.readers.UNITS`): required for text/CSV files;
    for an ``.AT2`` file optional and checked against its header.
``column``
    The acceleration column of a file of several (``time,ax,ay``; OpenSees' ``Node`` recorder output with
    ``-time``: the time, then one column per node and dof): a header name (any case) or a 1-based index of the
    file's columns; the first column is the time unless ``dt`` is given. So both directions (and a vertical)
    come from one file, each on its own row.
``location``
    pelicun's location number of the row's floor (1 the ground floor, a whole number): the same on every row
    of a floor, different floors at different locations; given on every row or on none
    (:func:`opsrock.inventory.pelicun.floor_locations`: without it, which floor is taken as the ground is said).
``dt``
    The sampling interval (s) of a one-column file that states none. A one-column file may state it in a
    comment line before its samples, ``# dt = 0.01`` (``s`` after the number allowed); a ``dt`` cell then must
    agree with it. ``.AT2`` and two-column files give their own step, and a ``dt`` cell for them is refused.

Each (record, floor, direction) appears once. A motion is named ``<record>@<floor>@<direction>`` (unique, and
safe in case ids: the parts use no ``@``), with ``info.floor`` the floor's label.

For the three-dimensional solver ``rigid3d``, :func:`paired_motions` pairs each (record, floor)'s direction-1
and direction-2 motions (:class:`MotionPair`, :meth:`MotionPair.plan` the
:class:`~opsrock.excitations.plan.PlanMotion` at a block azimuth).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from opsrock._files import not_a_file
from opsrock.campaign.toml import NAME_PATTERN
from opsrock.errors import MISSING, InputError, OpsrockError
from opsrock.excitations.plan import PlanMotion
from opsrock.excitations.readers import UNITS, read_record
from opsrock.excitations.records import Record, check_plausible_record
from opsrock.inventory.items import DIRECTIONS
from opsrock.inventory.readers import Row, TableFileError, number_cell, read_csv_rows
from opsrock.limits import check

#: The manifest's columns.
MANIFEST_COLUMNS: tuple[str, ...] = ("record", "floor", "direction", "file", "units", "dt", "column", "location")

#: The columns every manifest has.
MANIFEST_REQUIRED: tuple[str, ...] = ("record", "floor", "direction", "file")

#: Separator of the parts of a motion's name (``LOS000@2@1``): not among the characters of a label.
NAME_SEPARATOR: str = "@"

#: Lines of a record file searched for a ``dt`` comment before its first sample.
HEADER_LINES: int = 50

_DT_LINE = re.compile(r"^\s*#\s*dt\s*[=:]\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(?:s|sec|seconds)?\s*$",
                      re.IGNORECASE | re.ASCII)


@dataclass(frozen=True)
class FloorMotion:
    """One floor acceleration history of the user's building.

    Parameters
    ----------
    record : str
        The ground-motion record (event) it comes from: the unit a record bootstrap resamples.
    floor : str
        The floor's label as the manifest gives it (``"1"``, ``"roof"``, ``"L3"``).
    direction : str
        ``"1"`` or ``"2"``: the horizontal direction (``Item.width`` lies along 1, ``depth`` along 2).
    motion : Record
        The acceleration history (m/s²).
    """

    record: str
    floor: str
    direction: str
    motion: Record = field(repr=False)

    @property
    def key(self) -> tuple[str, str, str]:
        """``(record, floor, direction)``."""
        return self.record, self.floor, self.direction


@dataclass(frozen=True)
class MotionSet:
    """Every floor motion of a manifest (or of the shipped shear building), each (record, floor, direction)
    once.

    Parameters
    ----------
    motions : tuple of FloorMotion
        In manifest order.
    source : str
        The manifest read, or a description of the building filter.
    locations : tuple of (str, int)
        Each floor label's pelicun location (the manifest's ``location`` column; 1 the ground floor); empty: not
        given (:func:`opsrock.inventory.pelicun.floor_locations` then says which floor it takes as the ground).
    storeys : int or None
        The storeys of the building the motions come from, where a building model gave them (the shipped shear
        building); None (a manifest): pelicun's ``NumberOfStories`` follows the floor labels.
    """

    motions: tuple[FloorMotion, ...]
    source: str
    locations: tuple[tuple[str, int], ...] = ()
    storeys: int | None = None

    def __post_init__(self) -> None:
        motions = tuple(self.motions)
        seen: set[tuple[str, str, str]] = set()
        dup = next((m.key for m in motions if m.key in seen or seen.add(m.key)), None)
        if dup is not None:
            raise InputError(f"motions {self.source}: record {dup[0]!r}, floor {dup[1]!r}, direction {dup[2]!r} "
                             "appears twice", argument="motions")
        object.__setattr__(self, "motions", motions)
        locations = tuple((str(f), int(n)) for f, n in self.locations)
        missing = [f for f in self.floors if f not in dict(locations)]
        if locations and missing:
            raise InputError(f"motions {self.source}: floor {missing[0]!r} has no location", argument="location")
        object.__setattr__(self, "locations", locations)
        if self.storeys is not None and (isinstance(self.storeys, bool) or not isinstance(self.storeys, int)
                                         or self.storeys < 1):
            raise InputError(f"motions {self.source}: storeys must be a whole number >= 1, got {self.storeys!r}",
                             argument="storeys")

    @property
    def floors(self) -> tuple[str, ...]:
        """The floors, in first-seen order."""
        return tuple(dict.fromkeys(m.floor for m in self.motions))

    @property
    def directions(self) -> tuple[str, ...]:
        """The directions, in first-seen order."""
        return tuple(dict.fromkeys(m.direction for m in self.motions))

    @property
    def records(self) -> tuple[str, ...]:
        """The records, in first-seen order."""
        return tuple(dict.fromkeys(m.record for m in self.motions))

    def select(self, floor: str | None = None, direction: str | None = None) -> tuple[FloorMotion, ...]:
        """The motions on ``floor`` in ``direction`` (None: any), in manifest order."""
        return tuple(m for m in self.motions if floor in (None, m.floor) and direction in (None, m.direction))

    def motion(self, record: str, floor: str, direction: str) -> FloorMotion:
        """The motion of ``(record, floor, direction)``; ``KeyError`` if the set has none."""
        for m in self.motions:
            if m.key == (record, floor, direction):
                return m
        raise KeyError(f"no motion of record {record!r} on floor {floor!r} in direction {direction!r} in {self.source}")


@dataclass(frozen=True)
class MotionPair:
    """The two horizontal floor motions of one record on one floor, for the three-dimensional solver.

    Parameters
    ----------
    first : FloorMotion
        Direction ``"1"`` (m/s²): along an item's ``width`` at azimuth 0.
    second : FloorMotion
        Direction ``"2"`` (m/s²) of the same record and floor: along the item's ``depth`` at azimuth 0.
    """

    first: FloorMotion
    second: FloorMotion

    def __post_init__(self) -> None:
        a, b = self.first, self.second
        if (a.record, a.floor, a.direction) != (b.record, b.floor, "1") or b.direction != "2":
            raise InputError(f"a motion pair is direction 1 and 2 of one record and floor, got {a.key!r} and "
                             f"{b.key!r}", argument="motions")

    @property
    def record(self) -> str:
        """The ground-motion record (event)."""
        return self.first.record

    @property
    def floor(self) -> str:
        """The floor's label."""
        return self.first.floor

    @property
    def name(self) -> str:
        """``<record>@<floor>``: unique in a motion set, safe in case ids."""
        return NAME_SEPARATOR.join((self.record, self.floor))

    def plan(self, azimuth: float = 0.0) -> PlanMotion:
        """Both directions as one plan motion, the block's width axis at ``azimuth`` (deg) from direction 1,
        counter-clockwise seen from above (:class:`~opsrock.excitations.plan.PlanMotion`)."""
        return PlanMotion(self.first.motion, self.second.motion, azimuth)


def paired_motions(motions: MotionSet) -> tuple[MotionPair, ...]:
    """Each (record, floor)'s direction-1 and direction-2 motions as a :class:`MotionPair`, in the order of
    the set's first direction-1 motions.

    Parameters
    ----------
    motions : MotionSet
        Floor motions (m/s²) in both directions.

    Raises
    ------
    InputError
        ``argument="motions"``: a record and floor with one direction only (named, with the set's source):
        the three-dimensional route needs both.
    """
    pairs: dict[tuple[str, str], dict[str, FloorMotion]] = {}
    for m in motions.motions:
        pairs.setdefault((m.record, m.floor), {})[m.direction] = m
    lone = [(key, tuple(found)) for key, found in pairs.items() if set(found) != set(DIRECTIONS)]
    if lone:
        (record, floor), have = lone[0]
        more = f" (and {len(lone) - 1} more record/floor pairs)" if len(lone) > 1 else ""
        raise InputError(f"motions {motions.source}: record {record!r} on floor {floor!r} has direction "
                         f"{have[0]} only{more}; two horizontal directions need both 1 and 2", argument="motions")
    return tuple(MotionPair(found["1"], found["2"]) for found in pairs.values())


def motion_name(record: str, floor: str, direction: str) -> str:
    """The name of a floor motion: ``<record>@<floor>@<direction>``."""
    return NAME_SEPARATOR.join((record, floor, direction))


def header_dt(path: Path) -> float | None:
    """The ``dt`` a one-column text/CSV record file states in a comment line before its first sample
    (``# dt = 0.01``), s; None when it states none or has more than one column (its time column rules)."""
    found = None
    if not_a_file(path) is not None:
        return None  # a FIFO would block; read_record names what it is
    try:
        with open(path, encoding="utf-8-sig", errors="replace") as fh:
            for _, line in zip(range(HEADER_LINES), fh):
                m = _DT_LINE.match(line)
                if m:
                    found = float(m.group(1))
                    continue
                text = line.strip()
                if not text or text.startswith("#"):
                    continue
                tokens = text.split(",") if path.suffix.lower() == ".csv" else text.split()
                if not _numeric(tokens[0]):
                    continue  # a header of column names
                return found if len(tokens) == 1 else None
    except OSError:
        return None  # read_record names the problem
    return found


def _numeric(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def _label(manifest: Path, row: Row, column: str) -> str:
    value, line = row.cells[column]
    if not NAME_PATTERN.match(value):
        raise TableFileError(manifest, line, column, value, "must use only letters, digits, '_', '.', '-'")
    return value


def _units_dt(manifest: Path, row: Row, path: Path) -> tuple[str | None, float | None]:
    """The ``units`` and ``dt`` to read the row's file with; refusals name the manifest line and column."""
    cells = row.cells
    units = cells["units"][0] if "units" in cells else None
    if units is not None and units not in UNITS:
        raise TableFileError(manifest, cells["units"][1], "units", units, f"must be one of {', '.join(UNITS)}")
    at2 = path.suffix.lower() == ".at2"
    if units is None and not at2:
        raise TableFileError(manifest, row.line, "units", MISSING, f"blank, and {path.name} is a text/CSV file, "
                             f"which does not state its units: give one of {', '.join(UNITS)}")
    dt = None
    if "dt" in cells:
        value, line = cells["dt"]
        try:
            dt = check("dt", number_cell(value))
        except OpsrockError as exc:
            raise TableFileError(manifest, line, "dt", value, str(exc)) from None
    stated = None if at2 or "column" in cells else header_dt(path)
    if stated is not None and dt is not None and abs(stated - dt) > 1e-9 * stated:
        raise TableFileError(manifest, cells["dt"][1], "dt", cells["dt"][0], f"but {path.name} states dt = {stated:g} s "
                             "in its header")
    return units, dt if dt is not None else stated


def _key(manifest: Path, row: Row) -> tuple[str, str, str]:
    """The row's ``(record, floor, direction)``, each checked."""
    for column in MANIFEST_REQUIRED:
        if column not in row.cells:
            raise TableFileError(manifest, row.line, column, MISSING, "blank: every motion needs it")
    record, floor = _label(manifest, row, "record"), _label(manifest, row, "floor")
    direction, line = row.cells["direction"]
    if direction not in DIRECTIONS:
        raise TableFileError(manifest, line, "direction", direction, f"must be {' or '.join(DIRECTIONS)} (1: along "
                             "each item's width, 2: along its depth; write X and Y as 1 and 2)")
    return record, floor, direction


def _motion(manifest: Path, row: Row, key: tuple[str, str, str], confirm: bool) -> FloorMotion:
    record, floor, direction = key
    text, line = row.cells["file"]
    path = Path(text) if Path(text).is_absolute() else manifest.parent / text
    units, dt = _units_dt(manifest, row, path)
    name = motion_name(record, floor, direction)
    column = row.cells["column"][0] if "column" in row.cells else None
    try:
        rec = read_record(path, units=units, dt=dt, name=name, column=column)
    except OpsrockError as exc:
        if column is not None and f"column = {column!r}" in str(exc):
            raise TableFileError(manifest, row.cells["column"][1], "column", column, str(exc)) from None
        raise TableFileError(manifest, line, "file", text, _how_to_address(str(exc))) from None
    check_plausible_record(rec, what=f"{manifest} line {row.line} ({text})", option="--accept-implausible",
                           confirm=confirm, declared_units=units, units_option="the units column")
    return FloorMotion(record, floor, direction, rec.with_name(name, floor=floor))


def _how_to_address(message: str) -> str:
    """A record reader's refusal, with how the manifest addresses a file of several columns."""
    if "pick the acceleration with column" in message:
        return message.replace("pick the acceleration with column", "pick the acceleration with the manifest's "
                               "column 'column'")
    return message


def _locations(manifest: Path, rows: list[Row]) -> tuple[tuple[str, int], ...]:
    """The ``location`` of each floor (every row or none; one per floor; distinct floors distinct)."""
    given = [r for r in rows if "location" in r.cells]
    if not given:
        return ()
    if len(given) != len(rows):
        blank = next(r for r in rows if "location" not in r.cells)
        raise TableFileError(manifest, blank.line, "location", MISSING, "blank while other rows give one: give the "
                             "location of every row's floor, or of none")
    out: dict[str, tuple[int, int]] = {}
    for r in rows:
        value, line = r.cells["location"]
        floor = r.cells["floor"][0]
        if not (value.isascii() and value.isdigit()) or int(value) < 1:
            raise TableFileError(manifest, line, "location", value, "must be a whole number >= 1 (pelicun's location: "
                                 "1 the ground floor)")
        if floor in out and out[floor][0] != int(value):
            raise TableFileError(manifest, line, "location", value, f"floor {floor!r} is at location {out[floor][0]} "
                                 f"on line {out[floor][1]}")
        other = next((f for f, (n, _) in out.items() if n == int(value) and f != floor), None)
        if other is not None:
            raise TableFileError(manifest, line, "location", value, f"floor {other!r} is at location {value} already")
        out.setdefault(floor, (int(value), line))
    return tuple((f, n) for f, (n, _) in out.items())


def read_motions(path: str | Path, *, confirm: bool = False) -> MotionSet:
    """Read a motions manifest (the module docstring).

    Parameters
    ----------
    path : str or Path
        The manifest CSV.
    confirm : bool
        True: motions whose PFA exceeds :data:`opsrock.limits.PLAUSIBLE` ``"pfa"`` are accepted (the user
        confirmed them, ``--accept-implausible``).

    Raises
    ------
    TableFileError
        Naming the manifest, its line, the column and the value (a record file's own problem quoted with its
        file and line).
    ImplausibleInputError
        A motion beyond 10 g, with its likely unit.
    """
    manifest = Path(path)
    rows = read_csv_rows(manifest, MANIFEST_COLUMNS, MANIFEST_REQUIRED)
    motions: list[FloorMotion] = []
    seen: dict[tuple[str, str, str], int] = {}
    for row in rows:
        key = _key(manifest, row)
        if key in seen:
            raise TableFileError(manifest, row.line, "record", key[0], f"floor {key[1]!r}, direction {key[2]!r} "
                                 f"listed twice (first on line {seen[key]})")
        seen[key] = row.line
        motions.append(_motion(manifest, row, key, confirm))
    return MotionSet(tuple(motions), str(manifest), locations=_locations(manifest, rows))


__all__ = ["FloorMotion", "HEADER_LINES", "MANIFEST_COLUMNS", "MANIFEST_REQUIRED", "MotionPair", "MotionSet",
           "NAME_SEPARATOR", "header_dt", "motion_name", "paired_motions", "read_motions"]
