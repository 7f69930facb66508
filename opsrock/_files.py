"""Files opsrock writes: output paths checked before any work, and atomic writes.

* :func:`output_file`, :func:`output_dir`: checks of output paths given by the user, made before
  any work starts. Each raises ``ValueError`` with one line naming the argument and the path, so a
  bad path is refused up front instead of failing after the computation, half-written.
  Writability is probed by creating and removing a file, which is right for every user, root
  included (``os.access`` says yes to root on a read-only folder it could not write to on a
  read-only mount, and the reverse).
* :func:`atomic_write`, :func:`atomic_text`, :func:`atomic_csv`: every output goes through a
  temporary file in the same folder and a rename, so an interrupted run never leaves a
  half-written file. Data files keep full precision.
* :func:`not_a_file`, :func:`input_file`: the check every file opsrock reads passes first (records, scenes,
  blocks files): a regular file, never a device, a FIFO, a socket or a folder. A character device reports
  size 0 (``/dev/zero`` would pass a size limit and then fill the memory) and a FIFO blocks the reader.
* :data:`UNITS_ROW`, :func:`units_row_text`, :func:`read_units`, :func:`write_units_table`,
  :func:`read_units_table`: the units row of a table (the SimCenter tabular
  form pelicun reads and writes: the header, then a row whose first cell is ``Units`` and whose other cells give
  each column's unit), written and read the same way by every layer that writes one (the campaign's
  ``cases.csv``, the contents study's tables); each layer defines its own columns' units.
* :func:`staged_folder`: a report folder written whole or not at all, that holds only the new run's
  outputs afterwards (:func:`remove_stale` removes an earlier run's outputs that the new run does not
  write, and only those: files a writer does not own are kept).
"""

from __future__ import annotations

import contextlib
import csv
import io
import os
import shutil
import stat
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Iterator, Sequence

if TYPE_CHECKING:
    import pandas as pd

from opsrock._pool import deferred_interrupts
from opsrock.errors import InputError


#: What a path that is not a regular file is, by its ``stat`` type.
_KINDS: tuple[tuple[Callable[[int], bool], str], ...] = (
    (stat.S_ISDIR, "a folder"), (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISSOCK, "a socket"))


def not_a_file(path: str | os.PathLike) -> str | None:
    """What ``path`` is when it exists and is not a regular file (``"a character device"``, ``"a folder"``,
    ...); None for a regular file (symbolic links followed) or a path that cannot be looked at (the reader
    then says why: missing, permission denied). Never opens the path (opening a FIFO would block)."""
    try:
        mode = os.stat(path).st_mode
    except (OSError, ValueError):
        return None
    if stat.S_ISREG(mode):
        return None
    return next((kind for test, kind in _KINDS if test(mode)), "not a regular file")


def input_file(name: str, path: str | os.PathLike) -> Path:
    """Check that ``path``, given as ``name`` (an option, ``"--record"``), is not a device, a FIFO, a socket
    or a folder; return it. Raises ``InputError`` ``"<name> '<path>': is a character device, not a file"``.
    A missing or unreadable path passes: the reader names that itself."""
    kind = not_a_file(path)
    if kind is not None:
        raise InputError(f"{name} {str(path)!r}: is {kind}, not a file")
    return Path(path)


def _probe_writable(name: str, shown: str, folder: Path) -> None:
    try:
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".opsrock-write-probe-")
    except OSError as exc:
        raise InputError(f"{name} {shown!r}: cannot write in folder {str(folder)!r} ({exc.strerror})") from None
    os.close(fd)
    os.unlink(probe)


def output_file(name: str, path: str | os.PathLike, suffix: str | None = None) -> Path:
    """Check that ``path`` can be written as a file, in an existing folder; return it.

    Parameters
    ----------
    name : str
        Argument name for the message (``"--plot"``).
    path : str or path-like
        The file to write.
    suffix : str, optional
        Required suffix, case-insensitive (``".png"``).
    """
    shown = str(path)
    if not shown.strip():
        raise InputError(f"{name} must name a file, got {shown!r}")
    p = Path(path)
    if suffix is not None and p.suffix.lower() != suffix:
        raise InputError(f"{name} must name a {suffix} file, got {shown!r}")
    parent = p.parent if str(p.parent) else Path(".")
    try:
        if p.is_dir():
            raise InputError(f"{name} {shown!r} is a folder; give a file name")
        parent_is_dir = parent.is_dir()
    except OSError as exc:  # a folder on the way that this user may not enter
        raise InputError(f"{name} {shown!r}: cannot write there ({exc.strerror or exc})") from None
    if not parent_is_dir:
        raise InputError(f"{name} {shown!r}: folder {str(parent)!r} does not exist")
    _probe_writable(name, shown, parent)
    return p


def output_dir(name: str, path: str | os.PathLike) -> Path:
    """Check that ``path`` is, or can be created as, a writable folder; return it.

    Missing folders are not created here (the caller creates them once the inputs are known
    to be good); the nearest existing ancestor must be a writable folder.
    """
    shown = str(path)
    if not shown.strip():
        raise InputError(f"{name} must name a folder, got {shown!r} (use '.' for the current folder)")
    p = Path(path)
    try:
        if p.exists() and not p.is_dir():
            raise InputError(f"{name} {shown!r} is a file, not a folder")
        ancestor = p
        while not ancestor.exists():
            if ancestor.parent == ancestor:
                break
            ancestor = ancestor.parent
        is_dir = ancestor.is_dir()
    except OSError as exc:  # a folder on the way that this user may not enter
        raise InputError(f"{name} {shown!r}: cannot write there ({exc.strerror or exc})") from None
    if not is_dir:
        raise InputError(f"{name} {shown!r}: {str(ancestor)!r} is a file, not a folder")
    _probe_writable(name, shown, ancestor)
    return p


def atomic_write(path: Path, write: Callable[[Any], None], *, binary: bool = False, durable: bool = True) -> None:
    """Write ``path`` by ``write(file_handle)`` through a temporary file and an atomic rename.

    Parameters
    ----------
    path : Path
        Target file.
    write : callable
        Writes the content to the open handle.
    binary : bool, optional
        Open in binary mode.
    durable : bool, optional
        ``fsync`` the file and the folder, so the rename survives a power cut (the campaign's
        store needs it; reports do not).
    """
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    try:
        with (open(tmp, "wb") if binary else open(tmp, "w", newline="", encoding="utf-8")) as fh:
            write(fh)
            if durable:
                fh.flush()
                os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
    if durable:
        dir_fd = os.open(path.parent, os.O_RDONLY)
        try:
            os.fsync(dir_fd)
        finally:
            os.close(dir_fd)


@contextlib.contextmanager
def staged_folder(out: str | os.PathLike, owned: Sequence[str] = ()) -> Iterator[Path]:
    """A folder of outputs written whole or not at all, holding only this run's outputs.

    Yields a new temporary folder beside ``out``; when the block ends normally, every file in it
    replaces its namesake in ``out`` (created if missing), each by an atomic rename, and then every
    file of ``out`` that matches one of the ``owned`` patterns but was not written now is removed (an
    earlier run's output that this run does not write: the figure of an item no longer studied, the
    table of a variant left out), with the folders that leaves empty. Files that match no pattern (a
    campaign's store, the user's own files) are never touched, and nothing is removed through a
    symbolic link out of ``out``. When the block raises (a failure, Ctrl-C), the temporary folder and
    any folder made for it are removed and ``out`` is left as it was: a failed command leaves nothing
    half-written.

    Parameters
    ----------
    out : str or path-like
        The output folder.
    owned : sequence of str
        Glob patterns, relative to ``out`` (``"report.md"``, ``"figures/*.png"``), of every output the
        writer owns; empty: nothing is removed.
    """
    out = Path(out)
    made = [d for d in (out, *out.parents) if not d.exists()][::-1][:-1]  # missing ancestors of out
    for d in made:
        d.mkdir()
    stage = None
    try:
        with deferred_interrupts():  # made and named together: a Ctrl-C here is raised once `stage` is known
            stage = Path(tempfile.mkdtemp(prefix=f".{out.name or 'out'}.staging-", dir=out.parent))
        yield stage
        out.mkdir(exist_ok=True)
        written = set()
        for f in sorted(stage.rglob("*")):
            if f.is_file():
                rel = f.relative_to(stage)
                dest = out / rel
                dest.parent.mkdir(parents=True, exist_ok=True)
                os.replace(f, dest)
                written.add(rel)
    except BaseException:
        if stage is not None:
            shutil.rmtree(stage, ignore_errors=True)
        for d in reversed(made):
            with contextlib.suppress(OSError):
                d.rmdir()
        raise
    # The outputs are in place: a Ctrl-C now waits for the clean-up, which it interrupted once (a fresh clone's
    # make test found the staging folder left beside the finished report).
    with deferred_interrupts():
        shutil.rmtree(stage, ignore_errors=True)
        remove_stale(out, owned, written)


def remove_stale(out: Path, owned: Sequence[str], keep: set[Path]) -> list[Path]:
    """Remove the files of ``out`` that match a pattern of ``owned`` (globs relative to ``out``) and are
    not in ``keep`` (paths relative to ``out``), then the folders of ``out`` that this leaves empty;
    returns the removed files. Only regular files and symbolic links found inside ``out`` itself are
    removed (a link is removed, never what it points to; a folder reached through a link is skipped)."""
    root = out.resolve()
    removed = []
    for pattern in owned:
        for p in sorted(out.glob(pattern)):
            rel = p.relative_to(out)
            if rel in keep or not (p.is_symlink() or p.is_file()) or p.parent.resolve() != root / rel.parent:
                continue
            p.unlink()
            removed.append(rel)
    for folder in sorted({r.parent for r in removed if r.parent != Path(".")}, key=lambda r: -len(r.parts)):
        with contextlib.suppress(OSError):  # not empty (a file the user keeps there): leave it
            (out / folder).rmdir()
    return [out / r for r in removed]


def atomic_text(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically."""
    atomic_write(Path(path), lambda fh: fh.write(text), durable=False)


def atomic_metrics(path: Path, metrics: dict) -> None:
    """Write a ``metric,value`` table atomically, every value at full precision as Python writes it (a numpy
    scalar as the Python number it holds: numpy 2's ``repr`` is ``np.float64(0.25)``, which no spreadsheet reads)."""
    def text(v: Any) -> str:
        return repr(v.item() if hasattr(v, "item") and hasattr(v, "dtype") else v)

    atomic_text(path, "metric,value\n" + "".join(f"{k},{text(v)}\n" for k, v in metrics.items()))


def atomic_csv(path: Path, df: "pd.DataFrame") -> None:
    """Write ``df`` (no index) to ``path`` atomically, at full precision (``repr`` of every float)."""
    atomic_write(Path(path), lambda fh: df.to_csv(fh, index=False), durable=False)


def read_table(path: str | os.PathLike, **options: Any) -> "pd.DataFrame":
    """A CSV table that opsrock wrote, read back to the last bit: every float exactly as written, on every
    pandas of the declared range. pandas 2's default C parser may differ from the written value in the last
    digit, so it is given ``float_precision="round_trip"`` (the shortest-repr rule the writer used); pandas 3.1
    parses every float exactly whatever the option and deprecates it (:func:`exact_float_options`).

    Parameters
    ----------
    path : str or PathLike
        The CSV file.
    **options
        Further keyword arguments of :func:`pandas.read_csv` (``usecols``, ``dtype``, ``index_col``).
    """
    import pandas as pd  # lazy: the command line's start-up does not need pandas

    return pd.read_csv(path, **exact_float_options(), **options)


def exact_float_options() -> dict[str, str]:
    """The :func:`pandas.read_csv` keywords that read every float exactly as written, on this pandas: none from
    pandas 3.1 (one exact converter for every mode; ``float_precision`` deprecated), else
    ``float_precision="round_trip"``."""
    import pandas as pd

    major, minor = (int(part) for part in pd.__version__.split(".")[:2])
    return {} if (major, minor) >= (3, 1) else {"float_precision": "round_trip"}


#: The first cell of a table's units row (pelicun's spelling, ``pelicun.file_io.load_data``).
UNITS_ROW: str = "Units"


def units_row_text(names: Sequence[str], units: Sequence[str]) -> str:
    """The first two lines of a table with a units row: the header ``names``, then ``Units`` and the units of the
    columns after the first (``units[0]``, the first column's, must be empty: a label or an id has no unit)."""
    if len(names) != len(units):
        raise ValueError(f"{len(names)} columns but {len(units)} units")
    if units and units[0]:
        raise ValueError(f"the first column of a table with a units row has no unit, not {names[0]!r}: {units[0]!r}")
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(list(names))
    w.writerow([UNITS_ROW, *units[1:]])
    return buf.getvalue()


def read_units(path: str | os.PathLike) -> tuple[list[str], list[str] | None]:
    """The header of the CSV table at ``path`` and its units (column by column, the first column's ``""``), or
    None when the second row is not a units row (its first cell is not :data:`UNITS_ROW`, or there is no second
    row). Reads two lines."""
    with open(path, encoding="utf-8", newline="") as fh:
        rows = csv.reader(fh)
        header, second = next(rows, []), next(rows, [])
    if not second or second[0] != UNITS_ROW:
        return header, None
    return header, ["", *second[1:]]


def write_units_table(df: "pd.DataFrame", path: str | os.PathLike, units: Sequence[str]) -> Path:
    """``df`` (no index) as the CSV table ``path`` with its units row (:func:`units_row_text`; ``units`` one per
    column), atomically, every float at full precision (its shortest repr)."""
    path = Path(path)
    head = units_row_text(list(df.columns), units)

    def write(fh) -> None:
        fh.write(head)
        df.to_csv(fh, index=False, header=False, lineterminator="\n")

    atomic_write(path, write, durable=False)
    return path


def read_units_table(path: str | os.PathLike, **options: Any) -> "pd.DataFrame":
    """A table :func:`write_units_table` wrote, every float as written (:func:`read_table`), its units row skipped;
    a table written before it had one (no units row after the header) reads to the same frame. ``options`` go to
    :func:`pandas.read_csv`."""
    _, units = read_units(path)
    return read_table(path, skiprows=[1] if units is not None else None, **options)


__all__ = ["UNITS_ROW", "atomic_csv", "atomic_text", "atomic_write", "input_file", "not_a_file", "output_dir",
           "output_file",
           "read_table", "read_units", "read_units_table", "remove_stale", "staged_folder", "units_row_text",
           "write_units_table"]
