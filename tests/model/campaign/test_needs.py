"""A scene states its need; solver = "auto" picks the cheapest solver that meets it (opsrock.campaign.needs)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from opsrock.campaign import run_campaign
from opsrock.campaign.cases import IDENTITY_EXCLUDED
from opsrock.campaign.needs import Needs, check, choose, evidence
from opsrock.campaign.scene import load_scene
from opsrock.errors import InputError, SceneError
from opsrock.solvers import SOLVERS
from opsrock.solvers.registry import plan_solver, solver_names
from _support import ROOT, case_rows



def test_the_shipped_evidence_is_what_the_validation_outputs_give():
    """The table is derived from validation/ and bench/ by tools/evidence.py, never retyped: rerunning the
    tool on the repository's outputs must give the shipped file byte for byte."""
    proc = subprocess.run([sys.executable, str(ROOT / "tools" / "evidence.py"), "--check"], capture_output=True)
    assert proc.returncode == 0, "opsrock/data/evidence/solvers.csv is stale: run tools/evidence.py"
    # every planar solver has its row; the solvers in plan (rigid3d, the box, chosen by the scene's plan need, and
    # cylinder3d, the cylinder, named for round items) have no row yet (no benchmark of them in bench/results.json:
    # opsrock.campaign.needs says so)
    assert {r["solver"] for r in evidence()} == set(SOLVERS) - set(solver_names(plan=True))
    assert plan_solver() == "rigid3d"


def test_cheapest_solver_meeting_the_need():
    assert choose(Needs(model="either")).solver == "housner_fast"
    assert choose(Needs(model="sdof", tolerance=0.01)).solver == "opensees"  # 3e-4 alpha measured, the cheaper
    # below OpenSees' measured error (3.1e-4 alpha) only the scipy SDOF solver (1.3e-10) qualifies
    assert choose(Needs(model="sdof", tolerance=1e-6)).solver == "sdof"
    assert choose(Needs(model="rigid", tolerance=1e-10)).solver == "housner"
    assert choose(Needs(), friction=True).solver == "friction"
    assert choose(Needs(answer="hysteresis")).solver == "opensees"


@pytest.mark.parametrize("needs, friction, match", [
    (Needs(model="sdof", tolerance=1e-12), False, "no solver of model 'sdof'"),
    (Needs(answer="hysteresis", model="rigid"), False, "hysteresis"),
    (Needs(model="sdof"), True, "no friction"),
])
def test_needs_no_solver_meets_are_refused(needs, friction, match):
    with pytest.raises(InputError, match=match):
        choose(needs, friction=friction)


@pytest.mark.parametrize("kwargs", [{"answer": "movies"}, {"model": "fem"}, {"tolerance": 0}, {"tolerance": "a"}])
def test_bad_needs(kwargs):
    with pytest.raises(InputError):
        Needs(**kwargs)


def test_a_named_solver_is_checked_against_the_need():
    assert check("sdof", Needs(model="sdof", tolerance=1e-6)).solver == "sdof"
    with pytest.raises(InputError, match="measured error"):
        check("opensees", Needs(model="sdof", tolerance=1e-6))
    with pytest.raises(InputError, match="cannot answer"):
        check("housner_fast", Needs(model="sdof"))


SCENE = """
blocks = "blocks.toml"
[solver]
name = "{solver}"
{needs}
[grid]
freq_ratio = [2.0]
pfa_ratio = [1.5, 3.0]
"""
BLOCKS = """
[[block]]
name = "b"
width = 0.4
height = 1.6
"""


def _scene(tmp_path, solver="auto", needs="[needs]\nmodel = \"either\"\ntolerance = 0.01"):
    (tmp_path / "blocks.toml").write_text(BLOCKS)
    (tmp_path / "scene.toml").write_text(SCENE.format(solver=solver, needs=needs))
    return tmp_path / "scene.toml"


def test_auto_scene_runs_and_its_manifest_states_the_choice(tmp_path):
    summary = run_campaign(_scene(tmp_path), tmp_path / "out", workers=1, progress=False)
    assert summary.solver == "housner_fast" and "cheapest" in summary.choice
    manifest = json.loads((tmp_path / "out" / "manifest.json").read_text())
    assert manifest["choice"]["solver"] == "housner_fast"
    assert manifest["choice"]["evidence"]["source"].startswith("validation/speed_accuracy")
    assert manifest["needs"] == {"answer": "verdicts", "tolerance": 0.01, "model": "either"}


def test_auto_without_needs_takes_the_default_need(tmp_path):
    assert load_scene(_scene(tmp_path, needs="")).solver == "housner_fast"


def test_a_need_no_solver_meets_is_refused_before_anything_runs(tmp_path):
    path = _scene(tmp_path, needs='[needs]\nmodel = "sdof"\ntolerance = 1e-12')
    with pytest.raises(SceneError, match="needs.tolerance"):
        run_campaign(path, tmp_path / "out", workers=1, progress=False)
    assert not (tmp_path / "out").exists()


def test_auto_refuses_settings(tmp_path):
    (tmp_path / "blocks.toml").write_text(BLOCKS)
    (tmp_path / "scene.toml").write_text(SCENE.format(solver="auto", needs="").replace(
        '[solver]\nname = "auto"', '[solver]\nname = "auto"\n[solver.settings]\nstep = 0.001'))
    with pytest.raises(SceneError, match="auto"):
        load_scene(tmp_path / "scene.toml")


def test_command_line_solver_names_are_the_registry():
    from opsrock.cli.parser import SOLVER_NAMES

    assert SOLVER_NAMES == SOLVERS


def test_sdof_verdicts_at_scale_run_as_a_multifidelity_campaign(tmp_path, monkeypatch, capsys):
    """With model 'sdof' and answer 'verdicts' for enough cases, `opsrock run` screens with the rigid body and
    runs OpenSees only where the verdict can differ (the threshold lowered here to keep the test small)."""

    from opsrock.campaign import needs as needs_module
    from opsrock.cli import main

    monkeypatch.setattr(needs_module, "MULTIFIDELITY_MIN_CASES", 2)
    path = _scene(tmp_path, needs='[needs]\nmodel = "sdof"\nanswer = "verdicts"\ntolerance = 0.01')
    assert load_scene(path).choice.strategy == "multifidelity"
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--no-progress", "--workers", "1"]) == 0
    out = capsys.readouterr().out
    assert "screened with housner_fast" in out and "multi-fidelity" in out
    rows = case_rows(tmp_path / "out" / "cases.csv")
    assert len(rows) == 2 and {r["source"] for r in rows} <= {"screen", "escalated", "audit"}


def test_run_campaign_and_opsrock_run_take_the_same_multifidelity_workflow(tmp_path, monkeypatch, capsys):
    """The library, not the command line, picks the workflow from [needs]: run_campaign on a scene whose needs
    chose multi-fidelity screens every case and runs the expensive solver only on the selected ones, and
    `opsrock run` on the same scene writes the same stores and the same table."""
    from opsrock.campaign import needs as needs_module
    from opsrock.campaign.multifidelity import MultiFidelitySummary
    from opsrock.campaign.store import read_rows
    from opsrock.cli import main

    monkeypatch.setattr(needs_module, "MULTIFIDELITY_MIN_CASES", 2)
    path = _scene(tmp_path, needs='[needs]\nmodel = "sdof"\nanswer = "verdicts"\ntolerance = 0.01')
    lib = run_campaign(path, tmp_path / "lib", workers=1, progress=False)
    assert isinstance(lib, MultiFidelitySummary), "run_campaign ignored the workflow the scene's needs chose"
    assert (lib.screen_solver, lib.solver) == ("housner_fast", load_scene(path).choice.solver)
    assert main(["run", str(path), "--out", str(tmp_path / "cli"), "--no-progress", "--workers", "1"]) == 0
    assert "screened with housner_fast" in capsys.readouterr().out

    def stored(folder: Path) -> dict:
        return {k: {c: v for c, v in row.items() if c not in IDENTITY_EXCLUDED} for k, row in read_rows(folder).items()}

    for stage in ("screen", "escalated"):
        assert stored(tmp_path / "lib" / stage) == stored(tmp_path / "cli" / stage), stage
    assert len(stored(tmp_path / "lib" / "screen")) == lib.n_cases == 2

    def table(folder: Path) -> list[dict]:
        return [{c: v for c, v in row.items() if c not in IDENTITY_EXCLUDED} for row in case_rows(folder / "cases.csv")]

    assert table(tmp_path / "lib") == table(tmp_path / "cli")
    # the expensive solver's store holds the selected cases only, the ones the table takes from it
    selected = {r["case_id"] for r in table(tmp_path / "lib") if r["source"] != "screen"}
    assert set(stored(tmp_path / "lib" / "escalated")) == selected
    assert len(selected) == lib.n_escalated + lib.n_audited
    manifests = [json.loads((tmp_path / d / "manifest.json").read_text()) for d in ("lib", "cli")]
    assert manifests[0]["kind"] == "multifidelity" and manifests[0] == manifests[1]
