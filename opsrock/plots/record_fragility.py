"""Figures of the record fragility study: IDA curves, the IM ranking and its robustness, and the sliding
fragilities per block and floor (each block's overturning fragility per floor is
:func:`opsrock.inventory.plots.plot_item_fragility`). Legend and tick text at least :data:`MIN_FONT` pt;
every axis names its quantity and unit; no curve pools blocks or floors."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

from opsrock.fragility.lognormal import fragility_probability  # noqa: E402
from opsrock.plots import log_ticks, save_figure  # noqa: E402

#: Height at which overturned cases are drawn on the IDA axes (theta_max / alpha).
OVERTURNED_Y: float = 1.25
#: Smallest legend text (pt).
MIN_FONT: float = 8.0


def plot_ida_curves(cases: pd.DataFrame, path: str | Path, measure_label: str = "level") -> Path:
    """One panel per block: theta_max/alpha against the scene's measure for every IDA curve, one
    line per (record, floor), coloured by floor; overturned cases drawn at the top, resurrections visible as
    drops. ``measure_label``: the x axis, the measure's quantity and unit."""
    blocks = list(dict.fromkeys(cases["block"]))
    n = len(blocks)
    cols = min(n, 2)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 3.6 * rows), squeeze=False, constrained_layout=True)
    floors = list(dict.fromkeys(cases["floor"]))
    colors = {f: c for f, c in zip(floors, plt.rcParams["axes.prop_cycle"].by_key()["color"] * 4)}
    for ax, block in zip(axes.ravel(), blocks):
        sub = cases[cases["block"] == block]
        segments, segment_colors = _ida_segments(sub, colors)
        # one collection of all the curves, in the order of the groups, each drawn as its own line
        ax.add_collection(LineCollection(segments, colors=segment_colors, linewidths=0.5, alpha=0.45), autolim=True)
        ax.autoscale_view()
        for f in floors:
            ax.plot([], [], "-", color=colors[f], label=f"floor {f}")
        ax.legend(fontsize=MIN_FONT, loc="center right")
        ax.axhline(1.0, color="k", lw=0.6, ls=":")
        ax.set_ylim(0, OVERTURNED_Y + 0.1)
        ax.set_yticks([0, 0.25, 0.5, 0.75, 1.0, OVERTURNED_Y])
        ax.set_yticklabels(["0", "0.25", "0.5", "0.75", "1", "overturned"])
        ax.set_xlabel(measure_label)
        ax.set_ylabel(r"peak rotation over slenderness $\theta_{max}/\alpha$ (-)")
        ax.set_title(str(block), fontsize=10)
    for ax in axes.ravel()[n:]:
        ax.set_visible(False)
    return save_figure(fig, path)


def _ida_segments(sub: pd.DataFrame, colors: dict) -> tuple[list[np.ndarray], list]:
    """The IDA curves of one block, one per (record, floor) in order of first appearance, each sorted by
    level: the polylines (split where a value is missing, as a plotted line is) and their colours."""
    keys = pd.MultiIndex.from_arrays([sub["record"], sub["floor"]])
    code, uniq = pd.factorize(keys, sort=False)
    level = sub["level"].to_numpy()
    order = np.lexsort((level, code))  # by curve, then by level (levels are distinct along a curve)
    x = sub["level_value"].to_numpy(float)[order]
    y = np.where(sub["y"].to_numpy(bool), OVERTURNED_Y,
                 np.minimum(sub["theta_max_over_alpha"].to_numpy(float), 1.0))[order]
    code = code[order]
    cuts = np.flatnonzero(np.diff(code)) + 1
    segments, segment_colors = [], []
    for k, (cx, cy) in enumerate(zip(np.split(x, cuts), np.split(y, cuts))):
        color = colors[uniq[code[cuts[k - 1]] if k else code[0]][1]]
        finite = np.isfinite(cx) & np.isfinite(cy)
        runs = np.split(np.flatnonzero(finite), np.flatnonzero(np.diff(np.flatnonzero(finite)) > 1) + 1)
        for run in runs:
            if run.size:
                segments.append(np.column_stack([cx[run], cy[run]]))
                segment_colors.append(color)
    return segments, segment_colors


def plot_sliding_fragility(cases: pd.DataFrame, sliding: pd.DataFrame, path: str | Path) -> Path:
    """One panel per block and floor: the fraction of its finished cases at each level that slid beyond each
    distance (or overturned), at the level's median PFA (m/s²), and the MLE curve in PFA of each distance
    (the rows of demand ``pfa`` of the per-floor sliding table, ``block`` and ``floor`` columns)."""
    from opsrock.fragility.sliding import slid_beyond

    pfa_rows = sliding[sliding["demand"] == "pfa"]
    panels = list(dict.fromkeys(zip(pfa_rows["block"], pfa_rows["floor"])))
    n = max(len(panels), 1)
    cols = min(n, 3)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.6 * cols, 3.8 * rows), constrained_layout=True, squeeze=False)
    for ax, (block, floor) in zip(axes.ravel(), panels):
        sel = cases[(cases["block"] == block) & (cases["floor"] == floor) & (cases["status"] == "ok")]
        pfa = sel["pfa"].to_numpy(float)
        x = np.geomspace(max(np.nanmin(pfa) * 0.7, 1e-6), np.nanmax(pfa) * 1.4, 300) if len(sel) else np.array([])
        here = pfa_rows[(pfa_rows["block"] == block) & (pfa_rows["floor"] == floor)]
        for k, ((_, r), color) in enumerate(zip(here.iterrows(), plt.rcParams["axes.prop_cycle"])):
            d, c = r["distance"], color["color"]
            ls, marker = [("-", "o"), ("--", "s"), ("-.", "^"), (":", "D")][k % 4]
            by_level = pd.DataFrame({"level": sel["level"].to_numpy(), "pfa": pfa,
                                     "beyond": slid_beyond(sel, d, r["measure"])}).groupby("level")
            ax.plot(by_level["pfa"].median(), by_level["beyond"].mean(), marker, ms=4, color=c, alpha=0.7, mfc="none")
            label = f"beyond {100 * d:g} cm"
            if r["success"] and np.isfinite(r["median"]) and r["beta"] > 0:
                ax.plot(x, fragility_probability(x, r["median"], r["beta"]), color=c, lw=1.4, ls=ls, marker=marker,
                        mfc="none", markevery=(12 * k, 40),  # staggered markers: coinciding curves stay apart
                        label=f"{label}: median {r['median']:.3g} m/s², beta {r['beta']:.2f}")
            else:  # the report's table says why
                ax.plot([], [], marker, color=c, label=f"{label}: no lognormal fit")
        ax.set_xscale("log")
        log_ticks(ax.xaxis)
        ax.set_ylim(-0.02, 1.02)
        ax.set_title(f"{block}, floor {floor}", fontsize=9)
        ax.set_xlabel("PFA, peak floor acceleration (m/s²)")
        ax.set_ylabel("P(slid beyond d or overturned) (-)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=MIN_FONT)
    for ax in axes.ravel()[len(panels):]:
        ax.set_visible(False)
    return save_figure(fig, path)


def plot_im_ranking(ims: pd.DataFrame, frequencies: pd.DataFrame, path: str | Path,
                    robustness: pd.DataFrame | None = None) -> Path:
    """Three panels: MLE beta with its interval per IM; HR per IM; share of record resamples (and,
    if given, of pulse block sets) in which each IM has the smallest beta, HR and CV."""
    fig, axes = plt.subplots(1, 3, figsize=(14.0, 4.0), constrained_layout=True)
    x = np.arange(len(ims))
    ax = axes[0]
    err = np.vstack([ims["beta"] - ims["beta_lo"], ims["beta_hi"] - ims["beta"]]).clip(min=0)
    ax.bar(x, ims["beta"], color="tab:blue", alpha=0.7)
    ax.errorbar(x, ims["beta"], yerr=np.nan_to_num(err), fmt="none", ecolor="k", capsize=3)
    ax.set_title("MLE dispersion beta (interval: records resampled)", fontsize=9)
    ax = axes[1]
    ax.bar(x, ims["HR"], color="tab:orange", alpha=0.7)
    ax.set_title("hybrid ratio HR (paper Eq. 12)", fontsize=9)
    ax = axes[2]
    w = 0.13
    series = [("record resamples", frequencies)] + ([("pulse block sets", robustness)] if robustness is not None else [])
    k = 0
    for label, df in series:
        for crit, hatch in (("beta", ""), ("HR", "//"), ("cv_percent", "..")):
            if f"share_{crit}" not in df:
                continue
            ax.bar(x + (k - 2.5) * w, df[f"share_{crit}"], w, hatch=hatch, alpha=0.7,
                   label=f"{label}: smallest {crit.replace('_percent', '')}")
            k += 1
    ax.set_ylim(0, 1)
    ax.set_title("how often each IM wins", fontsize=9)
    ax.legend(fontsize=MIN_FONT, loc="best")
    axes[0].set_ylabel("beta (-)")
    axes[1].set_ylabel("HR (-)")
    ax.set_ylabel("share of resamples or sets (-)")
    for ax in axes:
        ax.set_xlabel("intensity measure")
        ax.set_xticks(x)
        ax.set_xticklabels(ims["im"])
    return save_figure(fig, path)
