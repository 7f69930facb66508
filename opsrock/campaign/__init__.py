"""Campaigns: a scene's cases run, stored as they finish, resumed after a stop.

The flow, one module a step:

* :mod:`~opsrock.campaign.scene`: a scene file (TOML) read and checked before anything runs;
  pulse scenes (``[grid]``) and record scenes (``[records]``, :mod:`~opsrock.campaign.records`);
* :mod:`~opsrock.campaign.run`: :func:`run_campaign`, every case solved in batches by an executor
  (:mod:`~opsrock.campaign.executors`: local processes or Dask), each under a wall-clock budget
  (:mod:`~opsrock.campaign.timeout`), each batch committed to the store
  (:mod:`~opsrock.campaign.store`) as it returns, then ``cases.csv``.
"""

from opsrock.campaign.run import (
           CASES_FILE,
           MANIFEST_FILE,
           CampaignSummary,
           run_campaign,
)
from opsrock.campaign.scene import BlockSpec, Scene, load_blocks, load_scene
from opsrock.errors import CampaignConflictError, SceneError, StoreError

__all__ = ["BlockSpec", "CASES_FILE", "CampaignConflictError", "CampaignSummary", "MANIFEST_FILE", "Scene",
           "SceneError", "StoreError", "load_blocks", "load_scene", "run_campaign"]
