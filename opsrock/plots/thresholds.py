"""Minimum-overturning-acceleration charts of the rocking literature, redrawn from our solvers.

Four panels, one per classical pulse: Housner's rectangular pulse, Makris and Roussos' half-sine,
Zhang and Makris' one-sine (both overturning branches and the safe window between them) and Makris
and Konstantinidis' one-cosine. The shaded bands are every overturning interval that
:func:`opsrock.analysis.threshold.threshold_chart` finds (``housner_fast``, linearised equation, as the papers
solve it; computed by :mod:`opsrock.analysis.charts`); the lines are the papers' closed forms
(:mod:`opsrock.published`).
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from opsrock.analysis.charts import Y_MAX, ChartData  # noqa: E402
from opsrock.plots import save_figure  # noqa: E402


def _draw_intervals(ax, data: ChartData, color: str, label: str) -> None:
    nu = data.freq_ratio
    # one band per column: each interval as a vertical segment, wide enough to tile the log axis
    from matplotlib.collections import PolyCollection

    width = np.gradient(np.log(nu)) if nu.size > 1 else np.array([0.05])
    boxes = []
    for x, w, ivs in zip(nu, width, data.intervals):
        x0, x1 = x * math.exp(-w / 2), x * math.exp(w / 2)
        boxes += [[(x0, a), (x1, a), (x1, min(b, Y_MAX)), (x0, min(b, Y_MAX))] for a, b in ivs]
    ax.add_collection(PolyCollection(boxes, facecolors=color, alpha=0.35, linewidths=0, label=label))


def plot_threshold_charts(data: dict[str, ChartData], path: str | Path) -> Path:
    """Draw the four panels of :func:`opsrock.analysis.charts.literature_charts` (or any data with those keys)
    into ``path``."""
    from opsrock.published import housner_1963, linearised, makris_roussos_2000

    fig, axes = plt.subplots(2, 2, figsize=(10.5, 8.0), constrained_layout=True)
    panels = [
        ("rectangular", "Rectangular pulse (Housner 1963)"),
        ("half-sine", "Half-sine pulse (Makris and Roussos 2000)"),
        ("one-sine", "One-sine pulse (Zhang and Makris 2001)"),
        ("one-cosine", "One-cosine pulse (Makris and Konstantinidis 2003)"),
    ]
    for ax, (shape, title) in zip(axes.ravel(), panels):
        d = data[shape]
        nu = d.freq_ratio
        _draw_intervals(ax, d, "tab:red", f"overturns (housner_fast, linearised, e = {d.restitution:.4g})")
        fine = np.geomspace(nu.min(), nu.max(), 100)
        if shape == "rectangular":
            ax.plot(fine, [housner_1963.minimum_overturning(math.pi / x) for x in fine], "k-", lw=1.2,
                    label=r"Housner: $1/(1-e^{-p t_1})$, $p t_1 = \pi/(\omega_p/p)$")
        else:
            curve = [linearised.minimum_no_impact(x, shape) for x in fine]
            ax.plot(fine, curve, "k-", lw=1.2, label="closed form, overturning without impact")
        if shape == "half-sine":
            ax.plot(fine, [makris_roussos_2000.housner_energy_estimate(x) for x in fine], "k--", lw=1.0,
                    label=r"energy estimate $\sqrt{1 + (p/\omega_p)^2}$")
        ax.set_xscale("log")
        ax.set_ylim(0.0, Y_MAX)
        ax.set_xlim(nu.min(), nu.max())
        ax.set_xlabel(r"$\omega_p / p$" + (r"  ($=\pi / p t_1$)" if shape == "rectangular" else ""))
        ax.set_ylabel(r"$a_p / (g\,\alpha)$")
        ax.set_title(title, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="upper left")
    return save_figure(fig, path)

