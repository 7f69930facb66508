"""The constants of :mod:`opsrock.solvers.rigid3d`'s kernel: status codes, contact modes, forcing forms, the layout of
the history rows and of the output vector, the physical thresholds and the tolerances of the iterations.
Units and frames as in :mod:`opsrock.solvers.rigid3d.kernel` (SI, per unit mass).
"""

from __future__ import annotations

import numpy as np

from opsrock.solvers import status as ST
from opsrock.solvers.rigid3d import pivot as PV

# --- status codes: the shared ones (:mod:`opsrock.solvers.status`) ------------------------------------
STATUS_OK = ST.OK
STATUS_NONFINITE = ST.NONFINITE
STATUS_MAX_STEPS = ST.MAX_STEPS
STATUS_TAIL = ST.MAX_FREE_TIME
#: The contact solver (NSGS) did not converge in ``nsgs_fail_steps`` consecutive steps.
STATUS_CONTACT = ST.NO_CONTACT_SOLUTION

# --- contact modes, indices into opsrock.result.MODES ----------------------------------------------
MODE_REST = 0
MODE_SLIDE = 1
MODE_ROCK = 2
MODE_SLIDE_ROCK = 3
MODE_FLIGHT = 4

# --- forcing forms ---------------------------------------------------------------------------------
FORCING_STEPWISE = 0
FORCING_LINEAR = PV.FORCING_LINEAR

# --- history rows (``kernel.run``'s ``hist``: a row per quantity, a column per sample) ---------------------------
H_T, H_THETA, H_THETA_DOT = 0, 1, 2
H_ROT = 3  # rotation vector, 3 rows
H_POS = 6  # CM displacement from rest, 3 rows
H_TWIST = 9
H_SLIDE = 10  # base centre's horizontal displacement, 2 rows
H_DOWN = 12
H_SIZE = 13

# --- layout of the kernel's output vector: the shared slots, then this kernel's own -----------------
OUT_STATUS, OUT_THETA_MAX, OUT_OVERTURNED, OUT_ROCKED = ST.OUT_STATUS, ST.OUT_THETA_MAX, ST.OUT_OVERTURNED, ST.OUT_ROCKED
OUT_IMPACTS, OUT_STEPS, OUT_N_HIST, OUT_EVENT_TIME = ST.OUT_IMPACTS, ST.OUT_STEPS, ST.OUT_N_HIST, ST.OUT_EVENT_TIME
OUT_FIRST_MODE = ST.OUT_COMMON
OUT_TIME_SLIDING = ST.OUT_COMMON + 1
OUT_TIME_ROCKING = ST.OUT_COMMON + 2
OUT_TIME_EDGE = ST.OUT_COMMON + 3
OUT_TIME_CORNER = ST.OUT_COMMON + 4
OUT_TIME_FLIGHT = ST.OUT_COMMON + 5
OUT_SLIDE_MAX = ST.OUT_COMMON + 6
OUT_TWIST_MAX = ST.OUT_COMMON + 7
OUT_INPUT_WORK = ST.OUT_COMMON + 8
OUT_FRICTION_WORK = ST.OUT_COMMON + 9
OUT_IMPACT_LOSS = ST.OUT_COMMON + 10
OUT_NSGS_FAILED = ST.OUT_COMMON + 11  # steps whose NSGS did not converge
OUT_NSGS_SWEEPS = ST.OUT_COMMON + 12  # sweeps over all contact solves
OUT_NSGS_MAX = ST.OUT_COMMON + 13  # most sweeps in one step
OUT_MAX_PENETRATION = ST.OUT_COMMON + 14
OUT_TIME = ST.OUT_COMMON + 15
OUT_REST_STEPS = ST.OUT_COMMON + 16  # steps taken by the rest skip
OUT_OVER_KIND = ST.OUT_COMMON + 17  # 1: over an edge, 2: over a corner
OUT_OVER_DIR = ST.OUT_COMMON + 18  # direction of overturning (rad, floor frame)
OUT_LIMIT_STEPS = ST.OUT_COMMON + 19  # local solves that met the infinite-friction limit (P_N < 0 to stick)
OUT_CONTACT_STEPS = ST.OUT_COMMON + 20  # steps that solved a contact problem
OUT_STATE = ST.OUT_COMMON + 21  # final state, 13 slots
OUT_STICK_STEPS = ST.OUT_COMMON + 34  # steps solved by the closed-form stick (_stick_all)
OUT_SLIDE_STEPS = ST.OUT_COMMON + 35  # steps solved by the closed-form flat slide (_slide_flat)
OUT_SMOOTH_STEPS = ST.OUT_COMMON + 36  # Runge-Kutta steps about stuck corners kept (:mod:`.pivot`)
OUT_SMOOTH_SPAN = ST.OUT_COMMON + 37  # Moreau-Jean steps those spanned
OUT_SMOOTH_TRIED = ST.OUT_COMMON + 38  # Runge-Kutta steps tried (kept or halved)
OUT_PEAK_STOP = ST.OUT_COMMON + 39  # 1.0: the run ended by the tail rule "peak"
OUT_NSGS_LOOSE = ST.OUT_COMMON + 40  # steps whose NSGS met only the looser tolerance (:func:`_solve_contacts`)
OUT_NSGS_EXTRA = ST.OUT_COMMON + 41  # the sweeps those took beyond nsgs_max_sweeps
OUT_COARSE_STEPS = ST.OUT_COMMON + 42  # coarse Moreau-Jean steps of a block sliding flat (_coarse_slide)
OUT_COARSE_SPAN = ST.OUT_COMMON + 43  # Moreau-Jean steps those spanned
OUT_EDGE_SLIP = ST.OUT_COMMON + 44  # steps solved by the closed-form slip on two corners (_edge_slip)
OUT_SLIP_STEPS = ST.OUT_COMMON + 45  # Runge-Kutta steps on slipping corners kept (_smooth_slip)
OUT_SLIP_SPAN = ST.OUT_COMMON + 46  # Moreau-Jean steps those spanned
OUT_SLIP_TRIED = ST.OUT_COMMON + 47  # Runge-Kutta steps on slipping corners tried (kept or halved)
OUT_SETTLED = ST.OUT_COMMON + 48  # times a block at rest on three corners was set down on four (_settle)
OUT_SETTLE_GAP = ST.OUT_COMMON + 49  # the largest gap (m) of a fourth corner so set down
OUT_NEEDS_FLAT = ST.OUT_COMMON + 50  # 1.0: the block slid flat where ``run``'s ``flat`` was None (no coarse slide
#                                      compiled): the solver runs the case again with ``flat`` True
OUT_SIZE = ST.OUT_COMMON + 51

# --- the run's phase state (``kernel.run``): an int64 vector, slots ``PH_*`` -------------------------------------
#: Moreau-Jean steps without an impact the block has spent in each phase that has smooth steps of its own: turning
#: about stuck corners (``smooth._smooth``), rocking on slipping corners (``smooth._smooth_slip``), sliding flat
#: (``smooth._coarse_slide``); negative after a smooth step of that phase failed: the steps left before it is tried
#: again (``kernel._next_phase``).
PH_PIVOT, PH_SLIP, PH_SLIDE = 0, 1, 2
PH_SEATED = 3  # 1: seated on its four stuck corners, at rest (the rest skip applies)
PH_RESTING = 4  # steps the block has been at rest after the excitation
PH_UNCONVERGED = 5  # consecutive steps whose NSGS did not converge
PH_LAST_DOWN = 6  # corners down the last time one was
PH_OUTSIDE = 7  # 1: the centre of mass's plan projection is outside the base's
PH_OVER_KIND = 8  # how it would overturn, set as the centre of mass leaves the base: 1 over an edge, 2 over a corner
PH_SIZE = 9
#: ``kernel._smooth_step``'s step count when the calm phase is sliding flat: ``run`` takes that phase's coarse slide
#: itself (``kernel._slide_step``, compiled only where its ``flat`` is True). Below the coarse slide's -1 (none tried).
SLIDE_DUE = -2

#: Speed of the base (m/s) below which the tail rule "peak" may end a run: a block on its base sliding at
#: 1 mm/s under friction ``mu`` stops within ``(1e-3)² / (2 mu g)``, 5e-8/mu m.
PEAK_BASE_SPEED = 1e-3

#: Friction coefficient standing for infinity in the limit solve of :func:`_local` (its relative error 1/LIMIT_MU).
LIMIT_MU = 1e6

#: Normal impulses of the closed-form flat slide down to ``-FLAT_ROUNDOFF`` times their sum count as zero (round-off
#: of its least-squares solve): a block with ``mu_k = b/h`` slides with its trailing corners exactly unloaded.
FLAT_ROUNDOFF = 1e-10

#: The status pairs :func:`_edge_slip` tries, in order (0 stick, 1 slip, 2 open).
EDGE_STATUSES = np.array([[0, 1], [1, 0], [1, 1], [2, 1], [1, 2]], dtype=np.int64)

#: A smooth step on slipping corners (:func:`_smooth_slip`) takes Runge-Kutta sub-steps no longer than
#: ``1/SLIP_TURN`` of each slipping corner's speed over its tangential acceleration: its slip direction turns by at
#: most about ``1/SLIP_TURN`` rad a sub-step, and it cannot stop or reverse inside one.
SLIP_TURN = 20.0

#: The shortest Runge-Kutta sub-step on slipping corners, in Moreau-Jean steps (shorter: the Moreau-Jean steps
#: go on).
SLIP_MIN_SUB = 2.0

#: A block at rest on three stuck corners whose fourth hangs above the floor by at most ``SETTLE_GAP`` times the
#: contact gap (the Moreau-Jean steps' drift; ``Limits.lift_gap``) is set down level on all four (:func:`_settle`).
SETTLE_GAP = 10.0

# --- tolerances of the iterations and tests (dimensionless unless stated) ------------------------------------
#: Relative change of the multiplier at which the secular equation's Newton iteration stops (:func:`_slip_direction`).
SECULAR_TOL = 1e-15
#: Residual angle (rad) and angle step (rad) at which Newton on one corner's slip angle stops (:func:`_slip_newton`).
SLIP_ANGLE_TOL, SLIP_STEP_TOL = 1e-13, 1e-14
#: Change of a slip direction's components at which the fixed point of :func:`_local` stops.
DIRECTION_TOL = 1e-11
#: A closed form's friction impulse lies in the static cone up to this relative round-off.
CONE_SLACK = 1e-12
#: Gaussian elimination refuses a pivot below this fraction of the matrix's largest entry (:func:`_solve_n`).
PIVOT_TOL = 1e-13
#: Newton's and the fixed points' stopping tolerance in :func:`_flat_newton` (relative to the velocities' scale)
#: and :func:`_edge_try` (the directions' components and angles, rad).
NEWTON_TOL = 1e-12
#: Forward-difference step of the Jacobians of :func:`_flat_newton` (relative) and :func:`_edge_try` (rad).
FD_STEP = 1e-7
#: A flat-sliding corner's velocity must lie along its slip direction to within this (``1 - cos``).
ALIGN_TOL = 1e-9
#: Extra margin (m) by which a smooth step on slipping corners sets its contact corners onto the floor.
SETDOWN_MARGIN = 1e-13

#: Corner signs ``(sx, sy)``: corners 0..3 at (+b, +d), (-b, +d), (-b, -d), (+b, -d) (counter-clockwise).
CORNER_SX = np.array([1.0, -1.0, -1.0, 1.0])
CORNER_SY = np.array([1.0, 1.0, -1.0, -1.0])

#: Non-literal constants for counters and flags passed to compiled functions: numba types a counter that starts
#: at ``0`` (or an argument written ``True``) as a literal while it infers a caller's types, and compiles the
#: callee, with everything it calls, once more for that literal (a fifth of the cold compile, measured).
ZERO, ONE, TWO, FOUR, SIX = np.int64(0), np.int64(1), np.int64(2), np.int64(4), np.int64(6)
REST_MODE = np.int64(MODE_REST)
NO, YES = np.bool_(False), np.bool_(True)
