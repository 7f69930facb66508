"""What an inventory study hands back and how it writes its tables: the layer below the study's routes (the
planar one, :mod:`opsrock.inventory.study`, and the one in three dimensions, :mod:`opsrock.inventory.three_d`),
which both import it and neither each other."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd


@dataclass(frozen=True)
class InventoryStudy:
    """What :func:`opsrock.inventory.study.run_inventory_study` computed and wrote.

    Parameters
    ----------
    design : opsrock.inventory.study.InventoryDesign
        The study as run.
    out_dir : str
        The output folder.
    tables : dict of str to str
        Key of :data:`opsrock.inventory.study.TABLES` -> CSV path.
    pelicun : dict of str to str
        pelicun file key -> path (:func:`opsrock.inventory.pelicun.write_pelicun_folder`).
    report : str
        ``report.md``.
    n_cases, n_computed, n_failed : int
        Cases of the campaigns, those computed by this call (0 on a resume with nothing missing), those failed.
    timings : dict of str to float
        Wall times (s): ``demands_s``, ``campaigns_s``, ``fits_s``, ``outputs_s``, ``total_s``.
    """

    design: Any
    out_dir: str
    tables: dict[str, str]
    pelicun: dict[str, str]
    report: str
    n_cases: int
    n_computed: int
    n_failed: int
    timings: dict[str, float]


def workers_of(workers: int | None) -> int:
    """``workers``, or every core this process may use."""
    import os

    if workers is not None:
        return workers
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


def write_csv(df: pd.DataFrame, path: Path) -> Path:
    """``df`` as CSV at full precision."""
    from opsrock._files import atomic_write

    atomic_write(path, lambda fh: df.to_csv(fh, index=False), durable=False)
    return path


__all__ = ["InventoryStudy", "workers_of", "write_csv"]
