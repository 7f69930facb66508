"""The study's figures: one per item (fragility curves of opsrock's variants and FEMA P-58's, per floor,
in PFV and in PFA), and FEMA's rule against the period and the aspect ratio beside opsrock's medians."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd

from opsrock.constants import G
from opsrock.inventory.fema.design import ContentsDesign, floor_name
from opsrock.fragility.lognormal import fragility_probability
from opsrock.published import fema_p58

#: Colours of the variants.
COLOURS: dict[str, str] = {"default": "#1b9e77", "housner": "#7570b3", "friction": "#d95f02"}

#: Line styles of the variants (the friction curve often lies on the default one: dashed, it stays visible).
STYLES: dict[str, str] = {"default": "-", "housner": "-", "friction": "--"}


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _observed(ax, cases: pd.DataFrame, column: str, div: float) -> None:
    """Observed share overturned of the default variant in ten bins of equal counts."""
    x = cases[column].to_numpy(float) / div
    y = cases["overturned"].to_numpy(bool)
    if len(x) < 20:
        return
    edges = np.quantile(x, np.linspace(0, 1, 11))
    idx = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, 9)
    mids = [np.exp(np.log(x[idx == k]).mean()) for k in range(10) if np.any(idx == k)]
    shares = [y[idx == k].mean() for k in range(10) if np.any(idx == k)]
    ax.plot(mids, shares, "o", ms=3, color=COLOURS["default"], alpha=0.6, label="observed (default)")


def _panel(ax, fits: pd.DataFrame, fema: list[tuple[str, float, float, str]], grid: np.ndarray) -> None:
    for _, r in fits.iterrows():
        if not math.isfinite(r["median"]):
            continue
        c = COLOURS.get(r["variant"], "grey")
        ax.plot(grid, fragility_probability(grid, r["median"], r["beta"]), STYLES.get(r["variant"], "-"), color=c, lw=1.6,
                label=f"opsrock {r['variant']}: {r['median']:.3g}, beta {r['beta']:.2f}")
        if math.isfinite(r["median_lo"]):
            ax.plot([r["median_lo"], r["median_hi"]], [0.5, 0.5], "|-", color=c, lw=1, ms=6)
    for label, median, beta, style in fema:
        ax.plot(grid, fragility_probability(grid, median, beta), style, color="k", lw=1.2, label=f"{label}: {median:.3g}")
    ax.set_xscale("log")
    ax.set_ylim(-0.02, 1.02)
    ax.grid(alpha=0.3)


def plot_item(item: str, fits: pd.DataFrame, cases: pd.DataFrame, design: ContentsDesign, path: Path) -> Path:
    """Fragility curves of one item: a column per floor, PFV (top) and PFA (bottom); opsrock's variants
    (median interval at P = 0.5), the observed share of the default variant, FEMA P-58's database curve
    and the rule at ``T_1``."""
    plt = _pyplot()
    it = fema_p58.item(item)
    numbers = design.floor_numbers
    fig, axes = plt.subplots(2, len(numbers), figsize=(3.6 * len(numbers) + 0.6, 6.4), squeeze=False)
    mine = fits[(fits["item"] == item) & (fits["campaign"] != "sweep")]
    for j, number in enumerate(numbers):
        for i, (demand, column, div, unit) in enumerate((("pfv", "pfv", 1.0, "m/s"), ("pfa", "pfa", G, "g"))):
            ax = axes[i][j]
            sel = mine[(mine["floor_number"] == number) & (mine["demand"] == demand)]
            obs = cases[(cases["item"] == item) & (cases["floor_number"] == number) & (cases["variant"] == "default")
                        & (cases["campaign"] == "rocking") & (cases["status"] == "ok")]
            if demand == "pfv":
                fema = [("FEMA P-58 database", it.median_mps, fema_p58.BETA, "-")]
                if number > 0:
                    fema.append((f"FEMA rule, T = {design.period:g} s",
                                 fema_p58.median_pfv(it.aspect_ratio, design.period), fema_p58.BETA, "--"))
            else:
                fema = [("uplift g b/h (rule in PFA)", it.aspect_ratio, fema_p58.BETA, ":")]
            finite = [v for v in [*sel["median"], *(f[1] for f in fema)] if math.isfinite(v)]
            grid = np.geomspace(min(finite) / 4.0, max(finite) * 4.0, 200)
            _panel(ax, sel, fema, grid)
            _observed(ax, obs, column, div)
            ax.set_xlabel(f"peak floor {'velocity' if demand == 'pfv' else 'acceleration'} ({unit})")
            if j == 0:
                ax.set_ylabel("P(overturned)")
            ax.set_title(floor_name(number, design.storeys), fontsize=9)
            ax.legend(fontsize=5.5, loc="upper left")
    fig.suptitle(f"{item}: {it.name}, {it.depth_in:g} x {it.height_in:g} in (b/h = {it.aspect_ratio:.3f}); "
                 f"building T1 = {design.period:g} s, {design.storeys} storeys", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    path = Path(path)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def plot_rule(ratios: pd.DataFrame, sweep: pd.DataFrame, design: ContentsDesign, path: Path) -> Path:
    """FEMA's rule ``g (b/h) T / 2 pi`` against ``T`` (left, one line per item) and ``b/h`` (right), with
    the database medians, and opsrock's default-variant medians (roofs against ``T``; every floor against
    ``b/h``)."""
    plt = _pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 5))
    cmap = plt.get_cmap("tab10")
    periods = np.geomspace(0.1, 3.0, 100)
    default = ratios[ratios["variant"] == "default"]
    for k, it in enumerate(fema_p58.ITEMS):
        c = cmap(k % 10)
        ax1.plot(periods, [fema_p58.median_pfv(it.aspect_ratio, t) for t in periods], color=c, lw=1,
                 label=f"{it.fema_id} (b/h {it.aspect_ratio:.2f})")
        ax1.plot(fema_p58.REFERENCE_PERIOD, it.median_mps, "s", color=c, mfc="none")
        pts = sweep[sweep["item"] == it.fema_id] if not sweep.empty else pd.DataFrame()
        if not pts.empty:
            ax1.plot(pts["T1"], pts["median_pfv"], "o-", color=c, ms=4, lw=0.8)
            ax1.vlines(pts["T1"], pts["median_pfv_lo"], pts["median_pfv_hi"], color=c, lw=0.8)
        roof = default[(default["item"] == it.fema_id) & (default["floor_number"] == design.storeys)]
        if not roof.empty and pts.empty:
            ax1.plot([design.period], roof["median_pfv"], "o", color=c, ms=5)
    ax1.set(xscale="log", yscale="log", xlabel="building period T (s)", ylabel="median PFV at overturning (m/s)",
            title="rule (lines), database (squares), opsrock roofs (dots)")
    ax1.legend(fontsize=6)
    ax1.grid(alpha=0.3, which="both")
    ratios_grid = np.linspace(0.1, 0.7, 50)
    for t, style in ((fema_p58.REFERENCE_PERIOD, "-"), (design.period, "--")):
        ax2.plot(ratios_grid, [fema_p58.median_pfv(r, t) for r in ratios_grid], style, color="k", lw=1,
                 label=f"rule, T = {t:.3g} s")
    ax2.plot([i.aspect_ratio for i in fema_p58.ITEMS], [i.median_mps for i in fema_p58.ITEMS], "ks", mfc="none",
             label="FEMA P-58 database")
    for number, g in default.groupby("floor_number"):
        ax2.plot(g["b_over_h"], g["median_pfv"], "o", ms=4, label=f"opsrock, {floor_name(int(number), design.storeys)}")
    ax2.set(xlabel="b/h (depth / height)", ylabel="median PFV at overturning (m/s)", yscale="log",
            title=f"against aspect ratio (building T1 = {design.period:g} s)")
    ax2.legend(fontsize=7)
    ax2.grid(alpha=0.3, which="both")
    from matplotlib.ticker import FuncFormatter, NullFormatter

    for axis in (ax1.xaxis, ax1.yaxis, ax2.yaxis):  # plain numbers on the log axes (0.5, 1, 2), not 2 x 10^0
        axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        axis.set_minor_formatter(NullFormatter())
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


__all__ = ["COLOURS", "STYLES", "plot_item", "plot_rule"]
