"""Campaigns: a scene's cases run, stored as they finish, resumed after a stop.

The flow, one module a step:

* :mod:`~opsrock.campaign.scene`: a scene file read and checked before anything runs, through the one
  TOML checker (:mod:`~opsrock.campaign.toml`); its design is a pulse grid
  (:mod:`~opsrock.campaign.grid`) or a record set (:mod:`~opsrock.campaign.records`, whose floor
  motions :mod:`~opsrock.campaign.motions` computes);
* :mod:`~opsrock.campaign.cases`: the cases of either kind and the one table they make;
* :mod:`~opsrock.campaign.run`: :func:`run_campaign`, every case solved in batches by an executor
  (:mod:`~opsrock.campaign.executors`: local processes or Dask), each under a wall-clock budget
  (:mod:`~opsrock.campaign.timeout`), each batch committed to the store
  (:mod:`~opsrock.campaign.store`) as it returns, then ``cases.csv``.
"""

from opsrock.campaign.run import CASES_FILE, MANIFEST_FILE, CampaignSummary, run_campaign
from opsrock.campaign.scene import BlockSpec, Scene, load_blocks, load_scene
from opsrock.errors import CampaignConflictError, SceneError, StoreError

__all__ = ["BlockSpec", "CASES_FILE", "CampaignConflictError", "CampaignSummary", "MANIFEST_FILE", "Scene",
           "SceneError", "StoreError", "load_blocks", "load_scene", "run_campaign"]
