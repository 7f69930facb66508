"""Record figures: acceleration, velocity and displacement histories and the response spectrum."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from opsrock.constants import G  # noqa: E402
from opsrock.excitations.records import Record  # noqa: E402
from opsrock.intensity.records import response_spectrum, velocity_displacement  # noqa: E402
from opsrock.plots import save_figure  # noqa: E402


def plot_record(record: Record, path: str | Path, *, floor: Record | None = None) -> Path:
    """Four panels of ``record`` (and of a floor motion filtered from it, if given).

    Parameters
    ----------
    record : Record
        The (ground) motion, m/s².
    path : str or Path
        Output PNG.
    floor : Record, optional
        A floor motion of the same record (drawn over it).

    Returns
    -------
    Path
    """
    fig, axes = plt.subplots(4, 1, figsize=(8.0, 9.0), constrained_layout=True)
    series = [(record, f"{record.name} ({record.info.floor})", "tab:blue")]
    if floor is not None:
        series.append((floor, f"{floor.name} ({floor.info.floor})", "tab:red"))
    for rec, label, color in series:
        v, d = velocity_displacement(rec)
        axes[0].plot(rec.time, rec.values / G, color=color, lw=0.7, label=label)
        axes[1].plot(rec.time, v, color=color, lw=0.8)
        axes[2].plot(rec.time, d, color=color, lw=0.8)
        spec = response_spectrum(rec)
        axes[3].loglog(spec["period"], spec["psa"] / G, color=color, lw=1.0)
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
