"""Regression: the scipy SDOF solver must not call a block 'at rest' while it is falling over."""

from __future__ import annotations

import math

import pytest

from opsrock import Block, OneSinePulse
from opsrock.solvers import simulate


def test_block_beyond_alpha_at_pulse_end_is_not_trapped():
    # Paper grid case bookcase/f02/a02 (omega_p/p = 1.556, PFA/(g tan alpha) = 2.056): at the end
    # of the pulse the block is at -3.1 alpha and moving away. Beyond alpha the table potential
    # falls below U(delta alpha), so an energy-only "trapped in the band" test stopped the run
    # and returned safe at 3.14 alpha. The rigid-body solver (independent) says it overturns.
    block = Block(0.40, 2.20)
    pulse = OneSinePulse.from_ratios(block, pfa_ratio=1.0 + 19 / 18, freq_ratio=0.5 + 19 / 18)
    sdof = simulate(block, pulse, solver="sdof")
    housner = simulate(block, pulse, solver="housner")
    assert housner.verdict == "overturned"
    assert sdof.verdict == "overturned"
    assert sdof.theta_max >= math.pi / 2


# Cases that rock *beyond* alpha and come back (theta_max 1.3-1.4 alpha, from the rigid-body solver
# housner_fast and confirmed safe by sdof): the regime where the old "trapped" test misfired.
# The previous cases here both overturned, so the assertion below never ran.
@pytest.mark.parametrize("case", [(0.40, 2.20, 4.25, 3.5), (0.60, 2.00, 3.5, 3.0)])
def test_safe_verdict_means_back_inside_alpha(case):
    # A safe verdict after the pulse implies the block ended inside |theta| < alpha (Eq. 5: beyond
    # alpha gravity tips it over); the last recorded state must say so.
    width, height, pfa_ratio, freq_ratio = case
    block = Block(width, height)
    r = simulate(block, OneSinePulse.from_ratios(block, pfa_ratio, freq_ratio), solver="sdof")
    assert r.verdict == "safe" and r.theta_max > block.alpha  # the case is what it claims to be
    assert abs(r.theta[-1]) < block.alpha
