"""Eq. 4 at the threshold: a pulse that cannot uplift the block leaves it seated, in every solver."""

from __future__ import annotations

import pytest

from opsrock import Block, OneSinePulse
from opsrock.model import SDOFModel, can_uplift
from opsrock.solvers import simulate


@pytest.mark.parametrize("solver", ["opensees", "sdof", "housner", "housner_fast"])
@pytest.mark.parametrize("size", [(0.40, 2.20), (0.50, 1.15), (1.00, 2.40)])
def test_threshold_row_of_the_paper_grid_never_uplifts(solver, size):
    # The paper grid's first row is PFA = 1.0 g tan(alpha) exactly: Eq. 4 needs more than that.
    # omega_p/p = 0.5 and 1.556 are the slowest pulses, where the SDOF model's finite stiff branch
    # tipped numerically (OpenSees, uplift_check=False: up to 0.026 alpha).
    block = Block(*size)
    for freq_ratio in (0.5, 0.5 + 19 / 18):
        pulse = OneSinePulse.from_ratios(block, pfa_ratio=1.0, freq_ratio=freq_ratio)
        r = simulate(block, pulse, solver=solver)
        assert r.verdict == "no_uplift", (solver, size, freq_ratio, r.theta_max_over_alpha)


def test_can_uplift_follows_the_lever():
    block = Block(0.4, 2.0)
    g_tan = block.uplift_acceleration
    assert not can_uplift(block, SDOFModel(), g_tan)
    assert can_uplift(block, SDOFModel(), 1.001 * g_tan)
    # the printed lever I_O cos(alpha)/R is 4/3 of m R cos(alpha): it uplifts at 0.75 g tan(alpha)
    assert can_uplift(block, SDOFModel(lever="printed"), 0.76 * g_tan)
    assert not can_uplift(block, SDOFModel(lever="printed"), 0.74 * g_tan)


@pytest.mark.opensees
def test_uplift_check_can_be_switched_off_to_see_the_model_tip():
    # The literal model at exactly the threshold: neutral equilibrium on the stiff branch's corner.
    block = Block(0.50, 1.15)
    pulse = OneSinePulse.from_ratios(block, pfa_ratio=1.0, freq_ratio=0.5)
    literal = simulate(block, pulse, solver="opensees", uplift_check=False)
    assert literal.ok and literal.theta_max > 0.0
    checked = simulate(block, pulse, solver="opensees")
    assert checked.theta_max == 0.0 and checked.n_steps == 0
