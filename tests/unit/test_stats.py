"""The general statistics helpers (:mod:`opsrock.stats`)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from opsrock.stats import Z_95, cluster_resamples, percentile_interval, wilson_interval


def test_z_is_the_two_sided_95_percent_quantile():
    from scipy.stats import norm

    assert Z_95 == pytest.approx(norm.ppf(0.975), rel=1e-15)


def test_wilson_interval_without_trials_is_nan():
    lo, hi = wilson_interval(0, 0)
    assert math.isnan(lo) and math.isnan(hi)


def test_percentile_interval_ignores_nan_draws():
    draws = np.column_stack([np.arange(101.0), np.r_[np.arange(100.0), np.nan]])
    lo, hi = percentile_interval(draws, 0.9, 2)
    assert lo.tolist() == pytest.approx([5.0, 4.95]) and hi.tolist() == pytest.approx([95.0, 94.05])


def test_percentile_interval_without_draws_is_nan():
    lo, hi = percentile_interval(np.array([], dtype=float), 0.95, 3)
    assert lo.shape == hi.shape == (3,) and np.isnan(lo).all() and np.isnan(hi).all()


def test_cluster_resamples_keep_each_stratum_and_are_seeded():
    strata = [np.array([0, 1, 2]), np.array([3, 4]), np.array([5])]
    draws = list(cluster_resamples(strata, 50, seed=3))
    assert len(draws) == 50
    for chosen in draws:
        # each stratum keeps its number of clusters, drawn from its own clusters only
        assert set(chosen[:3]) <= {0, 1, 2} and set(chosen[3:5]) <= {3, 4} and chosen[5:].tolist() == [5]
    assert len({tuple(c) for c in draws}) > 1  # with replacement: the draws differ
    again = list(cluster_resamples(strata, 50, seed=3))
    assert all(np.array_equal(a, b) for a, b in zip(draws, again))
