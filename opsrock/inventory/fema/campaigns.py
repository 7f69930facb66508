"""The study's campaigns as the contents study's one runner takes them (:func:`campaign_jobs`, run by
:func:`opsrock.inventory.campaigns.run_campaigns`), and the floor velocities of a campaign that ran.

The floor motions depend on the records and the building only, not on the blocks or the solver, but
a campaign keys its cache of them by its whole digest. So that the friction campaign does not filter
the 44 records through the building a second time, its cache is seeded from the no-slip campaign's
when the two record sets are the same (:func:`seed_motions`); if the cache format ever changes the
seed is simply not recognised and the campaign computes the motions itself.
"""

from __future__ import annotations

import functools
import math
import pickle
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from opsrock.campaign.cases import read_cases
from opsrock.inventory.fema.design import split_block_name
from opsrock.fragility.cases import check_some_finished

#: Columns of ``cases.csv`` the study reads.
CASE_COLUMNS: tuple[str, ...] = ("case_id", "block", "width", "height", "alpha", "R", "p", "e", "e_R", "record",
                                 "floor", "level", "level_value", "scale", "pfa", "pfv", "status", "overturned")


def seed_motions(src: Path, dst: Path, src_scene, dst_scene) -> bool:
    """Copy the floor-motion cache of the campaign ``src_scene`` (folder ``src``) to the folder ``dst`` of
    ``dst_scene``, keyed for it, when both have the same records, floors and levels and ``dst`` has none.
    Returns whether it did."""
    from opsrock._files import atomic_write
    from opsrock.campaign.motions import MOTIONS_FILE

    if src_scene.records.fingerprint() != dst_scene.records.fingerprint() or (dst / MOTIONS_FILE).exists():
        return False
    try:
        with open(src / MOTIONS_FILE, "rb") as fh:
            saved = pickle.load(fh)
    except (OSError, EOFError, pickle.UnpicklingError, AttributeError):
        return False
    if not isinstance(saved, dict) or saved.get("digest") != src_scene.digest():
        return False
    dst.mkdir(parents=True, exist_ok=True)
    atomic_write(dst / MOTIONS_FILE, lambda fh: pickle.dump({"digest": dst_scene.digest(), "results": saved["results"]},
                                                            fh), binary=True)
    return True


def campaign_jobs(scenes: dict[str, Any]) -> list[Any]:
    """The study's campaigns (:func:`opsrock.inventory.fema.design.campaign_scenes`: ``rocking``, ``friction``,
    ``sweep``) as the study's one runner takes them (:class:`opsrock.inventory.campaigns.CampaignJob`), each into
    ``store/<name>``: the friction campaign's floor motions seeded from the no-slip one's (:func:`seed_motions`),
    and a campaign whose every case failed refused as it is read (nothing to fit:
    :func:`opsrock.fragility.cases.check_some_finished`, one line, exit 2)."""
    from opsrock.inventory.campaigns import CampaignJob

    jobs = []
    for name, scene in scenes.items():
        seed = None
        if name == "friction" and "rocking" in scenes:
            seed = functools.partial(_seed_from_rocking, scenes["rocking"], scene)
        jobs.append(CampaignJob(name, scene, functools.partial(_read_cases, campaign=name, scene=scene), seed=seed))
    return jobs


def _seed_from_rocking(rocking, scene, folder: Path) -> bool:
    return seed_motions(folder.parent / "rocking", folder, rocking, scene)


def _read_cases(path: str, campaign: str, scene) -> pd.DataFrame:
    cols = list(CASE_COLUMNS) + (["response"] if campaign == "friction" else [])
    df = read_cases(path, usecols=cols)
    if not (df["status"].astype(str) == "ok").any():  # nothing to fit: one line (AllCasesFailedError), exit 2
        check_some_finished(read_cases(path, usecols=["status", "reason"]), str(Path(path).parent))
    df["campaign"] = campaign
    parts = df["block"].map(split_block_name)
    df["item"] = [p[0] for p in parts]
    df["variant"] = [p[1] for p in parts]
    floors = _floor_numbers(scene)
    df["floor_number"] = df["floor"].map(lambda f: floors[f][0]).astype(int)
    df["building_period"] = df["floor"].map(lambda f: floors[f][1]).astype(float)
    if "response" not in df:
        df["response"] = np.where(df["overturned"], "overturned", "rocked")
    return df


def _floor_numbers(scene) -> dict[str, tuple[int, float]]:
    """``{floor label: (floor number, building period)}``: 0 and NaN on the ground."""
    return {f.label: ((0, math.nan) if f.building is None else (f.floor, f.building.period))
            for f in scene.records.floors}


def floor_velocities(scene, folder: Path) -> pd.DataFrame:
    """The unscaled floor motions of a campaign: per record and floor, PFA (m/s²), the peak absolute
    velocity ``pfv`` and the peak velocity relative to the ground ``pfv_rel`` (m/s), both by the project's
    integration and baseline correction (:func:`opsrock.intensity.records.velocity_displacement`).

    Reads the campaign's floor-motion cache (:func:`opsrock.campaign.motions.cached_motions`); the
    campaign must have run."""
    from opsrock.campaign.motions import cached_motions
    from opsrock.excitations.records import Record
    from opsrock.intensity.records import velocity_displacement

    def missing(items):
        raise RuntimeError(f"the floor motions of {folder} are not cached: run the campaign first")

    motions = cached_motions(folder, scene.digest(), scene.records.motion_items(), missing)
    grounds = {g.name: g for g in scene.records.grounds}
    rows = []
    for (rname, flabel), m in motions.items():
        if isinstance(m, str):
            continue
        ground = grounds[rname]
        v_floor, _ = velocity_displacement(m.record)
        padded = np.zeros(len(m.record.values))
        padded[: len(ground.values)] = ground.values
        v_ground, _ = velocity_displacement(Record(dt=ground.dt, values=padded, name=rname, units="m/s2"))
        rows.append({"record": rname, "floor": flabel, "pfa": m.measures.pfa, "pfv": m.measures.pfv,
                     "pfv_rel": float(np.max(np.abs(v_floor - v_ground)))})
    return pd.DataFrame(rows)


__all__ = ["CASE_COLUMNS", "campaign_jobs", "floor_velocities", "seed_motions"]
