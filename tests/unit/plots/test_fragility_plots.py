"""Fragility figures (6a, 6b, 8-12) are written from a small synthetic cases table."""

from __future__ import annotations

import numpy as np
import pandas as pd
from _synthetic_cases import BOUNDARY_SLOPE, GRID_IM1, GRID_IM2, grid_cases

from opsrock import Block
from opsrock.fragility import FragilitySettings, analyse_fragility
from opsrock.plots.fragility import overturning_boundary, paper_figures

# PNG files start with this 8-byte signature (PNG specification, section 5.2).
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def _campaign() -> pd.DataFrame:
    rng = np.random.default_rng(0)
    parts = []
    for width, height, name in ((0.4, 1.6, "B1"), (0.6, 1.2, "B2")):
        c = grid_cases(Block(width, height, name=name))
        c["freq_ratio"] = c["omega_p"] / c["p"]
        c["pfa_ratio"] = c["pfa"] / (9.81 * np.tan(c["alpha"]))
        c["theta_max_over_alpha"] = np.where(c["overturned"], 40.0, rng.uniform(0.05, 1.2, len(c)))
        parts.append(c)
    cases = pd.concat(parts, ignore_index=True)
    # one no-uplift and one failed case, so the markers for both are exercised
    cases.loc[0, ["rocked", "overturned", "verdict"]] = [False, False, "no_uplift"]
    cases.loc[1, ["status", "rocked", "overturned", "verdict"]] = ["failed", False, False, "failed"]
    return cases


def test_overturning_boundary_follows_the_construction():
    # grid verdicts: overturned iff IM2 > 1.7 IM1; the lowest overturning IM2 at IM1 = 3 is
    # the first grid value above 5.1, i.e. 1.5 + 4 * 9.5/9 = 5.7222 (construction in
    # test_fragility.py); no column at IM1 >= 7 overturns (1.7 * 7 = 11.9 > 11).
    c = grid_cases()
    c["freq_ratio"] = c["omega_p"] / c["p"]
    c["pfa_ratio"] = c["pfa"] / (9.81 * np.tan(c["alpha"]))
    b = overturning_boundary(c).set_index("freq_ratio")["pfa_ratio_min"]
    assert abs(b.loc[b.index[np.isclose(b.index, 3.0)][0]] - GRID_IM2[4]) < 1e-9
    assert b.index.max() < 7.0 and GRID_IM2[4] > BOUNDARY_SLOPE * 3.0 > GRID_IM2[3]
    assert len(b) == int(np.sum(GRID_IM1 * BOUNDARY_SLOPE < GRID_IM2.max()))


def test_paper_figures_are_written(tmp_path):
    cases = _campaign()
    # three IMs (one decreasing, one with full overlap, one log-scaled) keep the 3 x 3
    # figures to one row: the drawing code per panel is the same for all nine
    analysis = analyse_fragility(cases, FragilitySettings(ims=("IM1", "IM2", "IM9"), n_boot=10))
    # a dense spectrum table (regular grid, > 400 cases) exercises the coloured-grid path
    block = Block(0.4, 1.6, name="B1")
    f, a = np.meshgrid(np.linspace(0.5, 10, 25), np.linspace(1.5, 11, 20))
    spectrum = pd.DataFrame({"block": "B1", "freq_ratio": f.ravel(), "pfa_ratio": a.ravel(),
                             "verdict": np.where(a.ravel() > BOUNDARY_SLOPE * f.ravel(),
                                                 "overturned", "safe")})
    assert block.name == "B1"
    paths = paper_figures(cases, analysis, tmp_path / "figs", spectrum=spectrum)
    assert set(paths) == {"fig6a", "fig6b", "fig8", "fig9", "fig10", "fig11", "fig12"}
    for name, path in paths.items():
        assert path.parent == tmp_path / "figs", name
        data = path.read_bytes()
        assert data[:8] == PNG_SIGNATURE and len(data) > 10_000, name
    assert not list((tmp_path / "figs").glob("*.tmp.png"))  # no half-written leftovers
