"""The linearised rocking equation under the harmonic pulses, solved in closed form.

In the dimensionless time ``tau = p t`` and rotation ``phi = theta / alpha``, the small-angle
rocking equation of the classical papers reads, on pivot ``s = sgn(phi)``::

    phi'' - phi = -s - A f(tau),      A = PFA / (g alpha),   f = sin(nu tau + phase),  nu = omega_p / p

with uplift from rest when ``|A f| > 1`` (towards ``s = -sgn(f)``), impacts at ``phi = 0`` that
multiply ``phi'`` by ``e``, and, after the pulse (``f = 0``), the conserved quantity
``H = phi'²/2 - (phi - s)²/2``: a block heading outwards with ``H > 0`` (or beyond ``|phi| = 1``
heading out) never returns. This module is written independently of the solvers: between events the
solution is ``phi_p + c1 cosh(tau - tau0) + c2 sinh(tau - tau0)`` with the particular solution
``phi_p = s + A f(tau) / (1 + nu²)``, and impacts are roots of that expression (Brent's method on a
fine bracket). It gives the reference values of validation case 7.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

#: (phase at tau = 0 in rad, duration in periods) of the harmonic pulses.
HARMONIC: dict[str, tuple[float, float]] = {
    "half-sine": (0.0, 0.5),
    "one-sine": (0.0, 1.0),
    "one-cosine": (0.5 * math.pi, 1.0),
}


def _uplift(A: float, nu: float, phase: float, tau: float, tau_end: float) -> tuple[float, float] | None:
    """First ``tau' >= tau`` with ``|A sin(nu tau' + phase)| > 1`` before ``tau_end``, and ``s``."""
    if A <= 1.0:
        return None
    beta = math.asin(1.0 / A)
    ph, ph_end = nu * tau + phase, nu * tau_end + phase
    m = math.floor(ph / math.pi)
    while True:
        lo, hi = m * math.pi + beta, (m + 1) * math.pi - beta
        if ph >= hi:
            m += 1
            continue
        start = max(ph, lo)
        if start >= ph_end:
            return None
        sign_f = 1.0 if m % 2 == 0 else -1.0
        return (start - phase) / nu, -sign_f


class _Segment:
    """The closed-form solution on pivot ``s`` from ``(tau0, phi0, dphi0)`` while the pulse lasts."""

    def __init__(self, A, nu, phase, s, tau0, phi0, dphi0):
        self.A, self.nu, self.phase, self.s, self.tau0 = A, nu, phase, s, tau0
        k = A / (1.0 + nu * nu)
        self.k = k
        self.c1 = phi0 - (s + k * math.sin(nu * tau0 + phase))
        self.c2 = dphi0 - k * nu * math.cos(nu * tau0 + phase)

    def phi(self, tau):
        d = tau - self.tau0
        return self.s + self.k * np.sin(self.nu * tau + self.phase) + self.c1 * np.cosh(d) + self.c2 * np.sinh(d)

    def dphi(self, tau):
        d = tau - self.tau0
        return self.k * self.nu * np.cos(self.nu * tau + self.phase) + self.c1 * np.sinh(d) + self.c2 * np.cosh(d)


def _free_overturns(phi: float, dphi: float, e: float) -> bool:
    """Verdict of free rocking (no floor motion) from ``(phi, dphi)``: the energy argument."""
    s = 1.0 if (phi > 0 or (phi == 0 and dphi > 0)) else -1.0
    for _ in range(3):
        outward = s * dphi > 0
        h = 0.5 * dphi * dphi - 0.5 * (phi - s) ** 2
        if abs(phi) > 1.0:
            if outward or h <= 0.0:
                return True
        elif outward:
            return h > 0.0
        # falls back to phi = 0 with |dphi| from H, impacts, and leaves on the other side
        v = math.sqrt(max(0.0, 2.0 * h + 1.0))
        phi, dphi, s = 0.0, -s * e * v, -s
        dphi = s * abs(dphi)
    return False


def overturns(A: float, nu: float, shape: str, e: float, samples: int = 4000) -> bool:
    """Does a harmonic pulse of amplitude ``A = PFA/(g alpha)`` and ``nu = omega_p/p`` overturn the
    block (linearised equation, restitution ``e``)? Events are located on the closed form."""
    phase, cycles = HARMONIC[shape]
    tau_end = 2.0 * math.pi * cycles / nu
    tau, phi, dphi, s = 0.0, 0.0, 0.0, 0.0
    for _ in range(10_000):
        if s == 0.0:
            up = _uplift(A, nu, phase, tau, tau_end)
            if up is None:
                return False
            tau, s = up
            phi, dphi = 0.0, 0.0
        seg = _Segment(A, nu, phase, s, tau, phi, dphi)
        grid = np.linspace(tau, tau_end, max(8, int(samples * (tau_end - tau) / tau_end) + 2))
        vals = s * seg.phi(grid)
        # the excursion starts at phi = 0 (after uplift or impact): skip the first sample
        cross = np.flatnonzero(vals[1:] < 0.0)
        if cross.size == 0:
            return _free_overturns(float(seg.phi(tau_end)), float(seg.dphi(tau_end)), e)
        j = int(cross[0]) + 1
        lo = grid[j - 1]
        if j - 1 == 0:  # the root bracket starts at the event itself: move off it
            lo = tau + 1e-12 * max(1.0, tau)
            if s * seg.phi(lo) <= 0.0:
                return False  # no excursion: the floor pushes straight back (seated)
        t_imp = brentq(lambda t: float(seg.phi(t)), lo, grid[j], xtol=1e-15, rtol=1e-15)
        v = float(seg.dphi(t_imp)) * e
        tau, phi, dphi, s = t_imp, 0.0, v, -s
        if abs(v) < 1e-10:
            s = 0.0
    raise RuntimeError("more than 10,000 impacts")


def no_impact_margin(A: float, nu: float, shape: str) -> float:
    """``phi' - (1 - phi)`` at the end of the pulse for the first excursion, assuming it has no
    impact: positive beyond the separatrix (overturning without impact, Zhang and Makris 2001)."""
    phase, cycles = HARMONIC[shape]
    tau_end = 2.0 * math.pi * cycles / nu
    up = _uplift(A, nu, phase, 0.0, tau_end)
    if up is None:
        return -1.0
    seg = _Segment(A, nu, phase, up[1], up[0], 0.0, 0.0)
    phi, dphi = up[1] * float(seg.phi(tau_end)), up[1] * float(seg.dphi(tau_end))
    return dphi + phi - 1.0


def minimum_no_impact(nu: float, shape: str, a_max: float = 500.0) -> float:
    """Smallest ``A = PFA/(g alpha)`` at which :func:`no_impact_margin` turns positive (the lower edge
    of the overturning-without-impact branch); nan if none below ``a_max``."""
    # spacing 1 % (600 points over 1..500): the margin changes sign once per branch edge, and the
    # overturning-without-impact branch is far wider than that
    grid = np.geomspace(1.0 + 1e-9, a_max, 600)
    m = np.array([no_impact_margin(a, nu, shape) for a in grid])
    pos = np.flatnonzero(m > 0.0)
    if pos.size == 0 or pos[0] == 0:
        return math.nan
    i = int(pos[0])
    return brentq(lambda a: no_impact_margin(a, nu, shape), grid[i - 1], grid[i], xtol=1e-13, rtol=1e-13)


def intervals(nu: float, shape: str, e: float, a_max: float = 60.0, n_scan: int = 1200,
              rtol: float = 1e-9) -> list[tuple[float, float]]:
    """Overturning intervals in ``A = PFA/(g alpha)`` by :func:`overturns` (scan, then bisection)."""
    grid = np.geomspace(1.0 + 1e-9, a_max, n_scan)
    v = [overturns(a, nu, shape, e) for a in grid]
    edges = []
    for i in range(1, len(grid)):
        if v[i] != v[i - 1]:
            lo, hi = grid[i - 1], grid[i]
            while hi / lo - 1.0 > rtol:
                mid = math.sqrt(lo * hi)
                if overturns(mid, nu, shape, e) == v[i - 1]:
                    lo = mid
                else:
                    hi = mid
            edges.append((hi if not v[i - 1] else lo, v[i]))
    out, start = [], None
    for x, to_over in edges:
        if to_over:
            start = x
        elif start is not None:
            out.append((start, x))
            start = None
    if start is not None or (v[0] and not edges):
        out.append((grid[0] if start is None else start, math.inf))
    return out
