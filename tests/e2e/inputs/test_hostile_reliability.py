"""Issue 46 through the real console script: what used to be accepted silently is refused in one line naming the
option (the promise of :mod:`_hostile`), the outputs mean what they say (``theta_max`` at most pi/2 in every
solver, the 3-D ``alpha`` and ``pfa_ratio`` of the weaker axis and the motion's direction, ``wall_time_s`` without
the compilation), one exit status per kind of fault, and a campaign that could compute nothing never returns as if
it had."""

from __future__ import annotations

import fcntl
import json
import math
import os
import subprocess
import sys
from collections import Counter
from pathlib import Path

import pytest
from _hostile import Case, one_per_option, sweep
from _support import ROOT, opsrock_command, run_opsrock

from opsrock.constants import G, OVERTURNING_ANGLE

BLOCKS = ROOT / "opsrock" / "data" / "blocks.toml"
SCENE = f"""\
name = "small"
blocks = "{BLOCKS}"
select = ["medicine_cabinet"]
[solver]
name = "housner_fast"
[grid.freq_ratio]
values = [1.0, 3.0]
[grid.pfa_ratio]
values = [0.8, 2.0]
"""
SIM = ("simulate", "--width", "0.4", "--height", "2.0")


@pytest.fixture(scope="module")
def base(tmp_path_factory) -> Path:
    """A scene of four housner_fast cases; a 1-s record in g at 0.01 s and a vertical one reaching -3 g, below -g
    for 0.78 s (inside MAX_FREE_FALL, 1 s) but leaving the floor 4.87 m below the block at the record's end
    (trapezoidal sums of ``gap'' = -(g + a_v)``; 0.77 m at half the scale)."""
    b = tmp_path_factory.mktemp("reliability")
    (b / "scene.toml").write_text(SCENE)
    (b / "h.txt").write_text("\n".join(f"{0.3 * math.sin(k / 5):.4f}" for k in range(100)) + "\n")
    rows = "".join(f"box{k},a box,0.4,0.5,1.0\n" for k in range(10_001))
    (b / "items.csv").write_text("id,description,width,depth,height\n" + rows)
    (b / "motions.csv").write_text("record,floor,direction,file,units,dt\nr1,1,1,h.txt,g,0.01\n")
    (b / "v.txt").write_text("\n".join(f"{-3.0 * math.sin(math.pi * k / 99):.4f}" for k in range(100)) + "\n")
    return b


def reliability_cases(b: Path) -> list[Case]:
    """The refusals of issue 46 that are not an inventory cell (those are in test_hostile_inventory)."""
    rec = ("--record", f"{b}/h.txt", "--units", "g", "--dt", "0.01")
    return [
        Case("contents inventory-of-10001-rows", ("contents", "--inventory", f"{b}/items.csv", "--motions",
                                                  f"{b}/motions.csv", "--out", "out"), ("items.csv", "10,001 items",
                                                                                        "10,000")),
        Case("version extra", ("--version", "extra"), ("--version", "'extra'")),
        Case("version then-command", ("--version", "simulate"), ("--version", "'simulate'")),
        Case("simulate --vertical-record below-minus-g", (*SIM, *rec, "--vertical-record", f"{b}/v.txt"),
             ("vertical", "-3 g", "fly free", "4.87 m below", "longer than the record")),
        Case("simulate --vertical-record scaled-below-minus-g", (*SIM, *rec, "--vertical-record", f"{b}/v.txt",
                                                                  "--scale", "0.5"), ("vertical", "-1.5 g")),
        # a short drop (-3 g for 0.09 s, landed at 0.52 s) is the friction solver's flight: test_hostile_friction
    ]


def test_reliability_case_counts(base):
    counts = Counter(c.name.rsplit(" ", 1)[0] for c in reliability_cases(base))
    assert counts == {"contents": 1, "version": 2, "simulate --vertical-record": 2}, counts


def test_silent_acceptances_are_refused_in_one_line(base, tmp_path):
    quick, rest = one_per_option(reliability_cases(base))
    assert sweep(quick + rest, tmp_path) == []  # five starts of the console script, about 1 s of CPU each


def test_a_long_record_show_says_how_large_it_is_first(base, monkeypatch, capsys):
    """The lines a 50-MB record file gets (issue 46: 10 million samples ran silent past 60 s; its spectra take
    minutes), shown on a small one by lowering the thresholds; in this process (the console script cannot be
    given the thresholds, and a file past them takes a minute)."""
    from opsrock.cli import main
    from opsrock.cli import records as cli_records

    import opsrock.intensity.records as spectra

    monkeypatch.setattr(cli_records, "LONG_READ_BYTES", 0)
    monkeypatch.setattr(cli_records, "LONG_SHOW_S", 0.0)
    monkeypatch.setattr(spectra, "SPECTRUM_WORK_BYTES", 3 * 8 * 100 * 50)  # 50 periods at a time: 5 chunks
    monkeypatch.setenv("OPSROCK_PROGRESS_INTERVAL", "1e-9")  # a line after every chunk
    assert main(["records", "show", str(base / "h.txt"), "--units", "g", "--dt", "0.01"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("opsrock records: reading ") and "h.txt (0.0 MB)" in err[0]
    assert "100 samples (1 s at dt 0.01 s): its response spectra at 211 periods take about 0 s" in err[1]
    assert err[2:] == [f"opsrock records: spectra {k}/211 periods" for k in (50, 100, 150, 200, 211)], err


def test_version_alone_prints_the_version(tmp_path):
    proc = run_opsrock(["--version"], tmp_path, timeout=60)
    assert proc.returncode == 0 and proc.stdout.startswith("opsrock ") and not proc.stderr


def test_a_store_that_is_a_folder_is_named_as_one(base, tmp_path):
    (tmp_path / "out" / "results.sqlite").mkdir(parents=True)
    proc = run_opsrock(["run", str(base / "scene.toml"), "--out", "out", "--no-progress"], tmp_path, timeout=120)
    assert proc.returncode == 2, proc.stderr
    assert "results.sqlite is a folder, not a campaign store" in proc.stderr and "permission" not in proc.stderr
    assert len(proc.stderr.splitlines()) == 1 and "Traceback" not in proc.stderr
    assert sorted(os.listdir(tmp_path / "out")) == [".lock", "results.sqlite"]  # nothing else written


def test_a_lock_held_by_another_run_is_an_environment_fault(base, tmp_path):
    """README: environment faults exit 1 (a store in use, a full disk), bad input 2; a held lock is the former."""
    out = tmp_path / "out"
    out.mkdir()
    fd = os.open(out / ".lock", os.O_RDWR | os.O_CREAT)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        proc = run_opsrock(["run", str(base / "scene.toml"), "--out", "out", "--no-progress"], tmp_path, timeout=120)
    finally:
        os.close(fd)
    assert proc.returncode == 1, proc.stderr
    assert "another opsrock run is writing" in proc.stderr and len(proc.stderr.splitlines()) == 1
    assert sorted(os.listdir(out)) == [".lock"]


@pytest.mark.slow  # a contents study twice (10 s); the lock's status is checked through `run` in make test
def test_a_lock_held_by_another_run_is_an_environment_fault_for_contents_too(tmp_path):
    """The same fault, the same status in every command (issue 46: ``contents`` gave 1 and ``run`` 2): a study
    finished once, then re-run while every store lock of its folder is held by another process."""
    args = ["contents", "--quick", "--items", "E.20.22.105a", "--variants", "default", "--n-boot", "2",
            "--records", "NORTHR_MUL009,NORTHR_LOS000",
            "--out", "out", "--no-progress"]
    first = run_opsrock(args, tmp_path, timeout=600)
    assert first.returncode == 0, first.stderr
    locks = sorted((tmp_path / "out").rglob(".lock"))
    assert locks  # each campaign store has its lock file
    fds = [os.open(p, os.O_RDWR) for p in locks]
    try:
        for fd in fds:
            fcntl.flock(fd, fcntl.LOCK_EX)
        again = run_opsrock(args, tmp_path, timeout=600)
    finally:
        for fd in fds:
            os.close(fd)
    assert again.returncode == 1, again.stderr
    assert "another opsrock run is writing" in again.stderr and len(again.stderr.splitlines()) == 1


@pytest.mark.parametrize("solver", ["friction", "housner_fast", "housner"])
def test_theta_max_of_an_overturned_block_is_pi_over_2_in_every_solver(solver, tmp_path):
    """Issue 46: ``friction`` reported 1.585 rad for this block, which overturns during the excitation."""
    proc = run_opsrock([*SIM, "--pfa-ratio", "6", "--freq-ratio", "3", "--solver", solver, "--json"], tmp_path,
                       timeout=300)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["overturned"] and out["theta_max"] == OVERTURNING_ANGLE


def test_three_d_alpha_and_pfa_ratio_are_those_of_the_weaker_axis_and_the_motions_direction(tmp_path):
    """0.6 x 0.4 x 2.0 m at azimuth 30 deg under 0.3 g along motion axis 1: along the block's width 0.3 cos 30 =
    0.260 g of the 0.3 g that uplifts across the width, across its depth 0.3 sin 30 = 0.15 g of 0.2 g; the
    smallest PFA along axis 1 that uplifts it is 0.3 / cos 30 = 0.346 g, so pfa_ratio = 0.3 / 0.346 = cos 30
    (issue 46: 1.0 was reported, the width's ratio). ``alpha`` is the depth's, the weaker axis, which
    ``theta_max_over_alpha`` divides by."""
    proc = run_opsrock(["simulate", "--solver", "rigid3d", "--width", "0.6", "--depth", "0.4", "--height", "2.0",
                        "--azimuth", "30", "--pfa", "0.3", "--freq-ratio", "3", "--json"], tmp_path, timeout=900)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["alpha"] == pytest.approx(math.atan(0.2 / 1.0), rel=1e-12) == out["alpha_depth"]
    assert out["alpha_width"] == pytest.approx(math.atan(0.3 / 1.0), rel=1e-12)
    assert out["pfa_ratio"] == pytest.approx(math.cos(math.radians(30.0)), rel=1e-12)
    assert out["pfa"] == pytest.approx(0.3 * G, rel=1e-12)
    assert out["verdict"] == "no_uplift"  # below the uplift level in its direction, as pfa_ratio < 1 says
    # the text says the same, in words: not "g tan alpha", which is the width's ratio (0.3 g / 0.3 g = 1)
    text = run_opsrock(["simulate", "--solver", "rigid3d", "--width", "0.6", "--depth", "0.4", "--height", "2.0",
                        "--azimuth", "30", "--pfa", "0.3", "--freq-ratio", "3"], tmp_path, timeout=900)
    assert text.returncode == 0, text.stderr
    assert "g tan alpha" not in text.stdout
    assert "(0.866 x the PFA that uplifts it in the motion's direction)" in text.stdout
    assert "x 0.1974 rad, the weaker axis's alpha" in text.stdout and "alpha across the width = 0.2915" in text.stdout


def test_wall_time_excludes_the_compilation(tmp_path):
    """A first solve in an empty numba cache compiles housner_fast's kernel (seconds) and solves (well under a
    millisecond here): the reported wall time is the solve's. A ratio within one run, not a speed: measured
    0.00022 s reported in a 15.8-s process (compilation and imports), a factor 70,000; asserted 20."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "numba")}
    t0 = _monotonic()
    proc = subprocess.run(opsrock_command([*SIM, "--pfa-ratio", "2", "--freq-ratio", "3", "--solver", "housner_fast",
                                           "--json"]), cwd=tmp_path, capture_output=True, text=True, timeout=600,
                          env=env)
    elapsed = _monotonic() - t0
    assert proc.returncode == 0, proc.stderr
    assert any((tmp_path / "numba").rglob("*.nbi"))  # it did compile (into the empty cache)
    assert 0.0 < json.loads(proc.stdout)["wall_time_s"] < elapsed / 20


def _monotonic() -> float:
    import time

    return time.monotonic()


STDIN_SCRIPT = """\
from opsrock.campaign import run_campaign
if __name__ == "__main__":
    run_campaign({scene!r}, "out", workers={workers}, progress=False)
    print("returned")
"""


def test_a_script_read_from_standard_input_refuses_several_workers_at_once(base, tmp_path):
    """``python3 - <<EOF`` with two workers: spawned workers cannot import ``<stdin>`` (issue 46: every case was
    lost and the call returned normally). Now: one error naming the cause and the fix, before anything is written;
    with one worker the cases run in the calling process."""
    script = STDIN_SCRIPT.format(scene=str(base / "scene.toml"), workers=2)
    proc = subprocess.run([sys.executable, "-"], input=script, cwd=tmp_path, capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 1 and "returned" not in proc.stdout
    last = proc.stderr.strip().splitlines()[-1]
    assert "UnguardedScriptError" in last and "<stdin>" in last and "workers=1" in last, proc.stderr
    assert not (tmp_path / "out").exists()
    one = subprocess.run([sys.executable, "-"], input=STDIN_SCRIPT.format(scene=str(base / "scene.toml"), workers=1),
                         cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert one.returncode == 0 and "returned" in one.stdout, one.stderr
    assert len((tmp_path / "out" / "cases.csv").read_text().splitlines()) == 2 + 4  # header, units row, cases


def test_a_hopeless_study_is_refused_up_front_with_its_number_of_cases(tmp_path):
    """Issue 46: ``contents`` on every floor of a 200-storey building (3.8 million cases) computed floor motions
    for minutes, days of work ahead; a campaign of more than MAX_CASES is now refused before any work, as a
    scene file of that size is, and nothing is written."""
    floors = ",".join(["ground", *map(str, range(1, 201))])
    proc = run_opsrock(["contents", "--storeys", "200", "--period", "4", "--floors", floors, "--out", "out",
                        "--no-sweep", "--no-progress"], tmp_path, timeout=300)
    assert proc.returncode == 2, proc.stderr
    assert proc.stderr.count("\n") == 1 and "MAX_CASES" in proc.stderr and "cases" in proc.stderr
    assert not (tmp_path / "out").exists()
