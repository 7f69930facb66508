"""Campaigns: a scene's cases run, stored as they finish, resumed after a stop.

The flow, one module a step:

* :mod:`~opsrock.campaign.scene`: a scene file read and checked before anything runs, through the one
  TOML checker (:mod:`~opsrock.campaign.toml`); its design is a pulse grid
  (:mod:`~opsrock.campaign.grid`) or a record set (:mod:`~opsrock.campaign.records`, whose floor
  motions :mod:`~opsrock.campaign.motions` computes);
* :mod:`~opsrock.campaign.cases`: the cases of either kind and the one table they make;
* :mod:`~opsrock.campaign.workflow`: :func:`run_campaign`, the workflow the scene's ``[needs]`` chose,
  over the engine of :mod:`~opsrock.campaign.run`: every case solved in batches by an executor
  (:mod:`~opsrock.campaign.executors`: local processes or Dask), each under a wall-clock budget
  (:mod:`~opsrock.campaign.timeout`), each batch committed to the store
  (:mod:`~opsrock.campaign.store`) as it returns, then ``cases.csv``: one engine (``Stage``), and the
  workflow the scene's ``[needs]`` chose as a policy over it (:mod:`~opsrock.campaign.multifidelity`).
"""

import importlib

#: Public names, by the module that defines them (imported on first use: ``opsrock run`` starts fast,
#: and a module of the package can be imported without the rest).
_EXPORTS = {
    "CASES_FILE": "opsrock.campaign.run", "MANIFEST_FILE": "opsrock.campaign.run",
    "CampaignSummary": "opsrock.campaign.run", "run_campaign": "opsrock.campaign.workflow",
    "CampaignOptions": "opsrock.campaign.workflow",
    "MultiFidelity": "opsrock.campaign.multifidelity", "MultiFidelitySummary": "opsrock.campaign.multifidelity",
    "BlockSpec": "opsrock.campaign.scene", "Scene": "opsrock.campaign.scene", "load_blocks": "opsrock.campaign.scene",
    "load_scene": "opsrock.campaign.scene", "CampaignConflictError": "opsrock.errors", "SceneError": "opsrock.errors",
    "StoreError": "opsrock.errors", "StoreUnavailableError": "opsrock.errors",
}


def __getattr__(name: str):
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'opsrock.campaign' has no attribute {name!r}")


__all__ = sorted(_EXPORTS)
