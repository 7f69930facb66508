"""``opsrock simulate --shape cylinder --diameter D --height H`` (issue 45) through the console script: the cylinder
runs ``cylinder3d`` with a homogeneous solid cylinder's mass distribution, its JSON and lines say so, and what does
not go with a round base is refused in one line on stderr with exit status 2, nothing on stdout."""

from __future__ import annotations

import json
import math

import pytest

from _support import run_opsrock

CYLINDER = ("simulate", "--shape", "cylinder", "--diameter", "0.23", "--height", "1.5")
PULSE = ("--pfa", "0.5", "--freq", "1.5")


def test_a_cylinder_under_a_pulse_runs_cylinder3d():
    """An oxygen cylinder 0.23 m across, 1.5 m tall: alpha = atan(0.115 / 0.75), radius of gyration sqrt(d²/16 +
    H²/12) (a homogeneous solid cylinder's), solver cylinder3d; a one-sine pulse of 0.5 g at 1.5 Hz is 3.3 times its
    uplift acceleration g r / h_cm and overturns it (housner_fast's verdict on the same planar block)."""
    done = run_opsrock([*CYLINDER, *PULSE, "--json"])
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert out["solver"] == "cylinder3d" and out["shape"] == "cylinder" and out["diameter"] == 0.23
    assert out["alpha"] == pytest.approx(math.atan2(0.115, 0.75), rel=1e-12)
    assert out["radius_of_gyration"] == pytest.approx(math.sqrt(0.23**2 / 16 + 1.5**2 / 12), rel=1e-12)
    assert out["verdict"] == "overturned" and out["overturned_over"] in ("rim", "rolling")
    assert "time_rim" in out and "time_corner" not in out
    text = run_opsrock([*CYLINDER, *PULSE])
    assert text.returncode == 0 and text.stdout.startswith("cylinder D x H = 0.23 x 1.5 m")
    assert "in plan: cylinder of diameter 0.23 m" in text.stdout


@pytest.mark.parametrize("extra, message", [
    (("--width", "0.2"), "--width 0.2 applies to a box"),
    (("--depth", "0.3"), "--depth 0.3 applies to a box"),
    (("--solver", "rigid3d"), "--shape cylinder is solved by --solver cylinder3d"),
    (("--restitution", "0.8"), "reproduces Housner's impact only"),
])
def test_what_does_not_go_with_a_round_base_is_refused(extra, message):
    done = run_opsrock([*CYLINDER, *PULSE, *extra])
    assert done.returncode == 2 and done.stdout == ""
    assert message in done.stderr and len(done.stderr.strip().splitlines()) == 1 and "Traceback" not in done.stderr


@pytest.mark.parametrize("args, message", [
    (("simulate", "--shape", "cylinder", "--height", "1.5", *PULSE), "--shape cylinder needs --diameter"),
    (("simulate", "--shape", "drum", "--diameter", "0.2", "--height", "1.5", *PULSE), "--shape must be one of"),
    (("simulate", "--diameter", "0.2", "--height", "1.5", *PULSE), "--diameter 0.2 applies to --shape cylinder"),
    (("simulate", "--height", "1.5", *PULSE), "--width is required"),
    (("simulate", "--shape", "cylinder", "--diameter", "50", "--height", "1.5", *PULSE), "--diameter = 50 m"),
])
def test_a_shape_without_its_size_is_refused(args, message):
    done = run_opsrock(list(args))
    assert done.returncode == 2 and done.stdout == ""
    assert message in done.stderr and len(done.stderr.strip().splitlines()) == 1
