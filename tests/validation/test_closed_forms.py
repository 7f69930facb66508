"""The closed forms themselves, and the closed_forms validation case for all solvers."""

import math

import pytest

from opsrock import Block
from opsrock.validation import closed_forms as cf


@pytest.mark.parametrize("width", [0.05, 0.1, 0.2])
def test_linearised_fall_time_is_the_small_alpha_limit(width):
    # slender limit: sin x -> x, cos x -> 1, so the relative gap must shrink like alpha^2
    block = Block(width, 2.0)
    gap = abs(cf.linearised_time_to_impact(block, 0.5 * block.alpha) / cf.exact_time_to_impact(block, 0.5 * block.alpha) - 1)
    assert gap < 0.1 * block.alpha**2


def test_peak_after_impact_limits():
    block = Block(0.4, 2.2)
    theta0 = 0.5 * block.alpha
    assert cf.peak_after_impact(block, theta0, e=1.0) == pytest.approx(theta0, rel=1e-12)  # elastic
    assert cf.peak_after_impact(block, theta0, e=1e-8) < 1e-10  # plastic: no rebound
    # any dissipation (e < 1) lowers the rebound peak
    assert cf.peak_after_impact(block, theta0) < theta0


def test_closed_forms_case_passes_for_every_solver(tmp_path):
    result = cf.run(tmp_path)
    assert (tmp_path / "closed_forms.csv").exists()
    assert set(result["solvers"]) == {"housner", "sdof", "opensees"}
    failed = [(r["solver"], r["check"], r["error"]) for r in result["rows"] if not r["passed"]]
    assert result["passed"], failed
    assert math.isfinite(result["wall_time_s"])
