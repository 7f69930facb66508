"""The append-only result store of a campaign: one SQLite file, one row per finished case.

Why SQLite: a campaign must lose nothing when it is interrupted (Ctrl-C, ``kill -9``, a
worker dying, a power cut). SQLite in WAL mode gives atomic, durable transactions from the
standard library, and readers (a progress monitor, a test) never block the writer.

* Only the campaign's main process writes; workers return results to it.
* Each batch of results that comes back from a worker is committed in one transaction as
  soon as it arrives (``synchronous=FULL``: the commit is on disk before the next batch is
  taken), so an interruption loses at most the batches still being computed.
* Rows are only ever inserted (``INSERT OR IGNORE`` on the ``case_id`` key: a case computed
  twice, e.g. after a worker was restarted, keeps its first result). The only deletion is
  :meth:`ResultStore.clear`, which ``run_campaign(force=True)`` uses to start over.
* A manifest table records what the rows were computed with (the scene's digest, solver and
  settings); the campaign refuses to add rows computed with anything else.
* One campaign at a time per folder: an exclusive ``flock`` on ``<out>/.lock``, released by
  the operating system however the process ends.
"""

from __future__ import annotations

import fcntl
import json
import math
import os
import sqlite3
from pathlib import Path
from typing import Any, Iterable, Mapping

from opsrock.errors import StoreError

#: File name of the store inside a campaign's output folder.
STORE_FILE: str = "results.sqlite"

#: Name of the human-readable copy of a campaign's manifest, beside the store.
MANIFEST_FILE: str = "manifest.json"

#: File locked by the campaign that writes to a folder.
LOCK_FILE: str = ".lock"

#: Version of the table layout below. A version-1 store (before the contact columns) is migrated in
#: place when opened (the columns are added, empty: its cases were solved without friction); a store
#: of any other version is refused.
SCHEMA_VERSION: int = 2

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
}

#: The columns schema version 2 added to version 1.
_ADDED_IN_2: tuple[str, ...] = ("response", "first_mode", "time_sliding", "time_rocking", "time_flight",
                                "slide_max", "slide_residual")

_BOOL_COLUMNS = ("overturned", "rocked")
_FLOAT_COLUMNS = ("theta_max", "theta_max_over_alpha", "wall_time_s", "time_sliding", "time_rocking", "time_flight",
                  "slide_max", "slide_residual")


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
    StoreError
        If another process holds the folder's lock, or the file has another schema version.
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
        try:
            # isolation_level=None: no implicit transactions; we BEGIN and COMMIT ourselves.
            self._db = sqlite3.connect(self.path, isolation_level=None, timeout=30.0)
            self._db.execute("PRAGMA journal_mode=WAL")
            self._db.execute("PRAGMA synchronous=FULL")
            self._create()
        except sqlite3.DatabaseError as exc:
            self.close()
            raise StoreError(
                f"{self.path} is not a usable opsrock store ({exc}); delete or move the file, or use "
                "another --out folder"
            ) from None
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
            raise StoreError(
                f"another opsrock run is writing to {self.path.parent} (lock {LOCK_FILE} is held); "
                "wait for it to finish or use another --out folder"
            ) from None
        self._lock_fd = fd

    def _release_lock(self) -> None:
        if self._lock_fd is not None:
            fcntl.flock(self._lock_fd, fcntl.LOCK_UN)
            os.close(self._lock_fd)
            self._lock_fd = None

    def _create(self) -> None:
        cols = ",\n  ".join(f"{name} {kind}" for name, kind in RESULT_COLUMNS.items())
        self._db.execute("BEGIN IMMEDIATE")
        try:
            self._db.execute("CREATE TABLE IF NOT EXISTS manifest (key TEXT PRIMARY KEY, value TEXT NOT NULL)")
            self._db.execute(f"CREATE TABLE IF NOT EXISTS results (\n  case_id TEXT PRIMARY KEY,\n  {cols}\n)")
            row = self._db.execute("SELECT value FROM manifest WHERE key = 'schema_version'").fetchone()
            if row is None:
                self._db.execute(
                    "INSERT INTO manifest (key, value) VALUES ('schema_version', ?)", (json.dumps(SCHEMA_VERSION),)
                )
            elif json.loads(row[0]) == 1:
                for name in _ADDED_IN_2:
                    self._db.execute(f"ALTER TABLE results ADD COLUMN {name} {RESULT_COLUMNS[name]}")
                self._db.execute("UPDATE manifest SET value = ? WHERE key = 'schema_version'",
                                 (json.dumps(SCHEMA_VERSION),))
            elif json.loads(row[0]) != SCHEMA_VERSION:
                raise StoreError(
                    f"{self.path} has store schema version {row[0]}, this opsrock writes {SCHEMA_VERSION}; "
                    "use another --out folder or --force to start over"
                )
            self._db.execute("COMMIT")
        except BaseException:
            self._db.execute("ROLLBACK")
            raise

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
        rows = self._db.execute("SELECT key, value FROM manifest WHERE key != 'schema_version'").fetchall()
        return {key: json.loads(value) for key, value in rows}

    def write_manifest(self, manifest: Mapping[str, Any]) -> None:
        """Replace the manifest by ``manifest`` (JSON-serialisable values), in one transaction."""
        self._db.execute("BEGIN IMMEDIATE")
        try:
            self._db.execute("DELETE FROM manifest WHERE key != 'schema_version'")
            self._db.executemany(
                "INSERT INTO manifest (key, value) VALUES (?, ?)",
                [(k, json.dumps(v, sort_keys=True)) for k, v in manifest.items()],
            )
            self._db.execute("COMMIT")
        except BaseException:
            self._db.execute("ROLLBACK")
            raise

    def clear(self) -> None:
        """Delete every result and the manifest (``force=True``: start over)."""
        self._db.execute("BEGIN IMMEDIATE")
        try:
            self._db.execute("DELETE FROM results")
            self._db.execute("DELETE FROM manifest WHERE key != 'schema_version'")
            self._db.execute("COMMIT")
        except BaseException:
            self._db.execute("ROLLBACK")
            raise

    # --- results ---------------------------------------------------------------------------
    def append(self, rows: Iterable[Mapping[str, Any]]) -> int:
        """Insert result rows in one durable transaction; return how many were new.

        Parameters
        ----------
        rows : iterable of dict
            Each with ``case_id`` and every key of :data:`RESULT_COLUMNS`. A ``case_id``
            already stored is left as it is (the first result wins).
        """
        names = ["case_id", *RESULT_COLUMNS]
        values = []
        for row in rows:
            missing = [n for n in names if n not in row]
            if missing:
                raise StoreError(f"result row for {row.get('case_id')!r} lacks {missing}")
            values.append(tuple(_to_sql(n, row[n]) for n in names))
        if not values:
            return 0
        sql = f"INSERT OR IGNORE INTO results ({', '.join(names)}) VALUES ({', '.join('?' * len(names))})"
        self._db.execute("BEGIN IMMEDIATE")
        try:
            before = self._db.total_changes
            self._db.executemany(sql, values)
            inserted = self._db.total_changes - before
            self._db.execute("COMMIT")
        except BaseException:
            self._db.execute("ROLLBACK")
            raise
        return inserted

    def done_ids(self) -> set[str]:
        """Case ids already stored."""
        return {r[0] for r in self._db.execute("SELECT case_id FROM results")}

    def __len__(self) -> int:
        return self._db.execute("SELECT COUNT(*) FROM results").fetchone()[0]

    def rows(self) -> dict[str, dict[str, Any]]:
        """Every stored row, keyed by ``case_id``, with booleans as bool and NULL floats as NaN."""
        names = list(RESULT_COLUMNS)
        out = {}
        for rec in self._db.execute(f"SELECT case_id, {', '.join(names)} FROM results"):
            out[rec[0]] = {n: _from_sql(n, v) for n, v in zip(names, rec[1:])}
        return out


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
            raise
    finally:
        db.close()
    missing = {n: _from_sql(n, None) for n in RESULT_COLUMNS if n not in names}
    return {rec[0]: {**missing, **{n: _from_sql(n, v) for n, v in zip(names, rec[1:])}} for rec in records}


__all__ = ["LOCK_FILE", "MANIFEST_FILE", "RESULT_COLUMNS", "STORE_FILE", "ResultStore", "StoreError", "read_rows"]
