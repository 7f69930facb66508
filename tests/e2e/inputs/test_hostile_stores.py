"""Hostile inputs of the campaign stores and scenes (issue 31), through the console script: stores whose
inside is damaged, scenes that ask what their solver does not model, and the faults of the environment a
store meets (another process holding it, a full disk).

The promise (tests/_hostile.py): bad input is one line naming the file or the key and the value, exit 2,
nothing written; an environment fault is one line naming the path and the cause, exit 1, with advice
that keeps the finished cases (never "delete"); a damaged store is left as it is.
"""

from __future__ import annotations

import os
import shutil
import sqlite3
import subprocess
import sys
import textwrap
import time
from collections import Counter
from pathlib import Path

import pytest

from opsrock.campaign.store import SCHEMA_VERSION
from _hostile import Case, sweep
from _support import BLOCKS, opsrock_command, run_opsrock

#: The tiny scene's case count (2 blocks x 3 x 3).
TINY_CASES = 18

_BLOCKS = textwrap.dedent("""\
    [[block]]
    name = "slider"
    width = 0.4
    height = 1.6
    friction = 0.3
    [[block]]
    name = "housner_e"
    width = 0.4
    height = 1.6
    restitution_factor = 1.0
    [[block]]
    name = "set_e"
    width = 0.4
    height = 1.6
    restitution = 0.8
    [[block]]
    name = "drawn"
    width = 0.4
    height = 1.6
    restitution_factor = { distribution = "normal", mean = 1.0, std = 0.02, low = 0.95, high = 1.05, seed = 1 }
    [[block]]
    name = "law"
    width = 0.4
    height = 1.6
    restitution = "colombo-limestone"
    [[block]]
    name = "default"
    width = 0.4
    height = 1.6
""")

_GRID = "[grid.freq_ratio]\nvalues = [2.0]\n[grid.pfa_ratio]\nvalues = [3.0]\n"
_RECORDS = ('[records]\nset = "fema-p695:far-field"\nnames = ["NORTHR_MUL009"]\ncomponents = ["a"]\n'
            'vertical = "synthetic"\n')


def _scene(root: Path, name: str, solver: str, select: list[str], design: str = _GRID, settings: str = "") -> str:
    path = root / f"{name}.toml"
    path.write_text(f'name = "{name}"\nblocks = "{root / "blocks.toml"}"\nselect = {select!r}\n'.replace("'", '"')
                    + f'[solver]\nname = "{solver}"\n{settings}' + design)
    return str(path)


def _sql(store: Path, *statements: str) -> None:
    db = sqlite3.connect(store)
    for s in statements:
        db.execute(s)
    db.commit()
    db.close()


def _rebuild_results(store: Path, old: str, new: str) -> None:
    """Table ``results`` declared with column ``old`` as ``new`` (``"theta_max TEXT"``), its rows kept."""
    db = sqlite3.connect(store)
    sql = db.execute("SELECT sql FROM sqlite_master WHERE name = 'results'").fetchone()[0]
    db.executescript(f"ALTER TABLE results RENAME TO old; {sql.replace(old, new)}; "
                     "INSERT INTO results SELECT * FROM old; DROP TABLE old;")
    db.commit()
    db.close()


#: Damaged stores: what is done to a finished tiny campaign's store, and the words of the refusal.
DAMAGE: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "schema_not_json": (("UPDATE manifest SET value = 'two' WHERE key = 'schema_version'",),
                        ("schema_version = 'two'", "not JSON")),
    "schema_text": (("UPDATE manifest SET value = '\"2\"' WHERE key = 'schema_version'",),
                    ("schema_version", "not a store schema version")),
    "schema_float": (("UPDATE manifest SET value = '2.5' WHERE key = 'schema_version'",),
                     ("schema_version = '2.5'",)),
    "schema_zero": (("UPDATE manifest SET value = '0' WHERE key = 'schema_version'",), ("schema_version = '0'",)),
    "schema_missing": (("DELETE FROM manifest WHERE key = 'schema_version'",), ("no schema_version",)),
    "schema_newer": ((f"UPDATE manifest SET value = '{SCHEMA_VERSION + 1}' WHERE key = 'schema_version'",),
                     (f"schema version {SCHEMA_VERSION + 1}", "newer opsrock")),
    "digest_not_json": (("UPDATE manifest SET value = 'abc' WHERE key = 'digest'",),
                        ("manifest digest = 'abc'", "not JSON")),
    "digest_number": (("UPDATE manifest SET value = '42' WHERE key = 'digest'",), ("manifest digest = 42",)),
    "digest_missing": (("DELETE FROM manifest WHERE key = 'digest'",), ("no digest",)),
    "other_key_not_json": (("UPDATE manifest SET value = '{' WHERE key = 'solver'",), ("manifest solver = '{'",)),
    "no_slide_max": (("ALTER TABLE results DROP COLUMN slide_max",), ("lacks column 'slide_max'",)),
    "no_contact_columns": (tuple(f"ALTER TABLE results DROP COLUMN {c}" for c in
                                 ("response", "first_mode", "slide_residual")), ("lacks column 'response'",)),
    "extra_column": (("ALTER TABLE results ADD COLUMN colour TEXT",), ("'colour'",)),
    "no_results_table": (("DROP TABLE results",), ("no table 'results'",)),
    "results_a_view": (("DROP TABLE results", "CREATE VIEW results AS SELECT 1 AS case_id"),
                       ("'results' is a view",)),
    "no_manifest_table": (("DROP TABLE manifest",), ("no table 'manifest'",)),
    "text_theta_max": (("UPDATE results SET theta_max = 'abc' WHERE rowid = 3",), ("theta_max = 'abc'",)),
    "text_overturned": (("UPDATE results SET overturned = 'yes' WHERE rowid = 1",), ("overturned = 'yes'",)),
    "status_unknown": (("UPDATE results SET status = 'done' WHERE rowid = 2",), ("status = 'done'",)),
    "verdict_unknown": (("UPDATE results SET verdict = 'fell' WHERE rowid = 5",), ("verdict = 'fell'",)),
    "null_theta_ok": (("UPDATE results SET n_steps = 'many' WHERE rowid = 6",), ("n_steps = 'many'",)),
    "blob_case_id": (("UPDATE results SET case_id = x'00ff' WHERE rowid = 4",), ("case_id",)),
}


def _damaged_stores(root: Path, base: Path) -> list[Case]:
    """A copy of the finished ``base`` campaign per kind of damage, and the case that resumes into it."""
    cases = []
    for name, (statements, needles) in DAMAGE.items():
        out = root / "stores" / name
        shutil.copytree(base, out)
        _sql(out / "results.sqlite", *statements)
        advice = () if name == "schema_newer" else ("move it aside",)
        cases.append(Case(f"store_{name}", ("run", "tiny", "--out", str(out), "--no-progress"),
                          ("results.sqlite", *needles, *advice)))
    file_damage = {
        "not_sqlite": lambda p: p.write_bytes(b"this is not an SQLite database, it is a text file\n" * 40),
        "truncated": lambda p: p.write_bytes(p.read_bytes()[:5000]),
        "zeroed_page": lambda p: p.write_bytes(p.read_bytes()[:4096] + b"\0" * 4096 + p.read_bytes()[8192:]),
        "garbage_tail_header": lambda p: p.write_bytes(b"SQLite format 3\0" + b"\xff" * 84 + p.read_bytes()[100:]),
    }
    for name, damage in file_damage.items():
        out = root / "stores" / name
        shutil.copytree(base, out)
        damage(out / "results.sqlite")
        cases.append(Case(f"store_{name}", ("run", "tiny", "--out", str(out), "--no-progress"),
                          ("results.sqlite", "damaged", "move it aside")))
    return cases


def _scene_cases(root: Path) -> list[Case]:
    """Scenes that ask what their solver does not model, and ``--solver`` choices that do the same."""
    (root / "blocks.toml").write_text(_BLOCKS)
    s = root
    table = [
        ("mj_default", "moreau_jean", ["default"], _GRID, "", ("solver.name = 'moreau_jean'", "restitution_factor")),
        ("mj_set_e", "moreau_jean", ["set_e"], _GRID, "", ("solver.name = 'moreau_jean'", "restitution = 0.8")),
        ("mj_law", "moreau_jean", ["law"], _GRID, "", ("solver.name = 'moreau_jean'", "restitution_factor")),
        ("mj_drawn", "moreau_jean", ["housner_e", "drawn"], _GRID, "", ("'drawn'", "distribution")),
        ("mj_end_time", "moreau_jean", ["housner_e"], _GRID, "[solver.settings]\nend_time = 5.0\n",
         ("solver.settings.end_time = 5.0",)),
        ("friction_end_time", "friction", ["slider"], _GRID, "[solver.settings]\nend_time = 5.0\n",
         ("solver.settings.end_time = 5.0",)),
        ("fast_end_time", "housner_fast", ["default"], _GRID, "[solver.settings]\nend_time = 5.0\n",
         ("solver.settings.end_time = 5.0",)),
        *[(f"{solver}_slider", solver, ["default", "slider"], _GRID, "", (f"solver.name = '{solver}'", "friction = 0.3"))
          for solver in ("housner", "housner_fast", "sdof", "opensees")],
        *[(f"{solver}_vertical", solver, ["default"], _RECORDS, "", ("records.vertical = 'synthetic'", solver))
          for solver in ("housner_fast", "opensees")],
    ]
    cases = [Case(f"scene_{name}", ("run", _scene(s, name, solver, select, design, settings), "--out", "out",
                                    "--no-progress"), needles)
             for name, solver, select, design, settings, needles in table]
    housner = _scene(s, "fine_housner", "housner", ["default"])
    slider = _scene(s, "fine_friction", "friction", ["slider"])
    vertical = _scene(s, "fine_vertical", "friction", ["default"], _RECORDS)
    cases += [
        Case("run_tiny_moreau_jean", ("run", "tiny", "--solver", "moreau_jean", "--out", "out", "--no-progress"),
             ("--solver moreau_jean", "restitution_factor = 0.95")),
        Case("run_housner_scene_moreau_jean", ("run", housner, "--solver", "moreau_jean", "--out", "out"),
             ("--solver moreau_jean", "restitution_factor")),
        Case("run_slider_housner", ("run", slider, "--solver", "housner", "--out", "out"),
             ("--solver housner", "friction = 0.3")),
        Case("run_slider_housner_fast", ("run", slider, "--solver", "housner_fast", "--out", "out"),
             ("--solver housner_fast", "friction = 0.3")),
        Case("run_vertical_housner_fast", ("run", vertical, "--solver", "housner_fast", "--out", "out"),
             ("--solver housner_fast", "records.vertical = 'synthetic'")),
    ]
    return cases


@pytest.fixture(scope="module")
def base(tmp_path_factory) -> Path:
    """A finished tiny campaign (18 cases, housner)."""
    root = tmp_path_factory.mktemp("stores")
    proc = run_opsrock(["run", "tiny", "--out", "base", "--workers", "1", "--no-progress"], root)
    assert proc.returncode == 0, proc.stderr
    return root / "base"


def all_cases(root: Path, base: Path) -> list[Case]:
    return _damaged_stores(root, base) + _scene_cases(root)


#: Scene cases swept by ``make test`` (one per kind of unmet need: a restitution, an end time, a vertical motion,
#: and ``--solver`` on a scene); the others, the same checks on other solvers, behind ``slow``
#: (tests/unit/campaign/test_scene_capabilities.py loads every solver x need combination in make test, in-process).
QUICK_SCENES: tuple[str, ...] = ("scene_mj_default", "scene_friction_end_time", "scene_opensees_vertical",
                                 "scene_sdof_slider", "run_slider_housner_fast")


def _quick(base, tmp_path) -> list:
    cases = [c for c in all_cases(tmp_path, base) if not c.name.startswith(("scene_", "run_")) or c.name in QUICK_SCENES]
    assert len(cases) == 26 + len(QUICK_SCENES)
    return cases


def _sweep_keeping_stores(cases, tmp_path) -> list[str]:
    """The broken promises of ``cases`` (empty: none), after checking that no damaged store was touched."""
    before = {c.name: (tmp_path / "stores" / c.name[6:] / "results.sqlite").read_bytes()
              for c in cases if c.name.startswith("store_")}
    work = tmp_path / "work"
    work.mkdir()
    broken = sweep(cases, work)
    for name, data in before.items():  # a damaged store is refused, never touched
        store = tmp_path / "stores" / name[6:] / "results.sqlite"
        assert store.read_bytes() == data, name
    return broken


def test_hostile_stores_and_scenes(base, tmp_path):
    # every other store and quick scene case; the others in the slow test below (make test under 10 minutes)
    broken = _sweep_keeping_stores(_quick(base, tmp_path)[0::2], tmp_path)
    assert not broken, "\n".join(broken)


@pytest.mark.slow
def test_every_scene_whose_solver_cannot_meet_a_need_is_refused(base, tmp_path):
    others = [c for c in _scene_cases(tmp_path) if c.name not in QUICK_SCENES]
    broken = _sweep_keeping_stores(_quick(base, tmp_path)[1::2] + others, tmp_path)
    assert not broken, "\n".join(broken)


def test_store_case_counts(base, tmp_path):
    # the closing note reports these counts: every case runs `opsrock run`
    cases = all_cases(tmp_path, base)
    assert Counter(c.args[0] for c in cases) == {"run": 44}
    assert Counter(c.name.split("_")[0] for c in cases) == {"store": 26, "scene": 13, "run": 5}


# --- the environment: another process, a full disk ------------------------------------------------------
def _resume_into(base: Path, out: Path, keep: int) -> None:
    """``out``: a copy of ``base`` whose store holds only its first ``keep`` cases (an interrupted run)."""
    shutil.copytree(base, out)
    (out / "cases.csv").unlink()
    _sql(out / "results.sqlite", f"DELETE FROM results WHERE rowid > {keep}")


def test_a_locked_store_is_in_use_not_damaged(base, tmp_path):
    out = tmp_path / "out"
    _resume_into(base, out, 7)
    holder = sqlite3.connect(out / "results.sqlite", isolation_level=None)
    holder.execute("BEGIN IMMEDIATE")  # another process writing: SQLite's write lock held
    try:
        t0 = time.perf_counter()
        proc = run_opsrock(["run", "tiny", "--out", str(out), "--workers", "1", "--no-progress"], tmp_path)
        waited = time.perf_counter() - t0
    finally:
        holder.execute("ROLLBACK")
        holder.close()
    lines = proc.stderr.splitlines()
    assert proc.returncode == 1 and len(lines) == 1 and "Traceback" not in proc.stderr, proc.stderr
    assert "results.sqlite" in lines[0] and "in use by another process" in lines[0] and "wait" in lines[0]
    assert "delete" not in lines[0] and "move" not in lines[0] and "damaged" not in lines[0]
    assert waited < 60
    again = run_opsrock(["run", "tiny", "--out", str(out), "--workers", "1", "--no-progress"], tmp_path)
    assert again.returncode == 0, again.stderr
    assert "(11 computed, 7 reused)" in again.stdout
    _assert_intact(out / "results.sqlite", TINY_CASES)


def _assert_intact(store: Path, n: int) -> None:
    db = sqlite3.connect(store)
    try:
        assert db.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
        assert db.execute("SELECT COUNT(DISTINCT case_id) FROM results").fetchone()[0] == n
    finally:
        db.close()


_FULL_DISK = """\
set -u
mount -t tmpfs -o size=1m tmpfs "$DISK" || exit 97
head -c 946176 /dev/zero > "$DISK/filler"  # 100 KiB left: the store is made, then fills it
"$@" > "$WORK/first.out" 2> "$WORK/first.err"; echo $? > "$WORK/first.rc"
"$PY" -c "import sqlite3, sys; print(sqlite3.connect(sys.argv[1]).execute('select count(*) from results').fetchone()[0])" \
  "$DISK/out/results.sqlite" > "$WORK/kept" 2>&1
rm "$DISK/filler"
"$@" > "$WORK/second.out" 2> "$WORK/second.err"; echo $? > "$WORK/second.rc"
cp -r "$DISK/out" "$WORK/out"
umount "$DISK"
"""


def _full_disk_command() -> list[str] | None:
    """How to mount a small tmpfs: in a mount namespace of our own (as root, or as a user mapped to root)."""
    if shutil.which("unshare") is None:
        return None
    head = ["unshare", "-m"] if os.geteuid() == 0 else ["unshare", "-rm"]
    probe = subprocess.run([*head, "true"], capture_output=True)
    return head if probe.returncode == 0 else None


def test_a_full_disk_keeps_the_finished_cases_and_resumes(tmp_path):
    head = _full_disk_command()
    if head is None:
        pytest.skip("no mount namespace here (unshare -m / -rm refused): cannot mount a small tmpfs")
    scene = tmp_path / "full.toml"
    scene.write_text(f'name = "full"\nblocks = "{BLOCKS}"\nselect = ["bookcase"]\n[solver]\nname = "housner"\n'
                     "[grid.freq_ratio]\nvalues = [1.0, 2.0, 3.0, 4.0]\n"
                     "[grid.pfa_ratio]\nvalues = [0.8, 1.2, 1.6, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]\n")
    disk, work = tmp_path / "disk", tmp_path / "work"
    disk.mkdir()
    work.mkdir()
    cmd = opsrock_command(["run", str(scene), "--out", str(disk / "out"), "--workers", "1", "--batch", "1",
                           "--no-progress"])
    env = {**os.environ, "DISK": str(disk), "WORK": str(work), "PY": sys.executable}
    proc = subprocess.run([*head, "sh", "-c", _FULL_DISK, "sh", *cmd], env=env, capture_output=True, text=True,
                          timeout=300)
    if proc.returncode == 97:
        pytest.skip(f"cannot mount a tmpfs in a mount namespace: {proc.stderr.strip()}")
    assert proc.returncode == 0, proc.stderr
    first = (work / "first.err").read_text()
    assert (work / "first.rc").read_text().strip() == "1", first
    assert len(first.splitlines()) == 1 and "Traceback" not in first, first
    assert "results.sqlite" in first and "disk is full" in first and "kept" in first and "resume" in first
    assert "rollback" not in first and "delete" not in first and "move" not in first
    kept = int((work / "kept").read_text())
    assert 0 < kept < 40
    second = (work / "second.out").read_text()
    assert (work / "second.rc").read_text().strip() == "0", (work / "second.err").read_text()
    assert f"({40 - kept} computed, {kept} reused)" in second
    _assert_intact(work / "out" / "results.sqlite", 40)
    assert len((work / "out" / "cases.csv").read_text().splitlines()) == 42  # header, units row, 40 cases
