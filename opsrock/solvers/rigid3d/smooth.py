"""Smooth steps (numba): Runge-Kutta steps about stuck corners (:mod:`.pivot`) and on slipping corners (the contact
forces at acceleration level), coarse Moreau-Jean steps of a block sliding flat; each kept only while a probe
Moreau-Jean step from its end solves the same contact, else halved. Units and frames as in
:mod:`opsrock.solvers.rigid3d.kernel` (SI, per unit mass).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from opsrock.constants import OVERTURNING_ANGLE
from opsrock.solvers.jitable import jitable
from opsrock.solvers.rigid3d import pivot as PV
from opsrock.solvers.rigid3d.constants import (LIMIT_MU, NO, OUT_COARSE_SPAN, OUT_COARSE_STEPS, OUT_FRICTION_WORK,
                                               OUT_SLIDE_STEPS, OUT_SLIP_SPAN, OUT_SLIP_STEPS, OUT_SLIP_TRIED,
                                               OUT_SMOOTH_SPAN, OUT_SMOOTH_STEPS, OUT_SMOOTH_TRIED, OUT_STICK_STEPS,
                                               SETDOWN_MARGIN, SLIP_MIN_SUB, SLIP_TURN, ZERO)
from opsrock.solvers.rigid3d.geometry import (_arms, _delassus_pair, _inv_inertia, _tilt)
from opsrock.solvers.rigid3d.sliding import (_edge_system, _solve_n)
from opsrock.solvers.rigid3d.step import (_book, _floor, _step)
from opsrock.solvers.rigid3d.workspace import (EVEC_P6, EVEC_Q, EVEC_U, EVEC_Y, Probe)


@jitable
def _flat_slip(act, touch, slip):
    """After a Moreau-Jean step: all four corners active and down, some slipping (a block sliding flat)."""
    sl = False
    for i in range(4):
        if not (act[i] and touch[i]):
            return False
        sl = sl or slip[i]
    return sl


@jitable
def _stuck_pivot(act, touch, slip, P):
    """After a Moreau-Jean step: one corner or two down, exactly those solved in contact, loaded, none slipping
    (the phase :mod:`.pivot` integrates)."""
    n = 0
    for i in range(4):
        if act[i] != touch[i] or (touch[i] and (slip[i] or P[i, 2] <= 0.0)):
            return False
        n += touch[i]
    return n == 1 or n == 2


@jitable
def _copy(dst, src):
    """``dst[:] = src`` (1-D, or 2-D row by row) element by element: numba compiles a slice assignment with its
    shape-mismatch error message, string formatting included (seconds of a cold compile)."""
    if dst.ndim == 1:
        for i in range(dst.shape[0]):
            dst[i] = src[i]
    else:
        for i in range(dst.shape[0]):
            for j in range(dst.shape[1]):
                dst[i, j] = src[i, j]


@jitable
def _span(floor, k, n_max):
    """The Moreau-Jean steps a smooth step from step ``k`` spans at first: to the next sample of the floor motion or
    the end of the excitation, at most ``n_max``; -1 if that is fewer than two (none is tried)."""
    n = PV.step_end(floor, k, n_max) - k
    return -1 if n < 2 else n


@jitable
def _halved(n):
    """The steps of the next smooth step tried after one of ``n`` steps left its phase: half of them, at least
    ``pivot.MIN_STEPS``; 0 if ``n`` was already that short (the Moreau-Jean steps then locate the event)."""
    return 0 if n <= PV.MIN_STEPS else max(PV.MIN_STEPS, n // 2)


@numba.njit(cache=True, inline='always')
def _same_phase(model, new, n_piv, ws, end, probe):
    """Is the end state ``new`` of a smooth step still in its phase? Every other corner above ``lift_gap``, and
    a Moreau-Jean probe step from it (``end.a``: the floor's accelerations of that step) solved with exactly the
    pivots ``end.piv[:n_piv]`` active, each loaded and stuck. ``probe`` is ``(act, P, state, out)`` scratch (``P``
    holds the warm start on entry and the probe's impulses on return); ``ws`` and ``end`` the kernel's
    :class:`.workspace.StepWork` and :class:`.workspace.EndWork`."""
    actp, Pp, sp, outp = probe.act, probe.P, probe.state, probe.out
    piv, a, Q1, r1 = end.piv, end.a, end.Q1, end.r1
    lift_gap, vel_tol = model.limits.lift_gap, model.limits.velocity_tol
    _arms(new, model.body, Q1, r1)
    for i in range(4):
        mine = i == piv[0] or (n_piv == 2 and i == piv[1])
        if not mine and new[2] + r1[i, 2] <= lift_gap:
            return False
    outp[:] = 0.0
    guess = ws.contact.mask
    for i in range(4):
        guess[i] = i == piv[0] or (n_piv == 2 and i == piv[1])
    sweeps = _step(model, new, (a[0], a[1], a[2]), model.numerics.dt, ws, probe, guess)
    if sweeps == 0 or sweeps > model.nsgs.max_sweeps:
        return False
    for i in range(4):
        mine = i == piv[0] or (n_piv == 2 and i == piv[1])
        if actp[i] != mine or (mine and Pp[i, 2] <= 0.0):
            return False
    if n_piv == 2:
        return outp[OUT_STICK_STEPS] > 0.5
    ri = ws.contact.r[piv[0]]  # the probe's arms
    u0 = sp[7] + sp[11] * ri[2] - sp[12] * ri[1]
    u1 = sp[8] + sp[12] * ri[0] - sp[10] * ri[2]
    return math.hypot(u0, u1) <= vel_tol


@numba.njit(cache=True, inline='always')
def _smooth(model, floor, state, k, work, corners, trial):
    """A smooth step (:mod:`opsrock.solvers.rigid3d.pivot`) about the corners down (``corners.touch``): from ``k`` to
    the next sample (at most ``pivot.MAX_DTAU``), halved while it leaves its phase (:func:`_halved`), into
    ``trial.state`` (its impulses ``trial.P``, its counts ``trial.out``). Returns ``(steps, largest tilt)``; 0 steps
    if none was kept, -1 if none could be tried (fewer than two steps to the next sample, or not one corner or two
    down); the Moreau-Jean steps then go on. ``work``: the kernel's :class:`.workspace.Workspace`."""
    ws = work.step  # (each taken apart once: numba counts a reference to every array of a named tuple at each
    end = work.end  # place it is dropped, and ``work`` (52 arrays) dropped at each return was a fifth of the
    wk = work.pivot  # kernel's compiled code; issue 43)
    probe = work.probe
    touch = corners.touch
    P, new, out = trial.P, trial.state, trial.out
    n_max = max(PV.MIN_STEPS, int(PV.MAX_DTAU / (model.body.p * model.numerics.dt)))
    piv = end.piv
    n_piv = ZERO
    for i in range(4):
        if touch[i]:
            if n_piv == 2:
                return 0, 0.0
            piv[n_piv] = i
            n_piv += 1
    if n_piv == 0:
        return 0, 0.0
    n = _span(floor, k, n_max)
    if n < 0:
        return -1, 0.0
    a = end.a
    Pp = probe.P
    while True:
        out[OUT_SMOOTH_TRIED] += 1.0
        tilt = PV.integrate(model, floor, state, piv[:n_piv], k, n, new, wk)
        a[0], a[1], a[2] = _floor(floor, k + n, model.numerics.theta_mj)
        _copy(Pp, P)
        if 0.0 <= tilt < OVERTURNING_ANGLE and _same_phase(model, new, n_piv, ws, end, probe):
            _copy(P, Pp)
            out[OUT_SMOOTH_STEPS] += 1.0
            out[OUT_SMOOTH_SPAN] += n
            return n, tilt
        n = _halved(n)
        if n == 0:
            return 0, 0.0


@numba.njit(cache=True, inline='always')
def _slip_free(model, y, F, sw):
    """The free motion of :func:`_slip_rhs` at the state ``y`` under the body force ``F``: into ``sw`` the arms,
    inertia, the contact corners' velocities ``u`` and free accelerations ``q`` (rows ``EVEC_U``, ``EVEC_Q``), their
    Delassus blocks ``D`` and a slipping corner's slip direction ``sdir``. Returns ``(ok, alpha_f)``: ``ok`` False
    if a slipping corner does not move; ``alpha_f = -I^-1 (omega x I omega)`` (a 3-tuple, rad/s²)."""
    Q, Iinv, Iw, r, D, sdir, idx, st = sw.Q, sw.Iinv, sw.Iw, sw.r, sw.D, sw.sdir, sw.idx, sw.st
    q, u = sw.vec[EVEC_Q], sw.vec[EVEC_U]
    _arms(y, model.body, Q, r)
    _inv_inertia(Q, model.body.inertia, Iinv, Iw)
    w0, w1, w2 = y[10], y[11], y[12]
    L0 = Iw[0, 0] * w0 + Iw[0, 1] * w1 + Iw[0, 2] * w2
    L1 = Iw[1, 0] * w0 + Iw[1, 1] * w1 + Iw[1, 2] * w2
    L2 = Iw[2, 0] * w0 + Iw[2, 1] * w1 + Iw[2, 2] * w2
    g0, g1, g2 = -(w1 * L2 - w2 * L1), -(w2 * L0 - w0 * L2), -(w0 * L1 - w1 * L0)
    al0 = Iinv[0, 0] * g0 + Iinv[0, 1] * g1 + Iinv[0, 2] * g2
    al1 = Iinv[1, 0] * g0 + Iinv[1, 1] * g1 + Iinv[1, 2] * g2
    al2 = Iinv[2, 0] * g0 + Iinv[2, 1] * g1 + Iinv[2, 2] * g2
    for k in range(2):
        ri = r[idx[k]]
        x0, x1, x2 = w1 * ri[2] - w2 * ri[1], w2 * ri[0] - w0 * ri[2], w0 * ri[1] - w1 * ri[0]
        u[3 * k], u[3 * k + 1], u[3 * k + 2] = y[7] + x0, y[8] + x1, y[9] + x2
        q[3 * k] = F[0] + al1 * ri[2] - al2 * ri[1] + w1 * x2 - w2 * x1
        q[3 * k + 1] = F[1] + al2 * ri[0] - al0 * ri[2] + w2 * x0 - w0 * x2
        q[3 * k + 2] = F[2] + al0 * ri[1] - al1 * ri[0] + w0 * x1 - w1 * x0
        for b in range(2):
            _delassus_pair(ri, r[idx[b]], Iinv, D[3 * k:3 * k + 3, 3 * b:3 * b + 3])
        if st[k] == 1:
            nu = math.hypot(u[3 * k], u[3 * k + 1])
            if nu == 0.0:
                return False, (0.0, 0.0, 0.0)
            sdir[k, 0], sdir[k, 1] = u[3 * k] / nu, u[3 * k + 1] / nu
    return True, (al0, al1, al2)


@numba.njit(cache=True, inline='always')
def _slip_loads(sw, mu_s):
    """The contact forces ``P6`` (row ``EVEC_P6``) of :func:`_slip_rhs` checked: ``(holds, friction power, stop
    time)`` as it returns them."""
    D, st = sw.D, sw.st
    q, P6, u = sw.vec[EVEC_Q], sw.vec[EVEC_P6], sw.vec[EVEC_U]
    holds = True
    power = 0.0
    t_stop = np.inf
    for k in range(2):
        if st[k] == 2:
            continue
        pz = P6[3 * k + 2]
        if pz <= 0.0 or (st[k] == 0 and math.hypot(P6[3 * k], P6[3 * k + 1]) > mu_s * pz):
            holds = False
        if st[k] == 1:
            at0, at1 = q[3 * k], q[3 * k + 1]
            for a in range(6):
                at0 += D[3 * k, a] * P6[a]
                at1 += D[3 * k + 1, a] * P6[a]
            a_t = math.hypot(at0, at1)
            if a_t > 0.0:
                t_stop = min(t_stop, math.hypot(u[3 * k], u[3 * k + 1]) / a_t)
            power -= P6[3 * k] * u[3 * k] + P6[3 * k + 1] * u[3 * k + 1]
    return holds, power, t_stop


@numba.njit(cache=True, inline='always')
def _slip_derivative(y, F, al, sw, dy):
    """``dy`` of :func:`_slip_rhs`: the body force ``F`` and the contact forces ``P6`` on the centre of mass, their
    torques and ``al`` (``alpha_f``) on the rotation, the quaternion's rate."""
    r, idx, st, P6, Iinv = sw.r, sw.idx, sw.st, sw.vec[EVEC_P6], sw.Iinv
    t0, t1, t2 = 0.0, 0.0, 0.0
    dy[7], dy[8], dy[9] = F[0], F[1], F[2]
    for k in range(2):
        if st[k] == 2:
            continue
        ri = r[idx[k]]
        p0, p1, p2 = P6[3 * k], P6[3 * k + 1], P6[3 * k + 2]
        dy[7] += p0
        dy[8] += p1
        dy[9] += p2
        t0 += ri[1] * p2 - ri[2] * p1
        t1 += ri[2] * p0 - ri[0] * p2
        t2 += ri[0] * p1 - ri[1] * p0
    dy[10] = al[0] + Iinv[0, 0] * t0 + Iinv[0, 1] * t1 + Iinv[0, 2] * t2
    dy[11] = al[1] + Iinv[1, 0] * t0 + Iinv[1, 1] * t1 + Iinv[1, 2] * t2
    dy[12] = al[2] + Iinv[2, 0] * t0 + Iinv[2, 1] * t1 + Iinv[2, 2] * t2
    dy[0], dy[1], dy[2] = y[7], y[8], y[9]
    w0, w1, w2 = y[10], y[11], y[12]
    qw, qx, qy, qz = y[3], y[4], y[5], y[6]
    dy[3] = -0.5 * (w0 * qx + w1 * qy + w2 * qz)
    dy[4] = 0.5 * (qw * w0 + w1 * qz - w2 * qy)
    dy[5] = 0.5 * (qw * w1 + w2 * qx - w0 * qz)
    dy[6] = 0.5 * (qw * w2 + w0 * qy - w1 * qx)


@jitable
def _slip_rhs(model, y, F, sw, dy):
    """Time derivative ``dy`` of the state ``y`` (13) of a block on the corners ``sw.idx`` with the statuses
    ``sw.st`` (0 stuck, 1 slipping, 2 not in contact) under the body force ``F`` (m/s², per unit mass): the contact
    forces per unit mass solve :func:`_edge_system` at acceleration level (a stuck corner's acceleration zero, a
    slipping corner's normal acceleration zero and its force ``N (-mu_k s, 1)``, ``s`` its slip velocity's
    direction; with infinite friction :func:`_local`'s limit, ``mu_k = LIMIT_MU``), the corners' free
    accelerations ``F + alpha_f x r + omega x (omega x r)`` with ``alpha_f = -I^-1 (omega x I omega)``
    (:func:`_slip_free`). Returns ``(holds, friction power, stop time)`` (:func:`_slip_loads`): ``holds`` False
    unless every contact presses (``N > 0``) and a stuck corner's force lies in its static cone; the power (W/kg)
    the slipping corners' friction dissipates; the smallest of the slipping corners' speed over tangential
    acceleration (s). ``sw`` is its :class:`.workspace.SlipWork`."""
    D, A, cols, sdir = sw.D, sw.A, sw.cols, sw.sdir
    q, yv, P6 = sw.vec[EVEC_Q], sw.vec[EVEC_Y], sw.vec[EVEC_P6]
    fric = model.friction
    mu_s, mu_k = (np.inf, LIMIT_MU) if fric.infinite else (fric.mu_s, fric.mu_k)
    ok, al = _slip_free(model, y, F, sw)
    if not ok:
        return False, 0.0, 0.0
    m = _edge_system(sw.st, sdir, mu_k, D, q, A, yv, cols)
    if not _solve_n(A, yv, m):
        return False, 0.0, 0.0
    for a in range(6):
        acc = 0.0
        for c in range(m):
            acc += cols[c, a] * yv[c]
        P6[a] = acc
    holds, power, t_stop = _slip_loads(sw, mu_s)
    _slip_derivative(y, F, al, sw, dy)
    return holds, power, t_stop


@jitable
def _slip_integrate(model, floor, s, k0, n_steps, new, sw):
    """Classical Runge-Kutta from state ``s`` at Moreau-Jean step ``k0`` over ``n_steps`` steps on the slipping
    (and stuck) corners ``sw.idx`` / ``sw.st`` (:func:`_slip_rhs`) into ``new``, in sub-steps of at most
    ``pivot.RK_DTAU``. Returns ``(largest tilt at the sub-steps' ends (rad), friction work (J/kg))``, the tilt -1
    as soon as a stage's forces stop holding (:func:`_slip_rhs`), a corner not in contact reaches the floor or
    the tilt reaches pi/2. ``sw`` is the workspace of :func:`_slip_rhs` and ``(dy, acc, ytmp, F)``."""
    dy, acc, ytmp, F = sw.dy, sw.acc, sw.ytmp, sw.F
    r, idx, st = sw.r, sw.idx, sw.st
    g, dt, theta_mj = model.body.g, model.numerics.dt, model.numerics.theta_mj
    _copy(new, s)
    PV.floor_at(floor, float(k0), k0, theta_mj, F, g)
    holds, _, t_stop = _slip_rhs(model, new, F, sw, dy)
    span = n_steps * dt
    if not holds or t_stop <= 0.0 or span * SLIP_TURN > n_steps * t_stop:  # (the last: a sub-step under dt)
        return -1.0, 0.0
    n_sub = max(1, int(math.ceil(span * model.body.p / PV.RK_DTAU)), int(math.ceil(span * SLIP_TURN / t_stop)))
    hs = n_steps / n_sub
    hdt = hs * dt
    if hs < SLIP_MIN_SUB:
        return -1.0, 0.0
    work = 0.0
    tilt_max = _tilt(new, NO)[0]
    for m in range(n_sub):
        kf = k0 + m * hs
        for stage in range(4):
            c = 0.0 if stage == 0 else (0.5 if stage < 3 else 1.0)
            w = 1.0 / 6.0 if (stage == 0 or stage == 3) else 1.0 / 3.0
            for a in range(13):
                ytmp[a] = new[a] + (c * hdt * dy[a] if stage > 0 else 0.0)
            PV.floor_at(floor, kf + c * hs, k0, theta_mj, F, g)
            holds, power, t_stop = _slip_rhs(model, ytmp, F, sw, dy)
            if not holds or 0.5 * SLIP_TURN * hdt > t_stop:
                return -1.0, 0.0
            work += w * hdt * power
            for a in range(13):
                acc[a] = (w * dy[a]) if stage == 0 else acc[a] + w * dy[a]
        for a in range(13):
            new[a] += hdt * acc[a]
        nq = math.sqrt(new[3] * new[3] + new[4] * new[4] + new[5] * new[5] + new[6] * new[6])
        for a in range(3, 7):
            new[a] /= nq
        tilt = _tilt(new, NO)[0]
        if tilt >= OVERTURNING_ANGLE:
            return -1.0, 0.0
        tilt_max = max(tilt_max, tilt)
        _arms(new, model.body, sw.Q, r)
        for i in range(4):
            mine = (i == idx[0] and st[0] != 2) or (i == idx[1] and st[1] != 2)
            if not mine and new[2] + r[i, 2] <= 0.0:
                return -1.0, 0.0
    # the contact corners back on the floor as the next Moreau-Jean step predicts them (their normal
    # acceleration is zero, so their gaps drift only by the initial normal velocity and round-off)
    shift = 0.0
    for k in range(2):
        if st[k] != 2:
            ri = r[idx[k]]
            un = new[9] + new[10] * ri[1] - new[11] * ri[0]
            shift = max(shift, new[2] + ri[2] + 0.5 * dt * un)
    if shift > 0.0:
        new[2] -= shift + SETDOWN_MARGIN
    return tilt_max, work


@jitable
def _slip_pivot(act, touch, slip, P):
    """After a Moreau-Jean step: one corner or two down, exactly those solved in contact, loaded, at least one
    slipping (the phase :func:`_smooth_slip` integrates)."""
    n = 0
    sl = False
    for i in range(4):
        if act[i] != touch[i] or (touch[i] and P[i, 2] <= 0.0):
            return False
        n += touch[i]
        sl = sl or (touch[i] and slip[i])
    return sl and (n == 1 or n == 2)


@numba.njit(cache=True, inline='always')
def _same_slip(model, new, a, ws, end, probe, sw):
    """Is the end state ``new`` of a smooth step on slipping corners still in its phase? Every corner not in
    contact above ``lift_gap``, and a Moreau-Jean probe step from it (``a``: its floor accelerations) solved with
    exactly the contact corners active, each loaded, slipping where it slipped (along the direction it slipped,
    in the half-plane of the end state's slip velocity) and stuck where it stuck (the contact corners ``sw.idx``
    with the statuses ``sw.st``). ``probe``, ``ws`` and ``end`` as in :func:`_same_phase`."""
    actp, Pp, sp, outp = probe.act, probe.P, probe.state, probe.out
    idx, st = sw.idx, sw.st
    guess = ws.contact.mask
    for i in range(4):
        guess[i] = (i == idx[0] and st[0] != 2) or (i == idx[1] and st[1] != 2)
    _arms(new, model.body, end.Q1, end.r1)
    for i in range(4):
        if not guess[i] and new[2] + end.r1[i, 2] <= model.limits.lift_gap:
            return False
    outp[:] = 0.0
    sweeps = _step(model, new, (a[0], a[1], a[2]), model.numerics.dt, ws, probe, guess)
    if sweeps == 0 or sweeps > model.nsgs.max_sweeps:
        return False
    u = sw.vec[EVEC_U]  # the end state's corner velocities, from its last _slip_rhs (the arms of ``new``)
    for k in range(2):
        i = idx[k]
        if st[k] == 2:
            continue
        if not actp[i] or Pp[i, 2] <= 0.0:
            return False
        ri = ws.contact.r[i]  # the probe's arms
        u0 = sp[7] + sp[11] * ri[2] - sp[12] * ri[1]
        u1 = sp[8] + sp[12] * ri[0] - sp[10] * ri[2]
        sl = math.hypot(u0, u1) > model.limits.velocity_tol
        if sl != (st[k] == 1) or (sl and u0 * u[3 * k] + u1 * u[3 * k + 1] <= 0.0):
            return False
    for i in range(4):  # (``guess`` is the contact solver's workspace: the membership again)
        if actp[i] and not ((i == idx[0] and st[0] != 2) or (i == idx[1] and st[1] != 2)):
            return False
    return True


@numba.njit(cache=True, inline='always')
def _smooth_slip(model, floor, state, k, work, corners, trial):
    """A smooth step on one or two corners of which at least one slips (:func:`_slip_integrate`): from ``k`` to
    the next sample (at most ``pivot.MAX_DTAU``), halved while it leaves its phase (:func:`_same_slip`,
    :func:`_halved`). Returns ``(steps, largest tilt)`` as :func:`_smooth` does, with its arguments; the friction
    work into ``trial.out``."""
    ws = work.step  # (each taken apart once, as in _smooth)
    end = work.end
    sw = work.slip
    probe = work.probe
    touch, slip = corners.touch, corners.slip
    P, new, out = trial.P, trial.state, trial.out
    n_max = max(PV.MIN_STEPS, int(PV.MAX_DTAU / (model.body.p * model.numerics.dt)))
    idx, st = sw.idx, sw.st
    n_c = ZERO
    for i in range(4):
        if touch[i]:
            if n_c == 2:
                return 0, 0.0
            idx[n_c] = i
            st[n_c] = 1 if slip[i] else 0
            n_c += 1
    if n_c == 0:
        return 0, 0.0
    if n_c == 1:
        idx[1], st[1] = (idx[0] + 1) % 4, 2
    n = _span(floor, k, n_max)
    if n < 0:
        return -1, 0.0
    a = end.a
    Pp = probe.P
    while True:
        out[OUT_SLIP_TRIED] += 1.0
        tilt, fw = _slip_integrate(model, floor, state, k, n, new, sw)
        if tilt >= 0.0:
            a[0], a[1], a[2] = _floor(floor, k + n, model.numerics.theta_mj)
            _copy(Pp, P)
            if _same_slip(model, new, a, ws, end, probe, sw):
                _copy(P, Pp)
                out[OUT_SLIP_STEPS] += 1.0
                out[OUT_SLIP_SPAN] += n
                out[OUT_FRICTION_WORK] += fw
                return n, tilt
        n = _halved(n)
        if n == 0:
            return 0, 0.0


@jitable
def _coarse_steps(model):
    """The longest coarse Moreau-Jean step of a block sliding flat (:func:`_coarse_slide`), in Moreau-Jean steps:
    ``pivot.SLIDE_DTAU``, at least two."""
    return max(2, int(PV.SLIDE_DTAU / (model.body.p * model.numerics.dt)))


@numba.njit(cache=True, inline='always')
def _coarse_slide(model, floor, state, k, work, corners, trial):
    """A block sliding flat on its four corners: one Moreau-Jean step of up to :func:`_coarse_steps` steps (to the
    next sample) into ``trial.state``, kept if its contact problem is the same, all four corners active, solved by
    the closed-form flat slide or stick (:mod:`.pivot`, ``SLIDE_DTAU``) and kept on the floor (no corner's normal
    velocity above ``vel_tol``; a corner may carry none of the load, the four corners' loads being indeterminate).
    Returns the steps taken (0: none kept, -1: none tried); arguments as :func:`_smooth`'s."""
    ws = work.step  # (each taken apart once, as in _smooth)
    end = work.end
    probe = work.probe
    vel_tol = model.limits.velocity_tol
    P, new, out = trial.P, trial.state, trial.out
    n = _span(floor, k, _coarse_steps(model))
    if n < 0:
        return -1
    a = end.a
    PV.mean_floor(floor, k, n, model.numerics.theta_mj, a)
    actp, Pp, outp = probe.act, probe.P, probe.out
    for i in range(4):
        for c in range(3):
            Pp[i, c] = P[i, c] * n
    outp[:] = 0.0
    sweeps = _step(model, state, (a[0], a[1], a[2]), n * model.numerics.dt, ws, Probe(actp, Pp, new, outp),
                   corners.touch)
    if sweeps != 1 or outp[OUT_SLIDE_STEPS] + outp[OUT_STICK_STEPS] < 0.5:
        return 0
    for i in range(4):  # every corner active and kept on the floor (a corner may carry no load: see _slide_flat)
        ri = ws.contact.r[i]
        if not actp[i] or abs(new[9] + new[10] * ri[1] - new[11] * ri[0]) > vel_tol:
            return 0
    _book(state, Probe(actp, Pp, new, out), ws.contact, end, corners, model)
    for i in range(4):
        for c in range(3):
            P[i, c] = Pp[i, c] / n
    out[OUT_SLIDE_STEPS] += outp[OUT_SLIDE_STEPS]
    out[OUT_STICK_STEPS] += outp[OUT_STICK_STEPS]
    out[OUT_COARSE_STEPS] += 1.0
    out[OUT_COARSE_SPAN] += n
    return n
