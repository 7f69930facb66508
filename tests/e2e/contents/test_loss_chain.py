"""The loss chain of issue 44 through the console script, in one command: a structural engineer's files (one CSV
per record and floor, ``time,ax,ay`` in m/s², both directions addressed by the manifest's ``column``, the floors'
pelicun locations given by ``location``), an inventory with an isotropic item (square in plan) and trolleys on
casters (low friction: they roll away), and the pelicun folder that comes out: each unit once (the units pelicun
instantiates are the quantity, per item and floor), the rolling-away damage state below overturning, priced."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
from _support import run_opsrock
from opsrock.inventory.columns import read_table

INVENTORY = """id,description,width,depth,height,mass,friction,floor,quantity,repair_cost,slide_distance,slide_cost
cylinder,an oxygen cylinder in a stand (square in plan: isotropic),0.25,0.25,1.4,60,,L1;L2,2,900,,
trolley,a ventilator trolley on casters,0.5,0.6,1.3,40,0.05,L2,3,45000,0.3,150
cabinet,a pharmacy cabinet,0.9,0.45,1.8,120,,L1;L2,1,2500,,
"""


def _files(folder: Path) -> tuple[Path, Path]:
    """Two records x two floors, one ``time,ax,ay`` file each (band-limited noise, fixed seeds, stronger
    upstairs), and the manifest addressing each direction by ``column`` with each floor's ``location``."""
    rng = np.random.default_rng(44)
    t = np.arange(0.0, 5.0, 0.01)
    rows = ["record,floor,direction,file,units,column,location"]
    for record in ("r1", "r2"):
        for k, (floor, location) in enumerate((("L1", 1), ("L2", 2))):
            env = np.sin(np.pi * t / 5.0) ** 2
            ax, ay = ((5.0 + 3.0 * k) * env * np.convolve(rng.normal(size=t.size), np.ones(8) / 8, "same")
                      for _ in range(2))
            name = f"{record}-{floor}.csv"
            np.savetxt(folder / name, np.c_[t, ax, ay], delimiter=",", header="time,ax,ay", comments="")
            rows += [f"{record},{floor},1,{name},m/s2,ax,{location}", f"{record},{floor},2,{name},m/s2,3,{location}"]
    (folder / "inventory.csv").write_text(INVENTORY)
    (folder / "motions.csv").write_text("\n".join(rows) + "\n")
    return folder / "inventory.csv", folder / "motions.csv"


def test_one_command_from_the_engineers_files_to_a_pelicun_folder_counting_each_unit_once(tmp_path):
    inv, man = _files(tmp_path)
    proc = run_opsrock(["contents", "--inventory", inv, "--motions", man, "--out", tmp_path / "out", "--quick",
                        "--n-boot", "2", "--workers", "1", "--no-progress"], tmp_path, timeout=600)
    assert proc.returncode == 0, proc.stderr
    assert "pelicun locations" not in proc.stderr  # given by the manifest: nothing assumed
    folder = tmp_path / "out" / "pelicun"
    inventory = pd.read_csv(folder / "inventory.csv", index_col=0)
    mapping, _ = read_table(folder / "mapping.csv", index_col=0)
    quantity = {"cylinder": 2, "trolley": 3, "cabinet": 1}
    # each unit once: one non-directional component per item and floor, its quantity as that many blocks
    assert inventory.index.is_unique and set(inventory["Direction"].astype(str)) == {"0"}
    for cid, r in inventory.iterrows():
        item = mapping.loc[cid, "item"]
        assert r["Theta_0"] == quantity[item] and r["Blocks"] == quantity[item]
    # the manifest's locations, not the order of the labels: L1 is the ground floor, a 2-storey building
    assert dict(zip(mapping["floor"], mapping["location"])) == {"L1": 1, "L2": 2}
    config = json.loads((folder / "config.json").read_text())
    assert config["GeneralInformation"]["NumberOfStories"] == 2
    assert config["DL"]["Options"]["NonDirectionalMultipliers"] == {"ALL": 1.0}
    # the trolley rolls away at its own distance: its component's first damage state is displacement, priced at
    # its slide_cost; overturning (when it happens) the second, at repair_cost
    trolley = mapping.loc["opsrock.trolley.L2"]
    assert trolley["ds1"].startswith("displaced") and bool(trolley["exported"])
    loss = pd.read_csv(folder / "loss_repair.csv", index_col=0)
    assert loss.loc["opsrock.trolley.L2-Cost", "DS1-Theta_0"] == 150.0
    expected, _ = read_table(tmp_path / "out" / "expected.csv")
    assert (expected["expected_damaged"] <= expected["quantity"]).all()
    assert expected.loc[expected["item"] == "trolley", "expected_damaged"].item() > 0
    report = (tmp_path / "out" / "report.md").read_text()
    assert "`L1` -> location 1" in report and "NumberOfStories: 2" in report


def test_case_timeout_is_refused_where_it_does_not_apply_or_is_out_of_range(tmp_path):
    from _hostile import Case, sweep

    inv, man = _files(tmp_path)
    cases = [Case("--case-timeout 0", ("contents", "--inventory", str(inv), "--motions", str(man), "--case-timeout", "0",
                                       "--out", "out"), ("--case-timeout", "0")),
             Case("--case-timeout without --inventory", ("contents", "--case-timeout", "60", "--out", "out"),
                  ("--case-timeout", "--inventory"))]
    assert sweep(cases, tmp_path) == []
