"""Zhang and Makris (2001), *Rocking response of free-standing blocks under cycloidal pulses*,
Earthquake Eng. Struct. Dyn. 30, 473-483: the one-sine pulse.

**Overturning without impact.** With the pulse ``a_p sin(omega_p t)`` on ``[0, 2 pi / omega_p]``, the
block uplifts at the phase ``psi = omega_p t_u`` where ``a_p sin(psi) = g alpha``. Solving the
linearised equation from there to the end of the pulse and asking that the block end on the
separatrix gives, with ``nu = omega_p / p``::

    nu sin(psi) - cos(psi) = -exp(-(2 pi - psi) / nu),      a_p / (g alpha) = 1 / sin(psi)

(:func:`minimum_no_impact` solves it). At ``nu = 5`` it gives 7.168.

**Overturning after one impact.** Below that branch lies a second one: the block rocks back, impacts
and is thrown over by the second half of the pulse. It depends on ``e``; between the two branches
lies a safe window. It has no closed form: :func:`intervals` finds both branches with the
closed-form event solution of :mod:`opsrock.published.linearised`.

**The locomotive example** (``alpha = 0.25 rad``, ``p = 2.14 rad/s``, ``e = 0.9``, ``omega_p =
15.7 rad/s``): first overturning at about 2.22 g, then safe between about 2.62 and 3.44 g. The
linearised equation does not reproduce it (it gives one branch, from 3.23 g); the exact equation
does (validation case 7 shows both).
"""

from __future__ import annotations

import math

from scipy.optimize import brentq

from opsrock.errors import InputError
from opsrock.published import linearised
from opsrock.published.reference import PublishedValue

#: ``omega_p / p`` range in which the relations are evaluated (dimensionless).
FREQ_RATIO_RANGE: tuple[float, float] = (0.5, 50.0)


def _check(freq_ratio: float) -> None:
    if not FREQ_RATIO_RANGE[0] <= freq_ratio <= FREQ_RATIO_RANGE[1]:
        raise InputError(f"freq_ratio must lie in {FREQ_RATIO_RANGE}, got {freq_ratio!r}")


def no_impact_equation(psi: float, freq_ratio: float) -> float:
    """``nu sin(psi) - cos(psi) + exp(-(2 pi - psi) / nu)``: zero on the overturning-without-impact
    boundary (``psi`` uplift phase in rad, ``nu = omega_p / p``)."""
    nu = freq_ratio
    return nu * math.sin(psi) - math.cos(psi) + math.exp(-(2.0 * math.pi - psi) / nu)


def minimum_no_impact(freq_ratio: float) -> float:
    """Lower edge of the overturning-without-impact branch, ``a_p / (g alpha) = 1 / sin(psi)``, from the
    root ``psi`` in ``(0, pi/2)`` of :func:`no_impact_equation` (dimensionless)."""
    _check(freq_ratio)
    # the function is negative at psi -> 0 (exp(-2 pi/nu) - 1 < 0) and positive at pi/2 (nu > 0)
    psi = brentq(no_impact_equation, 1e-12, 0.5 * math.pi, args=(freq_ratio,), xtol=1e-15, rtol=1e-15)
    return 1.0 / math.sin(psi)


def intervals(freq_ratio: float, restitution: float, a_max: float = 60.0) -> list[tuple[float, float]]:
    """Every overturning interval in ``a_p / (g alpha)`` (linearised, restitution ``e``), both
    branches, by the closed-form event solution."""
    _check(freq_ratio)
    return linearised.intervals(freq_ratio, "one-sine", restitution, a_max=a_max)


#: The locomotive example's block and pulse.
LOCOMOTIVE: dict[str, float] = {"alpha": 0.25, "p": 2.14, "restitution": 0.9, "omega_p": 15.7}

VALUES: tuple[PublishedValue, ...] = (
    PublishedValue(
        key="zhang_makris2001_no_impact_5", source="Zhang and Makris (2001), one-sine pulse, overturning without "
        "impact", pulse="one-sine", equations="linearised", quantity="a_p / (g alpha)", value=7.168,
        tolerance=1e-4, tolerance_reason="printed to 4 digits (half a unit in the last is 7e-5); boundary "
        "bracketed to 1e-6", parameters={"freq_ratio": 5.0}),
    PublishedValue(
        key="zhang_makris2001_locomotive_first", source="Zhang and Makris (2001), locomotive example, first "
        "overturning amplitude", pulse="one-sine", equations="exact", quantity="a_p (g)", value=2.22,
        tolerance=5e-3, tolerance_reason="read as 'about 2.22 g' (3 digits: half a unit in the last is 2.3e-3 "
        "relative) and the example's block is given by alpha and p to 2-3 digits", parameters=LOCOMOTIVE),
    PublishedValue(
        key="zhang_makris2001_locomotive_window_low", source="Zhang and Makris (2001), locomotive example, safe "
        "window, lower edge", pulse="one-sine", equations="exact", quantity="a_p (g)", value=2.62,
        tolerance=5e-3, tolerance_reason="as the first overturning amplitude", parameters=LOCOMOTIVE),
    PublishedValue(
        key="zhang_makris2001_locomotive_window_high", source="Zhang and Makris (2001), locomotive example, safe "
        "window, upper edge", pulse="one-sine", equations="exact", quantity="a_p (g)", value=3.44,
        tolerance=5e-3, tolerance_reason="as the first overturning amplitude", parameters=LOCOMOTIVE),
)
