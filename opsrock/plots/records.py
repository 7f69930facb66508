"""Record figures: acceleration, velocity and displacement histories and the response spectrum."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from opsrock.constants import G  # noqa: E402
from opsrock.plots import save_figure  # noqa: E402

if TYPE_CHECKING:
    from opsrock.analysis.record_curves import RecordCurves


def plot_record(record: RecordCurves, path: str | Path, *, floor: RecordCurves | None = None) -> Path:
    """Four panels of ``record`` (and of a floor motion filtered from it, if given).

    Parameters
    ----------
    record : RecordCurves
        The (ground) motion's curves (:func:`opsrock.analysis.record_curves.record_curves`).
    path : str or Path
        Output PNG.
    floor : RecordCurves, optional
        The curves of a floor motion of the same record (drawn over it).

    Returns
    -------
    Path
    """
    fig, axes = plt.subplots(4, 1, figsize=(8.0, 9.0), constrained_layout=True)
    series = [(record, f"{record.name} ({record.info.floor})", "tab:blue")]
    if floor is not None:
        series.append((floor, f"{floor.name} ({floor.info.floor})", "tab:red"))
    for rec, label, color in series:
        axes[0].plot(rec.time, rec.acceleration / G, color=color, lw=0.7, label=label)
        axes[1].plot(rec.time, rec.velocity, color=color, lw=0.8)
        axes[2].plot(rec.time, rec.displacement, color=color, lw=0.8)
        axes[3].loglog(rec.period, rec.psa / G, color=color, lw=1.0)
    for ax, ylabel in zip(axes, ("acceleration (g)", "velocity (m/s)", "displacement (m)", "PSA, 5 % (g)")):
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
    for ax in axes[:3]:
        ax.set_xlabel("time (s)")
    axes[3].set_xlabel("period (s)")
    axes[0].legend(loc="upper right", fontsize=8)
    info = record.info
    axes[0].set_title(f"{record.name}: {info.event} {info.year or ''}, {info.station}".strip(", "))
    return save_figure(fig, path)


__all__ = ["plot_record"]
