"""Shenton's mode-initiation diagram, read off the ``friction`` solver's first mode.

A block at rest under a step of floor acceleration ``a/g`` (held 0.05 s) starts to rest, slide, rock
or slide-rock. Over a grid of friction ``mu`` and slenderness ``b/h``, at three accelerations, the
solver's first mode is compared with the closed-form regions (:mod:`opsrock.published.shenton_1996`);
cells within 1 % of a boundary are set apart (there the answer hangs on the last digits of the step).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from opsrock.block import Block
from opsrock.constants import G
from opsrock.excitations import RectangularPulse

#: The accelerations of the panels (a/g) and the grid.
ACCELERATIONS: tuple[float, ...] = (0.3, 0.6, 1.0)
MU_GRID = np.linspace(0.05, 1.0, 39)
BETA_GRID = np.linspace(0.1, 1.0, 37)
#: Relative distance to a region boundary below which a cell is not counted.
MARGIN = 0.01
#: Colours of the modes in the figure.
MODE_COLOURS = {"rest": "#dddddd", "slide": "#4c72b0", "rock": "#dd8452", "slide_rock": "#55a868"}


def _near_boundary(lam: float, beta: float, mu: float) -> bool:
    from opsrock.published.shenton_1996 import mu_crit

    bounds = [(lam, mu), (lam, beta), (beta, mu)] + ([(mu_crit(lam, beta), mu)] if lam > beta else [])
    return any(abs(a - b) <= MARGIN * max(a, b) for a, b in bounds)


def diagram(quick: bool = False) -> list[dict]:
    """One row per cell: the solver's first mode, the closed form's, and whether the cell is counted."""
    from opsrock.published.shenton_1996 import initial_mode
    from opsrock.solvers import friction

    mus, betas = (MU_GRID[::4], BETA_GRID[::4]) if quick else (MU_GRID, BETA_GRID)
    rows = []
    for lam in ACCELERATIONS[:1] if quick else ACCELERATIONS:
        for beta in betas:
            for mu in mus:
                block = Block(2.0 * beta, 2.0, friction=float(mu), friction_kinetic=min(float(mu), 1.3),
                              restitution_factor=1.0) if math.atan(beta) < 0.95 else None
                if block is None:
                    continue
                r = friction.solve(block, RectangularPulse(lam * G, math.pi / 0.05))
                ref = initial_mode(lam * G, 0.0, float(beta), float(mu)).mode
                rows.append({"a_g": lam, "b_over_h": float(beta), "mu": float(mu), "solver": r.contact.first_mode,
                             "closed_form": ref, "near_boundary": _near_boundary(lam, float(beta), float(mu))})
    return rows


def plot_diagram(rows: list[dict], path: str | Path) -> Path:
    """The diagram: one panel per acceleration, cells coloured by the solver's first mode, the closed
    form's boundaries drawn over them."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    from opsrock.published.shenton_1996 import mu_crit

    lams = sorted({r["a_g"] for r in rows})
    fig, axes = plt.subplots(1, len(lams), figsize=(4.2 * len(lams), 4.0), squeeze=False, sharey=True)
    for ax, lam in zip(axes[0], lams):
        sel = [r for r in rows if r["a_g"] == lam]
        betas, mus = sorted({r["b_over_h"] for r in sel}), sorted({r["mu"] for r in sel})
        codes = np.full((len(mus), len(betas)), np.nan)
        for r in sel:
            codes[mus.index(r["mu"]), betas.index(r["b_over_h"])] = list(MODE_COLOURS).index(r["solver"])
        ax.pcolormesh(betas, mus, codes, cmap=ListedColormap(list(MODE_COLOURS.values())), vmin=-0.5,
                      vmax=len(MODE_COLOURS) - 0.5, shading="nearest")
        bad = [r for r in sel if r["solver"] != r["closed_form"] and not r["near_boundary"]]
        ax.scatter([r["b_over_h"] for r in bad], [r["mu"] for r in bad], marker="x", c="k", s=25)
        beta = np.linspace(0.1, 1.0, 200)
        ax.plot(beta, beta, "k-", lw=1)
        up = beta[beta < lam]
        ax.plot(up, [mu_crit(lam, b) for b in up], "k--", lw=1)
        ax.axvline(lam, color="k", lw=0.8, ls=":")
        ax.axhline(lam, color="k", lw=0.8, ls=":", xmin=0, xmax=1)
        ax.set_title(f"a/g = {lam:g}")
        ax.set_xlabel("b/h")
    axes[0][0].set_ylabel("friction coefficient mu")
    handles = [Patch(color=c, label=m) for m, c in MODE_COLOURS.items()]
    fig.legend(handles=handles, loc="lower center", ncol=4, frameon=False)
    fig.suptitle("First mode from rest (solver, colours) and the closed-form regions (lines)")
    fig.tight_layout(rect=(0, 0.06, 1, 0.95))
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def diagram_metrics(rows: list[dict]) -> dict:
    """Cells counted (away from the boundaries) and the share where the solver agrees with the closed form."""
    counted = [r for r in rows if not r["near_boundary"]]
    agree = sum(r["solver"] == r["closed_form"] for r in counted)
    return {"n_cells": len(rows), "n_counted": len(counted), "agreement": agree / len(counted) if counted else math.nan}


__all__ = ["ACCELERATIONS", "MARGIN", "diagram", "diagram_metrics", "plot_diagram"]
