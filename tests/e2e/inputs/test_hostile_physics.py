"""Any block the physics allows, through the real console script (issue 32, helper "physics").

The table: mass distributions no block can have (``--cm-height``, ``--radius-of-gyration``, a blocks file's
``cm_height`` and ``radius_of_gyration``) and models a solver cannot represent (a block that lands flat on the
SDOF model, a rebound on a block that lands flat), each refused with exit 2 and one line naming the argument (the
promise of ``_hostile``). Then valid inputs that must run: a loaded bookcase, a wide block that can only slide,
and frictionless blocks that end with the motion.
"""

from __future__ import annotations

import json
import math
from collections import Counter
from pathlib import Path

import pytest
from _hostile import Case, sweep
from _support import run_opsrock, without_compile_notice

from opsrock.campaign.scene import load_blocks
from opsrock.constants import G

SIM = ("simulate", "--width", "0.5", "--height", "2.0")
PULSE = ("--pfa-ratio", "2", "--freq-ratio", "3")
WIDE = ("simulate", "--width", "2.0", "--height", "1.0")

SCENE = """name = "t"
blocks = "blocks.toml"
[solver]
name = "{solver}"
[grid.freq_ratio]
values = [3.0]
[grid.pfa_ratio]
values = [1.5]
"""


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> Path:
    """Scenes whose blocks file holds a mass distribution no block can have, or a wide block on the SDOF model."""
    base = tmp_path_factory.mktemp("physics_inputs")
    blocks = {
        "cm_above": "cm_height = 2.5", "cm_text": 'cm_height = "low"', "r_far": "radius_of_gyration = 1.5",
    }
    for name, line in blocks.items():
        folder = base / name
        folder.mkdir()
        (folder / "blocks.toml").write_text(f'[[block]]\nname = "b"\nwidth = 0.5\nheight = 2.0\n{line}\n')
        (folder / "scene.toml").write_text(SCENE.format(solver="housner"))
    folder = base / "wide_on_sdof"
    folder.mkdir()
    (folder / "blocks.toml").write_text('[[block]]\nname = "desk"\nwidth = 2.0\nheight = 1.0\n')
    (folder / "scene.toml").write_text(SCENE.format(solver="sdof"))
    (base / "step.txt").write_text("0.1\n" * 100 + "0\n" * 100)  # the floor ends moving at 0.976 m/s
    return base


def physics_cases(b: Path) -> list[Case]:
    """Bad mass distributions and models a solver cannot represent, on simulate and run."""
    cases = []
    for v in ("2.5", "0", "nan", "low"):
        cases.append(Case(f"simulate --cm-height {v!r}", (*SIM, *PULSE, "--cm-height", v), ("--cm-height",)))
    for v in ("1.5", "nan"):
        cases.append(Case(f"simulate --radius-of-gyration {v!r}", (*SIM, *PULSE, "--radius-of-gyration", v),
                          ("--radius-of-gyration",)))
    cases += [
        # all the mass at the corner farthest from a centre of mass 0.1 m up: r <= hypot(0.25, 1.9) = 1.916 m
        Case("simulate radius beyond the far corner of a low centre", (*SIM, *PULSE, "--cm-height", "0.1",
                                                                       "--radius-of-gyration", "1.92"),
             ("--radius-of-gyration", "1.92", "1.91")),
        Case("simulate a centre of mass a hair above the top", (*SIM, *PULSE, "--cm-height", "2.0000001"),
             ("--cm-height", "2.0000001")),
        Case("simulate a wide block on the SDOF model", (*WIDE, *PULSE, "--solver", "sdof"),
             ("solver 'sdof'", "lands flat", "'housner'")),
        Case("simulate a wide block on OpenSees", (*WIDE, *PULSE, "--solver", "opensees"),
             ("solver 'opensees'", "lands flat")),
        Case("simulate a rebound the friction solver cannot apply", (*WIDE, *PULSE, "--solver", "friction",
                                                                     "--friction", "0.5", "--restitution", "0.5"),
             ("--restitution", "land it flat")),
    ]
    for name in ("cm_above", "cm_text"):
        cases.append(Case(f"run blocks file {name}", ("run", f"{b}/{name}/scene.toml", "--out", "out"),
                          ("block[0].cm_height",)))
    for name in ("r_far",):
        cases.append(Case(f"run blocks file {name}", ("run", f"{b}/{name}/scene.toml", "--out", "out"),
                          ("block[0].radius_of_gyration",)))
    cases.append(Case("run a wide block on the SDOF model", ("run", f"{b}/wide_on_sdof/scene.toml", "--out", "out"),
                      ("solver.name", "lands flat")))
    return cases


def test_physics_inputs_are_refused(files, tmp_path):
    # every other case; the others behind slow (make test under 10 minutes)
    broken = sweep(physics_cases(files)[0::2], tmp_path, workers=4, timeout=60)
    assert not broken, "\n".join(broken)


@pytest.mark.slow
def test_the_other_physics_inputs_are_refused(files, tmp_path):
    broken = sweep(physics_cases(files)[1::2], tmp_path, workers=4, timeout=60)
    assert not broken, "\n".join(broken)


def test_physics_case_counts(files):
    counts = Counter(c.args[0] for c in physics_cases(files))
    assert counts == {"simulate": 11, "run": 4}, counts


# --- valid input ----------------------------------------------------------------------------------------
def _json(args: tuple[str, ...], cwd: Path) -> dict:
    proc = run_opsrock((*args, "--json"), cwd, timeout=120)
    assert proc.returncode == 0 and not without_compile_notice(proc.stderr), proc.stderr
    return json.loads(proc.stdout)


def test_a_loaded_bookcase_runs_with_its_closed_forms(tmp_path):
    """cm_height 0.7 m, r 0.5 m on a 0.5 x 2.0 m block: p = sqrt(g R / (r² + R²)) and e_R = 1 - 2 b² / (r² + R²)
    with R = hypot(0.25, 0.7) (to round-off: the same formulas), and --pfa-ratio is of its own g b / h_cm."""
    d = _json((*SIM, *PULSE, "--cm-height", "0.7", "--radius-of-gyration", "0.5", "--solver", "housner_fast"),
              tmp_path)
    R = math.hypot(0.25, 0.7)
    assert d["status"] == "ok" and d["cm_height"] == 0.7 and d["radius_of_gyration"] == 0.5
    assert d["p"] == pytest.approx(math.sqrt(G * R / (0.25 + R * R)), rel=1e-14)
    assert d["e_R"] == pytest.approx(1.0 - 2.0 * 0.0625 / (0.25 + R * R), rel=1e-14)
    assert d["pfa"] == pytest.approx(2.0 * G * 0.25 / 0.7, rel=1e-14)


def test_a_wide_block_with_friction_slides_and_never_rocks(files, tmp_path):
    """2.0 x 1.0 m with mu = 0.5 < tan(alpha) = 2 under a floor that ends moving (0.1 g for 1 s): it only slides."""
    d = _json((*WIDE, "--record", f"{files}/step.txt", "--units", "g", "--dt", "0.01", "--friction", "0.5"), tmp_path)
    assert d["status"] == "ok" and d["e"] == 0.0 and d["e_R"] < 0.0
    assert d["theta_max"] == 0.0 and not d["rocked"] and d["response"] in ("slid", "at_rest")


@pytest.mark.parametrize("solver", ["friction", "moreau_jean"])
def test_friction_zero_ends_with_the_motion(files, solver, tmp_path):
    """--friction 0 --friction-kinetic 0 on a floor that ends moving (0.1 g for 0.99 s and a ramp to 0 over 0.01 s:
    0.976095 m/s): the run ends, with the block still sliding at -0.976095 m/s relative to the floor (no max_steps or
    max_free_time failure; to 1e-6 as tests/e2e/inputs/test_hostile_friction.py)."""
    extra = ("--restitution-law", "housner") if solver == "moreau_jean" else ()
    d = _json((*SIM, "--record", f"{files}/step.txt", "--units", "g", "--dt", "0.01", "--friction", "0",
               "--friction-kinetic", "0", "--solver", solver, *extra), tmp_path)
    assert d["status"] == "ok" and d["response"] == "slid"
    assert d["slip_velocity_end"] == pytest.approx(-0.1 * G * 0.995, rel=1e-6)


def test_blocks_file_takes_the_mass_distribution(tmp_path):
    path = tmp_path / "blocks.toml"
    path.write_text('[[block]]\nname = "bookcase"\nwidth = 0.9\nheight = 2.0\ncm_height = 0.6\n'
                    'radius_of_gyration = 0.55\nfriction = 0.4\n[[block]]\nname = "plain"\nwidth = 0.4\nheight = 1.2\n')
    bookcase, plain = load_blocks(path)
    assert (bookcase.cm_height, bookcase.radius_of_gyration) == (0.6, 0.55)
    assert bookcase.block.h_cm == 0.6 and bookcase.block.r_gyration == 0.55 and bookcase.block.friction == 0.4
    assert plain.cm_height is None and plain.block.homogeneous
