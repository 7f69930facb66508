"""Sliding beyond a distance as a damage mode (opsrock.fragility.sliding)."""

from __future__ import annotations

import io
import math

import numpy as np
import pandas as pd
import pytest
from scipy.stats import norm

from _support import write_friction_campaign
from opsrock._files import read_table, read_units
from opsrock.analysis.record_columns import TABLE_UNITS, read_record_table, units_of
from opsrock.errors import InputError
from opsrock.fragility.pelicun_export import read_pelicun_csv, write_pelicun_csv
from opsrock.fragility.sliding import fit_sliding, slid_beyond, sliding_component_id, sliding_components, sliding_table


#: sliding.csv's columns, in order (its units row: ``TABLE_UNITS["sliding"]``).
SLIDING_COLUMNS = tuple(TABLE_UNITS["sliding"])


def _cases(n_records: int = 40, median: float = 4.0, beta: float = 0.4, seed: int = 1) -> pd.DataFrame:
    """A synthetic campaign whose peak slide exceeds 0.1 m with probability Phi(ln(pfa/median)/beta)."""
    rng = np.random.default_rng(seed)
    rows = []
    for r in range(n_records):
        for k, pfa in enumerate(np.geomspace(0.5, 30.0, 12)):
            beyond = rng.random() < norm.cdf(math.log(pfa / median) / beta)
            rows.append({"block": "cab", "record": f"r{r}", "status": "ok", "overturned": "False", "pfa": pfa,
                         "pfv": pfa / 10.0, "slide_max": 0.3 if beyond else 0.01, "slide_residual": -0.01})
    return pd.DataFrame(rows)


def test_outcome_counts_overturned_as_beyond():
    c = pd.DataFrame({"overturned": ["True", "False", "False"], "slide_max": [0.0, 0.2, 0.01]})
    assert slid_beyond(c, 0.05).tolist() == [True, True, False]


def test_fit_recovers_the_generating_fragility():
    """480 cases from a known lognormal: the MLE median within its record-bootstrap interval of the truth and
    within 15 %, beta within 30 % (sampling error of 40 records, seeded: the test is deterministic)."""
    fit = fit_sliding(_cases(), "cab", 0.1, demand="pfa", n_boot=100, seed=0)
    assert fit.success
    assert fit.median_lo <= 4.0 <= fit.median_hi
    assert abs(fit.median / 4.0 - 1.0) < 0.15 and abs(fit.beta / 0.4 - 1.0) < 0.3


def test_components_round_trip_through_the_pelicun_file(tmp_path):
    table = sliding_table(_cases(), (0.1,), n_boot=20)
    comps, skipped = sliding_components(table)
    assert not skipped and {c.component_id for c in comps} == {"opsrock.cab.SLIDE100MM.PFA", "opsrock.cab.SLIDE100MM.PFV"}
    back = read_pelicun_csv(write_pelicun_csv(comps, tmp_path / "slide.csv"))
    assert back == comps


def test_no_transition_is_reported_not_fitted():
    fit = fit_sliding(_cases(), "cab", 5.0)  # no slide beyond 5 m: every case on one side
    assert not fit.success and "no transition" in fit.message and math.isnan(fit.median)


@pytest.mark.parametrize("kwargs, match", [({"distance": 0.0}, "distance"), ({"distance": 0.1, "measure": "x"}, "measure")])
def test_bad_arguments(kwargs, match):
    with pytest.raises(InputError, match=match):
        slid_beyond(_cases(), **kwargs)
    with pytest.raises(InputError, match="friction"):
        slid_beyond(pd.DataFrame({"overturned": ["False"]}), 0.1)


def test_component_id():
    assert sliding_component_id("bookcase", 0.05, "pfv") == "opsrock.bookcase.SLIDE50MM.PFV"


# --- the sliding section of `opsrock fragility` ----------------------------------------------------------------
def _friction_campaign(d, solver: str = "friction"):
    """A small record campaign solved with friction: two blocks, six synthetic ground motions (a noisy
    sine of 1 to 3 Hz in a 6 s envelope), five levels of PFA: 60 cases, some sliding beyond 5 and 20 cm."""
    from opsrock.campaign import run_campaign

    summary = run_campaign(write_friction_campaign(d, solver), d / "out", workers=1, progress=False)
    assert summary.n_failed == 0
    return d / "out"


@pytest.fixture(scope="module")
def friction_cases(tmp_path_factory) -> pd.DataFrame:
    from opsrock.analysis.record_report import read_cases

    return read_cases(_friction_campaign(tmp_path_factory.mktemp("friction")))


def test_the_report_says_which_solver_and_why_auto_chose_it(tmp_path):
    # a scene with solver = "auto" and blocks with friction: the need is answered by the block with friction,
    # and the report says so from the campaign's manifest; a table without its manifest names the solver only
    from opsrock.analysis.record_report import read_cases, write_record_report

    out = _friction_campaign(tmp_path, solver="auto")
    write_record_report(read_cases(out), tmp_path / "rep", n_boot=5, seed=0, source=str(out))
    text = (tmp_path / "rep" / "report.md").read_text()
    assert 'Solver: `friction`, chosen by `solver = "auto"` for the scene\'s needs: ' in text
    (tmp_path / "alone").mkdir()
    (tmp_path / "alone" / "cases.csv").write_bytes((out / "cases.csv").read_bytes())
    write_record_report(read_cases(tmp_path / "alone"), tmp_path / "rep2", n_boot=5, seed=0,
                        source=str(tmp_path / "alone"))
    assert "Solver: `friction`.\n" in (tmp_path / "rep2" / "report.md").read_text()


def _files(folder) -> set[str]:
    return {str(p.relative_to(folder)) for p in folder.rglob("*") if p.is_file()}


def test_fragility_report_of_a_friction_campaign_has_a_sliding_section(friction_cases, tmp_path):
    from opsrock.campaign.cases import CONTACT_COLUMNS
    from opsrock.analysis.record_report import SLIDE_DISTANCES, write_record_report

    n_boot = 15
    res = write_record_report(friction_cases, tmp_path / "with", n_boot=n_boot, seed=2)
    assert res.sliding is not None
    plain = write_record_report(friction_cases.drop(columns=list(CONTACT_COLUMNS)), tmp_path / "without",
                                n_boot=n_boot, seed=2)
    # without the contact columns: the files of any record campaign, nothing about sliding
    assert plain.sliding is None
    assert _files(tmp_path / "with") == _files(tmp_path / "without") | {"sliding.csv", "figures/sliding.png"}
    assert "Sliding" not in (tmp_path / "without" / "report.md").read_text()
    # the overturning study is the same either way
    for name in ("ims", "measure_fits", "blocks", "frequencies", "sufficiency", "resurrections"):
        assert (tmp_path / "with" / f"{name}.csv").read_bytes() == (tmp_path / "without" / f"{name}.csv").read_bytes()

    # sliding.csv is sliding_table of each floor's finished cases (one floor here), every block x distance x demand,
    # with the floor after the block and the demand's unit after the demand (the cases': PFA m/s2, PFV m/s), under
    # its units row; read_table parses round-trip: pandas before 3 reads the last digit of some floats differently
    assert read_units(tmp_path / "with" / "sliding.csv")[1] == units_of("sliding", list(SLIDING_COLUMNS))
    table = read_record_table(tmp_path / "with" / "sliding.csv")
    (floor,) = friction_cases["floor"].unique()
    expected = sliding_table(friction_cases, SLIDE_DISTANCES, n_boot=n_boot, seed=2)
    expected.insert(1, "floor", floor)
    expected.insert(expected.columns.get_loc("demand") + 1, "unit", expected["demand"].map({"pfa": "m/s2",
                                                                                            "pfv": "m/s"}))
    assert list(table.columns) == list(SLIDING_COLUMNS)
    assert len(table) == 2 * len(SLIDE_DISTANCES) * 2
    pd.testing.assert_frame_equal(table, read_table(io.StringIO(expected.to_csv(index=False))))
    fitted = table[table["success"] & (table["beta"] > 0)]
    assert {"crate", "shelf"} <= set(fitted["block"]) and set(fitted["distance"]) >= {0.05, 0.2}
    assert (fitted["median_lo"] <= fitted["median"]).all() and (fitted["median"] <= fitted["median_hi"]).all()

    # the pelicun file: the overturning components as before, plus one SLIDE component per fitted row
    with_comps = read_pelicun_csv(tmp_path / "with" / "fragility_pelicun.csv")
    plain_comps = read_pelicun_csv(tmp_path / "without" / "fragility_pelicun.csv")
    slides = [c for c in with_comps if ".SLIDE" in c.component_id]
    assert [c for c in with_comps if ".SLIDE" not in c.component_id] == plain_comps
    assert [c.component_id for c in slides] == [f"opsrock.{r.block}.{floor}.SLIDE{round(1000 * r.distance)}MM."
                                                f"{r.demand.upper()}" for r in fitted.itertuples()]
    assert [(c.median, c.beta) for c in slides] == list(zip(fitted["median"], fitted["beta"]))

    # the report: a table per block and the figure
    report = (tmp_path / "with" / "report.md").read_text()
    section = report[report.index("## Sliding beyond a distance"):]
    assert f"### crate, floor {floor}" in section and f"### shelf, floor {floor}" in section and "![Sliding](figures/sliding.png)" in section
    assert (tmp_path / "with" / "figures" / "sliding.png").stat().st_size > 1000
