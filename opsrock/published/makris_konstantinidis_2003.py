"""Makris and Konstantinidis (2003), *The rocking spectrum and the limitations of practical design
methodologies*, Earthquake Eng. Struct. Dyn. 32, 265-289: the one-cosine pulse.

A one-cosine pulse ``a(t) = a_p cos(omega_p t)`` on ``[0, 2 pi / omega_p]`` starts at its peak, so a
pulse with ``a_p > g alpha`` uplifts the block at ``t = 0``. The paper's example: ``T_p = 2 s``
(``omega_p = pi rad/s``), ``alpha = 15°``, blocks of ``p = 1`` and ``p = 2 rad/s``, for which it
gives the minimum overturning acceleration.

We solve the linearised equation with ``e = e_R = 1 - 1.5 sin²(alpha)`` (Housner's value, 0.8995 at
15°) and the exact equation with the same ``e``. Both branches are found: overturning without impact
(:func:`minimum_no_impact`, closed form of :mod:`opsrock.published.linearised`) and, much lower,
after one impact (:func:`intervals`). The paper's printed minima were not available to us when this
case was written, so no number of the paper is tested here: validation case 7 lists ours, by
equation form, and leaves the published column empty.
"""

from __future__ import annotations

import math

from opsrock.published import linearised

#: The paper's example.
T_P: float = 2.0
ALPHA: float = math.radians(15.0)
P_VALUES: tuple[float, ...] = (1.0, 2.0)


def restitution(alpha: float = ALPHA) -> float:
    """Housner's ``e_R = 1 - 1.5 sin²(alpha)`` (dimensionless)."""
    return 1.0 - 1.5 * math.sin(alpha) ** 2


def minimum_no_impact(freq_ratio: float) -> float:
    """Lower edge of the overturning-without-impact branch, ``a_p / (g alpha)`` (dimensionless)."""
    return linearised.minimum_no_impact(freq_ratio, "one-cosine")


def intervals(freq_ratio: float, e: float, a_max: float = 60.0) -> list[tuple[float, float]]:
    """Every overturning interval in ``a_p / (g alpha)`` (linearised, restitution ``e``)."""
    return linearised.intervals(freq_ratio, "one-cosine", e, a_max=a_max)


#: No published value is tested (see the module docstring).
VALUES: tuple = ()
