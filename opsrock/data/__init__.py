"""Data shipped inside the package: the project's blocks and scenes.

* ``blocks.toml``: the four blocks of the paper's reproduction (see the file for why each);
* ``scenes/*.toml``: the scenes, named by their file stem (``paper``, ``spectrum``, ``tiny``,
  ``fema-far-field-ida``, ``fema-far-field-ida-b3``); a scene names its blocks file relative to
  itself (``blocks = "../blocks.toml"``);
* ``inventories/<name>.csv``: the shipped inventories of contents (``fema-p58-nine``, ``example``;
  :func:`opsrock.inventory.items.shipped_inventory`), each with a ``.md`` giving every number's source;
* ``examples/floor-motions/``: the example floor motions of a three-storey building (a manifest
  ``motions.csv`` and its record files; :func:`example_motions_manifest`), made by
  ``tools/make_example_motions.py``;
* ``experiments/*.csv``: measured free rocking of limestone blocks (Colombo et al., University of
  Minho, DOI 10.60756/uminho-jh25, CC BY 4.0; ``experiments/SOURCE.md``), for validation case
  ``experiments``.

Found with :mod:`importlib.resources`, so an installed opsrock (a wheel, not a checkout) finds them
too: ``opsrock run paper --out DIR`` runs a shipped scene named without a path.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path


def _root() -> Path:
    # the package is installed as files (setuptools' wheels are never zipped), so the resource is a path
    return Path(str(resources.files(__name__)))


def _stems(folder: str, suffix: str) -> tuple[str, ...]:
    """Stems of the files ``<folder>/*<suffix>``, sorted."""
    return tuple(sorted(p.stem for p in (_root() / folder).glob(f"*{suffix}")))


def _shipped(folder: str, suffix: str, name: str, what: str) -> Path:
    """Path of ``<folder>/<name><suffix>``; ``KeyError`` naming ``what`` and the shipped names if none."""
    path = _root() / folder / f"{name}{suffix}"
    if not path.is_file():
        raise KeyError(f"no shipped {what} {name!r} (shipped: {', '.join(_stems(folder, suffix))})")
    return path


def scene_names() -> tuple[str, ...]:
    """Names of the shipped scenes (file stems), sorted."""
    return _stems("scenes", ".toml")


def scene_file(name: str) -> Path:
    """Path of the shipped scene ``name`` (a file stem of :func:`scene_names`); ``KeyError`` if none."""
    return _shipped("scenes", ".toml", name, "scene")


def blocks_file() -> Path:
    """Path of the shipped blocks file (``blocks.toml``)."""
    return _root() / "blocks.toml"


def block_library_names() -> tuple[str, ...]:
    """Names of the shipped blocks libraries (``blocks/<name>.toml``), sorted: a scene names one as
    ``blocks = "<name>"``."""
    return _stems("blocks", ".toml")


def block_library(name: str) -> Path:
    """Path of the shipped blocks library ``name`` (:func:`block_library_names`); ``KeyError`` if none."""
    return _shipped("blocks", ".toml", name, "blocks library")


def inventory_names() -> tuple[str, ...]:
    """Names of the shipped inventories (``inventories/<name>.csv``), sorted."""
    return _stems("inventories", ".csv")


def inventory_file(name: str) -> Path:
    """Path of the shipped inventory ``name`` (:func:`inventory_names`); ``KeyError`` if none."""
    return _shipped("inventories", ".csv", name, "inventory")


def example_motions_manifest() -> Path:
    """Path of the manifest of the shipped example floor motions (``examples/floor-motions/motions.csv``)."""
    return _root() / "examples" / "floor-motions" / "motions.csv"


__all__ = ["block_library", "block_library_names", "blocks_file", "example_motions_manifest", "inventory_file",
           "inventory_names", "scene_file", "scene_names"]
