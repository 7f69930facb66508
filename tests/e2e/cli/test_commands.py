"""The ``opsrock`` command line: JSON answers, one-line errors with exit status 2."""

from __future__ import annotations

import json
import math

import pytest

from _support import run_opsrock
from opsrock.cli import main

REQUIRED_KEYS = {"theta_max", "theta_max_over_alpha", "overturned", "status", "solver", "alpha", "R", "p", "e",
                 "wall_time_s"}


@pytest.mark.parametrize("solver", ["opensees", "sdof", "housner", "housner_fast"])
def test_simulate_json_has_the_documented_keys(solver, capsys):
    rc = main(["simulate", "--width", "0.4", "--height", "2.2", "--pfa-ratio", "3", "--freq-ratio", "4",
               "--solver", solver, "--json"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0
    assert REQUIRED_KEYS <= out.keys()
    assert out["solver"] == solver and out["status"] == "ok"
    # alpha = atan(0.2/1.1) for this block (docs/guide/modelling.md s.2)
    assert out["alpha"] == pytest.approx(0.17985349979247828, rel=1e-12)
    assert out["theta_max_over_alpha"] == pytest.approx(out["theta_max"] / out["alpha"], rel=1e-12)


def test_simulate_units_of_pfa_and_freq(capsys):
    # --pfa is in g and --freq in Hz: 0.5 g, 1 Hz -> PFA 4.905 m/s², omega_p 2 pi rad/s
    main(["simulate", "--width", "0.4", "--height", "2.2", "--pfa", "0.5", "--freq", "1", "--solver", "housner", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert out["pfa"] == pytest.approx(0.5 * 9.81)
    assert out["omega_p"] == pytest.approx(2 * 3.141592653589793)


def test_simulate_below_uplift_does_not_rock(capsys):
    main(["simulate", "--width", "0.4", "--height", "2.2", "--pfa-ratio", "0.9", "--freq-ratio", "2", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert out["verdict"] == "no_uplift" and not out["overturned"]


def test_simulate_plot_writes_png(tmp_path, capsys):
    png = tmp_path / "case.png"
    rc = main(["simulate", "--width", "0.4", "--height", "2.2", "--pfa-ratio", "2.5", "--freq-ratio", "3",
               "--plot", str(png)])
    assert rc == 0
    assert png.stat().st_size > 10_000  # three panels of lines, not an empty canvas
    assert not list(tmp_path.glob("*.tmp*"))


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["simulate", "--width", "-1", "--height", "2", "--pfa", "1", "--freq", "1"], "--width"),
        (["simulate", "--width", "0.4", "--height", "nan", "--pfa", "1", "--freq", "1"], "--height"),
        (["simulate", "--width", "0.4", "--height", "2", "--freq", "1"], "--pfa"),
        (["simulate", "--width", "0.4", "--height", "2", "--pfa", "1", "--pfa-ratio", "2", "--freq", "1"], "--pfa-ratio"),
        (["simulate", "--width", "0.4", "--height", "2", "--pfa", "1", "--freq", "1", "--solver", "abaqus"], "--solver"),
        (["simulate", "--width", "0.4", "--height", "2", "--pfa", "1", "--freq", "1", "--delta", "3"], "delta"),
        (["simulate", "--width", "0.4", "--height", "2", "--pfa", "1", "--freq", "1", "--lever", "long"], "--lever"),
        (["simulate", "--width", "0.4", "--height", "2", "--pfa", "1", "--freq", "1", "--damper", "eq8"], "--damper"),
        (["simulate", "--width", "0.4", "--height", "2", "--pfa", "1", "--freq", "1", "--solver", "housner",
          "--damper", "energy"], "--damper"),
        (["simulate", "--width", "0.4", "--height", "2", "--pfa", "1", "--freq", "1", "--solver", "housner", "--dt", "1e-3"], "--dt"),
        (["simulate", "--width", "3", "--height", "2", "--pfa", "1", "--freq", "1"], "lands flat (e = 0)"),  # issue 32: valid, but not on the SDOF model
        (["simulate", "--width", "0.4", "--height", "2", "--pfa", "1", "--freq", "1", "--plot", "x.jpg"], "--plot"),
        (["nonsense"], "invalid choice"),
    ],
)
def test_bad_arguments_exit_2_with_one_line(args, needle, capsys):
    assert main(args) == 2
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1, err
    assert needle in lines[0]


@pytest.mark.parametrize("args", [["simulate", "--width", "-1", "--height", "2", "--pfa", "1", "--freq", "1"],
                                  ["simulate", "--width", "3", "--height", "2", "--pfa", "1", "--freq", "1"]])
def test_console_entry_point_exits_2_without_traceback(args):
    # The real process: exit status 2, one line on stderr, no traceback (docs/guide/modelling.md section 1).
    proc = run_opsrock(args)
    assert proc.returncode == 2
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip() and "Process 0 Terminating" not in ln]
    assert len(lines) == 1, proc.stderr
    assert "Traceback" not in proc.stderr


def test_damper_option_reaches_the_sdof_solver(capsys):
    # --damper entry_velocity is the paper's Eq. 8: the result's settings carry it
    main(["simulate", "--width", "0.5", "--height", "1.15", "--pfa-ratio", "3", "--freq-ratio", "4", "--solver", "sdof",
          "--damper", "entry_velocity", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert out["settings"]["model"]["damper"] == "entry_velocity"  # both SDOF solvers nest their model


def test_simulate_reports_the_solver_wall_time(capsys):
    # The solver's own wall time is reported (process start-up and imports excluded); its size is the
    # benchmarks' business (opsrock bench), not a test's: a loaded machine would fail any bound here.
    main(["simulate", "--width", "0.6", "--height", "2.0", "--pfa-ratio", "4", "--freq-ratio", "2", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert out["wall_time_s"] > 0.0 and math.isfinite(out["wall_time_s"])
