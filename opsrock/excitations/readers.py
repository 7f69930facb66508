"""Record files: PEER NGA ``.AT2`` and plain text/CSV, read into SI :class:`Record` objects.

Formats
-------
``.AT2`` (PEER NGA strong-motion database)
    Four header lines: title, event/station/component, ``ACCELERATION TIME SERIES IN UNITS OF G``
    (the units), and ``NPTS= n, DT= dt SEC`` (the older ``n dt NPTS, DT`` order is read too);
    then the ``n`` samples, several per line. The sample count must match ``NPTS``.
Text and CSV
    One column of accelerations at a given ``dt``, or two columns ``time acceleration`` (time in
    s, uniformly spaced: every step within 0.1 % of the first). Columns are separated by commas
    (``.csv``) or white space (anything else). Lines starting with ``#`` are comments; one header
    line of names (e.g. ``time,acc``) may come first and must have as many names as the data
    has columns. A line ``dt = 0.01`` before the samples (``#`` in front, ``:`` or ``,`` for ``=``, and a
    trailing ``s`` or ``sec`` allowed; any case) states the time step of a one-column file, which then
    needs no ``dt`` argument (one that differs is refused; a two-column file's time column must agree with
    it). The units of the acceleration are not in such files and must be declared.
Several columns (``time,ax,ay``; OpenSees' ``Node`` recorder with ``-time``: the time, then one column per node
and dof)
    Read with ``column``: a header name (any case) or a 1-based index of the file's columns picks the
    acceleration; the first column is the time unless ``dt`` is given (then no column is the time).

Every problem (missing file, empty file, wrong header, non-numeric or NaN value, ragged rows,
non-uniform time step, count mismatch, missing units) raises :class:`RecordFileError` whose
message is ``"<file>:<line>: <reason>"``.
"""

from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np

from opsrock._files import not_a_file
from opsrock.errors import InputError, RecordFileError, UnknownRecordError
from opsrock.excitations.records import LIBRARY_PREFIX, UNITS, Record, RecordInfo, safe_name
from opsrock.limits import LIMITS

#: Largest relative deviation of a time step from the first one in a two-column file: time
#: columns printed with a few decimals stay far inside it, a record with a changed sampling
#: rate or a gap far outside.
DT_RTOL: float = 1e-3

def units_factor(units: str | None, *, where: str = "units") -> float:
    """Factor from ``units`` (one of :data:`UNITS`) to m/s²; ``ValueError`` naming ``where``."""
    if units not in UNITS:
        raise InputError(f"{where} must be one of {', '.join(UNITS)}; got {units!r}")
    return UNITS[units]


def read_record(path: str | Path, *, units: str | None = None, dt: float | None = None,
                name: str = "", column: str | int | None = None) -> Record:
    """Read a record into a :class:`Record` in m/s²: the one way to read a record, from a file or from the
    record library.

    Parameters
    ----------
    path : str or Path
        ``.AT2`` file (any case), a text/CSV file, or a library reference ``fema-p695:<set>/<name>``
        (:mod:`opsrock.excitations.library`, which refuses ``units`` and ``dt``: a library record has
        its own).
    units : {"g", "m/s2", "cm/s2"}, optional
        Units of a text/CSV file's accelerations (required there); for ``.AT2`` files the header
        says the units, and a different ``units`` is refused.
    dt : float, optional
        Sampling interval (s) of a one-column text/CSV file; refused for two-column files and
        ``.AT2`` files, whose own time step is used.
    name : str, optional
        Record name; default the file's stem (characters outside ``[A-Za-z0-9_.-]`` become ``_``).
    column : str or int, optional
        The acceleration column of a text/CSV file of several columns: a header name or a 1-based index (the
        first column the time, unless ``dt`` is given); refused for ``.AT2`` files (one component each).

    Raises
    ------
    RecordFileError
        Naming the file, the line and the reason.
    """
    if isinstance(path, str) and path.startswith(LIBRARY_PREFIX):
        from opsrock.excitations import library

        if units is not None or dt is not None:
            raise UnknownRecordError("units and dt apply to record files, not to library records")
        return library.load(path)
    path = Path(path)
    lines = _read_lines(path)
    name = name or safe_name(path.stem)
    if path.suffix.lower() == ".at2":
        if column is not None:
            raise RecordFileError(path, None, f"column = {column!r} given, but an .AT2 file holds one component")
        return _read_at2(path, lines, units, dt, name)
    return _read_text(path, lines, units, dt, name, column)


def _read_lines(path: Path) -> list[str]:
    limit = LIMITS["record_file_bytes"]
    kind = not_a_file(path)  # a device reports size 0 and never ends; a FIFO blocks: neither is opened
    if kind is not None:
        raise RecordFileError(path, None, f"is {kind}, not a record file")
    try:
        size = path.stat().st_size
    except FileNotFoundError:
        raise RecordFileError(path, None, "no such file") from None
    except OSError as exc:
        raise RecordFileError(path, None, f"cannot be read: {exc.strerror or exc}") from None
    if size > limit.high:
        raise RecordFileError(path, None, _too_big(size, limit.high))
    try:
        with open(path, "rb") as fh:
            data = fh.read(int(limit.high) + 1)  # a hard cap: the file may have grown since stat
        if len(data) > limit.high:
            raise RecordFileError(path, None, _too_big(len(data), limit.high))
        # utf-8-sig: a byte-order mark is not part of the first line (a one-column file would lose its
        # first sample to a "header")
        text = data.decode("utf-8-sig", errors="strict")
    except IsADirectoryError:
        raise RecordFileError(path, None, "is a folder, not a record file") from None
    except PermissionError:
        raise RecordFileError(path, None, "cannot be read: permission denied") from None
    except UnicodeDecodeError as exc:
        raise RecordFileError(path, None, f"not a text file ({exc.reason} at byte {exc.start})") from None
    except OSError as exc:
        raise RecordFileError(path, None, f"cannot be read: {exc.strerror or exc}") from None
    lines = text.splitlines()
    if not any(line.strip() for line in lines):
        raise RecordFileError(path, None, "empty file: no samples")
    return lines


def _too_big(size: float, high: float) -> str:
    return f"{size / 1e6:.1f} MB is more than the {high / 1e6:.0f} MB a record file may hold (4 million samples); not read"


def _numbers(path: Path, lineno: int, tokens: list[str]) -> list[float]:
    out = []
    for tok in tokens:
        try:
            v = float(tok)
        except ValueError:
            raise RecordFileError(path, lineno, f"{tok!r} is not a number") from None
        if not np.isfinite(v):
            raise RecordFileError(path, lineno, f"{tok!r} is not a finite number")
        out.append(v)
    return out


# --- PEER NGA .AT2 ------------------------------------------------------------------------------
_AT2_NPTS = re.compile(r"NPTS\s*=\s*(\d+)\s*,?\s*DT\s*=\s*([0-9.eE+-]+)", re.IGNORECASE)
_AT2_OLD = re.compile(r"^\s*(\d+)\s+([0-9.eE+-]+)\s+NPTS\s*,\s*DT", re.IGNORECASE)
_AT2_UNITS = re.compile(r"UNITS\s+OF\s+(G|CM/S(?:\^?2|/S)|M/S(?:\^?2|/S))\b", re.IGNORECASE)


def _at2_units(path: Path, line: str) -> str:
    m = _AT2_UNITS.search(line)
    if not m:
        raise RecordFileError(path, 3, f"wrong header: expected 'ACCELERATION ... IN UNITS OF G' "
                                       f"(the units), got {line.strip()[:60]!r}")
    unit = m.group(1).upper()
    return "g" if unit == "G" else ("cm/s2" if unit.startswith("CM") else "m/s2")


def _read_at2(path: Path, lines: list[str], units: str | None, dt: float | None, name: str) -> Record:
    if len(lines) < 5:
        raise RecordFileError(path, len(lines), "wrong header: a PEER .AT2 file has 4 header lines and then samples")
    file_units = _at2_units(path, lines[2])
    if units is not None and units != file_units:
        raise RecordFileError(path, 3, f"the header says units of {file_units}, but units = {units!r} was given")
    if dt is not None:
        raise RecordFileError(path, 4, f"dt = {dt!r} given, but an .AT2 file states its own DT")
    m = _AT2_NPTS.search(lines[3]) or _AT2_OLD.search(lines[3])
    if not m:
        raise RecordFileError(path, 4, f"wrong header: expected 'NPTS= n, DT= dt SEC', got {lines[3].strip()[:60]!r}")
    try:
        npts, step = int(m.group(1)), float(m.group(2))
    except ValueError:
        raise RecordFileError(path, 4, f"NPTS = {m.group(1)!r}, DT = {m.group(2)!r}: not numbers") from None
    if not (np.isfinite(step) and step > 0):
        raise RecordFileError(path, 4, f"DT = {m.group(2)!r} must be positive")
    values = _at2_values(path, lines)
    if len(values) != npts:
        raise RecordFileError(path, len(lines), f"the header says NPTS = {npts}, the file holds {len(values)} samples")
    info = RecordInfo(source=str(path), event=lines[1].split(",")[0].strip(), units_in_file=file_units,
                      component=lines[1].split(",")[-1].strip() if "," in lines[1] else "")
    return _record(path, step, np.asarray(values), file_units, name, info)


def _at2_values(path: Path, lines: list[str]) -> np.ndarray:
    """The samples after an .AT2 file's 4 header lines, several per line: numpy converts the tokens all at once (each
    the double Python's ``float`` gives it); a token it cannot read, or a value that is not finite, is found again
    line by line to name its line."""
    try:
        values = np.array(" ".join(lines[4:]).split(), dtype=float)
    except ValueError:
        values = None
    if values is None or not np.isfinite(values).all():
        found: list[float] = []
        for lineno, line in enumerate(lines[4:], start=5):
            found.extend(_numbers(path, lineno, line.split()))
        values = np.asarray(found, dtype=float)
    return values


# --- text / CSV ---------------------------------------------------------------------------------
_DT_LINE = re.compile(r"^#?\s*dt\s*[=:,]?\s*([0-9.eE+-]+)\s*(?:s|sec|seconds)?\s*,?\s*$", re.IGNORECASE)


def _dt_line(path: Path, lines: list[str]) -> tuple[int, float] | None:
    """``(line number, dt)`` of a ``dt = ...`` line before the samples, or None."""
    for lineno, raw in enumerate(lines, start=1):
        line = raw.strip()
        m = _DT_LINE.match(line)
        if m:
            try:
                step = float(m.group(1))
            except ValueError:
                raise RecordFileError(path, lineno, f"dt = {m.group(1)!r} is not a number") from None
            if not (np.isfinite(step) and step > 0):
                raise RecordFileError(path, lineno, f"dt = {m.group(1)!r} must be positive")
            return lineno, step
        if line and not line.startswith("#") and _looks_numeric(line.replace(",", " ").split()[0]):
            return None  # the samples have begun
    return None


def _data_rows(path: Path, lines: list[str]) -> tuple[list[tuple[int, list[str]]], list[str] | None]:
    sep = "," if path.suffix.lower() == ".csv" else None
    rows: list[tuple[int, list[str]]] = []
    header = None
    for lineno, raw in enumerate(lines, start=1):
        line = raw.strip()
        if not line or line.startswith("#") or (not rows and _DT_LINE.match(line)):
            continue
        tokens = [t.strip() for t in line.split(sep)] if sep else line.split()
        if not rows and header is None and not _looks_numeric(tokens[0]):
            header = tokens
            header_line = lineno
            continue
        rows.append((lineno, tokens))
    if not rows:
        raise RecordFileError(path, None, "empty file: no samples (only comments or a header)")
    ncol = len(rows[0][1])
    if header is not None and len(header) != ncol:
        raise RecordFileError(path, header_line, f"wrong header: {len(header)} names {header} for {ncol} data column(s)")
    return rows, header


def _looks_numeric(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return token.lower() in ("nan", "inf", "-inf", "+inf")
    return True


def _head(path: Path, lines: list[str]) -> tuple[int, list[str] | None, int | None] | None:
    """Where the samples begin, as :func:`_data_rows` reads a file: ``(index of the first data line, header names
    or None, the header's line number or None)``, looking at the leading lines only; None without samples."""
    sep = "," if path.suffix.lower() == ".csv" else None
    header = header_line = None
    for index, raw in enumerate(lines):
        line = raw.strip()
        if not line or line.startswith("#") or _DT_LINE.match(line):
            continue
        tokens = [t.strip() for t in line.split(sep)] if sep else line.split()
        if header is None and not _looks_numeric(tokens[0]):
            header, header_line = tokens, index + 1
            continue
        return index, header, header_line
    return None


def _fast_table(path: Path, lines: list[str]) -> tuple[np.ndarray, list[str] | None, int] | None:
    """The samples of a well-formed text/CSV file, read by numpy's C parser (about 20 times faster than
    :func:`_data_rows` on a file of millions of samples): ``(data, header, line number of the first sample)``,
    each value the same double as Python's ``float`` gives. None whenever the careful reading is needed to accept
    or to name a fault: a comment or ``#`` among the samples, ragged rows, a token numpy does not read, a value
    that is not finite, a header that does not fit; :func:`_data_rows` then reads the file and names the line."""
    head = _head(path, lines)
    if head is None:
        return None
    start, header, _ = head
    body = "\n".join(lines[start:])
    if "#" in body:
        return None
    try:
        data = np.loadtxt(io.StringIO(body), delimiter="," if path.suffix.lower() == ".csv" else None,
                          comments=None, ndmin=2, dtype=float)
    except ValueError:
        return None
    if data.size == 0 or not np.isfinite(data).all() or (header is not None and len(header) != data.shape[1]):
        return None
    return data, header, start + 1


def _sample_line(lines: list[str], first: int, i: int) -> int:
    """The line number of sample row ``i`` (0-based) of a table whose first sample is on line ``first``: blank
    lines between samples are skipped (used only to name a fault, so a rescan is cheap enough)."""
    seen = -1
    for lineno in range(first, len(lines) + 1):
        if lines[lineno - 1].strip():
            seen += 1
            if seen == i:
                return lineno
    return len(lines)


def _table(path: Path, lines: list[str]) -> tuple[np.ndarray, list[str] | None, object]:
    """The samples of a text/CSV file as a 2-D array, its header names (or None), and the line number of sample
    row ``i`` as a function of ``i`` (to name a fault): numpy's fast reading when the file is well formed, else the
    careful one, which names the first line at fault."""
    fast = _fast_table(path, lines)
    if fast is not None:
        data, header, first = fast
        return data, header, lambda i: _sample_line(lines, first, i)
    rows, header = _data_rows(path, lines)
    ncol = len(rows[0][1])
    data = np.empty((len(rows), ncol))
    for i, (lineno, tokens) in enumerate(rows):
        if len(tokens) != ncol:
            raise RecordFileError(path, lineno, f"{len(tokens)} column(s) where the first data row has {ncol}")
        data[i] = _numbers(path, lineno, tokens)
    return data, header, lambda i: rows[i][0]


def _read_text(path: Path, lines: list[str], units: str | None, dt: float | None, name: str,
               column: str | int | None = None) -> Record:
    if units is None:
        raise RecordFileError(path, None, "units missing: a text/CSV record needs units = g, m/s2 or cm/s2")
    units_factor(units)
    data, header, line_of = _table(path, lines)
    ncol = data.shape[1]
    if column is not None:
        return _read_column(path, lines, (data, header, line_of), (units, dt, name), column)
    if ncol not in (1, 2):
        names = f" ({', '.join(header)})" if header else ""
        raise RecordFileError(path, line_of(0), f"{ncol} columns{names}: expected 1 (acceleration) or 2 (time, "
                                                "acceleration); pick the acceleration with column (a header name or "
                                                "a 1-based index, the first column the time)")
    stated = _dt_line(path, lines)
    if ncol == 1:
        dt = _one_column_dt(path, dt, stated)
        acc = data[:, 0]
    else:
        if dt is not None:
            raise RecordFileError(path, None, f"dt = {dt!r} given, but the file has a time column")
        dt = _uniform_step(path, line_of, data[:, 0])
        if stated is not None and abs(stated[1] - dt) > DT_RTOL * dt:
            raise RecordFileError(path, stated[0], f"dt = {stated[1]!r} s, but the time column steps by {dt:.6g} s")
        acc = data[:, 1]
    info = RecordInfo(source=str(path), units_in_file=units)
    return _record(path, dt, acc, units, name, info)


def _column_index(path: Path, header: list[str] | None, ncol: int, column: str | int) -> int:
    """The 0-based index of ``column`` (a header name, any case, or a 1-based index as int or digits)."""
    text = str(column).strip()
    if isinstance(column, int) or (text.isascii() and text.isdigit()):
        k = int(text)
        if not 1 <= k <= ncol:
            raise RecordFileError(path, None, f"column = {column!r}: the file has {ncol} columns (1 to {ncol})")
        return k - 1
    names = [h.lower() for h in header or ()]
    if text.lower() not in names:
        known = f"its header names {', '.join(header)}" if header else "it has no header row of names"
        raise RecordFileError(path, None, f"column = {column!r} is not a column of the file ({known}; or give a "
                                          f"1-based index, 1 to {ncol})")
    return names.index(text.lower())


def _read_column(path: Path, lines: list[str], table: tuple, how: tuple, column: str | int) -> Record:
    """One acceleration column of a file of several (``table`` as :func:`_table` gives it): the first column the
    time unless ``dt`` is given."""
    units, dt, name = how
    data, header, line_of = table
    k = _column_index(path, header, data.shape[1], column)
    if dt is None and k == 0:
        raise RecordFileError(path, None, f"column = {column!r} is the first column, the time (give dt if the file has "
                                          "no time column)")
    stated = _dt_line(path, lines)
    if dt is None:
        dt = _uniform_step(path, line_of, data[:, 0])
        if stated is not None and abs(stated[1] - dt) > DT_RTOL * dt:
            raise RecordFileError(path, stated[0], f"dt = {stated[1]!r} s, but the time column steps by {dt:.6g} s")
    elif stated is not None and abs(dt - stated[1]) > DT_RTOL * stated[1]:
        raise RecordFileError(path, stated[0], f"the file states dt = {stated[1]!r} s, but dt = {dt!r} was given")
    info = RecordInfo(source=f"{path} column {column}", units_in_file=units)
    return _record(path, dt, data[:, k], units, name, info)


def _one_column_dt(path: Path, dt: float | None, stated: tuple[int, float] | None) -> float:
    """The time step of a one-column file: ``dt`` given, or its ``dt =`` line; both must agree."""
    if stated is None:
        if dt is None:
            raise RecordFileError(path, None, "one-column record: give its time step dt (s), or a line 'dt = ...' "
                                              "before the samples")
        return dt
    if dt is not None and abs(dt - stated[1]) > DT_RTOL * stated[1]:
        raise RecordFileError(path, stated[0], f"the file states dt = {stated[1]!r} s, but dt = {dt!r} was given")
    return stated[1]


def _uniform_step(path: Path, line_of, times: np.ndarray) -> float:
    """The time step of a time column ``times``; ``line_of(i)`` is the line number of sample ``i`` (a fault's)."""
    if times.size < 2:
        raise RecordFileError(path, line_of(0), "a two-column record needs at least 2 samples")
    steps = np.diff(times)
    step = float(steps[0])
    if step <= 0:
        raise RecordFileError(path, line_of(1), f"time does not increase ({times[0]!r} then {times[1]!r})")
    bad = np.flatnonzero(np.abs(steps - step) > DT_RTOL * step)
    if bad.size:
        i = int(bad[0])
        raise RecordFileError(path, line_of(i + 1), f"non-uniform time step: {steps[i]!r} s after {step!r} s "
                                                    f"(resample the record to a constant step)")
    return (float(times[-1]) - float(times[0])) / (times.size - 1)


def _record(path: Path, dt: float, values: np.ndarray, units: str, name: str, info: RecordInfo) -> Record:
    """The record of ``values`` in ``units`` (converted to m/s² by :class:`Record`)."""
    try:
        return Record(dt=dt, values=values, name=name, info=info, units=units)
    except (TypeError, ValueError) as exc:
        raise RecordFileError(path, None, str(exc)) from None


__all__ = ["DT_RTOL", "LIBRARY_PREFIX", "RecordFileError", "UNITS", "read_record", "units_factor"]
