"""Tests of the closed forms of the friction model: Shenton's (1996) initiation criteria
(:mod:`opsrock.published.shenton_1996`) and Newmark's (1965) rigid-plastic sliding block
(:mod:`opsrock.published.newmark_1965`).

References are independent of the code under test: algebraic identities of ``mu_crit`` derived in
docs/guide/friction.md (leaving rest; checked with sympy in the research note behind it), the region table and its seven
verification points of that section, and a direct numerical integration (scipy ``solve_ivp`` with a
terminal event at the end of the slip) of the rigid-plastic equation ``u'' = -a(t) + mu g_v``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from opsrock.constants import G
from opsrock.errors import InputError
from opsrock.published import newmark_1965 as nm
from opsrock.published import shenton_1996 as sh

BETAS = (0.1, 0.2, 0.3, 0.5, 1.0)


# =============================================================================================
# Shenton (1996): mu_crit and the initial mode
# =============================================================================================


@pytest.mark.parametrize("beta", BETAS)
def test_mu_crit_equals_beta_at_the_uplift_threshold(beta):
    """mu_crit(beta, beta) = beta: at lambda = beta rocking needs exactly b/h (docs/guide/friction.md, leaving rest). The
    expression is rational, so only round-off separates the two (1e-15 relative)."""
    assert sh.mu_crit(beta, beta) == pytest.approx(beta, rel=1e-15)


@pytest.mark.parametrize("beta", BETAS)
def test_mu_crit_grows_with_lambda_at_the_derived_rate(beta):
    """d mu_crit / d lambda = 4 (1 + beta²)² / (4 + beta² + 3 lambda beta)² > 0 (docs/guide/friction.md, leaving rest).
    A central difference with step 1e-5 has truncation error ~1e-10 relative and round-off ~1e-11, so
    1e-8 relative separates a wrong formula from a right one."""
    lams = np.linspace(0.0, 5.0, 26)[1:]
    vals = [sh.mu_crit(lam, beta) for lam in lams]
    assert np.all(np.diff(vals) > 0.0)
    d = 1e-5
    for lam in lams:
        fd = (sh.mu_crit(lam + d, beta) - sh.mu_crit(lam - d, beta)) / (2 * d)
        exact = 4.0 * (1.0 + beta**2) ** 2 / (4.0 + beta**2 + 3.0 * lam * beta) ** 2
        assert fd == pytest.approx(exact, rel=1e-8)


@pytest.mark.parametrize("beta", BETAS)
def test_mu_crit_limits(beta):
    """mu_crit(0, beta) = 3 beta / (4 + beta²) (Housner's impact impulse ratio); mu_crit -> (1 + 4 beta²)
    / (3 beta) (the Painlevé bound at theta = 0) as lambda -> infinity: at lambda = 1e6 the gap is
    (4 + beta²)/(3 lambda beta) relative, below 1.5e-4 for beta >= 0.1, so 2e-4 relative."""
    assert sh.mu_crit(0.0, beta) == pytest.approx(3.0 * beta / (4.0 + beta**2), rel=1e-15)
    assert sh.mu_crit(1e6, beta) == pytest.approx((1.0 + 4.0 * beta**2) / (3.0 * beta), rel=2e-4)


@pytest.mark.parametrize("beta", BETAS)
def test_mu_crit_lies_between_beta_and_lambda(beta):
    """mu_crit - lambda = 3 (beta - lambda)(1 + lambda beta) / (4 + beta² + 3 lambda beta) (sympy), hence
    beta < mu_crit < lambda for lambda > beta (round-off only: 1e-12 absolute)."""
    for lam in (1.01 * beta, 1.5 * beta, 3.0 * beta, 10.0):
        m = sh.mu_crit(lam, beta)
        ident = 3.0 * (beta - lam) * (1.0 + lam * beta) / (4.0 + beta**2 + 3.0 * lam * beta)
        assert m - lam == pytest.approx(ident, abs=1e-12)
        assert beta < m < lam


#: The seven verification points of docs/guide/friction.md, point checks (beta = 0.3): (lambda, mu, mode); the modes were
#: also found by the Moreau-Jean prototype there.
SHENTON_POINTS = [(0.5, 0.25, "slide"), (0.5, 0.32, "slide_rock"), (0.5, 0.38, "rock"), (0.25, 0.20, "slide"),
                  (0.25, 0.28, "rest"), (1.0, 0.45, "slide_rock"), (1.0, 0.55, "rock")]


@pytest.mark.parametrize("lam, mu, mode", SHENTON_POINTS)
@pytest.mark.parametrize("a_v_g", [0.0, -0.3, 0.5])
def test_region_table_points(lam, mu, mode, a_v_g):
    """The region table, with lambda = |a_h| / (g + a_v): the vertical acceleration enters only through
    g_v. Corner: s = -sgn(a_h) for rock and slide-rock, the slip direction -sgn(a_h) for slide."""
    g_v = G * (1.0 + a_v_g)
    for sign in (1.0, -1.0):
        res = sh.initial_mode(-sign * lam * g_v, a_v_g * G, 0.3, mu)
        assert res.mode == mode
        assert res.corner == (0 if mode == "rest" else int(sign))


def test_region_boundaries():
    """On each boundary the table's closed side holds: lambda = mu (mu < beta) and lambda = beta stay at
    rest; mu = beta slide-rocks (lambda > beta); mu = mu_crit rocks. Values built so that each boundary
    is exact in floating point (dyadic fractions)."""
    beta = 0.375
    assert sh.initial_mode(-0.25 * G, 0.0, beta, 0.25).mode == "rest"  # lambda = mu < beta
    assert sh.initial_mode(-beta * G, 0.0, beta, 0.5).mode == "rest"  # lambda = beta
    assert sh.initial_mode(-0.5 * G, 0.0, beta, beta).mode == "slide_rock"  # mu = beta < mu_crit
    mc = sh.mu_crit(0.5, beta)
    assert sh.initial_mode(-0.5 * G, 0.0, beta, mc).mode == "rock"
    assert sh.initial_mode(-0.5 * G, 0.0, beta, mc * (1 - 1e-12)).mode == "slide_rock"


def test_kinetic_friction_at_most_b_over_h_slides_flat():
    """With mu_k < mu: where the pivot cannot stick (beta <= mu < mu_crit) the block slide-rocks only if
    mu_k >= beta; with mu_k < beta it slides with both corners down (the table's last row)."""
    lam, beta, mu = 0.5, 0.3, 0.32  # mu_crit = 0.348
    assert sh.initial_mode(-lam * G, 0.0, beta, mu, mu_k=0.31).mode == "slide_rock"
    assert sh.initial_mode(-lam * G, 0.0, beta, mu, mu_k=0.25) == sh.InitialMode("slide", 1)
    assert sh.initial_mode(-lam * G, 0.0, beta, 0.38, mu_k=0.25).mode == "rock"  # sticks: mu_k plays no part
    with pytest.raises(InputError):
        sh.initial_mode(-lam * G, 0.0, beta, mu, mu_k=0.4)  # above the static coefficient


def test_shenton_abstract_statements():
    """What Shenton's abstract says, on a grid: slide-rock starts from rest for friction above b/h and
    below a critical value, and the friction needed to rock grows with the acceleration."""
    beta = 0.25
    for lam in (0.3, 0.6, 1.2, 3.0):
        mc = sh.mu_crit(lam, beta)
        assert sh.initial_mode(-lam * G, 0.0, beta, 0.5 * (beta + mc)).mode == "slide_rock"
        assert sh.initial_mode(-lam * G, 0.0, beta, mc).mode == "rock"
    assert np.all(np.diff([sh.mu_crit(lam, beta) for lam in (0.3, 0.6, 1.2, 3.0)]) > 0)


@pytest.mark.parametrize("call", [
    lambda: sh.mu_crit(-0.1, 0.3), lambda: sh.mu_crit(0.5, 0.0), lambda: sh.mu_crit(0.5, math.nan),
    lambda: sh.initial_mode(1.0, -G, 0.3, 0.5), lambda: sh.initial_mode(1.0, 0.0, 0.3, -0.1),
    lambda: sh.initial_mode(2e3, 0.0, 0.3, 0.5), lambda: sh.initial_mode(1.0, 0.0, 20.0, 0.5),
])
def test_shenton_ranges(call):
    """Arguments outside the declared ranges (and a weightless block) are refused with InputError."""
    with pytest.raises(InputError):
        call()


# =============================================================================================
# Newmark (1965): rigid-plastic sliding
# =============================================================================================


def _direct_slide(accel, t_start: float, mu: float, g_v: float, t_max: float) -> float:
    """Slide magnitude by direct integration of ``w' = a(t) - mu g_v`` (``w = -u'``, slip towards -x) from
    ``t_start`` until ``w`` returns to 0 (terminal event), with rtol 1e-12: a reference independent of the
    closed forms."""
    def rhs(t, z):
        return [z[1], accel(t) - mu * g_v]

    def stop(t, z):
        return z[1]
    stop.terminal, stop.direction = True, -1
    sol = solve_ivp(rhs, (t_start, t_max), [0.0, 1e-300], rtol=1e-12, atol=1e-15, events=stop, max_step=1e-3)
    return float(sol.y_events[0][0][0]) if sol.t_events[0].size else float(sol.y[0, -1])


@pytest.mark.parametrize("a_p_g, t1, mu, a_v_g", [(0.5, 0.3, 0.2, 0.0), (0.5, 0.3, 0.2, -0.3), (0.9, 0.1, 0.4, 0.5),
                                                  (0.25, 2.0, 0.2, 0.0)])
def test_newmark_rectangular_equals_direct_integration(a_p_g, t1, mu, a_v_g):
    """Newmark's V²/(2 g N)(1 - N/A) with g -> g + a_v against the direct integration (1e-8 relative: the
    integrator's rtol 1e-12 and the event location leave ~1e-10)."""
    a_p, g_v = a_p_g * G, G * (1.0 + a_v_g)
    ref = _direct_slide(lambda t: a_p if t <= t1 else 0.0, 0.0, mu, g_v, 100.0)
    assert nm.rectangular_slide(a_p, t1, mu, a_v_g * G) == pytest.approx(ref, rel=1e-8)
    assert nm.rectangular_slide(a_p, t1, mu, a_v_g * G) == pytest.approx(
        (a_p - mu * g_v) * t1**2 * a_p / (2 * mu * g_v), rel=1e-14)


def test_newmark_rectangular_documented_values():
    """The values of docs/guide/friction.md, rigid-plastic sliding (closed form and a Moreau-Jean prototype agreed
    to 7 digits)."""
    assert nm.rectangular_slide(0.5 * G, 0.3, 0.2) == pytest.approx(0.3310875, rel=1e-7)
    assert nm.rectangular_slide(0.5 * G, 0.3, 0.2, -0.3 * G) == pytest.approx(0.5675786, rel=1e-6)
    assert nm.rectangular_slide(0.2 * G, 0.3, 0.2) == 0.0  # a_p = mu g: no slip


@pytest.mark.parametrize("a_p_g, f_hz, mu, a_v_g, case", [
    (0.5, 2.0, 0.2, 0.0, "A"), (0.25, 2.0, 0.2, 0.0, "B"), (0.21, 1.0, 0.2, 0.0, "B"), (0.5, 2.0, 0.2, -0.3, "A"),
    (0.3, 1.0, 0.2, 0.4, "B"), (1.0, 0.5, 0.3, 0.0, "A"),
])
def test_newmark_half_sine_equals_direct_integration(a_p_g, f_hz, mu, a_v_g, case):
    """The half-sine closed form (cases A and B, derived here) against the direct integration from the
    onset of slip at asin(mu g_v / a_p) / omega (1e-8 relative, as above)."""
    a_p, w, g_v = a_p_g * G, 2.0 * math.pi * f_hz, G * (1.0 + a_v_g)
    t_end = math.pi / w
    t_s = math.asin(mu * g_v / a_p) / w
    ref = _direct_slide(lambda t: a_p * math.sin(w * t) if t <= t_end else 0.0, t_s, mu, g_v, 100.0)
    assert nm.half_sine_case(a_p, w, mu, a_v_g * G) == case
    assert nm.half_sine_slide(a_p, w, mu, a_v_g * G) == pytest.approx(ref, rel=1e-8)


def test_newmark_half_sine_case_boundary():
    """Case B holds above r = mu g_v / a_p = 0.7246 (docs/guide/friction.md, rigid-plastic sliding) and the two
    cases meet there continuously: the slide just above and below the boundary differs by O(dr) (1e-6
    relative for dr = 1e-9 r)."""
    r_b = nm.case_b_ratio()
    assert r_b == pytest.approx(0.7246, abs=5e-5)
    w, mu = 2.0 * math.pi, 0.2
    below = nm.half_sine_slide(mu * G / (r_b * (1 - 1e-9)), w, mu)
    above = nm.half_sine_slide(mu * G / (r_b * (1 + 1e-9)), w, mu)
    assert nm.half_sine_case(mu * G / (r_b * (1 - 1e-9)), w, mu) == "A"
    assert nm.half_sine_case(mu * G / (r_b * (1 + 1e-9)), w, mu) == "B"
    assert above == pytest.approx(below, rel=1e-6)
    assert nm.half_sine_slide(0.2 * G, w, 0.2) == 0.0


def test_newmark_vertical_is_g_substitution():
    """A constant a_v only replaces g by g + a_v: the slide with (mu, a_v) equals the slide with
    mu' = mu (g + a_v) / g and no a_v (same yield acceleration) for the half-sine, where g appears
    nowhere else (1e-12 relative: the same arithmetic up to rounding)."""
    a_p, w = 0.6 * G, 3.0
    assert nm.half_sine_slide(a_p, w, 0.2, 0.25 * G) == pytest.approx(nm.half_sine_slide(a_p, w, 0.25), rel=1e-12)


@pytest.mark.parametrize("call", [
    lambda: nm.rectangular_slide(0.0, 0.3, 0.2), lambda: nm.rectangular_slide(1.0, -1.0, 0.2),
    lambda: nm.rectangular_slide(1.0, 0.3, 0.0), lambda: nm.rectangular_slide(1.0, 0.3, 0.2, -G),
    lambda: nm.half_sine_slide(1.0, 0.0, 0.2), lambda: nm.half_sine_slide(math.inf, 1.0, 0.2),
    lambda: nm.newmark_displacement(1.0, 0.5, -0.1),
])
def test_newmark_ranges(call):
    """Arguments outside the declared ranges are refused with InputError."""
    with pytest.raises(InputError):
        call()
