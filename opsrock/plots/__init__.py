"""Figures: each function writes a PNG to an explicit path and returns it."""

from __future__ import annotations

import math
from pathlib import Path

#: Resolution of every figure (dots per inch).
FIGURE_DPI: int = 110


def save_figure(fig, path: str | Path) -> Path:
    """Write ``fig`` to ``path`` through a temporary file (no half-written figure if
    interrupted), close it, and return the path."""
    import matplotlib.pyplot as plt

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.stem + ".tmp" + path.suffix)
    try:
        fig.savefig(tmp, dpi=FIGURE_DPI)
        tmp.replace(path)
    except BaseException:
        tmp.unlink(missing_ok=True)  # nothing half-written is left behind
        raise
    finally:
        plt.close(fig)
    return path


def log_ticks(axis) -> None:
    """Plain numbers on a log axis (``0.2``, ``0.5``, ``1``, ``2``), labelled at 1, 2 and 5 of each decade only,
    so that no two labels overlap (matplotlib is imported here, lazily, as by every figure module)."""
    from matplotlib.ticker import FuncFormatter

    def label(value: float, _pos) -> str:
        if value <= 0:
            return ""
        lead = round(value / 10 ** math.floor(math.log10(value) + 1e-9), 6)
        return f"{value:g}" if lead in (1.0, 2.0, 5.0) else ""

    axis.set_major_formatter(FuncFormatter(label))
    axis.set_minor_formatter(FuncFormatter(label))


def figure_pool(workers: int):
    """A pool of ``workers`` processes for independent figures (matplotlib draws in one thread). Its workers
    ignore Ctrl-C: the parent gets it and shuts the pool down. Submit the first figure inside
    :func:`opsrock.fragility._pool.deferred_interrupts` (the workers are forked there)."""
    from opsrock._pool import process_pool

    return process_pool(workers)
