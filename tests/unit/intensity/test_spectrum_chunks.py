"""A response spectrum taken in chunks of periods (to bound eqsig's work arrays) is the spectrum taken at once.

Reference: eqsig's ``true_response_spectra`` over all periods in one call; the chunked values must be equal bit for
bit, since eqsig's Nigam-Jennings recurrence works period by period, element-wise.
"""

from __future__ import annotations

import numpy as np
import pytest

import opsrock.intensity.records as spectra
from opsrock.excitations.records import Record


@pytest.mark.parametrize("per_chunk", [1, 7, 64])
def test_chunked_spectrum_is_the_spectrum_taken_at_once(monkeypatch, per_chunk):
    rec = Record(dt=0.01, values=np.random.default_rng(3).normal(0.0, 1.0, 300), name="r", units="m/s2")
    periods = np.geomspace(0.02, 5.0, 70)
    whole = spectra.response_spectrum(rec, periods)
    monkeypatch.setattr(spectra, "SPECTRUM_WORK_BYTES", 3 * 8 * 300 * per_chunk)
    assert spectra.periods_per_chunk(300) == per_chunk
    done = []
    parts = spectra.response_spectrum(rec, periods, progress=lambda k, n: done.append((k, n)))
    for key in ("sd", "psa", "sa"):
        assert np.array_equal(whole[key], parts[key]), key
    assert done[-1] == (70, 70) and len(done) == -(-70 // per_chunk)


def test_work_arrays_stay_within_the_budget():
    """Three float64 arrays of periods x samples: at most SPECTRUM_WORK_BYTES (one period always)."""
    for n in (1, 1_000, 100_000, 6_300_000, 10**9):
        k = spectra.periods_per_chunk(n)
        assert k == 1 or 3 * 8 * n * k <= spectra.SPECTRUM_WORK_BYTES
