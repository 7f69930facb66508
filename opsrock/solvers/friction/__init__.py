"""The rigid block on a floor with Coulomb friction, under horizontal and vertical floor motion:
event-driven and compiled (numba), for campaigns.

The block is the planar rectangle of the other rigid-body solvers; its base may slip on the floor
(static coefficient ``mu = Block.friction``, kinetic ``mu_k = Block.friction_kinetic``) and the
floor may move vertically (``g`` becomes ``g + a_v(t)`` in every mode). Five contact modes: rest,
slide, rock, slide-rock, flight. The equations of each mode, the rules for leaving rest (the
critical friction of Shenton's criteria), the stick-slip and loss-of-contact events and the impact
law (Housner's where the striking corner sticks, Coulomb's impulse where it slips) are in
docs/guide/friction.md; :mod:`.modes` and :mod:`.impacts` hold them, :mod:`.kernel` steps them.

Method: as :mod:`opsrock.solvers.housner_fast`, fixed-step RK4 inside each forcing segment with every
event located on the Runge-Kutta map; the block at rest jumps in closed form to the next time the
floor overcomes it. A block whose contact force would turn negative flies: its centre of mass moves
ballistically under gravity (relative to the floor: ``g + a_v``, and ``-a_h``), it turns at a constant
rate, and it lands by the impact law in the landing corner's position (one already beyond its hump and
turning outwards overturns). A record whose floor accelerates downward faster than ``g`` for more than
:data:`opsrock.excitations.vertical.MAX_FREE_FALL` on end is refused. After the excitation the block is
followed until it is at rest, except a pure slide that friction cannot stop within ``max_free_time``
(always on a frictionless floor): the run ends there, with status ok and the slip velocity
(``ContactSummary.slip_velocity_end``); the rest of that slide is a closed form (docs/guide/friction.md, the
ending rule). On a frictionless floor the block slides flat: ``u = -x_g`` (plus initial terms).

Without ``friction`` the base never slips and the solver is the no-slip rigid block of
``housner_fast`` (plus the vertical motion); the reference of a different formulation is
:mod:`opsrock.solvers.moreau_jean`.
"""

from opsrock.solvers.friction.kernel import STATUS_OK
from opsrock.solvers.friction.settings import FrictionSettings
from opsrock.solvers.friction.solver import SOLVER_NAME, solve, warm_up_paths

__all__ = ["SOLVER_NAME", "STATUS_OK", "FrictionSettings", "solve", "warm_up_paths"]
