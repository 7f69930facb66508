"""Floor motions as the compiled event-driven solvers see them (numba): one piece of forcing per
integration segment, and the exact first time its magnitude exceeds a level.

In the dimensionless time ``tau = p t`` of a block, a floor acceleration over ``g`` is a sequence of
segments, each of one closed form (:data:`FORM_LINEAR`, :data:`FORM_SINE`, :data:`FORM_RICKER`): an
analytic pulse is one segment (:func:`pulse_forcing`), a record one linear segment per sample
interval (:func:`segment`). A solver steps inside a segment and never across its end, where the
acceleration or its slope jumps. :func:`next_exceedance` finds, in closed form on each segment, when
``|a|/g`` first exceeds a level: the uplift of a seated block (``tan(alpha)``), the start of slip
(``mu``).

Shared by :mod:`opsrock.solvers.housner_fast` and :mod:`opsrock.solvers.friction`.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numba
import numpy as np

from opsrock.excitations.pulses import RICKER_HALF_WIDTH
from opsrock.solvers.jitable import jitable

#: Relative margin on a level: an acceleration within 1e-12 of ``g tan(alpha)`` counts as *at* the
#: threshold, which does not uplift (Eq. 4 needs strict exceedance). Without it, round-off
#: in ``PFA = ratio * g * tan(alpha)`` (``b/h`` against ``tan(atan2(b, h))``, 1 ulp) could
#: turn the spectrum's ``pfa_ratio = 1`` row into a rocking of 1e-24 rad.
EXCEEDANCE_RTOL = 1e-12

# --- forms of the floor acceleration inside one integration segment ----------------------------
#: ``a/g = c0 + c1 (tau - c2)``: one sample interval of a record, or the rectangular pulse.
FORM_LINEAR = 0
#: ``a/g = c0 sin(c1 tau + c2)``: half-sine, one-sine and one-cosine pulses.
FORM_SINE = 1
#: ``a/g = c0 (1 - 2 x²) exp(-x²)``, ``x = c1 (tau - c2)``: the Ricker wavelet.
FORM_RICKER = 2

#: :data:`FORM_RICKER` as a non-literal: numba compiles a callee once more for a literal argument met while it
#: infers a caller (issue 43: cold compile time).
_RICKER = np.int64(FORM_RICKER)

# --- analytic pulses known to the kernel (ids of :func:`pulse_forcing`) -------------------------
PULSE_RECTANGULAR = 0
PULSE_HALF_SINE = 1
PULSE_ONE_SINE = 2
PULSE_ONE_COSINE = 3
PULSE_RICKER = 4
#: Kernel id of every pulse shape of :data:`opsrock.excitations.PULSE_SHAPES`.
PULSE_IDS: dict[str, int] = {"rectangular": PULSE_RECTANGULAR, "half-sine": PULSE_HALF_SINE,
                             "one-sine": PULSE_ONE_SINE, "one-cosine": PULSE_ONE_COSINE,
                             "ricker": PULSE_RICKER}


#: A horizontal floor motion as the kernels take it (``tau = p t``): the ``form`` and coefficients ``(c0, c1, c2)``
#: of :func:`forcing` of an analytic pulse (one segment, :func:`pulse_forcing`), or a record's samples ``kvals``
#: (``a/g`` at ``tau = i dtau``, linear between, :func:`record_forcing`), ending at ``tau_end`` (units of 1/p).
Excitation = namedtuple("Excitation", ["form", "c0", "c1", "c2", "tau_end", "kvals", "dtau"])


def record_forcing(kvals: np.ndarray, dtau: float, tau_end: float) -> Excitation:
    """The :class:`Excitation` of a record: samples ``kvals`` (``a/g``, dimensionless) every ``dtau``, ending at
    ``tau_end`` (units of ``1/p``). Typed as :func:`pulse_forcing` types a pulse's (one compiled kernel for both:
    a writable float array, float scalars)."""
    kvals = np.require(kvals, dtype=np.float64, requirements=["C", "W"])
    return Excitation(FORM_LINEAR, 0.0, 0.0, 0.0, float(tau_end), kvals, float(dtau))


@jitable
def forcing(tau, form, c0, c1, c2):
    """Floor acceleration over g at ``tau`` inside a segment of the given form."""
    if form == FORM_LINEAR:
        return c0 + c1 * (tau - c2)
    if form == FORM_SINE:
        return c0 * math.sin(c1 * tau + c2)
    x = c1 * (tau - c2)
    return c0 * (1.0 - 2.0 * x * x) * math.exp(-x * x)


@jitable
def next_exceedance_sine(tau, level, k, nu, phase, tau_end):
    """First time >= tau at which ``|k sin(nu tau + phase)| > level`` before ``tau_end``, and the
    sign of a there; (-1.0, 0.0) if none. Closed form: the exceedance windows in the phase
    ``Phi = nu tau + phase`` are ``(m pi + beta, (m + 1) pi - beta)``, ``beta = asin(level / k)``,
    with the sign of a ``(-1)^m``."""
    if k <= level * (1.0 + EXCEEDANCE_RTOL):
        return -1.0, 0.0
    beta = math.asin(level / k)
    ph = nu * tau + phase
    ph_end = nu * tau_end + phase
    m = math.floor(ph / math.pi)
    while True:
        lo = m * math.pi + beta
        hi = (m + 1.0) * math.pi - beta
        sgn = 1.0 if m % 2 == 0 else -1.0
        if ph >= hi:
            m += 1.0
            continue
        if ph > lo:
            return tau, sgn
        if lo >= ph_end:
            return -1.0, 0.0
        return (lo - phase) / nu, sgn


@jitable
def next_exceedance_ricker(tau, level, k, c, t0, tau_end):
    """First time >= tau at which the Ricker wavelet ``|a|/g`` exceeds ``level`` before ``tau_end``,
    and the sign of a there; (-1.0, 0.0) if none. ``a`` is monotone between its extremes
    (``x = -+sqrt(3/2)``, 0), so each piece holds at most one crossing, found by bisection to the
    last bit (the returned time is on the exceeding side)."""
    thr = level * (1.0 + EXCEEDANCE_RTOL)
    if k <= thr:
        return -1.0, 0.0
    d = math.sqrt(1.5) / c
    bounds = (0.0, t0 - d, t0, t0 + d, tau_end)
    for j in range(4):
        ta = bounds[j]
        tb = bounds[j + 1]
        if tb <= tau:
            continue
        s = max(tau, ta)
        fa = forcing(s, _RICKER, k, c, t0)
        if fa > thr:
            return s, 1.0
        if fa < -thr:
            return s, -1.0
        fb = forcing(tb, _RICKER, k, c, t0)
        if fb > thr:
            sgn = 1.0
        elif fb < -thr:
            sgn = -1.0
        else:
            continue
        lo = s
        hi = tb
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if mid <= lo or mid >= hi:
                break
            if sgn * forcing(mid, _RICKER, k, c, t0) > thr:
                hi = mid
            else:
                lo = mid
        return hi, sgn
    return -1.0, 0.0


@jitable
def next_exceedance_record(tau, level, kvals, dtau):
    """First time >= tau at which |a|/g > level for the piecewise-linear record ``kvals``
    (a/g at ``tau = i dtau``), exact on the linear segments, and the sign of a there;
    (-1.0, 0.0) if none before the end of the record."""
    thr = level * (1.0 + EXCEEDANCE_RTOL)
    n = kvals.shape[0]
    i = min(int(tau / dtau), n - 2)
    while i < n - 1:
        ta = i * dtau
        ka = kvals[i]
        kb = kvals[i + 1]
        t0 = max(tau, ta)
        k0 = ka + (kb - ka) * (t0 - ta) / dtau
        if k0 > thr:
            return t0, 1.0
        if k0 < -thr:
            return t0, -1.0
        if kb > thr:  # rising through +thr inside the segment (ka < thr < kb)
            return ta + (thr - ka) / (kb - ka) * dtau, 1.0
        if kb < -thr:
            return ta + (-thr - ka) / (kb - ka) * dtau, -1.0
        i += 1
    return -1.0, 0.0


@jitable
def next_exceedance_scaled(tau, level, kvals, gvals, dtau):
    """First time >= tau at which ``|a|/g > level (1 + a_v/g)`` for the piecewise-linear records
    ``kvals`` (``a/g``) and ``gvals`` (``1 + a_v/g``) on the same grid ``tau = i dtau``, exact on the
    linear segments, and the sign of ``a`` there; (-1.0, 0.0) if none before the end. Where
    ``1 + a_v/g <= 0`` (the floor falls faster than gravity) any ``a`` exceeds."""
    thr = level * (1.0 + EXCEEDANCE_RTOL)
    n = kvals.shape[0]
    i = min(int(tau / dtau), n - 2)
    while i < n - 1:
        ta = i * dtau
        t0 = max(tau, ta)
        k0 = kvals[i] + (kvals[i + 1] - kvals[i]) * (t0 - ta) / dtau
        g0 = gvals[i] + (gvals[i + 1] - gvals[i]) * (t0 - ta) / dtau
        best = -1.0
        sgn = 0.0
        for d in (1.0, -1.0):
            f0 = d * k0 - thr * g0
            if f0 > 0.0:
                return t0, d
            fb = d * kvals[i + 1] - thr * gvals[i + 1]
            if fb > 0.0:
                t = t0 + (ta + dtau - t0) * (-f0) / (fb - f0)
                if best < 0.0 or t < best:
                    best = t
                    sgn = d
        if best >= 0.0:
            return best, sgn
        i += 1
    return -1.0, 0.0


@jitable
def next_exceedance(tau, level, exc):
    """First uplift time >= tau (``|a|/g > level``) and the sign of a there, for any form of the
    :class:`Excitation` ``exc``."""
    if exc.form == FORM_LINEAR:
        return next_exceedance_record(tau, level, exc.kvals, exc.dtau)
    if exc.form == FORM_SINE:
        return next_exceedance_sine(tau, level, exc.c0, exc.c1, exc.c2, exc.tau_end)
    return next_exceedance_ricker(tau, level, exc.c0, exc.c1, exc.c2, exc.tau_end)


@jitable
def segment(exc, tau, i):
    """Forcing of the :class:`Excitation` ``exc`` on the segment that holds ``tau`` (the search starts at segment
    ``i``): (segment index, c0, c1, c2, segment end) with ``(c0, c1, c2)`` the coefficients of :func:`forcing`. An
    analytic pulse is one segment; a record (``FORM_LINEAR``) has one per sample interval (its acceleration has a
    kink at each)."""
    if exc.form != FORM_LINEAR:
        return 0, exc.c0, exc.c1, exc.c2, exc.tau_end
    kvals, dtau = exc.kvals, exc.dtau
    n = kvals.shape[0]
    while i < n - 2 and tau >= (i + 1) * dtau:
        i += 1
    end = exc.tau_end if i == n - 2 else (i + 1) * dtau
    return i, kvals[i], (kvals[i + 1] - kvals[i]) / dtau, i * dtau, end


@numba.njit(cache=True)
def pulse_forcing(pulse, k, nu):
    """The :class:`Excitation` of an analytic pulse of peak ``k = PFA/g`` and ``nu = omega_p/p``, in the
    dimensionless time ``tau = p t``."""
    empty = np.zeros(0)
    if pulse == PULSE_RECTANGULAR:
        tau_end = math.pi / nu
        return Excitation(FORM_LINEAR, 0.0, 0.0, 0.0, tau_end, np.array([k, k]), tau_end)
    if pulse == PULSE_HALF_SINE:
        return Excitation(FORM_SINE, k, nu, 0.0, math.pi / nu, empty, 1.0)
    if pulse == PULSE_ONE_COSINE:
        return Excitation(FORM_SINE, k, nu, 0.5 * math.pi, 2.0 * math.pi / nu, empty, 1.0)
    if pulse == PULSE_RICKER:
        t0 = RICKER_HALF_WIDTH * 2.0 * math.pi / nu
        return Excitation(FORM_RICKER, k, 0.5 * nu, t0, 2.0 * t0, empty, 1.0)
    return Excitation(FORM_SINE, k, nu, 0.0, 2.0 * math.pi / nu, empty, 1.0)


__all__ = ["EXCEEDANCE_RTOL", "Excitation", "FORM_LINEAR", "FORM_RICKER", "FORM_SINE", "PULSE_HALF_SINE", "PULSE_IDS",
           "PULSE_ONE_COSINE", "PULSE_ONE_SINE", "PULSE_RECTANGULAR", "PULSE_RICKER", "forcing", "next_exceedance",
           "next_exceedance_record", "next_exceedance_ricker", "next_exceedance_scaled", "next_exceedance_sine",
           "pulse_forcing", "record_forcing", "segment"]
