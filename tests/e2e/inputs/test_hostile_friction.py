"""Friction and vertical floor motion through the real console script (issue 31, area A).

The table: bad friction values and floor motions no floor makes, on ``simulate`` and ``threshold``, each
refused with exit 2 and one line naming the argument (the promise of ``_hostile``). Then valid inputs that
must END with a stated result: frictionless and near-frictionless blocks (``--friction 0``, ``1e-320``,
with a vertical motion, under ``threshold``, in a blocks file run by ``opsrock run``), a block still
sliding when its floor stops, and a short free flight (docs/guide/friction.md: the ending rule, the flight rule).
"""

from __future__ import annotations

import json
import time
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from _hostile import Case, every_other, one_per_option, sweep
from _support import case_rows, run_opsrock, without_compile_notice

SIM = ("simulate", "--width", "0.4", "--height", "2.2")
PULSE = ("--pfa", "1", "--freq", "1")
THR = ("threshold", "--width", "0.4", "--height", "2.2", "--freq-ratio", "3")



@pytest.fixture(scope="module")
def files(tmp_path_factory) -> Path:
    """Record files: a still horizontal floor, vertical motions that fall faster than g (for 9.99 s, for
    1.5 s, for 0.1 s), a floor that stops moving and one that ends moving."""
    base = tmp_path_factory.mktemp("friction_inputs")
    (base / "still.txt").write_text("0\n" * 1000)
    (base / "drop.txt").write_text("-3\n" * 1000)  # -3 g for the whole 9.99 s: 1.5 km down
    (base / "drop_long.txt").write_text("-1.5\n" * 151 + "0\n" * 849)  # -1.5 g for 1.5 s
    (base / "drop_short.txt").write_text("-3\n" * 10 + "0\n" * 990)  # -3 g for 0.09 s, then a ramp to 0
    (base / "step.txt").write_text("0.1\n" * 100 + "0\n" * 100)  # the floor ends moving at 0.976 m/s
    return base


def _rec(b: Path, name: str = "still.txt") -> tuple[str, ...]:
    return ("--record", f"{b}/{name}", "--units", "g", "--dt", "0.01")


def friction_cases(b: Path) -> list[Case]:
    """Bad friction values and implausible vertical motions, on simulate and threshold."""
    cases = []
    for cmd, prefix, suffix in (("simulate", SIM, PULSE), ("threshold", THR, ())):
        for v in ("-0.1", "-1e-320", "nan", "inf", "-inf", "high", "", "0x1p-2", "1e400"):
            cases.append(Case(f"{cmd} --friction {v!r}", (*prefix, "--friction", v, *suffix), ("--friction",)))
        for v in ("-0.2", "nan", "inf", "low", "1.31"):
            cases.append(Case(f"{cmd} --friction-kinetic {v!r}", (*prefix, "--friction", "2", "--friction-kinetic", v,
                                                                     *suffix), ("--friction-kinetic",)))
        cases += [
            Case(f"{cmd} kinetic a hair above static", (*prefix, "--friction", "0.3", "--friction-kinetic", "0.3000001",
                                                        *suffix), ("--friction-kinetic", "0.3000001", "0.3")),
            Case(f"{cmd} kinetic one ulp above static", (*prefix, "--friction", "0.3", "--friction-kinetic",
                                                         "0.30000000000000004", *suffix),
                 ("--friction-kinetic", "0.30000000000000004", "friction = 0.3:")),
            Case(f"{cmd} kinetic above a frictionless static", (*prefix, "--friction", "0", "--friction-kinetic", "1e-300",
                                                                *suffix), ("--friction-kinetic", "1e-300")),
            Case(f"{cmd} kinetic without static", (*prefix, "--friction-kinetic", "0.3", *suffix), ("--friction-kinetic",)),
            Case(f"{cmd} friction with a no-slip solver", (*prefix, "--friction", "0.3", "--solver", "housner", *suffix),
                 ("--friction",)),
        ]
    cases += [
        # pulses: a constant vertical acceleration must keep g + a_v > 0 (the floor would fall for ever)
        Case("simulate --vertical -1 (free fall)", (*SIM, *PULSE, "--friction", "0.5", "--vertical", "-1"), ("--vertical",)),
        Case("simulate --vertical -3", (*SIM, *PULSE, "--friction", "0.5", "--vertical", "-3"), ("--vertical",)),
        Case("simulate --vertical nan", (*SIM, *PULSE, "--friction", "0.5", "--vertical", "nan"), ("--vertical",)),
        Case("simulate --vertical inf", (*SIM, *PULSE, "--friction", "0.5", "--vertical", "inf"), ("--vertical",)),
        Case("simulate --vertical with a record", (*SIM, *_rec(b), "--friction", "0.5", "--vertical", "0.3"),
             ("--vertical",)),
        # records: a floor that accelerates downward faster than g for longer than MAX_FREE_FALL
        Case("simulate --vertical-record -3 g for 9.99 s", (*SIM, *_rec(b), "--friction", "0.5", "--vertical-record",
                                                            f"{b}/drop.txt"), ("vertical", "9.99 s", "faster than g")),
        Case("simulate --vertical-record -1.5 g for 1.5 s", (*SIM, *_rec(b), "--vertical-record", f"{b}/drop_long.txt"),
             ("vertical", "1.5", "faster than g")),
        Case("simulate --vertical-record frictionless -3 g", (*SIM, *_rec(b), "--friction", "0", "--vertical-record",
                                                              f"{b}/drop.txt"), ("vertical", "9.99 s")),
        Case("simulate --vertical-record missing", (*SIM, *_rec(b), "--vertical-record", f"{b}/nope.txt"),
             ("--vertical-record", "nope.txt")),
        Case("simulate --vertical-record without --record", (*SIM, *PULSE, "--vertical-record", f"{b}/drop.txt"),
             ("--vertical-record",)),
    ]
    return cases


def test_friction_and_vertical_inputs_are_refused(files, tmp_path):
    quick, _ = one_per_option(friction_cases(files))  # one bad value per option, every other option
    broken = sweep(every_other(quick)[0], tmp_path, workers=4, timeout=60)
    assert not broken, "\n".join(broken)


@pytest.mark.slow
def test_every_friction_option_refuses_every_bad_value(files, tmp_path):
    quick, rest = one_per_option(friction_cases(files))
    assert sweep(every_other(quick)[1] + rest, tmp_path, workers=4, timeout=60) == []


def test_friction_case_counts(files):
    counts = Counter(c.args[0] for c in friction_cases(files))
    assert counts == {"simulate": 29, "threshold": 19}, counts


# --- valid input that must end, with a stated result -------------------------------------------------
def _run(args: tuple[str, ...], cwd: Path) -> tuple[str, float]:
    start = time.monotonic()
    proc = run_opsrock(args, cwd, timeout=120)  # the timeout is the guard against a run that never ends
    took = time.monotonic() - start
    assert proc.returncode == 0 and not without_compile_notice(proc.stderr), proc.stderr
    return proc.stdout, took


@pytest.mark.parametrize("extra", [("--friction", "0"), ("--friction", "1e-320"), ("--friction", "0", "--vertical", "0.5"),
                                   ("--friction", "1e-300", "--friction-kinetic", "0")])
def test_a_frictionless_block_slides_minus_the_floor_displacement_and_ends(extra, tmp_path):
    """The one-sine floor (1 g, 1 s) moves A T / omega = 1.5613 m and ends at rest: the block, which no
    horizontal force reaches, is left 1.561 m behind, at rest."""
    out, _ = _run((*SIM, *PULSE, "--solver", "friction", *extra), tmp_path)
    assert "slid; first mode slide" in out and "residual -1.561 m" in out and "still sliding" not in out


def test_a_frictionless_block_on_a_floor_that_ends_moving_is_still_sliding(files, tmp_path):
    out, _ = _run((*SIM, *_rec(files, "step.txt"), "--friction", "0", "--json"), tmp_path)
    d = json.loads(out)
    assert d["status"] == "ok" and d["response"] == "slid"
    assert d["slip_velocity_end"] == pytest.approx(-0.976095, rel=1e-6)  # -v_g at the end of the record
    assert d["slide_residual"] == pytest.approx(-1.4568177, rel=1e-6)  # -x_g at the end of the record
    text, _ = _run((*SIM, *_rec(files, "step.txt"), "--friction", "1e-320"), tmp_path)
    assert "still sliding at -0.9761 m/s" in text


def test_threshold_of_a_frictionless_block_ends_quickly(tmp_path):
    out, took = _run((*THR, "--friction", "0", "--json"), tmp_path)
    d = json.loads(out)
    assert d["intervals_pfa_ratio"] == [] and d["failed"] == [] and d["n_solves"] == 600


def test_a_short_free_flight_is_followed(files, tmp_path):
    """-3 g for 0.09 s then a 0.01-s ramp to 0: the block flies 0.5176 s (closed form in
    tests/model/solvers/test_friction_ending.py) and lands flat, at rest."""
    out, _ = _run((*SIM, *_rec(files), "--friction", "0.5", "--vertical-record", f"{files}/drop_short.txt", "--json"),
                  tmp_path)
    d = json.loads(out)
    assert d["status"] == "ok" and d["first_mode"] == "flight" and d["response"] == "at_rest"
    assert d["time_flight"] == pytest.approx(0.51765, abs=1e-4)


def test_a_blocks_file_with_a_frictionless_block_runs(tmp_path):
    (tmp_path / "blocks.toml").write_text('[[block]]\nname = "slick"\nwidth = 0.4\nheight = 2.2\n'
                                          'reason = "a frictionless floor"\nfriction = 0.0\n')
    (tmp_path / "scene.toml").write_text('name = "slick"\nblocks = "blocks.toml"\n[solver]\nname = "friction"\n'
                                         '[grid.freq_ratio]\nvalues = [1.0, 3.0]\n[grid.pfa_ratio]\nvalues = [0.8, 2.0]\n')
    proc = run_opsrock(("run", "scene.toml", "--out", "out", "--no-progress", "--workers", "1"), tmp_path, timeout=120)
    assert proc.returncode == 0, proc.stderr
    rows = case_rows(tmp_path / "out" / "cases.csv")
    assert len(rows) == 4
    assert {r["status"] for r in rows} == {"ok"} and {r["response"] for r in rows} == {"slid"}
    # the one-sine floors end at rest: each block is left -x_g(T) = -pfa T_p / omega_p behind
    for r in rows:
        x_g = float(r["pfa"]) * 2.0 * np.pi / float(r["omega_p"]) ** 2
        assert float(r["slide_residual"]) == pytest.approx(-x_g, rel=1e-8)
