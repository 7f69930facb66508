"""Sliding beyond a distance as a damage mode (opsrock.fragility.sliding)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from scipy.stats import norm

from opsrock.errors import InputError
from opsrock.fragility.pelicun_export import read_pelicun_csv, write_pelicun_csv
from opsrock.fragility.sliding import fit_sliding, slid_beyond, sliding_component_id, sliding_components, sliding_table


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
