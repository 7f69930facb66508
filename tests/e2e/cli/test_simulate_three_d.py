"""``opsrock simulate`` with a box in three dimensions (issue 33), in this process: the dispatch of a
:class:`PlanMotion` (a planar one runs a planar solver as its first component, to the same answer; another is
refused naming the solver), the default solver and restitution of the plan options, the motion the command
builds from ``--record2`` and ``--azimuth``, and the lines and JSON keys of the three-dimensional outputs
(from a result built here: the solver's own numbers are the kernel's tests)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from opsrock.block import Block
from opsrock.cli import main
from opsrock.cli import simulate as cli_simulate
from opsrock.cli.parser import build_parser
from opsrock.constants import G
from opsrock.errors import ModelNotSupported
from opsrock.excitations import OneSinePulse
from opsrock.excitations.plan import PlanMotion
from opsrock.result import PlanSummary, RockingResult
from opsrock.solvers import planar_excitation, simulate

BLOCK = Block(width=0.4, height=1.6, depth=0.6)
PULSE = OneSinePulse.from_ratios(BLOCK, pfa_ratio=3.0, freq_ratio=3.0)


def test_a_planar_plan_motion_runs_a_planar_solver_to_the_same_answer():
    plain = simulate(BLOCK, PULSE, solver="housner_fast")
    for azimuth in (0.0, 360.0, -360.0):
        planned = simulate(BLOCK, PlanMotion(PULSE, azimuth=azimuth), solver="housner_fast")
        assert planned.theta_max == plain.theta_max and planned.verdict == plain.verdict  # the same call, bit for bit
    assert planar_excitation("housner_fast", PlanMotion(PULSE)) is PULSE
    assert isinstance(planar_excitation("rigid3d", PlanMotion(PULSE)), PlanMotion)  # the solver in plan keeps it


@pytest.mark.parametrize("motion", [PlanMotion(PULSE, azimuth=30.0), PlanMotion(PULSE, PULSE)])
def test_a_plan_motion_that_turns_or_has_two_components_is_refused_for_a_planar_solver(motion):
    with pytest.raises(ModelNotSupported, match="solver 'friction' is planar.*use solver 'rigid3d'") as info:
        simulate(BLOCK, motion, solver="friction")
    assert info.value.argument == "solver"


def _args(*extra: str):
    args = build_parser().parse_args(["simulate", "--width", "0.4", "--height", "1.6", "--pfa-ratio", "3",
                                      "--freq-ratio", "3", *extra])
    cli_simulate._check_args(args)
    return args


def test_plan_options_default_to_rigid3d_with_housners_impact():
    args = _args("--depth", "0.6", "--azimuth", "30")
    assert args.solver == "rigid3d"
    block = cli_simulate._block(args)
    assert block.depth == 0.6 and block.restitution_factor == 1.0 and block.restitution is None
    motion = cli_simulate._plan(args, block, PULSE, None)
    assert isinstance(motion, PlanMotion) and motion.azimuth == 30.0 and motion.second is None
    # a friction block with plan options stays with rigid3d (it models friction and vertical motion)
    assert _args("--depth", "0.6", "--friction", "0.5").solver == "rigid3d"
    # without plan options nothing changes: the planar default and the paper's restitution
    args = _args()
    assert args.solver == "opensees" and cli_simulate._block(args).restitution_factor == 0.95
    assert cli_simulate._plan(args, cli_simulate._block(args), PULSE, None) is PULSE


def test_record2_is_read_filtered_and_scaled_as_record(tmp_path):
    (tmp_path / "a.txt").write_text("\n".join(f"{0.1 * math.sin(k / 5):.6f}" for k in range(300)) + "\n")
    (tmp_path / "b.txt").write_text("\n".join(f"{0.2 * math.cos(k / 7):.6f}" for k in range(300)) + "\n")
    args = build_parser().parse_args(["simulate", "--width", "0.4", "--height", "1.6", "--record", str(tmp_path / "a.txt"),
                                      "--record2", str(tmp_path / "b.txt"), "--units", "g", "--dt", "0.01",
                                      "--scale", "2", "--depth", "0.6", "--azimuth", "-45"])
    cli_simulate._check_args(args)
    block = cli_simulate._block(args)
    first, scale = cli_simulate._record(args, block)
    motion = cli_simulate._plan(args, block, first, scale)
    assert scale == 2.0 and motion.azimuth == -45.0
    # both components scaled by the one factor of --scale: the files' peaks (g, as written) times G times 2
    peak_a = max(abs(round(0.1 * math.sin(k / 5), 6)) for k in range(300))
    assert motion.first.pfa == pytest.approx(2 * peak_a * G, rel=1e-12)
    assert motion.second.pfa == pytest.approx(2 * 0.2 * G, rel=1e-12)  # cos(0) = 1: the peak is the first sample


def _plan_result(over: str) -> RockingResult:
    theta_max = math.pi / 2 if over else 0.3
    plan = PlanSummary(tilt_max=theta_max, twist_max=0.05, slide_max=0.012, slide_residual=(0.01, -0.004),
                       overturned_over=over, overturn_direction=30.0 if over else math.nan, time_edge=0.4,
                       time_corner=0.2, time_sliding=0.1, time_flight=0.0)
    return RockingResult(solver="rigid3d", settings={}, alpha=BLOCK.alpha, time=np.zeros(0), theta=np.zeros(0),
                         theta_dot=np.zeros(0), theta_max=theta_max, overturned=bool(over), rocked=True, n_steps=10,
                         wall_time_s=0.01, n_impacts=0, plan=plan)


@pytest.mark.parametrize("over, phrase", [("corner", "overturned over a corner towards 30 deg"),
                                          ("edge", "overturned over an edge towards 30 deg"), ("", "")])
def test_three_d_outputs_are_printed_and_in_the_json(over, phrase):
    result, motion = _plan_result(over), PlanMotion(PULSE, azimuth=30.0)
    out = cli_simulate._summary(result, BLOCK, motion, None)
    assert out["tilt_max"] == result.plan.tilt_max and out["twist_max"] == 0.05 and out["azimuth"] == 30.0
    assert out["slide_residual"] == [0.01, -0.004] and out["overturned_over"] == over and out["depth"] == 0.6
    json.dumps(out, default=str)  # as --json prints it
    text = cli_simulate._text(result, BLOCK, motion, out)
    assert "azimuth 30 deg" in text and "twist_max = 0.05 rad" in text and "residual (x, y) = (0.01, -0.004) m" in text
    assert (phrase in text) if phrase else ("overturned over" not in text)


def test_a_planar_solver_given_azimuth_360_answers_as_without_it(capsys):
    base = ["simulate", "--width", "0.4", "--height", "1.6", "--pfa-ratio", "3", "--freq-ratio", "3", "--solver",
            "housner_fast", "--json"]
    assert main(base) == 0
    plain = json.loads(capsys.readouterr().out)
    assert main([*base, "--azimuth", "360"]) == 0
    turned = json.loads(capsys.readouterr().out)
    assert turned["theta_max"] == plain["theta_max"] and "azimuth" not in turned


def test_a_box_under_two_records_runs_end_to_end(tmp_path, capsys):
    """rigid3d through the command, in this process: two 2-s records (one along each motion axis), a block turned
    30 deg; the JSON carries the three-dimensional outputs, and the tilt is theta_max (rigid3d's definition)."""
    (tmp_path / "a.txt").write_text("\n".join(f"{0.3 * math.sin(2 * math.pi * 1.5 * k / 100):.6f}" for k in range(200)))
    (tmp_path / "b.txt").write_text("\n".join(f"{0.2 * math.sin(2 * math.pi * 2.0 * k / 100):.6f}" for k in range(200)))
    status = main(["simulate", "--width", "0.4", "--height", "1.2", "--depth", "0.6", "--record", str(tmp_path / "a.txt"),
                   "--record2", str(tmp_path / "b.txt"), "--units", "g", "--dt", "0.01", "--azimuth", "30", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert status == (0 if out["status"] == "ok" else 1) and out["solver"] == "rigid3d"
    assert out["azimuth"] == 30.0 and out["record2"] == "b" and out["depth"] == 0.6
    if out["status"] == "ok":
        assert out["tilt_max"] == out["theta_max"] and len(out["slide_residual"]) == 2
        assert (out["overturned_over"] in ("edge", "corner")) == out["overturned"]
