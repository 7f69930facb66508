"""The figures of validation case ``experiments``: ``restitution.png`` and ``decay.png`` (matplotlib is
imported when a figure is drawn)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from opsrock.published.colombo_limestone import EventArrays
from opsrock.validation.experiments.constants import MODELS, PAPER_FACTOR, RELEASE_RATIOS


def plot_restitution(a: EventArrays, by_group: pd.DataFrame, by_impact: pd.DataFrame, factor: tuple,
                     path: Path) -> None:
    """Three panels: first-impact ratios against alpha with ``e_R`` and ``0.95 e_R``; the factor per
    geometry; the median factor per impact number.

    Parameters
    ----------
    a : EventArrays
        The impacts.
    by_group, by_impact : pandas.DataFrame
        :func:`restitution_table` rows per geometry and per impact number.
    factor : tuple
        The fitted factor ``(estimate, low, high)`` (dimensionless).
    path : pathlib.Path
        The PNG.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from opsrock.plots import save_figure

    fig, ax = plt.subplots(1, 3, figsize=(15, 4.6), constrained_layout=True)
    first = a.event == 1
    al = np.linspace(0.05, 0.26, 200)
    e_r = 1.0 - 1.5 * np.sin(al) ** 2
    ax[0].scatter(a.alpha[first], a.ratio[first], s=10, color="0.3", label="measured, impact 1 (134 trials)")
    ax[0].plot(al, e_r, color="C0", label="Housner e_R")
    ax[0].plot(al, PAPER_FACTOR * e_r, color="C3", ls="--", label="paper 0.95 e_R")
    ax[0].plot(al, factor[0] * e_r, color="C2", ls=":", label=f"fitted {factor[0]:.4f} e_R")
    ax[0].set(xlabel="alpha = atan(B/H) (rad)", ylabel="angular-velocity ratio after/before",
              title="first impact", ylim=(0.75, 1.1))
    for k, (label, mk) in enumerate((("all", "o"), ("1-10", "s"), ("1", "^"))):
        t = by_group[by_group["impacts"] == label]
        x = t["alpha_rad"] + (k - 1) * 0.003
        ax[1].errorbar(x, t["factor"], yerr=[t["factor"] - t["factor_lo"], t["factor_hi"] - t["factor"]],
                       fmt=mk, ms=4, capsize=2, label=f"impacts {label}")
    n = by_impact["n"].to_numpy(float)  # arrays, not Series: with numpy 1.24 and pandas 2 the mask test fails
    ax[2].fill_between(n, by_impact["factor_lo"].to_numpy(float), by_impact["factor_hi"].to_numpy(float), color="C0",
                       alpha=0.25,
                       label="95 % interval (trial bootstrap)")
    ax[2].plot(n, by_impact["factor"].to_numpy(float), "o-", ms=3, color="C0", label="median")
    for axis in ax[1:]:
        axis.axhline(1.0, color="C0", lw=0.8)
        axis.axhline(PAPER_FACTOR, color="C3", ls="--", lw=0.8, label="paper 0.95")
        axis.axhspan(factor[1], factor[2], color="C2", alpha=0.25, label=f"fitted {factor[0]:.4f} (all impacts)")
        axis.set(ylabel="measured / e_R", ylim=(0.9, 1.06))
        axis.legend(fontsize=7, loc="lower left")
    ax[1].set(xlabel="alpha (rad)", title="factor per geometry (median, 95 % interval)")
    ax[2].set(xlabel="impact number", title="factor per impact number, all geometries")
    ax[0].legend(fontsize=7, loc="lower left")
    save_figure(fig, path)


#: Line style per model in the decay figure.
_STYLE = {"rigid e_R": ("C0", "-"), "rigid fitted": ("C2", "-"), "rigid 0.95 e_R": ("C3", "--"),
          "sdof": ("C1", "-"), "opensees": ("C4", ":"), "sdof e_R": ("C5", "-.")}


def plot_decay(measured: pd.DataFrame, predicted: pd.DataFrame, geometry: dict, path: Path) -> None:
    """One panel per geometry: the measured running product (median, 25-75 % and 10-90 % of trials)
    and each model's, at every release angle (the first solid, the others thin).

    Parameters
    ----------
    measured : pandas.DataFrame
        :func:`measured_decay`.
    predicted : pandas.DataFrame
        :func:`predicted_table`.
    geometry : dict
        ``{group: (B, H)}`` (m).
    path : pathlib.Path
        The PNG.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from opsrock.plots import save_figure

    groups = sorted(predicted["group"].unique())
    ncol = min(4, len(groups))
    nrow = -(-len(groups) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(3.6 * ncol, 3.0 * nrow), sharex=True, squeeze=False,
                             constrained_layout=True)
    for axis, g in zip(axes.flat, groups):
        m = measured[measured["group"] == g]
        x, col = m["impact"].to_numpy(float), (lambda name: m[name].to_numpy(float))
        axis.fill_between(x, col("p10"), col("p90"), color="0.85", label="measured 10-90 %")
        axis.fill_between(x, col("p25"), col("p75"), color="0.65", label="measured 25-75 %")
        axis.plot(m["impact"], m["median"], "k.-", ms=3, lw=1.2, label="measured median")
        for (model, rel), s in predicted[predicted["group"] == g].groupby(["model", "release_ratio"], sort=False):
            color, ls = _STYLE[model]
            primary = rel == RELEASE_RATIOS[0]
            if MODELS[model][0] == "housner" and not primary:
                continue  # the rigid body's ratios do not depend on the release angle
            axis.plot(s["impact"], s["product"], color=color, ls=ls, lw=1.3 if primary else 0.7,
                      alpha=1 if primary else 0.7,
                      label=model + ("" if MODELS[model][0] == "housner" else f" {rel:g} alpha"))
        b, h = geometry[g]
        axis.set_yscale("log")
        axis.set_ylim(0.05, 1.3)
        axis.set_title(f"group {g}: {b:g} x {h:g} m", fontsize=9)
    for axis in axes[-1]:
        axis.set_xlabel("impact number n")
    for axis in axes[:, 0]:
        axis.set_ylabel("velocity after n impacts / before 1st")
    for axis in list(axes.flat)[len(groups):]:
        axis.set_visible(False)
    axes.flat[0].legend(fontsize=6, loc="lower left")
    save_figure(fig, path)
