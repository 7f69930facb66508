"""Makris and Roussos (2000), *Rocking response of rigid blocks under near-source ground motions*,
Géotechnique 50(3), 243-262: the half-sine pulse, linearised, overturning without impact.

A half-sine pulse ``a(t) = a_p sin(omega_p t)``, ``0 <= t <= pi / omega_p``, uplifts the block when
``a_p sin(omega_p t_u) = g alpha``. From there the linearised equation is solved in closed form
(:mod:`opsrock.published.linearised`) to the end of the pulse, and the block overturns without
impact if it ends the pulse beyond the separatrix of the free motion. The minimum ``a_p / (g alpha)``
as a function of ``omega_p / p`` is the root of that condition. At ``omega_p / p = 1`` it is
1.3224, below the 1.414 of Housner's energy estimate (which is therefore unconservative there).
"""

from __future__ import annotations

import math

from opsrock.errors import InputError
from opsrock.published import linearised
from opsrock.published.reference import PublishedValue

#: ``omega_p / p`` range in which the closed form is evaluated (dimensionless).
FREQ_RATIO_RANGE: tuple[float, float] = (0.05, 50.0)


def minimum_overturning(freq_ratio: float) -> float:
    """Minimum overturning ``a_p / (g alpha)`` of a half-sine pulse without impact (dimensionless).

    Parameters
    ----------
    freq_ratio : float
        ``omega_p / p`` (dimensionless), within :data:`FREQ_RATIO_RANGE`.
    """
    if not FREQ_RATIO_RANGE[0] <= freq_ratio <= FREQ_RATIO_RANGE[1]:
        raise InputError(f"freq_ratio must lie in {FREQ_RATIO_RANGE}, got {freq_ratio!r}")
    return linearised.minimum_no_impact(freq_ratio, "half-sine")


def housner_energy_estimate(freq_ratio: float) -> float:
    """``sqrt(1 + (p / omega_p)²)``: the energy estimate the paper compares against; it gives the
    1.414 the paper quotes at ``omega_p / p = 1`` (shown for orientation, not a tested value)."""
    return math.sqrt(1.0 + 1.0 / freq_ratio**2)


VALUES: tuple[PublishedValue, ...] = (
    PublishedValue(
        key="makris_roussos2000_half_sine_1", source="Makris and Roussos (2000), half-sine pulse, minimum "
        "overturning acceleration without impact", pulse="half-sine", equations="linearised",
        quantity="a_p / (g alpha)", value=1.3224, tolerance=5e-5,
        tolerance_reason="printed to 5 digits (half a unit in the last is 4e-5); boundary bracketed to 1e-6",
        parameters={"freq_ratio": 1.0}),
)
