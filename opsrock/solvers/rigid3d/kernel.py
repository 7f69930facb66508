"""Compiled kernel of :mod:`opsrock.solvers.rigid3d` (numba): Moreau-Jean time stepping of a rigid box on a
rigid floor with its four base corners as contacts, Newton's impact law with ``e_n = 0`` and isotropic Coulomb
friction, the contact problem of each step solved by nonsmooth Gauss-Seidel (docs/guide/three-dimensions.md).

Everything here is per unit mass: positions in m, velocities in m/s and rad/s, impulses in m/s (N s per kg),
energies in J/kg, inertias in m² (``I / m``). Frames: the floor frame ``(x, y, z)`` is the block frame at rest
(``x`` along the width, ``y`` along the depth, ``z`` up, origin at the base centre at rest); the floor's
accelerations enter as the body force ``(-a_x, -a_y, -(g + a_v))``.

State (13 floats): centre of mass ``X`` (3, floor frame), orientation as a unit quaternion ``q = (w, x, y, z)``
(body to floor), CM velocity ``V`` (3) and angular velocity ``omega`` (3, floor frame). The inertia is diagonal
in the body frame, ``I_b = diag(I_x, I_y, I_z)``; in the floor frame ``I = Q I_b Q^T`` (``Q`` the rotation
matrix of ``q``).

Corner ``i`` sits at ``c_i = (sx_i b, sy_i d, -h)`` in the body frame (``h`` the height of the centre of mass
above the base), at ``r_i = Q c_i`` from the centre of mass; its velocity is ``u_i = V + omega x r_i``, its gap
the height ``X_z + r_i,z``. The contact frame is the floor's: tangents ``x``, ``y``, normal ``z``. An impulse
``P_j`` at corner ``j`` changes ``u_i`` by ``W_ij P_j``, ``W_ij = 1 - S_i I^-1 S_j`` (``S`` the cross-product
matrix of ``r``).

Only :func:`run` is a numba dispatcher (``cache=True``); every function it calls, here and in the modules it imports, is
a :data:`opsrock.solvers.jitable.jitable` helper (numba's ``register_jitable``, without a C-callable wrapper) compiled
into it, without the CPython wrapper a dispatcher gets (the conversion of each argument from a Python object, every
array of a named tuple) whether or not Python calls it: those wrappers were about a fifth of the cold compile (issue
43). Called from Python (as the closed-form tests do), a helper runs as plain Python.
"""

from __future__ import annotations

import math

import numba

from opsrock.solvers.jitable import jitable
from opsrock.solvers.rigid3d.constants import (ALIGN_TOL, CONE_SLACK, CORNER_SX, CORNER_SY, DIRECTION_TOL,
                                               EDGE_STATUSES, FD_STEP, FLAT_ROUNDOFF, FORCING_LINEAR,
                                               FORCING_STEPWISE, FOUR, H_DOWN, H_POS, H_ROT, H_SIZE, H_SLIDE, H_T,
                                               H_THETA, H_THETA_DOT, H_TWIST, LIMIT_MU, MODE_FLIGHT, MODE_REST,
                                               MODE_ROCK, MODE_SLIDE, MODE_SLIDE_ROCK, NEWTON_TOL, NO, ONE,
                                               OUT_COARSE_SPAN, OUT_COARSE_STEPS, OUT_CONTACT_STEPS, OUT_EDGE_SLIP,
                                               OUT_EVENT_TIME, OUT_FIRST_MODE, OUT_FRICTION_WORK, OUT_IMPACTS,
                                               OUT_IMPACT_LOSS, OUT_INPUT_WORK, OUT_LIMIT_STEPS, OUT_MAX_PENETRATION,
                                               OUT_NEEDS_FLAT, OUT_NSGS_EXTRA, OUT_NSGS_FAILED, OUT_NSGS_LOOSE,
                                               OUT_NSGS_MAX, OUT_NSGS_SWEEPS, OUT_N_HIST, OUT_OVERTURNED, OUT_OVER_DIR,
                                               OUT_OVER_KIND, OUT_PEAK_STOP, OUT_REST_STEPS, OUT_ROCKED, OUT_SETTLED,
                                               OUT_SETTLE_GAP, OUT_SIZE, OUT_SLIDE_MAX, OUT_SLIDE_STEPS,
                                               OUT_SLIP_SPAN, OUT_SLIP_STEPS, OUT_SLIP_TRIED, OUT_SMOOTH_SPAN,
                                               OUT_SMOOTH_STEPS, OUT_SMOOTH_TRIED, OUT_STATE, OUT_STATUS, OUT_STEPS,
                                               OUT_STICK_STEPS, OUT_THETA_MAX, OUT_TIME, OUT_TIME_CORNER,
                                               OUT_TIME_EDGE, OUT_TIME_FLIGHT, OUT_TIME_ROCKING, OUT_TIME_SLIDING,
                                               OUT_TWIST_MAX, PEAK_BASE_SPEED, PIVOT_TOL, REST_MODE, SECULAR_TOL,
                                               SETDOWN_MARGIN, SETTLE_GAP, SIX, SLIP_ANGLE_TOL, SLIP_MIN_SUB,
                                               SLIP_STEP_TOL, SLIP_TURN, STATUS_CONTACT, STATUS_MAX_STEPS,
                                               STATUS_NONFINITE, STATUS_OK, STATUS_TAIL, TWO, YES,
                                               ZERO)  # noqa: F401  (the layout, re-exported)
from opsrock.constants import OVERTURNING_ANGLE
from opsrock.solvers.rigid3d import pivot as PV
from opsrock.solvers.rigid3d.constants import (PH_LAST_DOWN, PH_OUTSIDE, PH_OVER_KIND, PH_PIVOT, PH_RESTING, PH_SEATED,
                                               PH_SIZE, PH_SLIDE, PH_SLIP, PH_UNCONVERGED, SLIDE_DUE)
from opsrock.solvers.rigid3d.geometry import (_arms, _cm_outside, _geometry, _tilt, _twist)
from opsrock.solvers.rigid3d.step import (_book, _count_sweeps, _floor, _rest_holds, _rest_span, _step)
from opsrock.solvers.rigid3d.smooth import (_coarse_slide, _coarse_steps, _copy, _flat_slip, _slip_pivot, _smooth,
                                            _smooth_slip, _stuck_pivot)
from opsrock.solvers.rigid3d.model import Floor
from opsrock.solvers.rigid3d.workspace import (ARENA_BYTES, make_corners, make_phase, make_trial, make_workspace)
from opsrock.solvers.scratch import keep_alive, make_arena, unmanaged


@jitable
def _record(hist, t, s, theta, theta_dot, down, h, out):
    """Store one history sample, column ``j`` of ``hist`` (a row per quantity, ``H_*``), if there is room
    (``out[OUT_N_HIST]``: the samples stored, counted on)."""
    j = int(out[OUT_N_HIST])
    if j >= hist.shape[1]:
        return
    w, x, y, z = s[3], s[4], s[5], s[6]
    nv = math.sqrt(x * x + y * y + z * z)
    ang = 2.0 * math.atan2(nv, w)
    f = ang / nv if nv > 0.0 else 2.0
    hist[H_T, j] = t
    hist[H_THETA, j] = theta
    hist[H_THETA_DOT, j] = theta_dot
    hist[H_ROT, j], hist[H_ROT + 1, j], hist[H_ROT + 2, j] = f * x, f * y, f * z
    hist[H_POS, j], hist[H_POS + 1, j], hist[H_POS + 2, j] = s[0], s[1], s[2] - h
    hist[H_TWIST, j] = _twist(s)
    q02, q12 = 2.0 * (x * z + w * y), 2.0 * (y * z - w * x)
    hist[H_SLIDE, j], hist[H_SLIDE + 1, j] = s[0] - h * q02, s[1] - h * q12
    hist[H_DOWN, j] = down
    out[OUT_N_HIST] = j + 1


@jitable
def _mode(touch, slip):
    """Contact mode (a ``MODE_*`` index) and corners down from the corners' contact and slip flags."""
    n = 0
    sl = False
    for i in range(4):
        if touch[i]:
            n += 1
            sl = sl or slip[i]
    if n >= 3:
        return (MODE_SLIDE if sl else MODE_REST), n
    if n >= 1:
        return (MODE_SLIDE_ROCK if sl else MODE_ROCK), n
    return MODE_FLIGHT, n


@jitable
def _tally(mode, n_down, dt, out):
    """First mode left rest into, and the times in each state."""
    if mode != MODE_REST and out[OUT_FIRST_MODE] < 0.0:
        out[OUT_FIRST_MODE] = mode
    if mode == MODE_SLIDE or mode == MODE_SLIDE_ROCK:
        out[OUT_TIME_SLIDING] += dt
    if mode == MODE_ROCK or mode == MODE_SLIDE_ROCK:
        out[OUT_TIME_ROCKING] += dt
    if n_down == 2:
        out[OUT_TIME_EDGE] += dt
    elif n_down == 1:
        out[OUT_TIME_CORNER] += dt
    elif n_down == 0:
        out[OUT_TIME_FLIGHT] += dt


@jitable
def _settle(state, touch, body, Q, r, gap_max, out):
    """A block at rest on three corners (``touch``) whose fourth hangs above the floor by at most ``gap_max`` (m):
    the gap is the Moreau-Jean steps' drift (a corner that rose above the contact gap while the block came to rest
    stays up, and the block would never be seated), so the block is set down level on all four, its base centre
    and twist kept (its centre of mass moves by at most ``gap_max``, its tilt by ``gap_max / min(2b, 2d)``). Returns
    True if it was (then seated by the caller). ``Q`` and ``r`` are workspace."""
    _arms(state, body, Q, r)
    up = -1
    for i in range(4):
        if not touch[i]:
            up = i
    if up < 0:
        return True
    gap = state[2] + r[up, 2]
    if not gap <= gap_max:
        return False
    h = body.h
    w, x, y, z = state[3], state[4], state[5], state[6]
    bx, by = state[0] - h * 2.0 * (x * z + w * y), state[1] - h * 2.0 * (y * z - w * x)
    tw = _twist(state)
    state[0], state[1], state[2] = bx, by, h
    state[3], state[4], state[5], state[6] = math.cos(0.5 * tw), 0.0, 0.0, math.sin(0.5 * tw)
    touch[up] = True
    out[OUT_SETTLED] += 1.0
    out[OUT_SETTLE_GAP] = max(out[OUT_SETTLE_GAP], gap)
    return True


@jitable
def _peak_reached(s, body, tilt_max, tail_av):
    """The tail rule "peak": after the excitation (a still floor, ``g' = g + tail_av``), the block's energy per
    unit mass above rest, bounded above by ``|V|²/2 + I_max |omega|²/2 + g' (z - h)``, can only fall; at a tilt
    ``theta`` its centre of mass stands at least ``h cos theta + min(b, d) sin theta`` above the floor. Once the
    bound is below half of ``g' (h cos theta_max + min(b, d) sin theta_max - h)`` (half: a margin for the
    scheme's energy error) and the base moves slower than :data:`PEAK_BASE_SPEED`, neither the verdict nor
    ``theta_max`` can change."""
    b, d, h, ib = body.b, body.d, body.h, body.inertia
    gp = body.g + tail_av
    i_max = max(ib[0], max(ib[1], ib[2]))
    w0, w1, w2 = s[10], s[11], s[12]
    e = 0.5 * (s[7] * s[7] + s[8] * s[8] + s[9] * s[9]) + 0.5 * i_max * (w0 * w0 + w1 * w1 + w2 * w2)
    e += gp * (s[2] - h)
    m = min(b, d)
    if e >= 0.5 * gp * (h * math.cos(tilt_max) + m * math.sin(tilt_max) - h):
        return False
    w, x, y, z = s[3], s[4], s[5], s[6]
    c0, c1, c2 = -h * 2.0 * (x * z + w * y), -h * 2.0 * (y * z - w * x), -h * (1.0 - 2.0 * (x * x + y * y))
    return math.hypot(s[7] + w1 * c2 - w2 * c1, s[8] + w2 * c0 - w0 * c2) < PEAK_BASE_SPEED


@numba.njit(cache=True, inline='always')
def _finite(state):
    """Is every component of the state finite (their sum is)?"""
    fin = 0.0
    for a in range(13):
        fin += state[a]
    return math.isfinite(fin)


@numba.njit(cache=True, inline='always')
def _in_phase(j, act, corners, P):
    """After a Moreau-Jean step: is the block in the phase ``j`` (``PH_PIVOT``, ``PH_SLIP``, ``PH_SLIDE``)?"""
    touch, slip = corners.touch, corners.slip
    if j == PH_PIVOT:
        return _stuck_pivot(act, touch, slip, P)
    if j == PH_SLIP:
        return _slip_pivot(act, touch, slip, P)
    return _flat_slip(act, touch, slip)


@numba.njit(cache=True, inline='always')
def _next_phase(phase, impact, act, corners, P):
    """The phase counts after a Moreau-Jean step (slots ``PH_PIVOT``, ``PH_SLIP``, ``PH_SLIDE`` of ``phase``): one
    more step in the phase the block is in if no corner landed (``impact``), the others back to 0; a cool-down
    (negative) counts up whatever the phase."""
    for j in range(PH_PIVOT, PH_SLIDE + 1):
        if phase[j] < 0:
            phase[j] += 1
        elif not impact and _in_phase(j, act, corners, P):
            phase[j] += 1
        else:
            phase[j] = 0


@numba.njit(cache=True, inline='always')
def _smooth_due(model, phase):
    """Is a smooth step due (:func:`_smooth_step`): smooth steps on and the block ``pivot.CALM_STEPS`` Moreau-Jean
    steps in a phase that has them (``phase``)? Tested apart, before the call: the call binds the whole workspace
    (52 arrays), and numba counts a reference to each, so calling it at every step took about a tenth of a 3-D case's
    CPU (issue 43)."""
    return model.numerics.smooth and max(phase[PH_PIVOT], phase[PH_SLIP], phase[PH_SLIDE]) >= PV.CALM_STEPS


@numba.njit(cache=True, inline='always')
def _smooth_step(model, floor, state, k, phase, work, corners, trial):
    """A smooth step of the phase the block has been in for ``pivot.CALM_STEPS`` Moreau-Jean steps (``phase``):
    about stuck corners (:func:`.smooth._smooth`), on slipping corners (:func:`.smooth._smooth_slip`), into
    ``trial``, with its input work; a phase whose smooth step failed cools down. Returns ``(steps, largest tilt)``,
    steps <= 0 if none was taken (the Moreau-Jean step then goes on), ``SLIDE_DUE`` if the phase is sliding flat
    (``run`` takes its coarse slide, :func:`_slide_step`). Called once :func:`_smooth_due` (smooth steps on, a phase
    calm): each branch drops ``work`` (52 arrays) once."""
    n, tilt_sub, smoothed = 0, 0.0, False
    F = work.pivot.F
    if phase[PH_PIVOT] >= PV.CALM_STEPS:
        n, tilt_sub = _smooth(model, floor, state, k, work, corners, trial)
        smoothed = n > 0
        if n == 0:
            phase[PH_PIVOT] = -4 * PV.MIN_STEPS  # none kept: the Moreau-Jean steps locate the event first
    elif phase[PH_SLIP] >= PV.CALM_STEPS:
        n, tilt_sub = _smooth_slip(model, floor, state, k, work, corners, trial)
        smoothed = n > 0
        if n == 0:
            phase[PH_SLIP] = -4 * PV.MIN_STEPS
    else:  # phase[PH_SLIDE] >= PV.CALM_STEPS
        n = SLIDE_DUE
    if smoothed:  # a smooth step's input work (the floor's force at its middle)
        g, new = model.body.g, trial.state
        PV.floor_at(floor, k + 0.5 * n, k, model.numerics.theta_mj, F, g)
        trial.out[OUT_INPUT_WORK] += F[0] * (new[0] - state[0]) + F[1] * (new[1] - state[1]) + \
            (F[2] + g) * (new[2] - state[2])
    return n, tilt_sub


@numba.njit(cache=True, inline='always')
def _slide_step(model, floor, state, k, phase, work, corners, trial):
    """The coarse Moreau-Jean step of a block sliding flat (:func:`.smooth._coarse_slide`; arguments as
    :func:`_smooth_step`'s); the phase cools down if none was kept. Returns the steps taken (0: none kept, -1: none
    tried). ``run`` calls it only where its ``flat`` is True: with None numba prunes the call on the argument's
    type (issue 43: 1.7-2.4 s of the kernel's first compile, measured twice), and :func:`_needs_flat` stands in."""
    n = _coarse_slide(model, floor, state, k, work, corners, trial)
    if n == 0:
        phase[PH_SLIDE] = -_coarse_steps(model)
    return n


@jitable
def _needs_flat(out):
    """In place of :func:`_slide_step` where ``run``'s ``flat`` is None (infinite friction: a block slides flat only in
    the friction's limit): marks the case for the specialisation with the coarse slide (``out[OUT_NEEDS_FLAT]``; the
    solver runs it again from its start with ``flat`` True) and takes no step. Returns 0."""
    out[OUT_NEEDS_FLAT] = 1.0
    return 0


@numba.njit(cache=True, inline='always')
def _mj_step(model, state, sweeps, cw, end, trial, corners, phase):
    """After a Moreau-Jean step (:func:`.step._step`, the corners down tried first; ``sweeps`` its contact solver's
    count) under the floor accelerations ``end.a``: its bookkeeping (:func:`.step._book`) and the phase counts after
    it (:func:`_next_phase`). Returns False once NSGS has failed ``nsgs.fail_steps`` steps in a row (the run fails).
    ``run`` calls the step itself and passes the contact arrays ``cw`` (:class:`.workspace.Contact`) only: numba
    counts a reference to every array of an inline function's parameters too (an atomic increment and decrement
    each), and the whole step workspace (19 arrays) passed here counted 11 more of each a step
    (issue 43)."""
    converged = _count_sweeps(sweeps, model.nsgs, trial.out)
    impact = _book(state, trial, cw, end, corners, model)
    if not converged:
        phase[PH_UNCONVERGED] += 1
        if phase[PH_UNCONVERGED] > model.nsgs.fail_steps:
            return False
    else:
        phase[PH_UNCONVERGED] = 0
    _next_phase(phase, impact, trial.act, corners, trial.P)
    return True


@numba.njit(cache=True, inline='always')
def _rest_skip(model, floor, k, state, theta, phase, hist, out):
    """The rest skip from step ``k`` (a seated, stuck block whose load the base carries stays at rest this step, and
    a whole sample interval of a record if it does at both its samples, and the whole rest of a still tail:
    :func:`.step._rest_span`), its history rows (``theta`` the block's signed tilt) and time at rest. Returns the
    step it ends at."""
    dt, hist_every = model.numerics.dt, model.numerics.hist_every
    n = _rest_span(model, floor, k, model.limits.rest_steps - phase[PH_RESTING])
    out[OUT_REST_STEPS] += n
    _tally(REST_MODE, FOUR, n * dt, out)
    # the history's steps in (k, k + n], the multiples of hist_every (stepped to, not tested one by one: a skip
    # spans up to the whole tail, and a remainder per step was a fifth of a 3-D case's CPU, issue 43)
    for kk in range((k // hist_every + 1) * hist_every, k + n + 1, hist_every):
        _record(hist, kk * dt, state, theta, 0.0, FOUR, model.body.h, out)
    k += n
    phase[PH_RESTING] = phase[PH_RESTING] + min(n, k - floor.n_exc + 1) if k >= floor.n_exc else 0
    return k


@jitable
def _start(model, state, ws, corners, phase, hist, out):
    """The run's start from ``state``: ``out`` cleared, the corners within ``lift_gap`` of the floor down (their
    number into ``phase[PH_LAST_DOWN]``), the first history row, the peaks of the start. Returns the signed tilt."""
    body = model.body
    out[:] = 0.0
    out[OUT_FIRST_MODE] = -1.0
    cw = ws.contact
    _geometry(state, body, ws.Q, cw.Iinv, cw.Iw, cw.r)
    for i in range(4):
        corners.touch[i] = state[2] + cw.r[i, 2] <= model.limits.lift_gap
    tilt, theta, _, _ = _tilt(state, body.weak_y)
    n_down = _mode(corners.touch, corners.slip)[1]
    _record(hist, 0.0, state, theta, state[10 + (0 if body.weak_y else 1)] * (-1.0 if body.weak_y else 1.0),
            n_down, body.h, out)
    out[OUT_THETA_MAX] = tilt
    out[OUT_TWIST_MAX] = abs(_twist(state))
    phase[PH_LAST_DOWN] = n_down
    return theta


@numba.njit(cache=True, inline='always')
def _track(body, state, n_down, tilt_sub, r1, phase, out):
    """After a step to ``state`` (``r1`` its arms, ``n_down`` corners down, ``tilt_sub`` the largest tilt inside a
    smooth step): the peaks of tilt, slide and twist into ``out``, the corners down last and how the block would
    overturn into ``phase``. Returns ``(signed tilt, lean x, lean y)``: the plan components of the body's vertical
    axis (their direction, an arctangent, is only wanted if the block overturns)."""
    if n_down > 0:
        phase[PH_LAST_DOWN] = n_down
    tilt, theta, lx, ly = _tilt(state, body.weak_y)
    sx, sy = state[0] - body.h * lx, state[1] - body.h * ly
    out[OUT_SLIDE_MAX] = max(out[OUT_SLIDE_MAX], math.hypot(sx, sy))
    out[OUT_TWIST_MAX] = max(out[OUT_TWIST_MAX], abs(_twist(state)))
    out[OUT_THETA_MAX] = max(out[OUT_THETA_MAX], tilt, tilt_sub)
    now_out = _cm_outside(state, r1)
    if now_out and not phase[PH_OUTSIDE]:
        phase[PH_OVER_KIND] = 1 if phase[PH_LAST_DOWN] >= 2 else 2
    phase[PH_OUTSIDE] = now_out
    return theta, lx, ly


@jitable
def _warm_start(P, acc, g, dt):
    """The impulses ``P`` (4 x 3, m/s) of a block leaving rest: the static impulses of the step's load (the floor
    accelerations ``acc``, m/s²; ``g``, m/s²; ``dt``, s), shared by the four corners, the contact solver's warm
    start."""
    gz = g + acc[2]
    for i in range(4):
        P[i, 0], P[i, 1], P[i, 2] = 0.25 * acc[0] * dt, 0.25 * acc[1] * dt, 0.25 * gz * dt


@jitable
def _seat(model, state, n_down, end, corners, phase, out):
    """A block at rest and still enough (``limits.velocity_tol``) on four corners, or on three with the fourth within
    the settling gap (:func:`_settle`, set down), is seated: its velocities zeroed, the rest skip on."""
    if n_down == 4 or _settle(state, corners.touch, model.body, end.Q1, end.r1, SETTLE_GAP * model.limits.lift_gap,
                              out):
        phase[PH_SEATED] = 1
        for a in range(7, 13):
            state[a] = 0.0


@jitable
def _finish(model, state, k, status, corners, hist, out):
    """The run's end at step ``k`` with ``status``: the last state's history row (if not stored) and the outputs."""
    dt, body = model.numerics.dt, model.body
    if k % model.numerics.hist_every != 0:
        tilt, theta, _, _ = _tilt(state, body.weak_y)
        _record(hist, k * dt, state, theta, -state[10] if body.weak_y else state[11],
                _mode(corners.touch, corners.slip)[1], body.h, out)
    out[OUT_STATUS] = status
    out[OUT_STEPS] = k
    out[OUT_ROCKED] = 1.0 if out[OUT_THETA_MAX] > model.limits.rocked_theta else 0.0
    for a in range(13):  # (element by element: a slice assignment compiles numba's shape-error message, seconds)
        out[OUT_STATE + a] = state[a]
    out[OUT_TIME] = k * dt
    out[OUT_EVENT_TIME] = k * dt * body.p
    return status


@jitable
def _unmanaged_inputs(floor, state, hist, out):
    """The run's input arrays as views without reference counts (:func:`opsrock.solvers.scratch.unmanaged`; the
    caller holds the arrays for the call): the floor motion's, the state, the history and the outputs."""
    floor = Floor(floor.form, unmanaged(floor.ax), unmanaged(floor.ay), unmanaged(floor.av), floor.sub, floor.n_exc,
                  floor.tail_av)
    return floor, unmanaged(state), unmanaged(hist), unmanaged(out)


@jitable
def _scratch(out, flat):
    """The run's scratch, all from one arena (:mod:`opsrock.solvers.scratch`): returns the arena (which must stay bound
    while the rest is used), the :class:`.workspace.Workspace`, the corners' flags, the trial step (writing into
    ``out``) and the phase counts."""
    arena = make_arena(ARENA_BYTES)
    return (arena, make_workspace(arena, OUT_SIZE, flat), make_corners(arena), make_trial(arena, out),
            make_phase(arena, PH_SIZE))


@numba.njit(cache=True)
def run(model, floor, state, hist, out, flat):
    """Integrate one case into ``out`` (``OUT_*``) and ``hist`` (rows ``H_*``); returns the status. Each step: the rest
    skip (seated, the load carried), else a smooth step of a calm phase (``phase``, ``PH_*``) or a Moreau-Jean step.

    Parameters
    ----------
    model : Model
        The block, its friction, the numerical settings and limits (:class:`.model.Model`, :func:`.model.make_model`).
    floor : Floor
        The floor motion in the block frame (:class:`.model.Floor`): :data:`FORCING_STEPWISE` or :data:`FORCING_LINEAR`
        (samples, ``sub`` steps per interval) for ``n_exc`` steps; then no horizontal motion, ``a_v = tail_av`` (m/s²).
    state : float64[13]
        Initial state; holds the final one on return.
    hist : float64[H_SIZE, n]
        History: rows ``H_*``, a column every ``model.numerics.hist_every`` steps (and the last state).
    out : float64[OUT_SIZE]
        The run's results and bookkeeping.
    flat : bool or None
        True: the flat slide and the coarse slide compiled (finite friction); None: neither (infinite friction), a
        block sliding flat marked in ``out[OUT_NEEDS_FLAT]`` for a run with True.
    """
    body, lim, dt, n_exc = model.body, model.limits, model.numerics.dt, floor.n_exc
    floor, state, hist, out = _unmanaged_inputs(floor, state, hist, out)
    arena, work, corners, trial, phase = _scratch(out, flat)  # (the arena kept to the end: keep_alive)
    ws, end = work.step, work.end
    theta = _start(model, state, ws, corners, phase, hist, out)
    status, k, going = STATUS_OK, ZERO, True
    while going:  # (one exit, its test: numba drops every array the loop holds at each exit; issue 43)
        if k >= n_exc and (lim.max_tail < 0 or phase[PH_RESTING] >= lim.rest_steps):
            going = False
            continue
        if k >= n_exc + max(lim.max_tail, 0) or k >= lim.max_steps:
            status, going = STATUS_TAIL if k < lim.max_steps else STATUS_MAX_STEPS, False
            continue
        acc = _floor(floor, k, model.numerics.theta_mj)
        if not math.isfinite(acc[0] + acc[1] + acc[2]):
            status, going = STATUS_NONFINITE, False
            continue
        if phase[PH_SEATED] and _rest_holds(acc[0], acc[1], acc[2], body, model.friction):
            k = _rest_skip(model, floor, k, state, theta, phase, hist, out)
            continue
        if phase[PH_SEATED]:  # leaving rest
            phase[PH_SEATED] = 0
            _warm_start(trial.P, acc, body.g, dt)
        n, tilt_sub = _smooth_step(model, floor, state, k, phase, work, corners, trial) if _smooth_due(model, phase) \
            else (0, 0.0)
        if n == SLIDE_DUE:  # sliding flat: the coarse slide, compiled only with flat True (numba prunes it on the type)
            n = _slide_step(model, floor, state, k, phase, work, corners, trial) if flat is not None else \
                _needs_flat(out)
        if n <= 0:
            n, end.a[0], end.a[1], end.a[2] = 1, acc[0], acc[1], acc[2]
            if not _mj_step(model, state, _step(model, state, acc, dt, ws, trial, corners.touch), ws.contact, end,
                            trial, corners, phase):
                status, going = STATUS_CONTACT, False
                continue
        _copy(state, trial.state)
        k += n
        if not _finite(state):
            status, going = STATUS_NONFINITE, False
            continue
        mode, n_down = _mode(corners.touch, corners.slip)
        _tally(mode, n_down, n * dt, out)
        theta, lx, ly = _track(body, state, n_down, tilt_sub, end.r1, phase, out)
        if k // model.numerics.hist_every != (k - n) // model.numerics.hist_every:
            _record(hist, k * dt, state, theta, -state[10] if body.weak_y else state[11], n_down, body.h, out)
        if out[OUT_THETA_MAX] >= OVERTURNING_ANGLE:
            out[OUT_OVERTURNED], out[OUT_OVER_KIND], out[OUT_OVER_DIR] = 1.0, phase[PH_OVER_KIND], math.atan2(ly, lx)
            going = False
            continue
        speed = max(abs(state[7]), abs(state[8]), abs(state[9]),
                    body.R * (abs(state[10]) + abs(state[11]) + abs(state[12])))
        rest = k >= n_exc and mode == MODE_REST and speed < lim.rest_velocity
        phase[PH_RESTING] = phase[PH_RESTING] + min(n, k - n_exc + 1) if rest else 0
        if lim.peak_rule and k >= n_exc and _peak_reached(state, body, out[OUT_THETA_MAX], floor.tail_av):
            out[OUT_PEAK_STOP] = 1.0
            going = False
            continue
        if mode == MODE_REST and speed < lim.velocity_tol:
            _seat(model, state, n_down, end, corners, phase, out)
    return _finish(model, state, k, status, corners, hist, out) + keep_alive(arena)
