"""The closed-form contact solutions of :mod:`opsrock.solvers.rigid3d.kernel` checked against Coulomb's law and
against the kernel's own nonsmooth Gauss-Seidel (NSGS), which solves the same contact problem by iteration.

The problems are those of a box (0.4 x 0.6 x 1.6 m, homogeneous) standing on one edge: tilted about it by an angle
in (0.02, 0.4) rad and turned in plan by any angle, the two corners of the edge active, and a free velocity
(before the contact impulses) drawn so that both corners approach the floor. A fixed seed makes the draws the
same on every run. The references: the law itself (a stuck corner's velocity zero and its impulse in the static
cone, a slipping corner's friction impulse ``mu_k`` times its normal impulse against its slip velocity, both
pressing with zero normal velocity), and NSGS to 1e-13 (its own tolerance; the closed form's round-off is
below 1e-12 of the velocities, hence 1e-8 on the velocities compared).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from opsrock.solvers.rigid3d import contact, geometry, sliding, sticking
from opsrock.solvers.rigid3d import kernel as kn
from opsrock.solvers.rigid3d.model import Body, ContactSolver, Friction
from opsrock.solvers.rigid3d.workspace import (ARENA_BYTES, VEC_OM, VEC_V, VEC_VF, FlatWork, make_edge_work,
                                               make_workspace)
from opsrock.solvers.scratch import make_arena

B, D, H = 0.2, 0.3, 0.8
IB = ((0.6**2 + 1.6**2) / 12, (0.4**2 + 1.6**2) / 12, (0.4**2 + 0.6**2) / 12)
#: The box (p and R are not read by the functions tested).
BODY = Body(b=B, d=D, h=H, g=9.81, p=3.0, R=1.0, inertia=IB, weak_y=False)
EDGE = (0, 3)  # the corners (+b, +d) and (+b, -d): the edge x = +b


def _quat(tilt: float, turn: float) -> np.ndarray:
    """Tilt about the body y axis (onto the edge x = +b), then a turn about the floor's z axis."""
    qt = np.array([math.cos(-tilt / 2), 0.0, math.sin(-tilt / 2), 0.0])
    qz = np.array([math.cos(turn / 2), 0.0, 0.0, math.sin(turn / 2)])
    w1, x1, y1, z1 = qz
    w2, x2, y2, z2 = qt
    return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])


def _problem(rng):
    """Arms ``r`` (4 x 3), ``Iinv`` and a free velocity ``vf`` (6) with both edge corners approaching."""
    s = np.zeros(13)
    s[3:7] = _quat(rng.uniform(0.02, 0.4), rng.uniform(-math.pi, math.pi))
    Q, Iinv, Iw, r = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((4, 3))
    geometry._geometry(s, BODY, Q, Iinv, Iw, r)
    assert abs(r[0, 2] - r[3, 2]) < 1e-12  # both corners of the edge at one height
    while True:
        vf = rng.normal(0.0, 0.3, 6)
        u = [vf[:3] + np.cross(vf[3:], r[i]) for i in EDGE]
        if u[0][2] < -0.02 and u[1][2] < -0.02:
            return r, Iinv, vf


def _workspace(r, vf, Iinv=None, Iw=None):
    """The kernel's contact-problem workspace holding the arms ``r``, the free velocity ``vf`` and the inertias
    given."""
    ws = make_workspace(make_arena(ARENA_BYTES), kn.OUT_SIZE, None).step.contact
    ws.r[:] = r
    ws.vec[VEC_VF] = vf
    if Iinv is not None:
        ws.Iinv[:] = Iinv
    if Iw is not None:
        ws.Iw[:] = Iw
    return ws


def _velocities(P, r, Iinv, vf):
    V = vf[:3] + P.sum(axis=0)
    Om = vf[3:] + Iinv @ sum(np.cross(r[i], P[i]) for i in range(4))
    return V, Om


def _check_law(P, r, Iinv, vf, mu):
    """The contact law at the two corners; returns how many slip."""
    V, Om = _velocities(P, r, Iinv, vf)
    scale = np.abs(vf).max()
    slipping = 0
    for i in EDGE:
        u = V + np.cross(Om, r[i])
        pt = math.hypot(P[i, 0], P[i, 1])
        assert P[i, 2] >= 0.0
        if P[i, 2] == 0.0:  # open: no impulse, not approaching
            assert pt == 0.0 and u[2] >= 0.0
            continue
        assert abs(u[2]) < 1e-10 * scale
        ut = math.hypot(u[0], u[1])
        if ut < 1e-10 * scale:
            assert pt <= mu * P[i, 2] * (1 + 1e-9)
        else:
            slipping += 1
            assert pt == pytest.approx(mu * P[i, 2], rel=1e-9)
            assert P[i, 0] * u[1] - P[i, 1] * u[0] == pytest.approx(0.0, abs=1e-9 * pt * ut)
            assert P[i, 0] * u[0] + P[i, 1] * u[1] < 0.0
    return slipping


def _nsgs(r, Iinv, vf, mu):
    act = np.zeros(4, dtype=np.bool_)
    act[list(EDGE)] = True
    ws = _workspace(r, vf, Iinv=Iinv)
    for i in EDGE:
        geometry._delassus(r[i], Iinv, ws.Wd[i])
        geometry._inv3(ws.Wd[i], ws.Wi[i])
    ws.vec[VEC_V, :3], ws.vec[VEC_OM, :3] = vf[:3], vf[3:]
    P = np.zeros((4, 3))
    nsgs = ContactSolver(tol=1e-13, max_sweeps=20000, fail_steps=1, loose_tol=1e-13, extra_sweeps=0)
    sweeps = contact._solve_contacts(ws, act, P, Friction(mu, mu, False), 1e-13, nsgs, np.zeros(kn.OUT_SIZE), False)
    return ws.vec[VEC_V, :3].copy(), ws.vec[VEC_OM, :3].copy(), P, sweeps <= nsgs.max_sweeps


def test_edge_slip_obeys_coulomb_and_agrees_with_gauss_seidel():
    """200 drawn problems at mu 0.3: ``_edge_slip`` answers every one whose solution by NSGS has a corner slipping
    (the others, stick-stick and stick-open, have closed forms of their own), and where it answers its impulses
    obey the law and give NSGS's velocities."""
    rng = np.random.default_rng(20261127)
    mu, answered = 0.3, 0
    act = np.zeros(4, dtype=np.bool_)
    act[list(EDGE)] = True
    for _ in range(200):
        r, Iinv, vf = _problem(rng)
        Vn, Omn, Pn, converged = _nsgs(r, Iinv, vf, mu)
        assert converged
        scale = np.abs(vf).max()
        slips = any(Pn[i, 2] > 0.0 and math.hypot(*(Vn + np.cross(Omn, r[i]))[:2]) > 1e-9 * scale for i in EDGE)
        ws, P = _workspace(r, vf, Iinv=Iinv), np.zeros((4, 3))
        if not sliding._edge_slip(ws, make_edge_work(make_arena(ARENA_BYTES)), act, P, Friction(mu, mu, False), np.zeros(kn.OUT_SIZE)):
            assert not slips
            continue
        V, Om = ws.vec[VEC_V, :3], ws.vec[VEC_OM, :3]
        answered += 1
        assert _check_law(P, r, Iinv, vf, mu) > 0
        np.testing.assert_allclose(V, Vn, atol=1e-8 * scale)
        np.testing.assert_allclose(Om, Omn, atol=1e-8 * scale / 0.3)  # over 0.3 m, the shortest half-side
    assert answered >= 150


@pytest.mark.parametrize("seed", range(5))
def test_edge_split_keeps_both_corners_in_their_cones(seed):
    """Two stuck corners share the impulse along their edge in any split: ``_edge_split`` moves it to the
    nearest split with both impulses in the static cone when one exists (checked on a grid of splits), and
    leaves it otherwise."""
    rng = np.random.default_rng(seed)
    mu, moved = 0.4, 0
    for _ in range(200):
        e = np.array([*rng.normal(size=2), rng.normal(0.0, 0.01)])
        e /= np.linalg.norm(e)
        Pa = np.array([*rng.normal(0.0, 0.3, 2), rng.uniform(0.05, 1.0)])
        Pb = np.array([*rng.normal(0.0, 0.3, 2), rng.uniform(0.05, 1.0)])
        ca, cb = Pa @ e, Pb @ e
        xa = sticking._edge_split(Pa, Pb, (e[0], e[1], e[2]), ca, cb, ca, mu)

        def inside(x, slack=0.0):
            x = np.atleast_1d(x)[:, None]
            a, b = Pa + (x - ca) * e, Pb + (ca - x) * e
            return ((np.hypot(a[:, 0], a[:, 1]) <= mu * a[:, 2] * (1 + slack) + 1e-15)
                    & (np.hypot(b[:, 0], b[:, 1]) <= mu * b[:, 2] * (1 + slack) + 1e-15))

        grid = np.linspace(ca - 3.0, ca + 3.0, 6001)
        feasible = grid[inside(grid)]
        if inside(ca)[0]:
            assert xa == ca
        elif feasible.size:
            moved += 1
            assert inside(xa, 1e-9)[0]
            assert abs(xa - ca) <= np.abs(feasible - ca).min() + 1e-9
        else:
            assert xa == ca
    assert moved >= 10  # the draws hold splits to move (18 to 26 of 200 per seed)


def test_flat_slide_obeys_coulomb_and_newton_finds_it_again():
    """300 drawn problems of the level box sliding and twisting on its four corners at mu 0.4 (the free velocity
    pressing by ``g dt``, ``dt`` 1e-3 s; slip and twist drawn about the size that stops within a few steps, where
    the slip directions turn fast): where ``_slide_flat`` answers (167 of 300 measured; the others have a
    corner that stops, left to NSGS), the block stays level, every corner presses and slips against its friction
    impulse of ``mu`` times its normal one, and the impulses carry the momentum change. The four normal impulses
    are indeterminate, so the answer is not compared with NSGS's; instead ``_flat_newton`` from the answer's
    velocities moved by 20 % comes back to them (all 167)."""
    rng = np.random.default_rng(1)
    mu, answered, regained = 0.4, 0, 0
    act = np.ones(4, dtype=np.bool_)
    idx = np.arange(4)
    for _ in range(300):
        s = np.zeros(13)
        s[3:7] = _quat(0.0, rng.uniform(-math.pi, math.pi))
        Q, Iinv, Iw, r = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((4, 3))
        geometry._geometry(s, BODY, Q, Iinv, Iw, r)
        vf = np.array([*rng.normal(0.0, 0.01, 2), -9.81e-3, 0.0, 0.0, rng.normal(0.0, 0.05)])
        ws, P = _workspace(r, vf, Iw=Iw), np.zeros((4, 3))
        sdir, Am = np.zeros((4, 2)), np.zeros((6, 7))
        if not sliding._slide_flat(ws, act, P, mu, sdir, Am):
            continue
        V, Om = ws.vec[VEC_V, :3].copy(), ws.vec[VEC_OM, :3].copy()
        answered += 1
        assert V[2] == 0.0 and Om[0] == 0.0 and Om[1] == 0.0
        np.testing.assert_allclose(V - vf[:3], P.sum(axis=0), atol=1e-12)
        np.testing.assert_allclose(Iw @ (Om - vf[3:]), sum(np.cross(r[i], P[i]) for i in range(4)), atol=1e-12)
        for i in range(4):
            u = V + np.cross(Om, r[i])
            assert P[i, 2] >= 0.0
            np.testing.assert_allclose(P[i, :2], -mu * P[i, 2] * u[:2] / math.hypot(u[0], u[1]), atol=1e-12)
        x = np.array([V[0], V[1], Om[2]]) * 1.2
        fw = FlatWork(idx, np.zeros(7), np.zeros(7), sdir, Am)
        if sliding._flat_newton(ws, fw, 4, mu, x):
            regained += 1
            np.testing.assert_allclose(fw.xs[4:7], [V[0], V[1], Om[2]], atol=1e-10)
    assert answered >= 100 and regained == answered


def test_slip_newton_obeys_coulomb_on_one_corner():
    """200 drawn problems on one corner of the edge (corner 0 alone active), mu 0.3 and the infinite-friction
    limit (``mu_k = LIMIT_MU``): where the corner cannot stick, ``_local`` solves the slip by ``_slip_newton``
    from the slip direction of the free velocity (measured: it converges on 180 of 188 problems; the fixed point
    ``_local`` falls back to takes the others, one of which has no slip solution) and every answer obeys the law:
    zero normal velocity, ``|P_t| = mu_k P_N`` against the slip velocity to 1e-9 (the round-off of a 3 x 3
    problem, as above)."""
    rng = np.random.default_rng(7)
    solved = newton = 0
    for _ in range(200):
        r, Iinv, vf = _problem(rng)
        W, Wi = np.zeros((3, 3)), np.zeros((3, 3))
        geometry._delassus(r[0], Iinv, W)
        geometry._inv3(W, Wi)
        q = vf[:3] + np.cross(vf[3:], r[0])
        for mu, limit in ((0.3, False), (kn.LIMIT_MU, True)):
            P = -Wi @ q
            if P[2] >= 0.0 and (limit or math.hypot(P[0], P[1]) <= mu * P[2]):
                continue  # sticks
            warm = np.zeros(3)
            ut = q[:2] - W[:2, 2] * q[2] / W[2, 2]
            ok, s0, s1 = contact._slip_newton(W, q, mu, ut[0] / math.hypot(*ut), ut[1] / math.hypot(*ut))
            newton += ok
            P = np.zeros(3)
            code = contact._local(W, Wi, q, mu, mu, limit, warm, P)
            if code == 2:  # no slip solution (W_zz - mu_k W_zt . s <= 0): left open
                assert not ok and not P.any()
                continue
            assert code == (1 if limit else 0)
            u = q + W @ P
            pt, vt = math.hypot(P[0], P[1]), math.hypot(u[0], u[1])
            assert abs(u[2]) < 1e-10 * np.abs(q).max()
            assert pt == pytest.approx(mu * P[2], rel=1e-9)
            assert P[0] * u[1] - P[1] * u[0] == pytest.approx(0.0, abs=1e-9 * pt * vt)
            assert P[0] * u[0] + P[1] * u[1] < 0.0
            solved += 1
    assert solved > 150 and newton >= 0.9 * solved


def test_settle_sets_a_block_at_rest_on_three_corners_down_on_four():
    """A block tilted about a horizontal axis so that corner 2 hangs 1e-9 m above the floor, corner 0 on it and
    the two others lower than corner 2 (the Moreau-Jean steps' drift: the corners within the contact gap count as
    down) is set down level on all four corners, its base centre and twist kept to round-off; one whose corner
    hangs by more than ``gap_max`` (here 1e-6 m) is left as it is."""
    b, d, h = B, D, H
    body = Body(b=b, d=d, h=h, g=9.81, p=3.0, R=1.0, inertia=IB, weak_y=False)
    for gap, settles in ((1e-9, True), (1e-5, False)):
        tilt = gap / math.hypot(2 * b, 2 * d)  # about the diagonal through corners 1 and 3
        axis = np.array([-2 * d, 2 * b, 0.0]) / math.hypot(2 * b, 2 * d)  # tips corner 2 up
        qt = np.array([math.cos(tilt / 2), *(math.sin(tilt / 2) * axis)])
        tw = 0.3
        qz = np.array([math.cos(tw / 2), 0.0, 0.0, math.sin(tw / 2)])
        w1, x1, y1, z1 = qz
        w2, x2, y2, z2 = qt
        s = np.zeros(13)
        s[3:7] = [w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                  w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2]
        Q, r = np.zeros((3, 3)), np.zeros((4, 3))
        geometry._arms(s, body, Q, r)
        s[2] = -min(r[:, 2])
        s[0], s[1] = 0.1, -0.2
        geometry._arms(s, body, Q, r)
        gaps = s[2] + r[:, 2]
        up = int(np.argmax(gaps))
        assert up == 2 and gaps[up] == pytest.approx(gap, rel=1e-6) and abs(gaps[0]) < 1e-15
        assert all(0.0 < gaps[i] < gap for i in (1, 3))
        touch = np.array([i != up for i in range(4)])
        before = s.copy()
        base = s[:2] - h * Q[:2, 2]
        out = np.zeros(kn.OUT_SIZE)
        assert kn._settle(s, touch, body, Q, r, 1e-6, out) == settles
        if not settles:
            assert np.array_equal(s, before) and not touch[up]
            continue
        geometry._arms(s, body, Q, r)
        assert touch.all() and np.allclose(s[2] + r[:, 2], 0.0, atol=1e-15)
        assert np.allclose(s[:2] - h * Q[:2, 2], base, atol=1e-12)
        assert geometry._twist(s) == pytest.approx(tw, abs=1e-12)
        assert out[kn.OUT_SETTLED] == 1.0 and out[kn.OUT_SETTLE_GAP] == pytest.approx(gap, rel=1e-3)
