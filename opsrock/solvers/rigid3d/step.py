"""The Moreau-Jean step and its bookkeeping (numba): the free velocity, the active corners, the contact problem by the
closed forms or NSGS, the update; then the input and friction work, the corners' contact and slip flags and an
impact's loss; the rest skip's test. Units and frames as in :mod:`opsrock.solvers.rigid3d.kernel` (SI, per unit
mass).
"""

from __future__ import annotations

import math

import numba

from opsrock.solvers.jitable import jitable
from opsrock.solvers.rigid3d.constants import (FORCING_LINEAR, FORCING_STEPWISE, NO, OUT_CONTACT_STEPS, OUT_EDGE_SLIP,
                                               OUT_FRICTION_WORK, OUT_IMPACTS, OUT_IMPACT_LOSS, OUT_INPUT_WORK,
                                               OUT_MAX_PENETRATION, OUT_NSGS_FAILED, OUT_NSGS_MAX, OUT_NSGS_SWEEPS,
                                               OUT_SLIDE_STEPS, OUT_STICK_STEPS, YES, ZERO)
from opsrock.solvers.rigid3d.geometry import (_arms, _cross_add, _delassus, _geometry, _inv3, _quat_step)
from opsrock.solvers.rigid3d.contact import _solve_contacts
from opsrock.solvers.rigid3d.sticking import (_stick_all, _stick_single, _stick_subset)
from opsrock.solvers.rigid3d.sliding import (_edge_slip, _slide_flat)
from opsrock.solvers.rigid3d.workspace import (VEC_OM, VEC_V, VEC_VF)


@jitable
def _floor(floor, k, theta_mj):
    """Floor accelerations ``(a_x, a_y, a_v)`` (m/s²) of ``floor`` (:class:`.model.Floor`) at the evaluation time
    ``(k + theta_mj) dt`` of step ``k``."""
    ax, ay, av, sub = floor.ax, floor.ay, floor.av, floor.sub
    if k >= floor.n_exc:
        return 0.0, 0.0, floor.tail_av
    if floor.form == FORCING_STEPWISE:
        return ax[k], ay[k], av[k]
    j = k // sub
    f = (k - j * sub + theta_mj) / sub
    return (ax[j] + f * (ax[j + 1] - ax[j]), ay[j] + f * (ay[j + 1] - ay[j]), av[j] + f * (av[j + 1] - av[j]))


@numba.njit(cache=True, inline='always')
def _free_velocity(s, acc, dt, g, cw):
    """The free velocity of a step from ``s`` under the floor accelerations ``acc = (a_x, a_y, a_v)`` (m/s²):
    gravity and the floor's inertia force on the centre of mass, the gyroscopic torque ``-omega x I omega`` at
    ``t_k``, into ``cw.vec`` rows ``VEC_V``, ``VEC_OM`` (where the impulses then add) and ``VEC_VF`` (kept); ``cw``
    (:class:`.workspace.Contact`) holds the inertia of ``s``."""
    Iinv, Iw, vec = cw.Iinv, cw.Iw, cw.vec
    V = vec[VEC_V]
    Om = vec[VEC_OM]
    V[0], V[1], V[2] = s[7] - dt * acc[0], s[8] - dt * acc[1], s[9] - dt * (g + acc[2])
    w0, w1, w2 = s[10], s[11], s[12]
    L0 = Iw[0, 0] * w0 + Iw[0, 1] * w1 + Iw[0, 2] * w2
    L1 = Iw[1, 0] * w0 + Iw[1, 1] * w1 + Iw[1, 2] * w2
    L2 = Iw[2, 0] * w0 + Iw[2, 1] * w1 + Iw[2, 2] * w2
    g0, g1, g2 = -(w1 * L2 - w2 * L1), -(w2 * L0 - w0 * L2), -(w0 * L1 - w1 * L0)
    for a in range(3):
        Om[a] = s[10 + a] + dt * (Iinv[a, 0] * g0 + Iinv[a, 1] * g1 + Iinv[a, 2] * g2)
    vf = vec[VEC_VF]
    vf[0], vf[1], vf[2], vf[3], vf[4], vf[5] = V[0], V[1], V[2], Om[0], Om[1], Om[2]


@numba.njit(cache=True, inline='always')
def _closed_form(ws, act, n_act, guess, P, fric, tol, out):
    """The step's contact problem by a closed form, tried in turn (docs/guide/three-dimensions.md): the corners that
    were down (``guess``) alone stuck, or else those that were not (:func:`_stick_subset`: a block rocking on an
    edge just after an impact has its other corners still predicted active, unloaded and separating); every active
    corner stuck (:func:`_stick_all`); on two corners each alone stuck (:func:`_stick_single`), then one or both
    slipping (:func:`_edge_slip`); on three or four all slipping (:func:`_slide_flat`). Returns True, counted in
    ``out``, if one solved it (into ``ws.contact.vec`` rows ``VEC_V``, ``VEC_OM`` and ``P``; a tried one may have
    written them); ``tol`` (m/s) the separation allowed."""
    cw = ws.contact
    n_down = 0  # the active corners that were down: a subset to try alone (_stick_subset) if one or two, not all
    for i in range(4):
        n_down += act[i] and guess[i]
    try_down = 0 < n_down <= 2 and n_down < n_act
    try_landing = 0 < n_act - n_down <= 2 and n_down > 0
    if n_act >= 2 and ((try_down and _stick_subset(cw, act, guess, NO, n_act, P, fric, tol))
                       or (try_landing and _stick_subset(cw, act, guess, YES, n_act, P, fric, tol))):
        out[OUT_STICK_STEPS] += 1.0
    elif n_act >= 2 and _stick_all(cw, act, n_act, P, fric):
        out[OUT_STICK_STEPS] += 1.0
    elif n_act == 2 and _stick_single(cw, act, P, fric, tol):
        out[OUT_STICK_STEPS] += 1.0
    elif n_act == 2 and _edge_slip(cw, ws.edge, act, P, fric, out):
        out[OUT_EDGE_SLIP] += 1.0
    elif n_act >= 3 and not fric.infinite and _slide_flat(cw, act, P, fric.mu_k, ws.sdir, ws.Am):
        out[OUT_SLIDE_STEPS] += 1.0
    else:
        return False
    return True


@numba.njit(cache=True, inline='always')
def _gauss_seidel(cw, act, n_act, P, fric, tol, nsgs, out):
    """The step's contact problem by NSGS (:func:`_solve_contacts`): the active corners' Delassus blocks at ``q_k``,
    the velocity warm-started from the impulses ``P`` (an inactive corner's zeroed). Returns the sweeps."""
    r, Iinv, Wd, Wi, vec = cw.r, cw.Iinv, cw.Wd, cw.Wi, cw.vec
    V, Om, vf = vec[VEC_V], vec[VEC_OM], vec[VEC_VF]
    V[0], V[1], V[2], Om[0], Om[1], Om[2] = vf[0], vf[1], vf[2], vf[3], vf[4], vf[5]
    for i in range(4):
        if act[i]:
            _delassus(r[i], Iinv, Wd[i])
            _inv3(Wd[i], Wi[i])
            V[0] += P[i, 0]
            V[1] += P[i, 1]
            V[2] += P[i, 2]
            _cross_add(r[i], P[i], Iinv, Om, 1.0)
        else:
            P[i, 0], P[i, 1], P[i, 2] = 0.0, 0.0, 0.0
    return _solve_contacts(cw, act, P, fric, tol, nsgs, out, n_act == 1)


@jitable
def _step(model, s, acc, dt, ws, trial, guess):
    """One Moreau-Jean step of length ``dt`` (s) from ``s`` under the floor accelerations ``acc = (a_x, a_y, a_v)``
    (m/s²) into ``trial`` (:class:`.workspace.Probe`: the active corners, the impulses ``P``, warm start on entry,
    the end state and the bookkeeping; docs/guide/three-dimensions.md): the free velocity
    (:func:`_free_velocity`), the active corners from the mid-step prediction of their gaps, the impulses by a
    closed form (:func:`_closed_form`, the corners down before the step ``guess`` tried alone first) or NSGS
    (:func:`_gauss_seidel`), then ``X_{k+1} = X_k + dt [(1 - theta_mj) V_k + theta_mj V_{k+1}]`` and the quaternion
    turned by ``dt`` times the same blend of the angular velocities. Returns the sweeps (0: no contact; 1: a closed
    form; ``model.nsgs.max_sweeps + 1``: NSGS did not converge). ``ws`` is the step's
    :class:`.workspace.StepWork`."""
    act, P, new, out = trial.act, trial.P, trial.state, trial.out
    body, fric, nsgs, theta_mj = model.body, model.friction, model.nsgs, model.numerics.theta_mj
    cw = ws.contact
    r, vec = cw.r, cw.vec
    _geometry(s, body, ws.Q, cw.Iinv, cw.Iw, r)
    _free_velocity(s, acc, dt, body.g, cw)
    V, Om, vf = vec[VEC_V], vec[VEC_OM], vec[VEC_VF]
    n_act = ZERO
    for i in range(4):
        ri = r[i]
        un = s[9] + s[10] * ri[1] - s[11] * ri[0]
        act[i] = s[2] + ri[2] + 0.5 * dt * un <= 0.0
        n_act += act[i]
    scale = max(body.g * dt, abs(vf[0]), abs(vf[1]), abs(vf[2]), body.R * (abs(vf[3]) + abs(vf[4]) + abs(vf[5])))
    tol = nsgs.tol * scale
    sweeps = 0
    if n_act >= 2 and _closed_form(ws, act, n_act, guess, P, fric, tol, out):
        sweeps = 1
    elif n_act > 0:
        sweeps = _gauss_seidel(cw, act, n_act, P, fric, tol, nsgs, out)
    else:
        for i in range(4):
            P[i, 0], P[i, 1], P[i, 2] = 0.0, 0.0, 0.0
    for a in range(3):
        new[a] = s[a] + dt * ((1.0 - theta_mj) * s[7 + a] + theta_mj * V[a])
        new[7 + a] = V[a]
        new[10 + a] = Om[a]
    _quat_step(s, (1.0 - theta_mj) * s[10] + theta_mj * Om[0], (1.0 - theta_mj) * s[11] + theta_mj * Om[1],
               (1.0 - theta_mj) * s[12] + theta_mj * Om[2], dt, new)
    return sweeps


@numba.njit(cache=True, inline='always')
def _contacts(new, cw, end, act, P, corners, limits, out):
    """After a step: friction work of the impulses, and each corner's contact and slip flags (``corners``:
    :class:`.workspace.Corners`; the arms ``cw.r`` of the step's start: the velocity rows the solver enforced;
    ``end.r1`` those of its end, for the gaps); returns True if a corner landed (an impact).

    A corner with a normal impulse is down (an impact if it was up), slipping if its tangential speed exceeds
    ``limits.velocity_tol``. A corner without impulse is up once it moves away from the floor faster than that or
    rises above ``limits.lift_gap``; otherwise it stays down (a pivot constrained at velocity level drifts up and
    takes an occasional free step; a level block may rest on three corners), slipping if it moves."""
    r, r1, touch, slip = cw.r, end.r1, corners.touch, corners.slip
    vel_tol, lift_gap = limits.velocity_tol, limits.lift_gap
    impact = False
    V0, V1, V2, w0, w1, w2 = new[7], new[8], new[9], new[10], new[11], new[12]
    for i in range(4):
        ri = r[i]
        u0 = V0 + w1 * ri[2] - w2 * ri[1]
        u1 = V1 + w2 * ri[0] - w0 * ri[2]
        u2 = V2 + w0 * ri[1] - w1 * ri[0]
        gap = new[2] + r1[i, 2]
        if act[i]:
            out[OUT_FRICTION_WORK] -= P[i, 0] * u0 + P[i, 1] * u1
        if P[i, 2] > 0.0:
            impact = impact or not touch[i]
            touch[i] = True
            slip[i] = math.hypot(u0, u1) > vel_tol
            out[OUT_MAX_PENETRATION] = max(out[OUT_MAX_PENETRATION], -gap)
        elif u2 > vel_tol or gap > lift_gap:
            touch[i] = False
            slip[i] = False
        elif touch[i]:  # down without load (a level block on three corners): slipping if it moves
            slip[i] = math.hypot(u0, u1) > vel_tol
    return impact


@jitable
def _rest_holds(a_x, a_y, a_v, body, fric):
    """Does a block at rest on its four corners, stuck, stay at rest under the floor accelerations? Iff
    ``g + a_v > 0``, the centre of pressure ``(a_x, a_y) h / (g + a_v)`` lies in the base ``[-b, b] x [-d, d]``
    and friction carries the load, ``hypot(a_x, a_y) <= mu (g + a_v)``."""
    gz = body.g + a_v
    if gz <= 0.0:
        return False
    h = body.h
    if abs(a_x) * h > body.b * gz or abs(a_y) * h > body.d * gz:
        return False
    return fric.infinite or math.hypot(a_x, a_y) <= fric.mu_s * gz


@jitable
def _count_sweeps(sweeps, nsgs, out):
    """A Moreau-Jean step's contact-solver counts (:func:`_step`'s ``sweeps``); returns True if it converged."""
    if sweeps > 0:
        out[OUT_CONTACT_STEPS] += 1.0
        out[OUT_NSGS_SWEEPS] += min(sweeps, nsgs.max_sweeps)
        out[OUT_NSGS_MAX] = max(out[OUT_NSGS_MAX], min(sweeps, nsgs.max_sweeps))
    converged = sweeps <= nsgs.max_sweeps
    if not converged:
        out[OUT_NSGS_FAILED] += 1.0
    return converged


@numba.njit(cache=True, inline='always')
def _book(state, trial, cw, end, corners, model):
    """The bookkeeping of a Moreau-Jean step from ``state`` to ``trial.state`` under the accelerations ``end.a`` with
    the active corners ``trial.act`` and impulses ``trial.P``, into ``trial.out``: input work, the corners' flags
    (``corners``) and friction work (:func:`_contacts`), an impact's loss. ``cw`` (the step's
    :class:`.workspace.Contact`) holds its arms ``r``, inertia ``Iw`` and free velocity (row ``VEC_VF``); the arms
    of the end state into ``end.r1`` (``end.Q1`` workspace). Returns True at an impact. Takes the contact arrays,
    not the whole :class:`.workspace.StepWork`: an inline function's parameters are counted too (issue 43)."""
    act, P, new, out = trial.act, trial.P, trial.state, trial.out
    a, Iw, vf = end.a, cw.Iw, cw.vec[VEC_VF]
    # energy bookkeeping (per unit mass): input work over the step's displacement, friction work in
    # _contacts, and at an impact the kinetic energy of the impulses' velocity change
    out[OUT_INPUT_WORK] -= a[0] * (new[0] - state[0]) + a[1] * (new[1] - state[1]) + a[2] * (new[2] - state[2])
    _arms(new, model.body, end.Q1, end.r1)
    impact = _contacts(new, cw, end, act, P, corners, model.limits, out)
    if impact:
        e = 0.0
        for c in range(3):
            dv = new[7 + c] - vf[c]
            e += 0.5 * dv * dv
            for c2 in range(3):
                e += 0.5 * (new[10 + c] - vf[3 + c]) * Iw[c, c2] * (new[10 + c2] - vf[3 + c2])
        out[OUT_IMPACT_LOSS] += e
        out[OUT_IMPACTS] += 1.0
    return impact


@jitable
def _rest_span(model, floor, k, tail_left):
    """Steps a seated block whose load the base carries at step ``k`` stays at rest (>= 1): a record's whole
    sample interval from its start if the base carries the load at both samples, the tail's remaining rest
    steps ``tail_left`` under a still floor, else one."""
    ax, ay, av, sub, body, fric = floor.ax, floor.ay, floor.av, floor.sub, model.body, model.friction
    if k >= floor.n_exc:
        return max(1, min(tail_left, model.limits.max_steps - k))
    if floor.form == FORCING_LINEAR and k % sub == 0:
        jj = k // sub
        if _rest_holds(ax[jj], ay[jj], av[jj], body, fric) and _rest_holds(ax[jj + 1], ay[jj + 1], av[jj + 1],
                                                                            body, fric):
            return sub
    return 1
