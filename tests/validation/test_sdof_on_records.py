"""The paper's SDOF model on broadband floor motions: findings of validation case 9 pinned here.

The records are band-passed noise (opsrock.validation.sdof_records.noise_record, seeded); the test reads
its record from tests/data at full precision, so that the input is the same on every numpy and scipy of
the declared range (the generator's filter differs by 1e-12 relative between scipy 1.10 and 1.17, and the
case is marginal for OpenSees: on the perturbed record the sign guard fails it as a numerical sawtooth
at t = 12.51 s, a failure it reports as such).
"""

from __future__ import annotations

import numpy as np
import pytest

from _support import TEST_DATA
from opsrock.block import Block
from opsrock.excitations import Record
from opsrock.solvers import simulate

pytestmark = pytest.mark.opensees


def test_opensees_seat_matches_the_scipy_solver_on_a_weak_record():
    # Seed 2, 0.5 x 1.15 m block at 1.3 g tan alpha: the block is lifted a little and sits down again
    # many times. OpenSees' Newmark steps kept the stiff branch's free oscillation (omega_e h >> 1) and
    # rattled the seated block out of it: theta_max 0.0069 alpha against the scipy solver's 0.0237,
    # in 330,000 steps. With the seat (the scipy solver's treatment: oscillation dropped once it fits
    # in the branch, steps landing on the uplift instant) it gives 0.02349 against 0.02371 in 13,000
    # steps. Reference: the scipy solver (same model, independent numerics). Tolerance 0.002 alpha
    # (ten times the measured difference, a fifth of the case's 0.01 alpha criterion).
    # case_motion((2, (0.5, 1.15), 1.3)) of the validation case, as written by the locked environment
    block = Block(0.5, 1.15)
    rec = Record(0.01, np.loadtxt(TEST_DATA / "sdof_records_seed2_weak.txt"), name="noise seed 2")
    ref = simulate(block, rec, "sdof")
    r = simulate(block, rec, "opensees")
    assert ref.ok and r.ok and ref.verdict == r.verdict == "safe"
    assert abs(r.theta_max_over_alpha - ref.theta_max_over_alpha) < 2e-3
    assert r.n_steps < 50_000

