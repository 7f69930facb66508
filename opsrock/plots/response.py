"""Response figures: rotation histories (paper Figure 4) and model hysteresis (Figure 3)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from opsrock.block import Block  # noqa: E402
from opsrock.model import restoring_moment  # noqa: E402
from opsrock.plots import save_figure as _save  # noqa: E402
from opsrock.result import RockingResult  # noqa: E402


def plot_response(result: RockingResult, block: Block, excitation, path: str | Path) -> Path:
    """Rotation history, and the model hysteresis of Figure 3 when the solver reports it.

    Parameters
    ----------
    result : RockingResult
        A solver's result.
    block : Block
        The block (for ``alpha`` and the exact restoring moment).
    excitation : Excitation
        The floor motion (plotted under the rotation history, in g).
    path : str or Path
        Output PNG file.
    """
    has_moments = result.spring_moment is not None and result.spring_moment.size == result.theta.size
    ncols = 3 if has_moments else 1
    fig, axes = plt.subplots(1, ncols, figsize=(4.6 * ncols, 3.8), squeeze=False)
    ax = axes[0, 0]
    ax.plot(result.time, result.theta / block.alpha, lw=1.1, label=r"$\theta/\alpha$")
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel("time (s)")
    ax.set_ylabel(r"$\theta / \alpha$")
    ax.set_title(f"{result.solver}: {result.verdict}, " + r"$|\theta|_{max}/\alpha$" + f" = {result.theta_max_over_alpha:.3g}")
    if result.time.size:
        t = np.linspace(0, max(result.time[-1], excitation.duration), 2000)
        ax2 = ax.twinx()
        ax2.plot(t, excitation.acceleration(t) / 9.81, color="tab:orange", lw=0.8, alpha=0.7)
        ax2.set_ylabel("floor acceleration (g)", color="tab:orange")
    if has_moments:
        mgRsa = block.mass * 9.81 * block.R * math.sin(block.alpha)
        total = result.spring_moment + result.damper_force
        ax = axes[0, 1]
        th = np.linspace(-min(1.5, result.theta_max / block.alpha * 1.1 + 0.1), min(1.5, result.theta_max / block.alpha * 1.1 + 0.1), 801) * block.alpha
        ax.plot(th / block.alpha, restoring_moment(block, th) / mgRsa, color="0.6", lw=0.8, ls="--", label="Eq. 5")
        ax.plot(result.theta / block.alpha, total / mgRsa, lw=0.9, label="spring + damper")
        ax.set_xlabel(r"$\theta / \alpha$")
        ax.set_ylabel(r"$(M_s + f_d) / (m g R \sin\alpha)$")
        ax.set_title("(a) total resisting moment")
        ax.legend(fontsize=8)
        ax = axes[0, 2]
        ax.plot(result.theta / block.alpha, result.damper_force / mgRsa, lw=0.9, color="tab:red")
        ax.set_xlabel(r"$\theta / \alpha$")
        ax.set_ylabel(r"$f_d / (m g R \sin\alpha)$")
        ax.set_title("(b) damper force")
    fig.tight_layout()
    return _save(fig, path)


def plot_histories(
    results: Sequence[RockingResult],
    titles: Sequence[str],
    path: str | Path,
    *,
    references: Sequence[RockingResult] | None = None,
    reference_label: str = "reference",
) -> Path:
    """Rotation histories in the layout of Figure 4 (a-f), optionally over reference histories.

    Parameters
    ----------
    results : sequence of RockingResult
        Histories to draw, one panel each (the paper shows three safe, three overturning).
    titles : sequence of str
        Panel titles.
    path : str or Path
        Output PNG file.
    references : sequence of RockingResult, optional
        A second solver's histories drawn under the first, one per panel.
    """
    n = len(results)
    ncols = 3
    nrows = math.ceil(n / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(13, 3.4 * nrows), squeeze=False)
    for i, (res, title) in enumerate(zip(results, titles)):
        ax = axes[i // ncols, i % ncols]
        if references is not None:
            ref = references[i]
            ax.plot(ref.time, ref.theta / ref.alpha, color="0.55", lw=2.2, label=f"{ref.solver} ({reference_label})")
        ax.plot(res.time, res.theta / res.alpha, lw=1.0, color="tab:blue", label=res.solver)
        ax.axhline(0, color="0.7", lw=0.5)
        ax.set_title(f"({chr(97 + i)}) {title}", fontsize=9)
        ax.set_xlabel("time (s)")
        ax.set_ylabel(r"$\theta/\alpha$")
        if res.overturned:
            ax.set_ylim(-3, 3)
        ax.legend(fontsize=7, loc="best")
    for j in range(n, nrows * ncols):
        axes[j // ncols, j % ncols].axis("off")
    fig.tight_layout()
    return _save(fig, path)
