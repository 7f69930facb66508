"""Figures of an inventory study's report. They draw tables computed beforehand
(:func:`opsrock.inventory.summary.curve_table`, :func:`opsrock.inventory.summary.demand_table`) and compute
nothing: one figure per item (its fragility on each floor, with the record-bootstrap band), one of the
floors' demands.

Readability rules of every figure here: legend and tick text at least :data:`MIN_FONT` pt; every axis
names its quantity and unit; each curve is one item on one floor (and direction), never pooled; curves that
coincide stay visible (each floor its own line style and marker, the markers staggered along the curve).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

from opsrock.plots import log_ticks, save_figure  # noqa: E402

#: Smallest legend and tick text (pt).
MIN_FONT: float = 9.0
#: Axis label of each demand (quantity and unit).
AXIS_LABELS: dict[str, str] = {"pfv": "PFV, peak floor velocity (m/s)", "pfa": "PFA, peak floor acceleration (g)"}
#: Line styles and markers, one pair per floor, in turn.
STYLES: tuple[tuple[str, str], ...] = (("-", "o"), ("--", "s"), ("-.", "^"), (":", "D"), ((0, (5, 1, 1, 1)), "v"),
                                       ((0, (8, 3)), "P"))


def _style(k: int) -> tuple:
    return STYLES[k % len(STYLES)]


def plot_item_fragility(curves: pd.DataFrame, item: str, path: str | Path, demand: str = "pfv",
                        outcome: str = "overturning") -> Path:
    """One item's fragility of ``outcome`` in ``demand`` on each floor (and direction): the MLE curve and the
    band of the bootstrap intervals.

    Parameters
    ----------
    curves : pandas.DataFrame
        :func:`opsrock.inventory.summary.curve_table` (``x`` in m/s for PFV, in g for PFA; ``p``
        dimensionless).
    item : str
        The item drawn.
    path : str or pathlib.Path
        The PNG written.
    demand : str
        ``"pfv"`` or ``"pfa"``.
    outcome : str
        ``"overturning"`` or ``"sliding"``.
    """
    sel = curves[(curves["item"] == item) & (curves["demand"] == demand) & (curves["outcome"] == outcome)]
    fig, ax = plt.subplots(figsize=(6.0, 4.2), constrained_layout=True)
    groups = list(sel.groupby(["floor", "direction"], sort=False))
    for k, ((floor, direction), g) in enumerate(groups):
        ls, _ = _style(k)
        # the direction always named (a legend that drops it when one direction has a curve reads as both);
        # fitted curves, no markers (markers read as data points)
        line, = ax.plot(g["x"], g["p"], ls=ls, lw=1.6, label=f"floor {floor}, direction {direction}")
        if g["p_lo"].notna().any():
            # arrays, not Series: numpy 1.24 (the floor pyproject.toml allows) cannot mask a Series whose index
            # does not start at 0
            ax.fill_between(g["x"].to_numpy(float), g["p_lo"].to_numpy(float), g["p_hi"].to_numpy(float),
                            color=line.get_color(), alpha=0.12, lw=0)
    if not groups:
        ax.text(0.5, 0.5, f"no fitted {outcome} curve", ha="center", va="center", transform=ax.transAxes, fontsize=10)
    ax.set_xscale("log")
    log_ticks(ax.xaxis)
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel(AXIS_LABELS[demand])
    ax.set_ylabel(f"P({outcome} | {demand.upper()}) (-)")
    ax.set_title(f"{item}: fitted {outcome} fragility per floor and direction (band: 95 % record bootstrap)",
                 fontsize=10)
    ax.tick_params(labelsize=MIN_FONT)
    ax.grid(True, which="both", alpha=0.3)
    if groups:
        ax.legend(fontsize=MIN_FONT)
    return save_figure(fig, path)


def plot_floor_demands(demands: pd.DataFrame, path: str | Path) -> Path:
    """Each motion's PFA (g) and PFV (m/s) per floor, one point per record, one marker per direction.

    Parameters
    ----------
    demands : pandas.DataFrame
        :func:`opsrock.inventory.summary.demand_table` (``pfa_g`` in g, ``pfv`` in m/s).
    path : str or pathlib.Path
        The PNG written.
    """
    floors = list(dict.fromkeys(demands["floor"]))
    fig, axes = plt.subplots(1, 2, figsize=(9.0, 3.8), constrained_layout=True)
    directions = list(dict.fromkeys(demands["direction"]))
    for ax, column, label in zip(axes, ("pfa_g", "pfv"), (AXIS_LABELS["pfa"], AXIS_LABELS["pfv"])):
        for k, direction in enumerate(directions):
            g = demands[demands["direction"] == direction]
            offset = (k - (len(directions) - 1) / 2) * 0.15  # side by side, so both directions are seen
            ax.plot(g["floor"].map({f: i for i, f in enumerate(floors)}) + offset, g[column], _style(k)[1],
                    mfc="none", ms=6, ls="none", label=f"direction {direction}")
        ax.set_xticks(range(len(floors)))
        ax.set_xticklabels(floors)
        ax.set_xlabel("floor (as the motions name it)")
        ax.set_ylabel(label)
        ax.tick_params(labelsize=MIN_FONT)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=MIN_FONT)
    fig.suptitle("The floors' demands: one point per record", fontsize=10)
    return save_figure(fig, path)


def item_figures(curves: pd.DataFrame, folder: str | Path, demand: str = "pfv",
                 outcome: str = "overturning") -> dict[str, Path]:
    """:func:`plot_item_fragility` of every item of ``curves`` that has a curve of ``outcome`` in ``demand`` into
    ``folder/<item>.png``: item -> PNG (an item without one gets no empty figure: the report says it in a line)."""
    folder = Path(folder)
    have = curves[(curves["demand"] == demand) & (curves["outcome"] == outcome)]
    return {item: plot_item_fragility(curves, item, folder / f"{item}.png", demand, outcome)
            for item in dict.fromkeys(have["item"])}


__all__ = ["AXIS_LABELS", "MIN_FONT", "item_figures", "plot_floor_demands", "plot_item_fragility"]
