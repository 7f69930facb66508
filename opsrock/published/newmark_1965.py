"""Newmark (1965), *Effects of earthquakes on dams and embankments*, Géotechnique 15(2), 139-160: the
rigid-plastic sliding block, for a block on a floor with Coulomb friction that cannot rock.

A block whose friction coefficient is below its width-to-height ratio (``mu < b / h``) never tips
while it slides (docs/guide/friction.md, slide): it moves as a rigid-plastic body.
Relative to the floor, while the base slips in the direction ``sigma``, its displacement ``u`` obeys
``u'' = -a(t) - sigma mu g_v``, ``g_v = g + a_v``; it sticks again when ``u' = 0`` and ``|a| <= mu g_v``.
A constant vertical floor acceleration ``a_v`` only changes the friction capacity, ``g -> g_v``.

* **Rectangular pulse** ``a = a_p`` for ``0 <= t <= t_1``: this is Newmark's sliding-block result for a
  single rectangular pulse, ``u_m = V² / (2 g N) (1 - N / A)`` with the pulse's velocity ``V = a_p t_1``,
  its acceleration ``A g = a_p`` and the yield acceleration ``N g = mu g_v`` (here with ``g -> g_v``).
  Expanded: ``u_m = (a_p - mu g_v) t_1² a_p / (2 mu g_v)``. We quote the relation as it is usually cited
  (the paper itself was not available to us); it is re-derived in docs/guide/friction.md (rigid-plastic sliding) and checked
  against direct integration in ``tests/validation/published/test_friction_closed_forms.py``.
* **Half-sine pulse** ``a = a_p sin(omega t)`` for ``0 <= t <= pi / omega``: derived here (not in
  Newmark's paper). With ``r = mu g_v / a_p < 1`` and ``psi = asin(r)`` (the slip starts at
  ``omega t = psi``), while slipping::

      |u'|(xi) = (a_p / omega) [cos psi - cos xi - r (xi - psi)],                     xi = omega t
      slide(xi) = (a_p / omega²) [(xi - psi) cos psi - (sin xi - sin psi) - r (xi - psi)² / 2]

  Case A, still slipping at the end of the pulse (``1 + cos psi - r (pi - psi) > 0``): the slide at
  ``xi = pi`` plus ``V_1² / (2 mu g_v)``, ``V_1 = (a_p / omega)[1 + cos psi - r (pi - psi)]``. Case B,
  the slip stops inside the pulse: ``slide(xi_e)`` at the root ``xi_e`` in ``(pi - psi, pi]`` of
  ``cos psi - cos xi - r (xi - psi) = 0``; case B holds for ``r`` above :func:`case_b_ratio` (0.7246).

Every slide is the magnitude (m); the base moves towards ``-sgn(a_p)`` relative to the floor (towards
negative x for the positive pulses of :mod:`opsrock.excitations.pulses`).
"""

from __future__ import annotations

import functools
import math

from scipy.optimize import brentq

from opsrock.constants import G
from opsrock.errors import InputError

#: Range of the pulse's peak acceleration ``a_p`` (m/s²): positive, at most 100 g.
ACCELERATION_RANGE: tuple[float, float] = (1e-9, 1e3)
#: Range of the rectangular pulse's duration ``t_1`` (s).
DURATION_RANGE: tuple[float, float] = (1e-6, 1e3)
#: Range of the half-sine's circular frequency ``omega`` (rad/s).
OMEGA_RANGE: tuple[float, float] = (1e-3, 1e4)
#: Range of the friction coefficient ``mu`` (dimensionless): positive (a frictionless base never
#: stops), at most the 100 of :data:`opsrock.limits.LIMITS`.
MU_RANGE: tuple[float, float] = (1e-6, 100.0)
#: Range of the constant vertical floor acceleration ``a_v`` (m/s², up), as :data:`opsrock.limits.LIMITS`
#: (``g + a_v > 0``).
VERTICAL_RANGE: tuple[float, float] = (-9.8, 1e3)


def _in_range(name: str, value: float, bounds: tuple[float, float], unit: str) -> float:
    """``value`` as a float if finite and within ``bounds`` (closed); the message names ``name``."""
    v = float(value)
    if not (math.isfinite(v) and bounds[0] <= v <= bounds[1]):
        raise InputError(f"{name} must lie in [{bounds[0]:g}, {bounds[1]:g}]{unit}, got {value!r}")
    return v


def _yield(mu: float, a_v: float) -> float:
    """The yield acceleration ``mu (g + a_v)`` (m/s²), arguments range-checked."""
    mu = _in_range("mu", mu, MU_RANGE, "")
    a_v = _in_range("a_v", a_v, VERTICAL_RANGE, " m/s²")
    return mu * (G + a_v)


def newmark_displacement(V: float, A: float, N: float, g: float = G) -> float:
    """Newmark's sliding-block displacement for one rectangular pulse, ``V² / (2 g N) (1 - N / A)`` (m).

    Parameters
    ----------
    V : float
        Velocity of the pulse, ``a_p t_1`` (m/s), > 0.
    A : float
        The pulse's acceleration in units of ``g`` (dimensionless), > 0.
    N : float
        Yield acceleration in units of ``g`` (dimensionless), > 0. ``N >= A``: no slide (0).
    g : float, optional
        Gravity (m/s²), ``g + a_v`` with a constant vertical floor acceleration. Default 9.81.
    """
    V = _in_range("V", V, (1e-12, 1e6), " m/s")
    A = _in_range("A", A, (1e-12, 1e6), "")
    N = _in_range("N", N, (1e-12, 1e6), "")
    g = _in_range("g", g, (1e-3, 1e4), " m/s²")
    return 0.0 if N >= A else V * V / (2.0 * g * N) * (1.0 - N / A)


def rectangular_slide(a_p: float, t1: float, mu: float, a_v: float = 0.0) -> float:
    """Slide of a block that cannot rock under a rectangular pulse (m): Newmark's relation.

    Parameters
    ----------
    a_p : float
        Pulse acceleration (m/s²), within :data:`ACCELERATION_RANGE`.
    t1 : float
        Pulse duration (s), within :data:`DURATION_RANGE`.
    mu : float
        Coulomb friction coefficient, static = kinetic (dimensionless), within :data:`MU_RANGE`.
    a_v : float, optional
        Constant vertical floor acceleration (m/s², positive up), within :data:`VERTICAL_RANGE`.
        Default 0.

    Returns
    -------
    float
        ``(a_p - mu g_v) t1² a_p / (2 mu g_v)`` (m); 0 when ``a_p <= mu g_v`` (no slip).
    """
    a_p = _in_range("a_p", a_p, ACCELERATION_RANGE, " m/s²")
    t1 = _in_range("t1", t1, DURATION_RANGE, " s")
    n_g = _yield(mu, a_v)
    g_v = G + float(a_v)
    return newmark_displacement(a_p * t1, a_p / g_v, n_g / g_v, g_v)


@functools.lru_cache(maxsize=1)
def case_b_ratio() -> float:
    """The ``r = mu g_v / a_p`` (dimensionless) above which a half-sine pulse's slip stops inside the
    pulse (case B): the root of ``1 + cos psi - r (pi - psi) = 0``, ``psi = asin(r)``; 0.7246."""
    return brentq(lambda r: 1.0 + math.cos(math.asin(r)) - r * (math.pi - math.asin(r)), 0.5, 0.99,
                  xtol=1e-15, rtol=1e-15)


def half_sine_case(a_p: float, omega: float, mu: float, a_v: float = 0.0) -> str:
    """Which case of the half-sine closed form applies: ``"none"`` (no slip, ``a_p <= mu g_v``), ``"A"``
    (still slipping at the end of the pulse) or ``"B"`` (stops inside it). Arguments as
    :func:`half_sine_slide`."""
    a_p = _in_range("a_p", a_p, ACCELERATION_RANGE, " m/s²")
    _in_range("omega", omega, OMEGA_RANGE, " rad/s")
    r = _yield(mu, a_v) / a_p
    if r >= 1.0:
        return "none"
    psi = math.asin(r)
    return "A" if 1.0 + math.cos(psi) - r * (math.pi - psi) > 0.0 else "B"


def half_sine_slide(a_p: float, omega: float, mu: float, a_v: float = 0.0) -> float:
    """Slide of a block that cannot rock under a half-sine pulse (m), cases A and B (module docstring).

    Parameters
    ----------
    a_p : float
        Peak acceleration of the pulse (m/s²), within :data:`ACCELERATION_RANGE`.
    omega : float
        Circular frequency of the sine (rad/s), within :data:`OMEGA_RANGE`; the pulse lasts ``pi / omega``.
    mu : float
        Coulomb friction coefficient, static = kinetic (dimensionless), within :data:`MU_RANGE`.
    a_v : float, optional
        Constant vertical floor acceleration (m/s², positive up), within :data:`VERTICAL_RANGE`.
        Default 0.

    Returns
    -------
    float
        The slide (m); 0 when ``a_p <= mu g_v``.
    """
    case = half_sine_case(a_p, omega, mu, a_v)
    if case == "none":
        return 0.0
    n_g = _yield(mu, a_v)
    r = n_g / a_p
    psi = math.asin(r)
    scale = a_p / (omega * omega)

    def slide(xi: float) -> float:
        return scale * ((xi - psi) * math.cos(psi) - (math.sin(xi) - math.sin(psi)) - 0.5 * r * (xi - psi) ** 2)

    if case == "A":
        v1 = a_p / omega * (1.0 + math.cos(psi) - r * (math.pi - psi))
        return slide(math.pi) + v1 * v1 / (2.0 * n_g)
    xi_e = brentq(lambda xi: math.cos(psi) - math.cos(xi) - r * (xi - psi), math.pi - psi, math.pi,
                  xtol=1e-15, rtol=1e-15)
    return slide(xi_e)


__all__ = ["ACCELERATION_RANGE", "DURATION_RANGE", "MU_RANGE", "OMEGA_RANGE", "VERTICAL_RANGE", "case_b_ratio",
           "half_sine_case", "half_sine_slide", "newmark_displacement", "rectangular_slide"]
