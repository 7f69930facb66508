"""opsrock: rocking and overturning of freestanding rigid blocks under floor motions.

Reproduces the OpenSees workflow of Liu, Huang & Liu (2023), *Seismic Overturning Fragility
Analysis for Rigid Blocks Subjected to Floor Motions*, Sustainability 15, 4945, and checks it
against independent scipy solvers and closed forms.

OpenSeesPy (and the system BLAS its Linux wheel links against) is loaded when the OpenSees model is
first used (:mod:`opsrock.opensees_session`), so everything else works on a machine without it.

The names below are imported when first used (PEP 562): ``import opsrock`` itself is light, so that the
command line (:mod:`opsrock.cli`) starts its handling of Ctrl-C and of the environment's faults before
numpy and the solvers load. ``from opsrock import Block`` works as before.

One way in from Python, by what you do:

* one block under one floor motion: :func:`simulate` (a :class:`Block`, a :class:`OneSinePulse` or
  :class:`Record`, a solver of :data:`SOLVERS`);
* a campaign of many cases, stored and resumable: :func:`run_campaign` (a scene file or a
  :class:`~opsrock.campaign.scene.Scene`; executor, solve function, batches and case budget in a
  :class:`CampaignOptions`);
* a contents study from an inventory and floor motions to a pelicun folder: :func:`run_study` (workers,
  progress, stores and case budget in a :class:`StudyOptions`).

``opsrock.__version__`` is the installed distribution's version (:func:`importlib.metadata.version`), whose one
source is ``pyproject.toml``; ``opsrock --version`` prints the same.
"""

from __future__ import annotations

import importlib

#: Each public name -> the module that defines it.
_EXPORTS: dict[str, str] = {
    "Block": "opsrock.block", "G": "opsrock.constants", "OneSinePulse": "opsrock.excitations",
    "Record": "opsrock.excitations", "SDOFModel": "opsrock.model", "RockingResult": "opsrock.result",
    "SOLVERS": "opsrock.solvers", "simulate": "opsrock.solvers", "run_campaign": "opsrock.campaign.workflow",
    "run_study": "opsrock.inventory.run", "CampaignOptions": "opsrock.campaign.workflow",
    "StudyOptions": "opsrock.inventory.run",
}


def __getattr__(name: str):
    if name == "__version__":  # read from the metadata when first asked: importlib.metadata is not light
        globals()[name] = value = _installed_version()
        return value
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'opsrock' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_EXPORTS, "__version__"})


def _installed_version() -> str:
    """The version of the installed distribution ``opsrock`` (pyproject.toml's), or ``"0+unknown"`` when the
    package is imported from a folder that was never installed (no metadata to read)."""
    from importlib.metadata import PackageNotFoundError, version  # lazy: only when the version is asked for

    try:
        return version("opsrock")
    except PackageNotFoundError:
        return "0+unknown"


__all__ = [
    "Block",
    "CampaignOptions",
    "G",
    "OneSinePulse",
    "Record",
    "RockingResult",
    "SDOFModel",
    "SOLVERS",
    "StudyOptions",
    "run_campaign",
    "run_study",
    "simulate",
]
