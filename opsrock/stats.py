"""The general statistics helpers of opsrock, in one place: pure functions, no state.

* :func:`wilson_interval`: the score interval of a proportion (campaign audits, IM-ranking shares,
  record-resample wins);
* :func:`percentile_interval`: the two-sided percentile interval of bootstrap draws, NaN draws ignored;
* :func:`cluster_resamples`: the seeded stratified cluster bootstrap (whole clusters drawn with
  replacement within each stratum, each stratum keeping its number of clusters).

The fragility fits keep their own resampling of cases (:func:`opsrock.fragility.mle.resample_indices`),
which draws all its resamples up front for the parallel fits.
"""

from __future__ import annotations

import math
from typing import Iterator, Sequence

import numpy as np

#: z of the two-sided 95 % normal interval, Phi^-1(0.975) (no unit).
Z_95: float = 1.959963984540054


def wilson_interval(k: int, n: int, z: float = Z_95) -> tuple[float, float]:
    """Wilson score interval of the proportion ``k / n``.

    Parameters
    ----------
    k : int
        Successes (count, no unit), ``0 <= k <= n``.
    n : int
        Trials (count, no unit); ``n <= 0`` gives ``(nan, nan)``.
    z : float
        Standard-normal quantile of the two-sided level (no unit); the default gives 95 %.

    Returns
    -------
    tuple of float
        ``(low, high)``, proportions in [0, 1] (no unit); exactly 0 (1) at ``k = 0`` (``k = n``).
    """
    if n <= 0:
        return math.nan, math.nan
    p = k / n
    d = 1.0 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    # exact ends: at k = 0 (k = n) the lower (upper) bound is 0 (1), not a round-off residue of it
    return (0.0 if k == 0 else max(0.0, c - h)), (1.0 if k == n else min(1.0, c + h))


def percentile_interval(draws: np.ndarray, level: float, size: int) -> tuple[np.ndarray, np.ndarray]:
    """Two-sided percentile interval of bootstrap draws, column by column, NaN draws ignored.

    Parameters
    ----------
    draws : numpy.ndarray
        ``(n_draws, size)`` draws of ``size`` statistics (each in its own unit).
    level : float
        Two-sided level in (0, 1) (no unit), e.g. 0.95.
    size : int
        Number of statistics (count, no unit): the width of the answer when there are no draws.

    Returns
    -------
    tuple of numpy.ndarray
        ``(low, high)``, each of length ``size``, in the statistics' units; NaN without draws.
    """
    if len(draws) == 0:
        return (np.full(size, math.nan),) * 2
    q = 50.0 * (1.0 - level)
    lo, hi = np.nanpercentile(draws, [q, 100.0 - q], axis=0)
    return lo, hi


def cluster_resamples(strata: Sequence[np.ndarray], n_boot: int, seed: int) -> Iterator[np.ndarray]:
    """Seeded stratified cluster bootstrap: per resample, the chosen cluster ids of every stratum.

    Parameters
    ----------
    strata : sequence of numpy.ndarray
        The cluster ids (integers, no unit) of each stratum.
    n_boot : int
        Number of resamples (count, no unit).
    seed : int
        Seed of :func:`numpy.random.default_rng` (no unit).

    Yields
    ------
    numpy.ndarray
        The cluster ids of one resample, stratum after stratum, each stratum drawn with replacement
        to its own number of clusters.
    """
    rng = np.random.default_rng(seed)
    for _ in range(n_boot):
        yield np.concatenate([rng.choice(ids, ids.size, replace=True) for ids in strata])


__all__ = ["Z_95", "cluster_resamples", "percentile_interval", "wilson_interval"]
