"""The directionality study's report and figures. They show the tables of
:mod:`opsrock.inventory.directionality.summary` and compute nothing (matplotlib is imported lazily: the command
line loads it only when it draws).

Figures: ``map.png`` (where planar analysis suffices: the 3-D over the planar median, per item, orientation and
floor), ``factor.png`` (the factor on ``max(PFV_1, PFV_2)`` the 3-D results imply, beside pelicun's 1.2) and
``mechanisms.png`` (the share of 3-D overturnings over a corner).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from opsrock.inventory.report import Section, write_sections
from opsrock.plots import save_figure
from opsrock.report.markdown import markdown_table
from opsrock.solvers.registry import planar_solver

#: Smallest tick and legend text (pt).
MIN_FONT: float = 9.0


def _panels(n: int, width: float = 5.5, height: float = 4.5):
    """A row of ``n`` panels (matplotlib imported here, lazily: the command line loads it only to draw)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, n, figsize=(width * n, height), squeeze=False, layout="constrained")
    return fig, axes[0]


def plot_map(table: pd.DataFrame, tolerance: float, path: Path) -> Path:
    """The map: one panel per floor, items (rows, by slenderness) x orientations, coloured by
    ``ratio_weak`` (3-D over planar median in the weaker axis's PFV), labelled with it; a cell outside the
    tolerance is framed."""
    cells = table[table["azimuth"] != "all"]
    floors = list(dict.fromkeys(cells["floor"]))
    fig, axes = _panels(len(floors), 6.0, 0.45 * cells["item"].nunique() + 2.0)
    for ax, floor in zip(axes, floors):
        t = cells[cells["floor"] == floor]
        items = t.drop_duplicates("item").sort_values("b_over_h")["item"].tolist()
        azimuths = list(dict.fromkeys(t["azimuth"]))
        grid = t.pivot(index="item", columns="azimuth", values="ratio_weak").reindex(index=items, columns=azimuths)
        values = np.log2(grid.to_numpy(float))
        image = ax.imshow(values, cmap="RdBu_r", vmin=-0.5, vmax=0.5, aspect="auto")
        verdicts = t.pivot(index="item", columns="azimuth", values="verdict").reindex(index=items, columns=azimuths)
        for i, item in enumerate(items):
            for j, az in enumerate(azimuths):
                r, v = grid.loc[item, az], verdicts.loc[item, az]
                ax.text(j, i, f"{r:.2f}" if np.isfinite(r) else v[:8], ha="center", va="center", fontsize=MIN_FONT)
                if v == "differs":
                    ax.add_patch(_frame(j, i))
        b = t.drop_duplicates("item").set_index("item")["b_over_h"]
        ax.set_yticks(range(len(items)), [f"{it} (b/h {b[it]:.2f})" for it in items], fontsize=MIN_FONT)
        ax.set_xticks(range(len(azimuths)), azimuths, fontsize=MIN_FONT)
        ax.set_xlabel("azimuth: item's width axis from direction 1 (deg)")
        ax.set_title(f"{_floor(floor)}: 3-D / planar median (weaker axis's PFV);\nframed: beyond +-{tolerance:.0%}")
    fig.colorbar(image, ax=list(axes), label="log2(3-D median / planar median)")
    return save_figure(fig, path)


def _floor(label: str) -> str:
    """``"ground"``, or ``"floor <n>"`` for the building's floor numbers."""
    return f"floor {label}" if str(label).isdigit() else str(label)


def _frame(j: int, i: int):
    from matplotlib.patches import Rectangle  # lazily, as matplotlib itself (:func:`_panels`)

    return Rectangle((j - 0.5, i - 0.5), 1.0, 1.0, fill=False, edgecolor="black", linewidth=2.0)


def _by_azimuth(table: pd.DataFrame, column: str, ylabel: str, path: Path, reference: float | None) -> Path:
    """One panel per floor: ``column`` against the orientation, one line per item."""
    cells = table[table["azimuth"] != "all"]
    floors = list(dict.fromkeys(cells["floor"]))
    fig, axes = _panels(len(floors))
    markers = "osD^vP*Xh<>p"
    for ax, floor in zip(axes, floors):
        t = cells[cells["floor"] == floor]
        for k, (item, g) in enumerate(t.groupby("item", sort=False)):
            ax.plot(g["azimuth"].astype(float), g[column].astype(float), marker=markers[k % len(markers)],
                    linestyle="-" if k < 7 else "--", label=item)
        if reference is not None:
            ax.axhline(reference, color="black", linewidth=1.5, linestyle=":", label=f"pelicun's {reference:g}")
        ax.set_xlabel("azimuth: item's width axis from direction 1 (deg)")
        ax.set_ylabel(ylabel)
        ax.set_title(_floor(floor))
        ax.tick_params(labelsize=MIN_FONT)
        ax.legend(fontsize=MIN_FONT, ncol=2)
    return save_figure(fig, path)


def write_figures(tables: dict[str, pd.DataFrame], folder: Path, tolerance: float) -> list[Path]:
    """The study's figures into ``folder`` (``tolerance``: the map's, a fraction)."""
    main = tables["directionality"]
    return [plot_map(main, tolerance, folder / "map.png"),
            _by_azimuth(main, "factor_implied", "factor on max(PFV_1, PFV_2) the 3-D fit implies", folder / "factor.png",
                        1.2),
            _by_azimuth(main, "share_corner", "share of 3-D overturnings over a corner", folder / "mechanisms.png", None)]


def _fmt(value: Any, digits: str = ".3g") -> str:
    if isinstance(value, (tuple, list)):
        return " to ".join(_fmt(v, digits) for v in value)
    if value is None:
        return "n/a"
    return format(value, digits) if isinstance(value, float) else str(value)


def _design_lines(d: Any, rounds: tuple[str, ...]) -> list[str]:
    return [
        f"* building: linear shear building, T1 = {d.period:g} s, {d.storeys} storeys, damping {d.damping:g}; floors "
        f"{', '.join(map(str, d.floors))}",
        f"* records: {len(d.pairs) or 'every'} pair(s) of {d.record_set} ({', '.join(d.pairs) or 'all'}), each "
        "pair's two components through the building as directions 1 and 2",
        f"* orientations (azimuth, deg): {', '.join(f'{a:g}' for a in d.azimuths)}",
        f"* IDA levels of max(PFA_1, PFA_2) / (g min(tan alpha, mu)) of the weaker axis: "
        f"{', '.join(f'{x:.3g}' for x in d.levels)}",
        f"* 3-D solver: {d.solver3d} {dict(d.settings3d) or ''}; planar: {planar_solver(False)} (no slip), "
        f"{planar_solver(True)} (items with friction); Housner's restitution throughout ({d.solver3d} models no other)",
        f"* fits: lognormal MLE, 95 % intervals from {d.n_boot} resamples of whole record pairs (seed {d.seed}); "
        f"planar analysis suffices within {d.tolerance:.0%}",
        *([f"* left out: {', '.join(rounds)} (a round base: no orientation to turn; the contents study solves it in "
           "three dimensions, `opsrock contents --inventory FILE --motions FILE --model 3d`)"] if rounds else []),
    ]


def write_report(path: Path, inputs: Any) -> Path:
    """``report.md`` from :class:`opsrock.inventory.directionality.summary.ReportInputs`."""
    d, t, h, fig = inputs.design, inputs.tables, inputs.headline, inputs.figures
    main = t["directionality"]
    pooled = main[main["azimuth"] == "all"][["item", "floor", "b_over_h", "median_3d_pfv_1", "median_3d_pfv_2",
                                             "median_3d_pfv_max", "median_3d_pfv_nd", "median_planar_pfv_weak",
                                             "factor_implied", "ratio_weak", "share_corner", "verdict"]]
    cells = h["cells"]
    head = Section("", (
        "    opsrock directionality --out studies/directionality", "",
        f"{h['n_cases']} cases ({h['n_failed']} failed; {h['n_computed']} computed by this run, the others read from "
        f"the stores) in {h['wall_time_s']:.0f} s of wall time (motions {h['timings'].get('motions_s', 0):.0f} s, "
        f"campaigns {h['timings'].get('campaigns_s', 0):.0f} s, fits {h['timings'].get('fits_s', 0):.0f} s). Design:", "",
        *_design_lines(d, inputs.left_out)))
    headline = Section("Headline", (
        f"* the factor on max(PFV_1, PFV_2) that makes the planar fragility of the weaker axis match the 3-D one "
        f"(orientations pooled): median {_fmt(h['factor_implied_median'])}, range {_fmt(h['factor_implied_range'])}; "
        "pelicun uses 1.2",
        f"* the motions' own part of it, peak of the velocity vector over the larger directional peak: mean "
        f"{_fmt(h['nd_over_max_mean'])}",
        f"* 3-D over planar median in the same demand (weaker axis's PFV), pooled: {_fmt(h['ratio_weak_range'])}",
        f"* map cells (item x floor x orientation): {cells['suffices']} suffice, {cells['differs']} differ, "
        f"{cells['never overturns']} never overturn, {cells['no fit']} without a fit; the tolerance "
        f"{d.tolerance:.0%} beside the median half-width of the planar medians' 95 % intervals, "
        f"{_fmt(h['planar_ci_halfwidth_median'])}",
        f"* share of 3-D overturnings over a corner: {_fmt(h['share_corner'])}",
        f"* cost: a 3-D case took {_fmt(h['cost_ratio_3d_cpu'])} times a planar case's CPU time and "
        f"{_fmt(h['cost_ratio_3d'])} times its wall time (medians, this run)"))
    return write_sections(path, "Directionality: contents under two horizontal components, in three dimensions", [
        head, headline,
        Section("Medians, orientations pooled (m/s)", (markdown_table(pooled),)),
        Section("Where planar analysis suffices", (f"![map]({fig.get('map', 'figures/map.png')})",)),
        Section("The factor on max(PFV_1, PFV_2)", (f"![factor]({fig.get('factor', 'figures/factor.png')})",)),
        Section("Edge or corner", (f"![mechanisms]({fig.get('mechanisms', 'figures/mechanisms.png')})",)),
        Section("Cost per case", (markdown_table(t["cost"]),)),
        Section("Files", ("`directionality.csv` (every orientation and pooled), `fits.csv` (every fit), `map.csv`, "
                          "`mechanisms.csv`, `cost.csv`, `demands.csv`: full precision, each with a `Units` row after "
                          "its header (PFV in m/s, PFA in g: docs/guide/directionality.md). The campaigns' stores are "
                          "not part of the folder's outputs.",)),
    ])


__all__ = ["plot_map", "write_figures", "write_report"]
