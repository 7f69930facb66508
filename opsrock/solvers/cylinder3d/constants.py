"""The constants of :mod:`opsrock.solvers.cylinder3d`'s kernel: status codes, forcing forms, the layout of the history
rows, of the run's tracker and of the output vector, and the named tolerances. Units and frames as in
:mod:`opsrock.solvers.cylinder3d.kernel` (SI, per unit mass)."""

from __future__ import annotations

from opsrock.solvers import status as ST

# --- status codes: the shared ones (:mod:`opsrock.solvers.status`) ------------------------------------
STATUS_OK = ST.OK
STATUS_NONFINITE = ST.NONFINITE
STATUS_MAX_STEPS = ST.MAX_STEPS
STATUS_TAIL = ST.MAX_FREE_TIME
#: The contact solver (NSGS on the base's rim points) did not converge in ``nsgs_fail_steps`` consecutive steps.
STATUS_CONTACT = ST.NO_CONTACT_SOLUTION

# --- forcing forms ---------------------------------------------------------------------------------
#: A value per step (pulses sampled at each step's evaluation time, a still floor).
FORCING_STEPWISE = 0
#: Record samples, linear in between, ``sub`` steps per sample interval.
FORCING_LINEAR = 1

# --- local contact statuses ----------------------------------------------------------------------------
OPEN, STICK, SLIP = 0, 1, 2

# --- history columns (as rigid3d's, ``H_DOWN`` the rim points on the floor) ---------------------------------
H_T, H_THETA, H_THETA_DOT = 0, 1, 2
H_ROT = 3  # rotation vector, 3 columns
H_POS = 6  # CM displacement from rest, 3 columns
H_TWIST = 9
H_SLIDE = 10  # base centre's horizontal displacement, 2 columns
H_DOWN = 12
H_SIZE = 13

# --- the run's tracker (a float vector the kernel's parts share) -----------------------------------------
T_TILT_MAX = 0  # peak tilt (rad)
T_SLIDE_MAX = 1  # peak slide of the base centre (m)
T_TWIST_MAX = 2  # peak |twist| (rad)
T_RESTING = 3  # steps at rest after the excitation
T_UNCONVERGED = 4  # consecutive unconverged contact steps
T_SEATED = 5  # 1.0: seated on the full base, at rest (the rest skip holds it)
T_PHI = 6  # body angle of the last single rim contact (rad; NaN: none)
T_TURN = 7  # angle the contact point has run round the rim since the rim phase began (rad)
T_LAST_N = 8  # rim points in contact at the previous step
T_CONTACT_RATE = 9  # |d phi / dt| of the contact point at the last step (rad/s)
T_CALM = 10  # Moreau-Jean steps in a row on one stuck, loaded rim point (negative: cooling after a smooth sub-step failed)
T_W_LAST = 11  # tilt at the last sub-step's end of the rolling phase after the excitation, unbroken (NaN: none)
T_W_RISING = 12  # 1.0: the tilt rose over that sub-step
T_W_MAXES = 13  # local maxima of the tilt in that unbroken rolling
T_W_TOP = 14  # largest tilt since the first of them (rad)
T_W_RATE = 15  # largest |omega_h| over those sub-steps (rad/s): the tilt's rate is at most it
T_SIZE = 16

# --- layout of the kernel's output vector: the shared slots, then this kernel's own -----------------
OUT_STATUS, OUT_THETA_MAX, OUT_OVERTURNED = ST.OUT_STATUS, ST.OUT_THETA_MAX, ST.OUT_OVERTURNED
OUT_ROCKED = ST.OUT_ROCKED
OUT_IMPACTS, OUT_STEPS, OUT_N_HIST, OUT_EVENT_TIME = ST.OUT_IMPACTS, ST.OUT_STEPS, ST.OUT_N_HIST, ST.OUT_EVENT_TIME
OUT_FIRST_MODE = ST.OUT_COMMON
OUT_TIME_SLIDING = ST.OUT_COMMON + 1  # a loaded rim point slipped (s)
OUT_TIME_ROCKING = ST.OUT_COMMON + 2  # on one rim point (s)
OUT_TIME_ROLLING = ST.OUT_COMMON + 3  # on one rim point running round the rim (s)
OUT_TIME_BASE = ST.OUT_COMMON + 4  # on the full base (s)
OUT_TIME_FLIGHT = ST.OUT_COMMON + 5  # off the floor (s)
OUT_SLIDE_MAX = ST.OUT_COMMON + 6
OUT_TWIST_MAX = ST.OUT_COMMON + 7
OUT_INPUT_WORK = ST.OUT_COMMON + 8  # work of the floor's inertia force (J/kg)
OUT_CONTACT_TURN = ST.OUT_COMMON + 9  # signed angle the single contact point ran round the rim, jumps left out (rad)
OUT_FLAT_STEPS = ST.OUT_COMMON + 10  # steps solved by the flat base's closed form (stuck or sliding on it)
OUT_NSGS_FAILED = ST.OUT_COMMON + 11  # steps whose NSGS did not converge
OUT_NSGS_SWEEPS = ST.OUT_COMMON + 12  # sweeps over all contact steps
OUT_CONTACT_STEPS = ST.OUT_COMMON + 13  # steps that solved a contact problem
OUT_REST_STEPS = ST.OUT_COMMON + 14  # steps taken by the rest skip
OUT_OVER_KIND = ST.OUT_COMMON + 15  # 1: over a rim point rocking, 2: rolling round the rim
OUT_OVER_DIR = ST.OUT_COMMON + 16  # direction of overturning (rad, floor frame)
OUT_TIME = ST.OUT_COMMON + 17
OUT_MAX_PENETRATION = ST.OUT_COMMON + 18  # deepest rim point below the floor (m)
OUT_SLIP_UNCONVERGED = ST.OUT_COMMON + 19  # local slip solves whose direction's fixed point did not settle
OUT_STATE = ST.OUT_COMMON + 20  # final state, 13 slots
OUT_TAIL_SETTLED = ST.OUT_COMMON + 33  # 1.0: the tail ended by the energy bound, the peak final, before rest
OUT_TAIL_CUT = ST.OUT_COMMON + 34  # 1.0: the tail ended still moving, unable to overturn, the peak within TILT_SLACK
OUT_TAIL_ENERGY = ST.OUT_COMMON + 35  # the energy bound over the lift to overturning when the tail's span ended
OUT_LIFT_STEPS = ST.OUT_COMMON + 36  # steps solved by the lift about the flat base's centre of pressure
OUT_FRICTION_WORK = ST.OUT_COMMON + 37  # work the contact impulses take at the step's end velocities (J/kg)
OUT_IMPACT_LOSS = ST.OUT_COMMON + 38  # kinetic energy of the impulses' velocity change at landings (J/kg)
OUT_TAIL_BOUND = ST.OUT_COMMON + 39  # 1.0: the tail ended at its span, the energy below what overturning takes
OUT_TILT_BOUND = ST.OUT_COMMON + 40  # largest tilt the final energy can reach (rad; at a tail ending by the energy)
OUT_ROLL_STEPS = ST.OUT_COMMON + 41  # Runge-Kutta sub-steps rolling on a rim point kept (:mod:`.rolling`)
OUT_ROLL_SPAN = ST.OUT_COMMON + 42  # Moreau-Jean steps those spanned
OUT_ROLL_FAILED = ST.OUT_COMMON + 43  # Runge-Kutta sub-steps tried and not kept
OUT_TAIL_WOBBLE = ST.OUT_COMMON + 44  # 1.0: the tail ended at its span in a steady wobble, its tilt periodic
OUT_SIZE = ST.OUT_COMMON + 45

# --- the physics' named thresholds and the iterations' tolerances -------------------------------------
#: Speed of the base (m/s) below which the tail may end by the energy bound (rigid3d's rule "peak"): a base sliding
#: at 1 mm/s under friction ``mu`` stops within ``(1e-3)² / (2 mu g)``, 5e-8/mu m.
PEAK_BASE_SPEED = 1e-3
#: The tail may end before its span (rule "bounded", :func:`opsrock.solvers.cylinder3d.kernel._tail_settled`) only if
#: the energy bound is below ``TAIL_CUT_MARGIN`` of what overturning takes (the lift of its centre of mass over the
#: rim, ``g (R - h)``), besides the rule's own bound on the tilt.
TAIL_CUT_MARGIN = 0.9
#: Round-off allowance of the energy test at the end of the tail's span, relative to the sum of the magnitudes of the
#: energy's terms (``|V|²/2``, ``i_h |omega|²/2``, ``|i_z - i_h| (omega . a)²/2``, ``(g + a_v)(z + h)``; J/kg): the
#: energy is some thirty floating-point operations on those terms, so its rounding error is below about ``30 eps``
#: (6.7e-15) of that sum (Higham, *Accuracy and Stability of Numerical Algorithms*, the error of a sum); the allowance
#: is 150 times that.
ENERGY_ROUNDOFF = 1e-12
#: The tail may end, the cylinder still moving, once its energy cannot raise its tilt more than ``TILT_SLACK`` of
#: ``alpha`` above the peak so far (``diagnostics["tilt_bound"]`` says how far it could): a wobble keeps its energy.
#: A fifth of the planar limit's tolerance on the peak (tests/model/solvers/test_cylinder3d.py), so that a block still
#: rising after a pulse is followed to its peak.
TILT_SLACK = 2e-4
#: Friction coefficient standing for infinity where a stuck rim point would need a pulling impulse (``friction =
#: None``): it then slides in the infinite-friction limit (relative error ``1 / LIMIT_MU``), as rigid3d's corners.
LIMIT_MU = 1e6
#: A stuck rim point's friction impulse lies in the static cone up to this relative round-off.
CONE_SLACK = 1e-12
#: Change of a slip direction's components (dimensionless) at which the local slip fixed point stops.
DIRECTION_TOL = 1e-12
#: Most iterations of the local slip fixed point (one that has not settled keeps its last iterate and is counted).
SLIP_ITERATIONS = 100
#: The contact point counts as running round the rim (rolling, wobbling) while its body angle turns faster than
#: ``ROLL_RATE p`` (rad/s): ``ROLL_RATE`` of a radian per unit of the rocking time ``1/p``.
ROLL_RATE = 0.05
#: A cylinder that overturns after its contact point has run more than ``ROLL_TURN`` (rad) round the rim since it
#: last stood on its base or landed overturned *rolling*; otherwise over a rim point, *rocking*.
ROLL_TURN = 0.05
#: A loaded single rim point is set back onto the floor after its step when it has drifted off it by at most this
#: many contact gaps (:func:`opsrock.solvers.cylinder3d.step._set_down`).
SET_DOWN_GAPS = 10.0
#: Largest angle (rad) the contact point may run round the rim in one step: a step is cut into sub-steps while it runs
#: faster (the cylinder rolling through a nearly flat state), at most ``MAX_SUBSTEPS`` of them.
PHI_STEP = 0.02
MAX_SUBSTEPS = 256
#: Body angle (rad) by which the lowest rim point must jump between steps to count as a landing (the base passed
#: through flat and the opposite rim point took the contact), and not as rolling.
LANDING_JUMP = 1.0
#: The base counts as flat (every rim point equally low; the contact runs on ``rim_points`` points round the rim)
#: while the rim's height varies by less than ``FLAT_GAP`` contact gaps (``2 r sin(tilt) <= FLAT_GAP * lift_gap``).
FLAT_GAP = 1.0

# --- the smooth phase rolling on a rim point (:mod:`opsrock.solvers.cylinder3d.rolling`) --------------------------
#: Longest Runge-Kutta sub-step, in units of ``1/p`` (twice rigid3d's ``RK_DTAU``): the peak tilt is read at the
#: sub-steps' ends, so it is missed by at most ``p² sin(alpha) (ROLL_DTAU / p)² / 8`` (below 1.3e-5 rad), and the
#: method's own error per unit time is of order ``ROLL_DTAU^4``.
ROLL_DTAU = 1e-2
#: Moreau-Jean steps in a row on one stuck, loaded rim point, without a landing, before a sub-step is tried.
ROLL_CALM = 4
#: Shortest sub-step tried, in Moreau-Jean steps: a sub-step that leaves the phase is halved down to it, and then
#: the Moreau-Jean steps cross the event that ended the phase (it lies within that many of them).
ROLL_MIN_STEPS = 8
#: Largest angle (rad) the contact point may run round the rim over a sub-step (and at its rate, over one): where it
#: whips round faster (the base passing through flat, Srinivasan & Ruina) the Moreau-Jean steps, cut into pieces of
#: ``PHI_STEP``, take it.
ROLL_PHI = 0.1
#: The phase holds only while the rim's height varies by more than ``ROLL_FLAT`` contact gaps (``2 r sin tilt``), a
#: hundred times the flat base's ``FLAT_GAP``: the contact point's rate ``phi'`` grows as ``1 / sin tilt`` near flat.
ROLL_FLAT = 100.0
