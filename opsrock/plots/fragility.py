"""Fragility figures of the paper: 6a, 6b, 8, 9, 10, 11 and 12.

Every function draws from a cases table (the campaign's ``cases.csv``) and/or a
:class:`opsrock.fragility.FragilityAnalysis`, writes one PNG to the explicit ``path`` it is
given, and returns that path. :func:`paper_figures` writes all of them into a folder.
Statistics use the rocking cases only (Eq. 13); no-uplift and failed cases appear only in
Figures 6a/6b, with their own markers.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Mapping

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from opsrock.fragility import FragilityAnalysis, table2  # noqa: E402
from opsrock.intensity import get_im  # noqa: E402
from opsrock.published.liu_huang_liu_2023 import TABLE2, TABLE3  # noqa: E402

#: Marker style per verdict (colour, marker, label), shared by Figures 6b and 8.
VERDICT_STYLE: dict[str, tuple[str, str, str]] = {
    "safe": ("tab:blue", "o", "safe rocking"),
    "overturned": ("tab:red", "x", "overturned"),
    "no_uplift": ("0.6", ".", "no uplift (left out)"),
    "failed": ("black", "s", "failed (left out)"),
}

#: Above this max/min ratio of an IM's values, its axis is logarithmic.
LOG_AXIS_RATIO: float = 50.0

#: Dense spectrum tables with more cases than this are drawn as a coloured grid, not markers.
DENSE_SPECTRUM_CASES: int = 400


from opsrock.plots import save_figure as _save  # noqa: E402


def _verdicts(cases: pd.DataFrame) -> pd.Series:
    if "verdict" in cases.columns:
        return cases["verdict"].astype(str)
    from opsrock.campaign.cases import as_bool

    status = cases["status"].astype(str)
    done = (status == "ok").to_numpy()  # a failed case is "failed" whatever its columns hold
    rocked, over = np.zeros(len(cases), dtype=bool), np.zeros(len(cases), dtype=bool)
    rocked[done] = as_bool(cases.loc[done, "rocked"], "rocked")  # the case reader's parser
    over[done] = as_bool(cases.loc[done, "overturned"], "overturned")
    return pd.Series(np.where(status != "ok", "failed", np.where(~rocked, "no_uplift",
                              np.where(over, "overturned", "safe"))), index=cases.index)


def _blocks(*tables: pd.DataFrame | None) -> list[str]:
    names: list[str] = []
    for t in tables:
        if t is not None and "block" in t.columns:
            names += [str(b) for b in t["block"].unique() if str(b) not in names]
    return names or [""]


def _block_rows(table: pd.DataFrame, name: str) -> pd.DataFrame:
    if "block" not in table.columns or name == "":
        return table
    return table[table["block"].astype(str) == name]


def _grid(n: int, max_cols: int = 4) -> tuple[int, int]:
    cols = min(n, max_cols)
    return math.ceil(n / cols), cols


def _maybe_log(ax, values: np.ndarray, axis: str = "x") -> None:
    v = values[np.isfinite(values) & (values > 0)]
    if v.size and v.max() / v.min() > LOG_AXIS_RATIO:
        (ax.set_xscale if axis == "x" else ax.set_yscale)("log")


# --- Figure 6a -------------------------------------------------------------------------------
def plot_case_distribution(cases: pd.DataFrame, path: str | Path) -> Path:
    """Figure 6a: where the cases lie, dimensionless and in physical units, per block.

    Parameters
    ----------
    cases : pandas.DataFrame
        Needs ``freq_ratio`` (omega_p/p), ``pfa_ratio`` (PFA/g tan alpha), ``pfa`` (m/s²) and
        ``omega_p`` (rad/s); ``block`` optional.
    path : str or Path
        PNG to write.
    """
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    markers = "osD^v<>ph*"
    for i, name in enumerate(_blocks(cases)):
        rows = _block_rows(cases, name)
        m = markers[i % len(markers)]
        ax1.scatter(rows["freq_ratio"], rows["pfa_ratio"], marker=m, s=28, facecolors="none",
                    edgecolors=f"C{i}", label=name or "cases")
        ax2.scatter(rows["omega_p"] / (2 * math.pi), rows["pfa"] / 9.81, marker=m, s=20,
                    color=f"C{i}", label=name or "cases")
    ax1.axhline(1.0, color="0.5", ls=":", lw=1)
    ax1.text(ax1.get_xlim()[1], 1.0, " uplift (Eq. 4)", va="bottom", ha="right", fontsize=8, color="0.4")
    ax1.set(xlabel=r"$\omega_p/p$ (IM1)", ylabel=r"PFA / $g\tan\alpha$ (IM2)",
            title="(a) cases, dimensionless")
    ax2.set(xlabel="pulse frequency $\\omega_p/2\\pi$ (Hz)", ylabel="PFA (g)",
            title="cases in physical units")
    ax1.legend(fontsize=8)
    fig.tight_layout()
    return _save(fig, path)


# --- Figure 6b -------------------------------------------------------------------------------
def overturning_boundary(table: pd.DataFrame) -> pd.DataFrame:
    """Lowest overturning ``pfa_ratio`` at each ``freq_ratio`` of a spectrum table.

    Returns a DataFrame ``freq_ratio, pfa_ratio_min`` (frequencies with no overturning are
    left out). The overturning region of a one-sine pulse is not convex (safe islands above
    the first overturning amplitude are known, Zhang & Makris 2001), so this is the lower
    boundary only.
    """
    v = _verdicts(table)
    over = table[v == "overturned"]
    if over.empty:
        return pd.DataFrame(columns=["freq_ratio", "pfa_ratio_min"])
    out = over.groupby("freq_ratio")["pfa_ratio"].min().reset_index()
    return out.rename(columns={"pfa_ratio": "pfa_ratio_min"}).sort_values("freq_ratio")


def _is_regular_grid(t: pd.DataFrame) -> bool:
    nf, na = t["freq_ratio"].nunique(), t["pfa_ratio"].nunique()
    return nf * na == len(t) and nf > 1 and na > 1


def plot_overturning_spectrum(
    cases: pd.DataFrame, path: str | Path, spectrum: pd.DataFrame | None = None
) -> Path:
    """Figure 6b: overturning spectrum per block, verdict markers and the lower boundary.

    Parameters
    ----------
    cases : pandas.DataFrame
        Campaign cases (``block``, ``freq_ratio``, ``pfa_ratio``, verdict columns).
    path : str or Path
        PNG to write.
    spectrum : pandas.DataFrame, optional
        A dense spectrum table with the same columns: drawn underneath (as a coloured grid
        when regular and large, else as small markers), with its own boundary.
    """
    names = _blocks(cases, spectrum)
    nr, nc = _grid(len(names))
    fig, axes = plt.subplots(nr, nc, figsize=(4.2 * nc, 3.8 * nr), squeeze=False)
    colours = {"no_uplift": 0, "safe": 1, "overturned": 2, "failed": 3}
    cmap = matplotlib.colors.ListedColormap(["0.92", "#c6dbef", "#fcbba1", "0.3"])
    for ax, name in zip(axes.flat, names):
        if spectrum is not None:
            sp = _block_rows(spectrum, name)
            if len(sp):
                v = _verdicts(sp).map(colours)
                if len(sp) > DENSE_SPECTRUM_CASES and _is_regular_grid(sp):
                    grid = sp.assign(c=v.to_numpy()).pivot_table(index="pfa_ratio", columns="freq_ratio",
                                                                 values="c", aggfunc="first")
                    ax.pcolormesh(grid.columns, grid.index, grid.to_numpy(), cmap=cmap, vmin=-0.5,
                                  vmax=3.5, shading="nearest")
                else:
                    ax.scatter(sp["freq_ratio"], sp["pfa_ratio"], c=v, cmap=cmap, vmin=-0.5, vmax=3.5,
                               s=6, marker="s")
                b = overturning_boundary(sp)
                ax.plot(b["freq_ratio"], b["pfa_ratio_min"], color="tab:red", lw=1.2, alpha=0.6,
                        label="dense boundary")
        rows = _block_rows(cases, name)
        v = _verdicts(rows)
        for verdict, (col, mk, label) in VERDICT_STYLE.items():
            sel = rows[v == verdict]
            if len(sel):
                kw = {"facecolors": "none", "edgecolors": col} if mk == "o" else {"color": col}
                ax.scatter(sel["freq_ratio"], sel["pfa_ratio"], marker=mk, s=26, label=label, **kw)
        b = overturning_boundary(rows)
        if len(b):
            ax.step(b["freq_ratio"], b["pfa_ratio_min"], where="mid", color="k", lw=1.2,
                    label="lowest overturning PFA")
        ax.axhline(1.0, color="0.5", ls=":", lw=1)
        ax.set(xlabel=r"$\omega_p/p$", ylabel=r"PFA / $g\tan\alpha$", title=name or "spectrum")
    for ax in axes.flat[len(names):]:
        ax.set_visible(False)
    axes.flat[0].legend(fontsize=7, loc="upper left")
    fig.suptitle("(b) overturning spectrum")
    fig.tight_layout()
    return _save(fig, path)


# --- Figure 8 --------------------------------------------------------------------------------
def plot_response_vs_im(analysis: FragilityAnalysis, path: str | Path) -> Path:
    """Figure 8: ``theta_max/alpha`` of the rocking cases against each IM, hybrid strip shaded.

    Overturned cases are drawn as crosses on a band above the largest safe response (their
    ``theta_max`` is wherever the run stopped, >= pi/2, and carries no information).
    """
    rock = analysis.split.rocking
    ims = list(analysis.results)
    nr, nc = _grid(len(ims), 3)
    fig, axes = plt.subplots(nr, nc, figsize=(4.2 * nc, 3.3 * nr), squeeze=False)
    over = rock["overturned"].to_numpy(bool)
    y = rock["theta_max_over_alpha"].to_numpy(float) if "theta_max_over_alpha" in rock else \
        np.full(len(rock), np.nan)
    y_safe = y[~over & np.isfinite(y)]
    top = 1.15 * max(float(y_safe.max()) if y_safe.size else 1.0, 1.0)
    for ax, im in zip(axes.flat, ims):
        r = analysis[im]
        x = rock[im].to_numpy(float)
        ax.scatter(x[~over], y[~over], s=10, facecolors="none", edgecolors="tab:blue", label="safe rocking")
        ax.scatter(x[over], np.full(over.sum(), top), s=14, marker="x", color="tab:red", label="overturned")
        h = r.hybrid
        if h.has_overlap:
            ax.axvspan(h.overlap_low, h.overlap_high, color="0.85", zorder=0, label="hybrid strip")
        ax.axhline(top, color="tab:red", lw=0.5, ls=":")
        _maybe_log(ax, x)
        ax.set(xlabel=get_im(im).label, ylabel=r"$|\theta|_{max}/\alpha$",
               title=f"{im}: HR = {h.HR:.2f}" + ("" if h.has_overlap else " (no overlap)"))
    for ax in axes.flat[len(ims):]:
        ax.set_visible(False)
    axes.flat[0].legend(fontsize=7, loc="center right")
    fig.tight_layout()
    return _save(fig, path)


# --- Figure 9 --------------------------------------------------------------------------------
def plot_hybrid_ratios(t2: pd.DataFrame, path: str | Path) -> Path:
    """Figure 9: ``W_HS/R_S`` against ``W_HS/R_O`` per IM, circles of constant HR, paper's points.

    Parameters
    ----------
    t2 : pandas.DataFrame
        Output of :func:`opsrock.fragility.table2`.
    path : str or Path
        PNG to write.
    """
    fig, ax = plt.subplots(figsize=(5.8, 5.2))
    phi = np.linspace(0, math.pi / 2, 100)
    for hr in (0.25, 0.5, 0.75, 1.0, 1.25, 1.5):
        ax.plot(hr * np.cos(phi), hr * np.sin(phi), color="0.85", lw=0.8, zorder=0)
        ax.text(hr * math.cos(0.8), hr * math.sin(0.8), f"HR {hr:g}", fontsize=7, color="0.6")
    for _, r in t2.iterrows():
        ax.scatter(r["W_HS_over_R_S"], r["W_HS_over_R_O"], color="tab:blue", zorder=3)
        ax.annotate(r["im"], (r["W_HS_over_R_S"], r["W_HS_over_R_O"]), fontsize=8,
                    xytext=(4, 3), textcoords="offset points", color="tab:blue")
        p = TABLE2.get(r["im"])
        if p is not None:
            ax.scatter(p.W_HS_over_R_S, p.W_HS_over_R_O, facecolors="none", edgecolors="tab:orange",
                       zorder=2)
            ax.annotate(r["im"], (p.W_HS_over_R_S, p.W_HS_over_R_O), fontsize=7, xytext=(4, -9),
                        textcoords="offset points", color="tab:orange")
    ax.scatter([], [], color="tab:blue", label="this campaign")
    ax.scatter([], [], facecolors="none", edgecolors="tab:orange", label="paper, Table 2")
    ax.set(xlabel=r"$W_{HS}/R_S$", ylabel=r"$W_{HS}/R_O$", xlim=(-0.03, 1.1), ylim=(-0.03, 1.1),
           aspect="equal", title="Hybrid ratio (Eq. 12): closer to 0 is better")
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    return _save(fig, path)


# --- Figures 10 and 12 -----------------------------------------------------------------------
def _curve_x(analysis: FragilityAnalysis, im: str) -> np.ndarray:
    x = analysis.split.rocking[im].to_numpy(float)
    lo, hi = float(x.min()), float(x.max())
    if hi / lo > LOG_AXIS_RATIO:
        return np.geomspace(lo, hi, 300)
    return np.linspace(lo, hi, 300)


def _label_probability_axes(ax, xs: np.ndarray, im: str, decreasing: bool) -> None:
    """Axis scale, labels and legend shared by the fragility-curve panels (Figures 10, 12)."""
    _maybe_log(ax, xs)
    ax.set(xlabel=get_im(im).label, ylabel="P(overturning)", ylim=(-0.03, 1.03), title=im)
    if ax.get_legend_handles_labels()[0]:  # a panel with no fitted curve has nothing to list
        ax.legend(fontsize=6, loc="center right" if decreasing else "lower right")


def _finish_grid(fig, axes, n_used: int, path: str | Path) -> Path:
    """Hide the unused panels of a grid, lay it out and save it."""
    for ax in axes.flat[n_used:]:
        ax.set_visible(False)
    fig.tight_layout()
    return _save(fig, path)


def plot_fragility_curves(analysis: FragilityAnalysis, path: str | Path, strip_factor: float = 1.0) -> Path:
    """Figure 10: strip fractions and fitted fragility curves (least squares and MLE) per IM."""
    ims = list(analysis.results)
    nr, nc = _grid(len(ims), 3)
    fig, axes = plt.subplots(nr, nc, figsize=(4.2 * nc, 3.3 * nr), squeeze=False)
    for ax, im in zip(axes.flat, ims):
        r = analysis[im]
        xs = _curve_x(analysis, im)
        st = r.strips.get(strip_factor)
        if st is not None:
            ax.scatter(st.centre, st.fraction, s=12 + 2 * st.n_cases, color="k", zorder=3,
                       label="strip fraction (Eq. 13)" + (" [fallback]" if st.fallback else ""))
        fit = r.ls_fits.get(strip_factor)
        if fit is not None and np.isfinite(fit.mu):
            ax.plot(xs, fit.probability(xs), color="tab:blue", ls="-" if fit.success else "--",
                    label=f"LS: mu {fit.mu:.3g}, beta {fit.beta:.2f}" + ("" if fit.success else " (flagged)"))
        m = r.mle
        if np.isfinite(m.mu) and np.isfinite(m.beta):
            ax.plot(xs, m.probability(xs), color="tab:green", ls="-" if m.success else "--",
                    label=f"MLE: mu {m.mu:.3g}, beta {m.beta:.2f}" + ("" if m.success else " (flagged)"))
        p = TABLE3.get(im, {}).get(strip_factor)
        if p is not None:
            ax.plot(xs, _paper_curve(xs, p.mu, p.beta, r.hybrid.decreasing), color="tab:orange",
                    ls=":", label=f"paper: mu {p.mu:g}, beta {p.beta:g}")
        _label_probability_axes(ax, xs, im, r.hybrid.decreasing)
    return _finish_grid(fig, axes, len(ims), path)


def _paper_curve(x: np.ndarray, mu: float, beta: float, decreasing: bool) -> np.ndarray:
    from opsrock.fragility import fragility_probability

    return fragility_probability(x, mu, beta, decreasing)


def plot_strip_widths(analysis: FragilityAnalysis, path: str | Path) -> Path:
    """Figure 12: least-squares fragility curves for each strip width (``W_AS / W_SAS``)."""
    ims = list(analysis.results)
    nr, nc = _grid(len(ims), 3)
    fig, axes = plt.subplots(nr, nc, figsize=(4.2 * nc, 3.3 * nr), squeeze=False)
    styles = ["-", "--", "-.", ":"]
    for ax, im in zip(axes.flat, ims):
        r = analysis[im]
        xs = _curve_x(analysis, im)
        for i, (fac, fit) in enumerate(sorted(r.ls_fits.items())):
            colour = f"C{i}"
            st = r.strips.get(fac)
            if st is not None:
                ax.scatter(st.centre, st.fraction, s=10, color=colour, alpha=0.7)
            if np.isfinite(fit.mu):
                ax.plot(xs, fit.probability(xs), color=colour, ls=styles[i % len(styles)],
                        label=f"{fac:g} W_SAS: CV {fit.cv_percent:.1f} %" + ("" if fit.success else " *"))
        _label_probability_axes(ax, xs, im, r.hybrid.decreasing)
    return _finish_grid(fig, axes, len(ims), path)


# --- Figure 11 -------------------------------------------------------------------------------
def plot_dispersion(analysis: FragilityAnalysis, path: str | Path, strip_factor: float = 1.0) -> Path:
    """Figure 11: the paper's CV = beta/mu per IM, and beside it beta (LS and MLE with CI).

    ``beta/mu`` depends on the IM's scale; ``beta`` does not (it does depend on powers of the
    IM), hence the second panel.
    """
    ims = list(analysis.results)
    pos = np.arange(len(ims))
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4))
    cv = [analysis[im].ls_fits[strip_factor].cv_percent if strip_factor in analysis[im].ls_fits else np.nan
          for im in ims]
    cv_p = [TABLE3[im][strip_factor].cv_percent if im in TABLE3 and strip_factor in TABLE3[im] else np.nan
            for im in ims]
    a1.bar(pos - 0.2, cv, 0.4, label="this campaign (LS)")
    a1.bar(pos + 0.2, cv_p, 0.4, label="paper, Table 3", color="tab:orange")
    a1.set(xticks=pos, xticklabels=ims, ylabel="CV = beta/mu (%)", title=f"CV, W_AS = {strip_factor:g} W_SAS")
    a1.legend(fontsize=8)
    beta = [analysis[im].ls_fits[strip_factor].beta if strip_factor in analysis[im].ls_fits else np.nan
            for im in ims]
    mle = np.array([analysis[im].mle.beta for im in ims], dtype=float)
    lo = np.array([analysis[im].mle.beta_lo for im in ims], dtype=float)
    hi = np.array([analysis[im].mle.beta_hi for im in ims], dtype=float)
    beta_p = [TABLE3[im][strip_factor].beta if im in TABLE3 and strip_factor in TABLE3[im] else np.nan
              for im in ims]
    a2.bar(pos - 0.27, beta, 0.27, label="LS (strips)")
    err = np.vstack([np.clip(mle - lo, 0, None), np.clip(hi - mle, 0, None)])
    err = np.where(np.isfinite(err), err, 0.0)
    a2.bar(pos, mle, 0.27, yerr=err, capsize=2, label="MLE (95 % bootstrap)", color="tab:green")
    a2.bar(pos + 0.27, beta_p, 0.27, label="paper, Table 3", color="tab:orange")
    a2.set(xticks=pos, xticklabels=ims, ylabel="beta", title="dispersion beta (scale-free)")
    a2.legend(fontsize=8)
    fig.tight_layout()
    return _save(fig, path)


# --- all of them -----------------------------------------------------------------------------
def paper_figures(
    cases: pd.DataFrame,
    analysis: FragilityAnalysis,
    out_dir: str | Path,
    spectrum: pd.DataFrame | None = None,
    workers: int = 1,
) -> Mapping[str, Path]:
    """Write Figures 6a, 6b, 8, 9, 10, 11 and 12 into ``out_dir``.

    Parameters
    ----------
    cases : pandas.DataFrame
        Campaign cases table.
    analysis : FragilityAnalysis
        :func:`opsrock.fragility.analyse_fragility` of the same table.
    out_dir : str or Path
        Folder for the PNGs (created if missing).
    spectrum : pandas.DataFrame, optional
        Dense spectrum table for Figure 6b.
    workers : int, optional
        Processes drawing figures at once (matplotlib is single-threaded; the figures are
        independent). Default 1: in this process.

    Returns
    -------
    dict
        ``{"fig6a": path, "fig6b": ..., "fig8": ..., "fig9": ..., "fig10": ..., "fig11": ...,
        "fig12": ...}``.
    """
    jobs = paper_figure_jobs(cases, analysis, out_dir, spectrum)
    if workers <= 1:
        return {name: fn(*args) for name, (fn, args) in jobs.items()}
    from opsrock._pool import deferred_interrupts
    from opsrock.plots import figure_pool

    with figure_pool(workers) as pool:
        with deferred_interrupts():
            futures = {name: pool.submit(fn, *args) for name, (fn, args) in jobs.items()}
        return {name: f.result() for name, f in futures.items()}


#: Relative drawing cost of each figure of :func:`paper_figures` (for ordering the jobs of a pool,
#: the longest first): the grids of nine panels cost the most.
FIGURE_COST: dict[str, float] = {"fig12": 1.3, "fig8": 1.2, "fig10": 1.2, "fig6b": 0.6, "fig6a": 0.35,
                                 "fig11": 0.3, "fig9": 0.25}


def paper_figure_jobs(cases: pd.DataFrame, analysis: FragilityAnalysis, out_dir: str | Path,
                      spectrum: pd.DataFrame | None = None) -> dict[str, tuple]:
    """The figures of :func:`paper_figures` as independent jobs ``name -> (function, args)`` (each writes
    one PNG and returns its path), for a caller that runs them in its own pool."""
    out = Path(out_dir)
    return {
        "fig6a": (plot_case_distribution, (cases, out / "fig6a_cases.png")),
        "fig6b": (plot_overturning_spectrum, (cases, out / "fig6b_spectrum.png", spectrum)),
        "fig8": (plot_response_vs_im, (analysis, out / "fig8_response_vs_im.png")),
        "fig9": (plot_hybrid_ratios, (table2(analysis), out / "fig9_hybrid_ratio.png")),
        "fig10": (plot_fragility_curves, (analysis, out / "fig10_fragility.png")),
        "fig11": (plot_dispersion, (analysis, out / "fig11_cv_beta.png")),
        "fig12": (plot_strip_widths, (analysis, out / "fig12_strip_widths.png")),
    }
