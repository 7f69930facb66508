"""The append-only SQLite store: durable rows, first result wins, manifest, lock, NaN round trip."""

from __future__ import annotations

import math
import sqlite3
import subprocess
import sys

import pytest

from opsrock.campaign.executors import LOST_PREFIX, is_lost
from opsrock.campaign.store import RESULT_COLUMNS, SCHEMA_VERSION, STORE_FILE, ResultStore, StoreError, StoreUnavailableError, read_rows, store_fault


def row(case_id: str, theta_max: float = 0.1, **over) -> dict:
    base = {
        "case_id": case_id,
        "status": "ok",
        "reason": "",
        "verdict": "safe",
        "theta_max": theta_max,
        "theta_max_over_alpha": theta_max / 0.2,
        "overturned": False,
        "rocked": True,
        "solver": "fake",
        "wall_time_s": 0.01,
        "cpu_time_s": 0.008,
        "n_steps": 10,
        "n_impacts": 2,
        # the contact columns, empty: a solver without friction
        "response": None,
        "first_mode": None,
        "time_sliding": math.nan,
        "time_rocking": math.nan,
        "time_flight": math.nan,
        "slide_max": math.nan,
        "slide_residual": math.nan,
    }
    base.update(over)
    return base


def test_rows_round_trip_exactly(tmp_path):
    # SQLite REAL is an IEEE-754 double: a float must come back bit for bit.
    value = 0.1 + 0.2  # not representable in few digits: any text round trip would show
    with ResultStore(tmp_path / STORE_FILE) as store:
        assert store.append([row("a", value), row("b", math.pi, overturned=True, verdict="overturned")]) == 2
        got = store.rows()
    assert got["a"]["theta_max"] == value
    assert got["b"]["theta_max"] == math.pi and got["b"]["overturned"] is True
    assert set(got["a"]) == set(RESULT_COLUMNS)


def test_nan_survives_as_nan(tmp_path):
    # SQLite stores NaN as NULL; a failed case with no history must read back as NaN, not 0.
    failed = row("f", math.nan, status="failed", reason="diverged", verdict="failed", rocked=False,
                 theta_max_over_alpha=math.nan, wall_time_s=math.nan, n_steps=None, n_impacts=None)
    with ResultStore(tmp_path / STORE_FILE) as store:
        store.append([failed])
        got = store.rows()["f"]
    assert math.isnan(got["theta_max"]) and math.isnan(got["wall_time_s"])
    assert got["status"] == "failed" and got["reason"] == "diverged"


def test_append_only_first_result_wins(tmp_path):
    with ResultStore(tmp_path / STORE_FILE) as store:
        assert store.append([row("a", 0.1)]) == 1
        assert store.append([row("a", 0.9), row("b", 0.2)]) == 1  # "a" kept, "b" new
        rows = store.rows()
    assert rows["a"]["theta_max"] == 0.1 and len(rows) == 2


def _failed(case_id: str, reason: str) -> dict:
    return row(case_id, math.nan, status="failed", reason=reason, verdict="failed", rocked=False,
               theta_max_over_alpha=math.nan, wall_time_s=math.nan, n_steps=None, n_impacts=None)


def test_a_lost_case_is_not_a_result_and_gives_way_to_its_next_row(tmp_path):
    # A case lost to the infrastructure (its worker died: LOST_PREFIX, or the text of a store written before
    # the prefix) is retried by a resume, and its next row replaces it; a solver's failure is a result and stays.
    lost_now = _failed("a", f"{LOST_PREFIX}worker process died while solving this case alone (BrokenProcessPool: x)")
    lost_old = _failed("b", "worker process died while solving this case alone (BrokenProcessPool: x)")
    solver_failed = _failed("c", "no convergence at t = 0.41 s")
    timed_out = _failed("d", "timeout: no answer within 35 s (the case budget plus 30 s of grace)")
    with ResultStore(tmp_path / STORE_FILE) as store:
        store.append([lost_now, lost_old, solver_failed, timed_out, row("e")])
        assert store.done_ids() == {"c", "d", "e"} and store.lost_ids() == {"a", "b"}
        assert store.append([row("a", 0.3), row("b", 0.4), row("c", 0.5), row("d", 0.6), row("e", 0.7)]) == 2
        got = store.rows()
        assert store.done_ids() == set("abcde") and not store.lost_ids()
    assert (got["a"]["status"], got["a"]["theta_max"], got["b"]["theta_max"]) == ("ok", 0.3, 0.4)
    assert got["c"]["reason"] == "no convergence at t = 0.41 s" and got["d"]["status"] == "failed"
    assert got["e"]["theta_max"] == 0.1  # a result: the first one wins
    assert is_lost(lost_old["reason"]) and not is_lost(timed_out["reason"]) and not is_lost("")


def test_forget_timeouts_leaves_every_other_failure_a_result(tmp_path):
    # issue 44: the inventory study computes cases stored as timed out again on a resume (within the budget it
    # is given); a solver's other failures and the results stay
    with ResultStore(tmp_path / STORE_FILE) as store:
        store.append([_failed("a", "timeout: no answer within the case budget of 300 s"),
                      _failed("b", "timeout: no answer within 35 s (the case budget plus 30 s of grace)"),
                      _failed("c", "no convergence at t = 0.41 s"), row("d")])
        assert store.forget_timeouts() == 2
        assert store.done_ids() == {"c", "d"}
        assert store.forget_timeouts() == 0


def test_incomplete_row_is_refused_and_nothing_written(tmp_path):
    bad = row("b")
    del bad["verdict"]
    with ResultStore(tmp_path / STORE_FILE) as store:
        with pytest.raises(StoreError, match="verdict"):
            store.append([row("a"), bad])
        assert len(store) == 0  # the batch is one transaction: all or nothing


def test_rows_survive_reopen_and_clear_empties(tmp_path):
    path = tmp_path / STORE_FILE
    with ResultStore(path) as store:
        store.write_manifest({"digest": "abc", "solver": "fake"})
        store.append([row(f"c{k}") for k in range(5)])
    with ResultStore(path) as store:
        assert store.manifest() == {"digest": "abc", "solver": "fake"}
        assert store.done_ids() == {f"c{k}" for k in range(5)}
        store.clear()
        assert len(store) == 0 and store.manifest() == {}


def test_committed_rows_survive_sigkill(tmp_path):
    # A writer killed with SIGKILL right after a commit: the row must be there (WAL + FULL sync).
    code = (
        "import os, signal, sys\n"
        "from opsrock.campaign.store import ResultStore\n"
        "sys.path.insert(0, sys.argv[2])\n"
        "from test_store import row\n"
        "s = ResultStore(sys.argv[1])\n"
        "s.append([row('x', 0.25)])\n"
        "os.kill(os.getpid(), signal.SIGKILL)\n"
    )
    from pathlib import Path

    proc = subprocess.run(
        [sys.executable, "-c", code, str(tmp_path / STORE_FILE), str(Path(__file__).parent)], capture_output=True
    )
    assert proc.returncode == -9
    rows = read_rows(tmp_path)
    assert rows["x"]["theta_max"] == 0.25


def test_second_writer_is_refused_but_readers_are_not(tmp_path):
    path = tmp_path / STORE_FILE
    with ResultStore(path) as store:
        store.append([row("a")])
        with pytest.raises(StoreError, match="another opsrock run"):
            ResultStore(path)
        assert set(read_rows(tmp_path)) == {"a"}  # a reader does not need the lock
    with ResultStore(path) as again:  # the lock is released on close
        assert len(again) == 1


def test_other_schema_version_is_refused(tmp_path):
    path = tmp_path / STORE_FILE
    ResultStore(path).close()
    db = sqlite3.connect(path)
    db.execute("UPDATE manifest SET value = '999' WHERE key = 'schema_version'")
    db.commit()
    db.close()
    with pytest.raises(StoreError, match="schema version 999"):
        ResultStore(path)


def _version_1_store(path):
    """A store as opsrock wrote it before the contact columns (schema version 1), with one row."""
    with ResultStore(path) as store:
        store.append([row("old", 0.5)])
    db = sqlite3.connect(path)
    for name in ("response", "first_mode", "time_sliding", "time_rocking", "time_flight", "slide_max",
                 "slide_residual", "tilt_max", "twist_max", "overturned_over", "time_rim",
                 "time_rolling", "cpu_time_s"):  # version 2's, 3's, 4's and 5's columns
        db.execute(f"ALTER TABLE results DROP COLUMN {name}")
    db.execute("UPDATE manifest SET value = '1' WHERE key = 'schema_version'")
    db.commit()
    db.close()


def test_a_version_1_store_is_migrated_and_keeps_its_rows(tmp_path):
    path = tmp_path / STORE_FILE
    _version_1_store(path)
    with ResultStore(path) as store:
        assert store.rows()["old"]["theta_max"] == 0.5
        store.append([row("new", 0.25)])
        assert len(store) == 2
    db = sqlite3.connect(path)
    assert db.execute("SELECT value FROM manifest WHERE key = 'schema_version'").fetchone()[0] == str(SCHEMA_VERSION)
    db.close()


def test_a_version_3_store_reads_its_cases_with_the_times_on_the_rim_unrecorded(tmp_path):
    """Schema version 4 stores a cylinder's time on its rim and rolling; a version-3 store (a study of the last
    release) is migrated: its cases read as they were, those two times NaN (not recorded), new rows keep theirs."""
    path = tmp_path / STORE_FILE
    with ResultStore(path) as store:
        store.append([{**row("old", 0.5), "tilt_max": 0.1, "overturned_over": "rim"}])
    db = sqlite3.connect(path)
    for name in ("time_rim", "time_rolling", "cpu_time_s"):  # version 4's and 5's columns
        db.execute(f"ALTER TABLE results DROP COLUMN {name}")
    db.execute("UPDATE manifest SET value = '3' WHERE key = 'schema_version'")
    db.commit()
    db.close()
    with ResultStore(path) as store:
        old = store.rows()["old"]
        assert (old["tilt_max"], old["overturned_over"]) == (0.1, "rim")
        assert math.isnan(old["time_rim"]) and math.isnan(old["time_rolling"])
        store.append([{**row("new", 0.25), "time_rim": 1.5, "time_rolling": 0.75}])
        assert (store.rows()["new"]["time_rim"], store.rows()["new"]["time_rolling"]) == (1.5, 0.75)


def test_a_version_4_store_reads_its_cases_with_their_cpu_times_unrecorded(tmp_path):
    """Schema version 5 stores each case's CPU time; a version-4 store (written before it was measured) is migrated:
    its cases read as they were, their CPU time NaN (not recorded), and new rows keep theirs."""
    path = tmp_path / STORE_FILE
    with ResultStore(path) as store:
        store.append([row("old", 0.5)])
    db = sqlite3.connect(path)
    db.execute("ALTER TABLE results DROP COLUMN cpu_time_s")
    db.execute("UPDATE manifest SET value = '4' WHERE key = 'schema_version'")
    db.commit()
    db.close()
    with ResultStore(path) as store:
        old = store.rows()["old"]
        assert (old["theta_max"], old["wall_time_s"]) == (0.5, 0.01) and math.isnan(old["cpu_time_s"])
        store.append([row("new", 0.25, cpu_time_s=0.125)])
        assert store.rows()["new"]["cpu_time_s"] == 0.125


@pytest.mark.parametrize(("statement", "words"), [
    ("UPDATE manifest SET value = 'two' WHERE key = 'schema_version'", "schema_version = 'two' is not JSON"),
    ("ALTER TABLE results DROP COLUMN slide_max", "lacks column 'slide_max'"),
    ("UPDATE results SET theta_max = 'x'", "theta_max = 'x'"),
    ("INSERT INTO manifest VALUES ('digest', 'abc')", "manifest digest = 'abc' is not JSON"),
])
def test_a_damaged_store_is_refused_in_one_line_and_left_as_it_is(tmp_path, statement, words):
    path = tmp_path / STORE_FILE
    with ResultStore(path) as store:
        store.append([row("a")])
    db = sqlite3.connect(path)
    db.execute(statement)
    db.commit()
    db.close()
    data = path.read_bytes()
    with pytest.raises(StoreError, match="damaged") as info:
        ResultStore(path)
    assert words in str(info.value) and "move it aside" in str(info.value) and "delete" not in str(info.value)
    assert not isinstance(info.value, StoreUnavailableError)
    assert path.read_bytes() == data


@pytest.mark.parametrize(("message", "kind", "words"), [
    ("database is locked", StoreUnavailableError, "in use by another process"),
    ("database or disk is full", StoreUnavailableError, "the disk is full"),
    ("disk I/O error", StoreUnavailableError, "an I/O error"),
    ("file is not a database", StoreError, "damaged"),
    ("database disk image is malformed", StoreError, "damaged"),
])
def test_a_fault_is_told_by_its_cause(message, kind, words):
    exc = store_fault("out/results.sqlite", sqlite3.OperationalError(message))
    assert type(exc) is kind and words in str(exc) and "out/results.sqlite" in str(exc) and "delete" not in str(exc)


def test_a_full_disk_during_a_commit_names_the_cause_not_the_rollback(tmp_path, monkeypatch):
    with ResultStore(tmp_path / STORE_FILE) as store:
        real = store._db

        class Full:  # SQLite rolls the transaction back itself on SQLITE_FULL: the ROLLBACK then fails
            in_transaction = False
            total_changes = 0

            def execute(self, sql, *args):
                if sql == "COMMIT":
                    real.execute("ROLLBACK")
                    raise sqlite3.OperationalError("database or disk is full")
                return real.execute(sql, *args)

            def executemany(self, sql, values):
                return real.executemany(sql, values)

        monkeypatch.setattr(store, "_db", Full())
        with pytest.raises(StoreUnavailableError, match="disk is full") as info:
            store.append([row("a")])
        assert "rollback" not in str(info.value)
        monkeypatch.setattr(store, "_db", real)
        assert len(store) == 0
