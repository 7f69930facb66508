"""The readers of the tables a user gives (an inventory, a motions manifest): a CSV file with a header row or a
TOML file of ``[[table]]`` entries, read as :class:`Row` objects (each cell with its line) before any value is
interpreted, and the cell readers every table shares (:func:`number_cell`, :func:`text_cell`). A bad file is a
:class:`TableFileError` naming the file, the line, the column and the value.

The bottom layer of the studies: it reads files and knows nothing of items, motions or campaigns.
"""

from __future__ import annotations

import csv
import io
import math
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from opsrock._files import not_a_file
from opsrock.errors import MISSING, InputError

#: Separator of several labels in one cell (``1;2;roof``): a TOML array of labels is joined with it.
LIST_SEPARATOR: str = ";"

#: Largest inventory or manifest file read (bytes): a table of a million rows; larger files are refused unread.
MAX_TABLE_BYTES: int = 64_000_000

_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$", re.ASCII)  # ASCII digits only: float()
# also reads Arabic-Indic or full-width digits, which the guide's "plain decimals" do not include


class TableFileError(InputError):
    """A bad inventory or motions-manifest file; the message names the file, the line, the column and the value.

    Parameters
    ----------
    path : str or Path
        The file.
    line : int or None
        Its line (1-based); None when the file as a whole is at fault.
    column : str or None
        The column (``argument`` of the error); None for the file or a row as a whole.
    value : object
        The cell's value (:data:`opsrock.errors.MISSING` when there is none to show).
    problem : str
        What is wrong.
    """

    def __init__(self, path: str | Path, line: int | None, column: str | None, value: Any, problem: str) -> None:
        where = f"{path}:{line}" if line else f"{path}"
        cell = "" if column is None else (f"{column}: " if value is MISSING else f"{column} = {value!r}: ")
        super().__init__(f"{where}: {cell}{problem}", argument=column)
        self.path, self.line, self.column, self.value, self.problem = str(path), line, column, value, problem


# --- reading rows -----------------------------------------------------------------------------------
@dataclass(frozen=True)
class Row:
    """One row of an inventory or manifest file, before its values are interpreted.

    Parameters
    ----------
    line : int
        Its line in the file (the ``[[item]]`` line of a TOML table).
    cells : dict
        Column -> ``(value, line)`` for every non-blank cell: text (CSV, trimmed) or a TOML value.
    typed : bool
        True for a TOML table, whose numbers must be TOML numbers (not strings).
    """

    line: int
    cells: dict[str, tuple[Any, int]]
    typed: bool = False


def read_text_file(path: Path) -> str:
    """The text of an inventory or manifest ``path`` (UTF-8, a byte-order mark dropped); ``TableFileError``
    naming the file when it cannot be read."""
    kind = not_a_file(path)
    if kind is not None:
        raise TableFileError(path, None, None, MISSING, f"is {kind}, not a file")
    try:
        with open(path, "rb") as fh:
            data = fh.read(MAX_TABLE_BYTES + 1)
    except FileNotFoundError:
        raise TableFileError(path, None, None, MISSING, "no such file") from None
    except OSError as exc:
        raise TableFileError(path, None, None, MISSING, f"cannot be read: {exc.strerror or exc}") from None
    if len(data) > MAX_TABLE_BYTES:
        raise TableFileError(path, None, None, MISSING, f"larger than {MAX_TABLE_BYTES / 1e6:.0f} MB; not read")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise TableFileError(path, None, None, MISSING, f"not UTF-8 text ({exc.reason} at byte {exc.start})") from None


def read_csv_rows(path: str | Path, known: tuple[str, ...], required: tuple[str, ...]) -> list[Row]:
    """The rows of a CSV table with a header row: ``#`` comment lines and blank lines skipped, names and cells
    trimmed, names matched without case; blank cells left out.

    Parameters
    ----------
    path : str or Path
        The file.
    known, required : tuple of str
        The columns it may have, and those it must have.

    Raises
    ------
    TableFileError
        An unknown, repeated or missing column, a row with more cells than the header, an empty file.
    """
    path = Path(path)
    lines = read_text_file(path).splitlines()
    text = "\n".join("" if ln.strip().startswith("#") else ln for ln in lines)
    reader = csv.reader(io.StringIO(text), skipinitialspace=True, strict=True)
    header: list[str] | None = None
    rows: list[Row] = []
    try:
        for cells in reader:
            cells = [c.strip() for c in cells]
            if not any(cells):
                continue
            if header is None:
                header, header_line = _header(path, reader.line_num, cells, known, required), reader.line_num
                continue
            rows.append(_csv_row(path, reader.line_num, header, cells))
    except csv.Error as exc:
        raise TableFileError(path, reader.line_num, None, MISSING, f"not valid CSV: {exc}") from None
    if header is None:
        raise TableFileError(path, None, None, MISSING, f"empty file: no header row (columns {', '.join(required)} "
                             "at least)")
    if not rows:
        raise TableFileError(path, header_line, None, MISSING, "no rows after the header")
    return rows


def _header(path: Path, line: int, cells: list[str], known: tuple[str, ...], required: tuple[str, ...]) -> list[str]:
    names = [c.lower() for c in cells]
    while names and not names[-1]:  # trailing empty names (a spreadsheet's trailing commas)
        names.pop()
    for name in names:
        if name not in known:
            problem = "an unnamed column" if not name else "unknown column"
            raise TableFileError(path, line, "header", name, f"{problem} (known: {', '.join(known)})")
        if names.count(name) > 1:
            raise TableFileError(path, line, "header", name, "column named twice")
    missing = [c for c in required if c not in names]
    if missing:
        raise TableFileError(path, line, "header", ",".join(cells), f"lacks the column(s) {', '.join(missing)} "
                             f"(required: {', '.join(required)})")
    return names


def _csv_row(path: Path, line: int, header: list[str], cells: list[str]) -> Row:
    extra = [c for c in cells[len(header):] if c]
    if extra:
        raise TableFileError(path, line, None, MISSING, f"{len(cells)} cells where the header names {len(header)} "
                             f"columns (first extra value {extra[0]!r}; quote a cell that holds a comma, "
                             '"uniform(0.3, 0.5)")')
    return Row(line, {name: (value, line) for name, value in zip(header, cells) if value})


def read_toml_rows(path: str | Path, table: str, known: tuple[str, ...], required: tuple[str, ...]) -> list[Row]:
    """The ``[[<table>]]`` tables of a TOML file as rows, with the line of each key; other top-level keys,
    unknown and missing keys refused (``TableFileError``)."""
    path = Path(path)
    text = read_text_file(path)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise TableFileError(path, None, None, MISSING, f"not valid TOML: {exc}") from None
    extra = sorted(set(data) - {table})
    if extra:
        raise TableFileError(path, None, extra[0], MISSING, f"unknown key: the file holds [[{table}]] tables only")
    entries = data.get(table)
    if not isinstance(entries, list) or not entries or not all(isinstance(e, dict) for e in entries):
        raise TableFileError(path, None, table, MISSING, f"needs at least one [[{table}]] table")
    where = _toml_lines(text, table)
    rows = []
    for k, entry in enumerate(entries):
        head, keys = where[k] if k < len(where) else (None, {})
        for key in entry:
            if key not in known:
                raise TableFileError(path, keys.get(key, head), key, entry[key], f"unknown key (known: {', '.join(known)})")
        for key in required:
            if key not in entry:
                raise TableFileError(path, head, key, MISSING, f"missing in [[{table}]] number {k + 1}")
        rows.append(Row(head or 0, {key: (_toml_cell(v), keys.get(key, head or 0)) for key, v in entry.items()
                                    if not (isinstance(v, str) and not v.strip())}, typed=True))
    return rows


def _toml_cell(value: Any) -> Any:
    """A TOML value as a cell: strings trimmed, an array of labels joined like a CSV cell, the rest as is."""
    if isinstance(value, str):
        return value.strip()
    if isinstance(value, list) and all(isinstance(v, (str, int)) and not isinstance(v, bool) for v in value):
        return LIST_SEPARATOR.join(str(v) for v in value)
    return value


_TOML_TABLE = re.compile(r"^\s*\[\[\s*([A-Za-z0-9_-]+)\s*\]\]")
_TOML_KEY = re.compile(r"""^\s*["']?([A-Za-z0-9_-]+)["']?\s*=""")


def _toml_lines(text: str, table: str) -> list[tuple[int, dict[str, int]]]:
    """For each ``[[table]]``: its line and the line of each of its keys (a plain scan of the text: a key
    written elsewhere, in an inline table, is not found and is then named by its table's line)."""
    out: list[tuple[int, dict[str, int]]] = []
    inside = False
    for n, line in enumerate(text.splitlines(), start=1):
        head = _TOML_TABLE.match(line)
        if head or line.lstrip().startswith("["):
            inside = bool(head) and head.group(1) == table
            if inside:
                out.append((n, {}))
            continue
        key = _TOML_KEY.match(line)
        if inside and key:
            out[-1][1].setdefault(key.group(1), n)
    return out


def number_cell(value: Any) -> float:
    """A cell's number: a plain decimal text (``0.32``, ``1e-3``; no ``nan``, ``inf``, ``_`` or hex) or a TOML
    number; ``InputError`` otherwise."""
    if isinstance(value, str):
        if not _NUMBER.match(value):
            raise InputError("is not a number")
        v = float(value)
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        v = float(value)
    else:
        raise InputError(f"must be a number, not {type(value).__name__}")
    if not math.isfinite(v):
        raise InputError("is not a finite number")
    return v


def text_cell(value: Any) -> str:
    """A cell's text: a string (a TOML number is refused, a CSV cell is text already) without control
    characters (a NUL byte or a tab inside a cell is a damaged file, not a name)."""
    if not isinstance(value, str):
        raise InputError(f"must be a string, not {type(value).__name__}")
    bad = next((ch for ch in value if ord(ch) < 32 or ord(ch) == 127), None)
    if bad is not None:
        raise InputError(f"holds the control character U+{ord(bad):04X} (a damaged file?)")
    return value


__all__ = ["LIST_SEPARATOR", "MAX_TABLE_BYTES", "Row", "TableFileError", "number_cell", "read_csv_rows", "read_text_file",
           "read_toml_rows", "text_cell"]
