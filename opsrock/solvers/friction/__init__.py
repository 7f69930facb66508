"""The rigid block on a floor with Coulomb friction, under horizontal and vertical floor motion:
event-driven and compiled (numba), for campaigns.

The block is the planar rectangle of the other rigid-body solvers; its base may slip on the floor
(static coefficient ``mu = Block.friction``, kinetic ``mu_k = Block.friction_kinetic``) and the
floor may move vertically (``g`` becomes ``g + a_v(t)`` in every mode). Five contact modes: rest,
slide, rock, slide-rock, flight. The equations of each mode, the rules for leaving rest (the
critical friction of Shenton's criteria), the stick-slip and loss-of-contact events and the impact
law (Housner's where the striking corner sticks, Coulomb's impulse where it slips) are in
docs/friction.md; :mod:`.modes` and :mod:`.impacts` hold them, :mod:`.kernel` steps them.

Method: as :mod:`opsrock.solvers.housner_fast`, fixed-step RK4 inside each forcing segment with every
event located on the Runge-Kutta map; the block at rest jumps in closed form to the next time the
floor overcomes it. Free flight is not modelled: a block that would leave the floor is reported as
failed with that reason, except one already beyond its hump and turning outwards, which overturns.
After the excitation the block is followed until it is at rest.

Without ``friction`` the base never slips and the solver is the no-slip rigid block of
``housner_fast`` (plus the vertical motion); the reference of a different formulation is
:mod:`opsrock.solvers.moreau_jean`.
"""

from opsrock.solvers.friction.kernel import STATUS_OK
from opsrock.solvers.friction.settings import FrictionSettings
from opsrock.solvers.friction.solver import SOLVER_NAME, solve

__all__ = ["SOLVER_NAME", "STATUS_OK", "FrictionSettings", "solve"]
