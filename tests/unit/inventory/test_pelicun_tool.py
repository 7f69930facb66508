"""``tools/pelicun_inventory.py --dl-calculation`` on every pelicun folder opsrock writes: the configuration it
hands to pelicun's ``DL_calculation``. pelicun 3.10's DL_calculation defaults its outputs to all of them, the
loss's included, and refuses a configuration without ``DL/Losses`` that asks for loss outputs ("No loss data
specified in config file", ``_parse_config_file``); a folder without repair costs (the contents study's FEMA P-58
nine) gets the damage assessment's outputs only, and says why. pelicun itself runs it in ``make test-pelicun``;
this checks the configuration without pelicun (the tool imports pelicun only inside its functions)."""

from __future__ import annotations

import json

from _support import ROOT, load_tool


def _tool():
    return load_tool("pelicun_inventory")


def _config(study):
    return json.loads((ROOT / "studies" / study / "pelicun" / "config.json").read_text())


def test_a_folder_without_repair_costs_runs_the_damage_assessment_only(tmp_path):
    """The committed FEMA P-58 nine's folder has no ``DL/Losses``: DL_calculation is told its outputs, demand,
    asset and damage in CSV, no loss output (the one its refusal looks for), and the tool gives the reason."""
    tool, config = _tool(), _config("contents")
    assert "Losses" not in config["DL"]
    run = tool.dl_configuration(config, tmp_path)
    outputs = run["DL"]["Outputs"]
    assert "Loss" not in outputs
    assert outputs["Damage"] == {"Sample": True, "Statistics": True, "GroupedSample": True, "GroupedStatistics": True}
    assert outputs["Format"] == {"CSV": True, "JSON": False}
    assert run["DL"]["Options"]["LogFile"] == str(tmp_path / "pelicun_log.txt")
    assert "repair_cost" in tool.no_loss_reason(config)
    assert "Outputs" not in config["DL"], "the folder's configuration is not changed"


def test_a_folder_with_repair_costs_keeps_pelicun_s_default_outputs(tmp_path):
    """The example inventory's folder prices damage: DL_calculation keeps its own default outputs (the loss's
    included: ``DV_repair_*``), and there is no reason to give."""
    tool, config = _tool(), _config("inventory-example")
    run = tool.dl_configuration(config, tmp_path)
    assert "Outputs" not in run["DL"]
    assert run["DL"]["Losses"] == config["DL"]["Losses"]
    assert tool.no_loss_reason(config) is None
