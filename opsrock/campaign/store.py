"""The append-only result store of a campaign: one SQLite file, one row per finished case.

Why SQLite: a campaign must lose nothing when it is interrupted (Ctrl-C, ``kill -9``, a
worker dying, a power cut). SQLite in WAL mode gives atomic, durable transactions from the
standard library, and readers (a progress monitor, a test) never block the writer.

* Only the campaign's main process writes; workers return results to it.
* Each batch of results that comes back from a worker is committed in one transaction as
  soon as it arrives (``synchronous=FULL``: the commit is on disk before the next batch is
  taken), so an interruption loses at most the batches still being computed.
* Rows are only ever inserted (on the ``case_id`` key: a case computed twice, e.g. after a worker was
  restarted, keeps its first result), except a case lost to the infrastructure (its worker died: reason
  marked by :data:`~opsrock.campaign.executors.LOST_MARKERS`, the old stores' ``"worker process died"``
  included): it is not a result (:meth:`ResultStore.done_ids` leaves it out, so a resume computes it
  again) and its row gives way to the case's next row. The only deletion is :meth:`ResultStore.clear`,
  which ``run_campaign(force=True)`` uses to start over.
* A manifest table records what the rows were computed with (the scene's digest, solver and
  settings); the campaign refuses to add rows computed with anything else.
* One campaign at a time per folder: an exclusive ``flock`` on ``<out>/.lock``, released by
  the operating system however the process ends.
* Opening a store checks its whole layout (:func:`check_layout`: both tables, every column with its
  type, the schema version, every manifest value JSON, every stored value of its column's type)
  before anything is added, so a damaged store is refused in one line naming the file and the damage.

What goes wrong with a store is told by its cause (:func:`store_fault`), and the advice never loses
finished cases:

* another process holds SQLite's lock, or the folder's lock (``database is locked``): the store is
  sound and in use; wait for that process or stop it (:class:`~opsrock.errors.StoreUnavailableError`);
* the disk is full, or an I/O error, or a read-only file system: the cases stored so far are kept;
  free space and run the same command again to resume (:class:`~opsrock.errors.StoreUnavailableError`);
* the file is not an SQLite database, is malformed, or its layout is not this opsrock's: the store is
  damaged (:class:`~opsrock.errors.StoreError`); move it aside (never delete it: whatever it holds
  may still be read by hand) and re-run, which computes its cases again;
* a store written by a newer opsrock: run that opsrock, or use another folder.
"""

from __future__ import annotations

import errno
import fcntl
import json
import math
import os
import sqlite3
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Iterable, Iterator, Mapping

from opsrock._files import not_a_file
from opsrock.campaign.executors import LOST_MARKERS
from opsrock.errors import StoreError, StoreUnavailableError
from opsrock.result import STATUSES, VERDICTS

#: File name of the store inside a campaign's output folder.
STORE_FILE: str = "results.sqlite"

#: Name of the human-readable copy of a campaign's manifest, beside the store.
MANIFEST_FILE: str = "manifest.json"

#: File locked by the campaign that writes to a folder.
LOCK_FILE: str = ".lock"

#: Version of the table layout below. A version-1 store (before the contact columns), version-2 store (before
#: the plan columns), version-3 store (before a cylinder's ``time_rim`` and ``time_rolling``) or version-4 store
#: (before ``cpu_time_s``) is migrated in place when opened (the columns are added, empty: its cases were solved
#: without friction, or in a plane, or their times on the rim or their CPU times were not recorded: NaN, and
#: ``--force`` computes them again to record them); a store of a newer version is refused.
SCHEMA_VERSION: int = 5

#: Columns stored per case (besides ``case_id``), with their SQLite types. Inputs (block,
#: pulse, intensity measures) are not stored: they follow from the scene, whose digest the
#: manifest holds, and are recomputed when ``cases.csv`` is assembled.
RESULT_COLUMNS: dict[str, str] = {
    "status": "TEXT NOT NULL",
    "reason": "TEXT NOT NULL",
    "verdict": "TEXT NOT NULL",
    "theta_max": "REAL",  # NULL = NaN (SQLite stores NaN as NULL): a failed run with no history
    "theta_max_over_alpha": "REAL",
    "overturned": "INTEGER NOT NULL",
    "rocked": "INTEGER NOT NULL",
    "solver": "TEXT NOT NULL",
    "wall_time_s": "REAL",  # NULL = NaN: not measured (the worker died)
    "cpu_time_s": "REAL",  # NULL = NaN: not measured (the worker died, or a store of schema version 4 or older)
    "n_steps": "INTEGER",
    "n_impacts": "INTEGER",
    # what a block with friction did (solvers of the friction model; NULL for the others)
    "response": "TEXT",
    "first_mode": "TEXT",
    "time_sliding": "REAL",
    "time_rocking": "REAL",
    "time_flight": "REAL",
    "slide_max": "REAL",
    "slide_residual": "REAL",
    # what a block did in three dimensions (solvers of the rigid3d model; NULL for the others)
    "tilt_max": "REAL",
    "twist_max": "REAL",
    "overturned_over": "TEXT",
    # a cylinder's time on one rim point and rolling round its rim (s; 0 for a box in plan, NULL for the others)
    "time_rim": "REAL",
    "time_rolling": "REAL",
}

#: The columns schema version 2 added to version 1.
_ADDED_IN_2: tuple[str, ...] = ("response", "first_mode", "time_sliding", "time_rocking", "time_flight",
                                "slide_max", "slide_residual")

#: The columns schema version 3 added to version 2.
_ADDED_IN_3: tuple[str, ...] = ("tilt_max", "twist_max", "overturned_over")

#: The columns schema version 4 added to version 3.
_ADDED_IN_4: tuple[str, ...] = ("time_rim", "time_rolling")

#: The columns schema version 5 added to version 4.
_ADDED_IN_5: tuple[str, ...] = ("cpu_time_s",)

#: The columns each schema version added, by version.
_ADDED: dict[int, tuple[str, ...]] = {2: _ADDED_IN_2, 3: _ADDED_IN_3, 4: _ADDED_IN_4, 5: _ADDED_IN_5}


def _columns_of(version: int) -> dict[str, str]:
    """The result columns (and their SQLite types) of a store of schema ``version``."""
    later = {c for v, cols in _ADDED.items() if v > version for c in cols}
    return {k: v for k, v in RESULT_COLUMNS.items() if k not in later}

#: The manifest table's columns, with their SQLite types.
MANIFEST_COLUMNS: dict[str, str] = {"key": "TEXT PRIMARY KEY", "value": "TEXT NOT NULL"}

#: How long a write waits for SQLite's lock before the store is reported in use (s). Only the campaign's
#: main process writes, under the folder's lock; readers never block it (WAL): a longer wait means another
#: program holds the file.
BUSY_TIMEOUT_S: float = 5.0

#: SQLite's primary result codes of a sound store that cannot be used now (another process holds it) ...
_BUSY_CODES = frozenset({"SQLITE_BUSY", "SQLITE_LOCKED"})
#: ... of a file system that refuses the write (the store itself is sound) ...
_DISK_CODES = frozenset({"SQLITE_FULL", "SQLITE_IOERR", "SQLITE_READONLY", "SQLITE_CANTOPEN", "SQLITE_PERM"})
#: ... and of a damaged file.
_DAMAGE_CODES = frozenset({"SQLITE_CORRUPT", "SQLITE_NOTADB", "SQLITE_FORMAT", "SQLITE_SCHEMA", "SQLITE_MISMATCH"})

#: ``errno`` values of a file system that refuses a write: full, over quota, failing, read-only.
DISK_ERRNOS: frozenset[int] = frozenset({errno.ENOSPC, errno.EDQUOT, errno.EIO, errno.EROFS})


def _lost_sql(table: str = "") -> str:
    """SQL condition: the row (of ``table``, when named) is that of a case lost to the infrastructure
    (:data:`~opsrock.campaign.executors.LOST_MARKERS`), not a result."""
    q = f"{table}." if table else ""
    marks = " OR ".join(f"instr({q}reason, '{m}') > 0" for m in LOST_MARKERS)  # the markers hold no quote
    return f"({q}status = 'failed' AND ({marks}))"


_BOOL_COLUMNS = ("overturned", "rocked")
_FLOAT_COLUMNS = ("theta_max", "theta_max_over_alpha", "wall_time_s", "cpu_time_s", "time_sliding", "time_rocking",
                  "time_flight", "slide_max", "slide_residual", "tilt_max", "twist_max", "time_rim", "time_rolling")


class ResultStore:
    """Append-only SQLite store of per-case results.

    Parameters
    ----------
    path : str or Path
        The SQLite file (created with its tables if missing).
    lock : bool, optional
        Take the folder's exclusive lock (``<folder>/.lock``) for as long as the store is
        open. The campaign does; readers need not. Default True.

    Raises
    ------
    StoreUnavailableError
        If another process holds the folder's lock or the file, or the file system refuses to write.
    StoreError
        If the file is damaged, its layout is not this opsrock's (:func:`check_layout`), or it was
        written by a newer opsrock.
    """

    def __init__(self, path: str | Path, *, lock: bool = True) -> None:
        self.path = Path(path)
        self._lock_fd: int | None = None
        self._db = None
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            if lock:
                self._take_lock()
        except OSError as exc:
            raise StoreError(f"cannot use folder {str(self.path.parent)!r}: {exc.strerror or exc}") from None
        kind = not_a_file(self.path)
        if kind is not None:  # sqlite would say "unable to open database file", told as a permission problem
            self.close()
            raise StoreError(f"{self.path} is {kind}, not a campaign store (a file); move it aside or use another "
                             "--out folder")
        try:
            with self._faults():
                # isolation_level=None: no implicit transactions; we BEGIN and COMMIT ourselves.
                self._db = sqlite3.connect(self.path, isolation_level=None, timeout=BUSY_TIMEOUT_S)
                self._db.execute("PRAGMA journal_mode=WAL")
                self._db.execute("PRAGMA synchronous=FULL")
                self._create()
        except BaseException:
            self.close()
            raise

    # --- lifecycle -------------------------------------------------------------------------
    def _take_lock(self) -> None:
        fd = os.open(self.path.parent / LOCK_FILE, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            raise StoreUnavailableError(
                f"another opsrock run is writing to {self.path.parent} (lock {LOCK_FILE} is held); "
                "wait for it to finish or stop it, or use another --out folder"
            ) from None
        self._lock_fd = fd

    def _release_lock(self) -> None:
        if self._lock_fd is not None:
            fcntl.flock(self._lock_fd, fcntl.LOCK_UN)
            os.close(self._lock_fd)
            self._lock_fd = None

    @contextmanager
    def _faults(self) -> Iterator[None]:
        """Tell an SQLite error by its cause (:func:`store_fault`), naming this store's file."""
        try:
            yield
        except sqlite3.Error as exc:
            raise store_fault(self.path, exc) from None

    @contextmanager
    def _transaction(self) -> Iterator[None]:
        """One write transaction: committed if the block ends, rolled back (if SQLite has not already
        rolled it back itself, as it does on a full disk) if it raises."""
        with self._faults():
            self._db.execute("BEGIN IMMEDIATE")
            try:
                yield
                self._db.execute("COMMIT")
            except BaseException:
                if self._db.in_transaction:
                    try:
                        self._db.execute("ROLLBACK")
                    except sqlite3.Error:  # the cause to tell is the first error, not the rollback's
                        pass
                raise

    def _create(self) -> None:
        """Make the tables of a new store, or check an existing one's (and migrate an older version's)."""
        cols = ",\n  ".join(f"{name} {kind}" for name, kind in RESULT_COLUMNS.items())
        with self._transaction():
            tables = _tables(self._db)
            if not tables:
                self._db.execute("CREATE TABLE manifest (key TEXT PRIMARY KEY, value TEXT NOT NULL)")
                self._db.execute(f"CREATE TABLE results (\n  case_id TEXT PRIMARY KEY,\n  {cols}\n)")
                self._db.execute("INSERT INTO manifest (key, value) VALUES ('schema_version', ?)",
                                 (json.dumps(SCHEMA_VERSION),))
                return
            version = check_layout(self.path, self._db)
            if version < SCHEMA_VERSION:
                for name in (c for v in range(version + 1, SCHEMA_VERSION + 1) for c in _ADDED[v]):
                    self._db.execute(f"ALTER TABLE results ADD COLUMN {name} {RESULT_COLUMNS[name]}")
                self._db.execute("UPDATE manifest SET value = ? WHERE key = 'schema_version'",
                                 (json.dumps(SCHEMA_VERSION),))

    def close(self) -> None:
        """Close the database and release the folder lock."""
        if getattr(self, "_db", None) is not None:
            self._db.close()
            self._db = None
        self._release_lock()

    def __enter__(self) -> "ResultStore":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # --- manifest --------------------------------------------------------------------------
    def manifest(self) -> dict[str, Any]:
        """The run manifest (without the schema version); empty for a new store."""
        with self._faults():
            rows = self._db.execute("SELECT key, value FROM manifest WHERE key != 'schema_version'").fetchall()
        return {key: json.loads(value) for key, value in rows}  # each value checked when the store opened

    def write_manifest(self, manifest: Mapping[str, Any]) -> None:
        """Replace the manifest by ``manifest`` (JSON-serialisable values), in one transaction."""
        with self._transaction():
            self._db.execute("DELETE FROM manifest WHERE key != 'schema_version'")
            self._db.executemany(
                "INSERT INTO manifest (key, value) VALUES (?, ?)",
                [(k, json.dumps(v, sort_keys=True)) for k, v in manifest.items()],
            )

    def clear(self) -> None:
        """Delete every result and the manifest (``force=True``: start over)."""
        with self._transaction():
            self._db.execute("DELETE FROM results")
            self._db.execute("DELETE FROM manifest WHERE key != 'schema_version'")

    def forget_timeouts(self) -> int:
        """Delete the stored cases that failed on their case budget (reason ``"timeout..."``), so that a resume
        computes them again (with the budget it is given); the other failures stay results. Returns how many."""
        with self._transaction():
            before = self._db.total_changes
            self._db.execute("DELETE FROM results WHERE status = 'failed' AND reason LIKE 'timeout%'")
            return self._db.total_changes - before

    # --- results ---------------------------------------------------------------------------
    def append(self, rows: Iterable[Mapping[str, Any]]) -> int:
        """Insert result rows in one durable transaction; return how many were new.

        Parameters
        ----------
        rows : iterable of dict
            Each with ``case_id`` and every key of :data:`RESULT_COLUMNS` (the plan columns, schema versions 3's
            and 4's, may be left out: stored NULL, a planar solver's row). A ``case_id``
            already stored is left as it is (the first result wins), unless its stored row is that of a
            case lost to the infrastructure: the new row replaces it.
        """
        names = ["case_id", *RESULT_COLUMNS]
        values = []
        for row in rows:
            missing = [n for n in names if n not in row and n not in (*_ADDED_IN_3, *_ADDED_IN_4)]
            if missing:
                raise StoreError(f"result row for {row.get('case_id')!r} lacks {missing}")
            values.append(tuple(_to_sql(n, row.get(n)) for n in names))
        if not values:
            return 0
        sql = (f"INSERT INTO results ({', '.join(names)}) VALUES ({', '.join('?' * len(names))}) "
               f"ON CONFLICT(case_id) DO UPDATE SET {', '.join(f'{n} = excluded.{n}' for n in RESULT_COLUMNS)} "
               f"WHERE {_lost_sql('results')}")
        with self._transaction():
            before = self._db.total_changes
            self._db.executemany(sql, values)
            inserted = self._db.total_changes - before
        return inserted

    def done_ids(self) -> set[str]:
        """Case ids whose result is stored: every stored case but those lost to the infrastructure (their
        worker died; :data:`~opsrock.campaign.executors.LOST_MARKERS`), which a resume computes again."""
        with self._faults():
            return {r[0] for r in self._db.execute(f"SELECT case_id FROM results WHERE NOT {_lost_sql()}")}

    def lost_ids(self) -> set[str]:
        """Case ids stored as lost to the infrastructure (not results: a resume computes them again)."""
        with self._faults():
            return {r[0] for r in self._db.execute(f"SELECT case_id FROM results WHERE {_lost_sql()}")}

    def __len__(self) -> int:
        with self._faults():
            return self._db.execute("SELECT COUNT(*) FROM results").fetchone()[0]

    def rows(self) -> dict[str, dict[str, Any]]:
        """Every stored row, keyed by ``case_id``, with booleans as bool and NULL floats as NaN."""
        names = list(RESULT_COLUMNS)
        with self._faults():
            records = self._db.execute(f"SELECT case_id, {', '.join(names)} FROM results").fetchall()
        return {rec[0]: {n: _from_sql(n, v) for n, v in zip(names, rec[1:])} for rec in records}


# --- the layout, and what can be wrong with it -----------------------------------------------------
def _tables(db: sqlite3.Connection) -> dict[str, str]:
    """Every named object of the database (table, view, index, trigger) by name, with its type."""
    return dict(db.execute("SELECT name, type FROM sqlite_master WHERE name NOT LIKE 'sqlite_%'").fetchall())


def _columns(db: sqlite3.Connection, table: str) -> dict[str, tuple[str, bool, bool]]:
    """The columns of ``table``: ``name -> (declared type, NOT NULL, primary key)``."""
    return {r[1]: (r[2].upper(), bool(r[3]), bool(r[5])) for r in db.execute(f"PRAGMA table_info({table})")}


def _declared(kind: str) -> tuple[str, bool, bool]:
    """``(type, NOT NULL, primary key)`` of a column declared as ``kind`` (``"TEXT NOT NULL"``)."""
    return kind.split()[0], "NOT NULL" in kind, "PRIMARY KEY" in kind


#: SQLite storage classes a stored value of each declared type may have (a REAL column keeps a whole
#: number it is given as REAL, but an older SQLite may keep it INTEGER).
_STORAGE = {"TEXT": ("text",), "REAL": ("real", "integer"), "INTEGER": ("integer",)}

#: The only values some columns may hold.
_VALUES: dict[str, tuple] = {"status": STATUSES, "verdict": VERDICTS, "overturned": (0, 1), "rocked": (0, 1)}


def check_layout(path: Path, db: sqlite3.Connection) -> int:
    """Check an existing store's whole layout and return its schema version (below :data:`SCHEMA_VERSION`: to
    migrate).

    Checked: the tables ``manifest`` and ``results``; every column of each, with its declared type, NOT
    NULL and key; the ``schema_version`` (JSON, a whole number, not newer than :data:`SCHEMA_VERSION`); every
    manifest value JSON, and ``digest`` a string when the manifest is not empty; every stored value of
    its column's storage class, and ``status``, ``verdict``, ``overturned``, ``rocked`` among their values.

    Raises
    ------
    StoreError
        Naming the file and what is wrong (:func:`damaged`), or saying that a newer opsrock wrote it.
    """
    tables = _tables(db)
    for name in ("manifest", "results"):
        if tables.get(name) != "table":
            raise damaged(path, f"it has no table {name!r}" if name not in tables else f"{name!r} is a {tables[name]}")
    _check_columns(path, db, "manifest", {k: _declared(v) for k, v in MANIFEST_COLUMNS.items()})
    version = _schema_version(path, db)
    expected = {"case_id": ("TEXT", False, True), **{k: _declared(v) for k, v in _columns_of(version).items()}}
    _check_columns(path, db, "results", expected)
    _check_manifest(path, db)
    _check_values(path, db, expected)
    return version


def _check_columns(path: Path, db: sqlite3.Connection, table: str, expected: dict[str, tuple[str, bool, bool]]) -> None:
    present = _columns(db, table)
    missing = [c for c in expected if c not in present]
    if missing:
        raise damaged(path, f"table {table!r} lacks column {missing[0]!r}" + (f" (and {len(missing) - 1} more)"
                                                                             if len(missing) > 1 else ""))
    extra = [c for c in present if c not in expected]
    if extra:
        raise damaged(path, f"table {table!r} has a column this opsrock does not write: {extra[0]!r}")
    for name, (kind, not_null, key) in expected.items():
        if present[name][0] != kind or present[name][2] != key or (not_null and not present[name][1]):
            got = f"{present[name][0] or 'untyped'}{' NOT NULL' if present[name][1] else ''}"
            raise damaged(path, f"column {table}.{name} is declared {got!r}, not as this opsrock declares it "
                                f"({'TEXT PRIMARY KEY' if key else kind + (' NOT NULL' if not_null else '')})")


def _schema_version(path: Path, db: sqlite3.Connection) -> int:
    row = db.execute("SELECT value FROM manifest WHERE key = 'schema_version'").fetchone()
    if row is None:
        raise damaged(path, "its manifest has no schema_version")
    try:
        version = json.loads(row[0])
    except (TypeError, ValueError):
        raise damaged(path, f"schema_version = {row[0]!r} is not JSON") from None
    if isinstance(version, bool) or not isinstance(version, int) or version < 1:
        raise damaged(path, f"schema_version = {row[0]!r} is not a store schema version (a whole number >= 1)")
    if version > SCHEMA_VERSION:
        raise StoreError(f"{path} has store schema version {version}, written by a newer opsrock; this opsrock "
                         f"reads versions 1 to {SCHEMA_VERSION}: run it with that opsrock, or use another --out folder")
    return version


def _check_manifest(path: Path, db: sqlite3.Connection) -> None:
    manifest = {}
    for key, value in db.execute("SELECT key, value FROM manifest WHERE key != 'schema_version'"):
        try:
            manifest[key] = json.loads(value)
        except (TypeError, ValueError):
            raise damaged(path, f"manifest {key} = {value!r} is not JSON") from None
    if manifest and not isinstance(manifest.get("digest"), str):
        raise damaged(path, "its manifest has no digest" if "digest" not in manifest
                      else f"manifest digest = {manifest['digest']!r} is not a digest (a string)")


def _check_values(path: Path, db: sqlite3.Connection, expected: dict[str, tuple[str, bool, bool]]) -> None:
    """Every stored value of its column's storage class (NULL only where the column allows it)."""
    tests = []
    for name, (kind, not_null, key) in expected.items():
        allowed = ", ".join(f"'{s}'" for s in _STORAGE[kind] + (() if not_null or key else ("null",)))
        values = _VALUES.get(name)
        tests.append(f"(typeof({name}) NOT IN ({allowed})"
                     + (f" OR {name} NOT IN ({', '.join(map(repr, values))}))" if values else ")"))
    names = list(expected)
    bad = db.execute(f"SELECT {', '.join(names)} FROM results WHERE {' OR '.join(tests)} LIMIT 1").fetchone()
    if bad is None:
        return
    for name, value, test in zip(names, bad, tests):
        if db.execute(f"SELECT {test} FROM (SELECT ? AS {name})", (value,)).fetchone()[0]:
            what = (f"one of {', '.join(map(repr, _VALUES[name]))}" if name in _VALUES
                    else f"a {expected[name][0]} value")
            raise damaged(path, f"a row of table 'results' (case_id {bad[0]!r}) holds {name} = {value!r}, not {what}")
    raise damaged(path, f"a row of table 'results' (case_id {bad[0]!r}) holds a value of the wrong type")


def damaged(path: str | Path, what: str) -> StoreError:
    """The refusal of a damaged store: the file, the damage, and advice that loses nothing."""
    return StoreError(f"{path} is damaged: {what}; move it aside (e.g. add .damaged to its name: its stored "
                      "cases are then computed again) and run the same command, or use another --out folder")


def store_fault(path: str | Path, exc: sqlite3.Error) -> StoreError:
    """What an SQLite error on the store at ``path`` means for the user, by its cause.

    Returns
    -------
    StoreUnavailableError
        Another process holds the file (wait for it or stop it), or the file system refused to write
        (disk full, I/O error, read-only: free space or fix it, and re-run to resume; finished cases are kept).
    StoreError
        The file is damaged (:func:`damaged`), or another SQLite error, told as it is.
    """
    code = "_".join((getattr(exc, "sqlite_errorname", "") or "").split("_")[:2])  # the primary result code
    cause = " ".join(str(exc).split()) or type(exc).__name__
    if code in _BUSY_CODES or "locked" in cause:
        return StoreUnavailableError(
            f"{path} is in use by another process (sqlite: {cause}): another opsrock process is probably "
            "writing to it; wait for it to finish, or stop it, then run the same command again (the store is "
            "left as it is)")
    if code in _DISK_CODES or "disk is full" in cause or "I/O error" in cause:
        what = ("the disk is full" if code == "SQLITE_FULL" or "full" in cause else
                "an I/O error" if code == "SQLITE_IOERR" or "I/O error" in cause else
                "the file system does not let it be written (permissions, or a read-only file system)")
        return StoreUnavailableError(
            f"cannot write {path}: {what} (sqlite: {cause}); the cases it holds are kept: free some space (or "
            "fix the file system) and run the same command again to resume")
    if code in _DAMAGE_CODES or "not a database" in cause or "malformed" in cause:
        return damaged(path, f"SQLite cannot read it ({cause})")
    return StoreError(f"cannot use the store {path} (sqlite: {cause})")


def disk_fault(path: str | Path, exc: OSError) -> StoreUnavailableError:
    """The refusal of a campaign file the file system would not write (``exc.errno`` in :data:`DISK_ERRNOS`)."""
    return StoreUnavailableError(
        f"cannot write {path}: {exc.strerror or exc}; the cases stored in its folder are kept: free some space "
        "(or fix the file system) and run the same command again to resume")


def _to_sql(name: str, value: Any) -> Any:
    if name in _BOOL_COLUMNS:
        return int(bool(value))
    if name in _FLOAT_COLUMNS:
        v = math.nan if value is None else float(value)
        return None if math.isnan(v) else v
    return value


def _from_sql(name: str, value: Any) -> Any:
    if name in _BOOL_COLUMNS:
        return bool(value)
    if name in _FLOAT_COLUMNS:
        return math.nan if value is None else float(value)
    return value


def read_rows(out_dir: str | Path) -> dict[str, dict[str, Any]]:
    """Read the stored rows of a campaign folder, read-only and without its lock (e.g. while it runs)."""
    path = Path(out_dir) / STORE_FILE
    if not path.is_file():
        return {}
    db = sqlite3.connect(f"{path.resolve().as_uri()}?mode=ro", uri=True, timeout=30.0)
    try:
        try:
            present = {rec[1] for rec in db.execute("PRAGMA table_info(results)")}
            # a version-1 store (read, not migrated) lacks the contact columns: they read as empty
            names = [n for n in RESULT_COLUMNS if n in present] if present else list(RESULT_COLUMNS)
            records = db.execute(f"SELECT case_id, {', '.join(names)} FROM results").fetchall()
        except sqlite3.OperationalError as exc:  # created but its tables not yet committed
            if "no such table" in str(exc):
                return {}
            raise store_fault(path, exc) from None
        except sqlite3.Error as exc:
            raise store_fault(path, exc) from None
    finally:
        db.close()
    missing = {n: _from_sql(n, None) for n in RESULT_COLUMNS if n not in names}
    return {rec[0]: {**missing, **{n: _from_sql(n, v) for n, v in zip(names, rec[1:])}} for rec in records}


__all__ = ["BUSY_TIMEOUT_S", "DISK_ERRNOS", "LOCK_FILE", "MANIFEST_COLUMNS", "MANIFEST_FILE", "RESULT_COLUMNS", "SCHEMA_VERSION",
           "STORE_FILE", "ResultStore", "StoreError", "StoreUnavailableError", "check_layout", "damaged", "disk_fault",
           "read_rows", "store_fault"]
