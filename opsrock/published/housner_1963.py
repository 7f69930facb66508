"""Housner (1963), *The behavior of inverted pendulum structures during earthquakes*, Bull. Seismol.
Soc. Am. 53(2), 403-417: the rectangular pulse.

A block at rest under a constant floor acceleration ``a`` for a time ``t_1`` (linearised equation,
``A = a / (g alpha)``): while the pulse lasts, ``phi = theta / alpha`` obeys ``phi'' = p² (phi - 1 + A)``
from rest, so ``phi = (A - 1) (cosh(p t) - 1)``. After it, the block is free and overturns if and only
if it ends the pulse on or beyond the separatrix ``phi' / p = 1 - phi`` of the free motion. Setting
``(A - 1) sinh(p t_1) = 1 - (A - 1)(cosh(p t_1) - 1)`` gives ``(A - 1)(exp(p t_1) - 1) = 1``::

    A_min = a_min / (g alpha) = 1 / (1 - exp(-p t_1))

No impact happens before overturning (the rotation grows monotonically), so ``e`` plays no part.
"""

from __future__ import annotations

import math

from opsrock.errors import InputError
from opsrock.published.reference import PublishedValue

#: ``p t_1`` range of the relation: any positive duration (dimensionless).
P_T1_RANGE: tuple[float, float] = (1e-3, 50.0)


def minimum_overturning(p_t1: float) -> float:
    """Minimum overturning ``a / (g alpha)`` of a rectangular pulse of duration ``t_1`` (dimensionless).

    Parameters
    ----------
    p_t1 : float
        ``p t_1`` (dimensionless), within :data:`P_T1_RANGE`.
    """
    if not P_T1_RANGE[0] <= p_t1 <= P_T1_RANGE[1]:
        raise InputError(f"p_t1 must lie in {P_T1_RANGE}, got {p_t1!r}")
    return 1.0 / (1.0 - math.exp(-p_t1))


#: The published value: ``p t_1 = 1``.
VALUES: tuple[PublishedValue, ...] = (
    PublishedValue(
        key="housner1963_rect_pt1_1", source="Housner (1963), rectangular pulse, minimum overturning acceleration",
        pulse="rectangular", equations="linearised", quantity="a / (g alpha)", value=1.58198,
        tolerance=1e-5, tolerance_reason="printed to 6 digits (half a unit in the last is 3e-6); the solver "
        "boundary is bracketed to 1e-6 and integrated with RK4 errors below 1e-7", parameters={"p_t1": 1.0}),
)
