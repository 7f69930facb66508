"""The three-dimensional rigid-cylinder solver ``cylinder3d``: a cylinder standing on its circular base on a rigid
floor with isotropic Coulomb friction, under two horizontal floor components and a vertical one, by Moreau-Jean time
stepping with contact and friction at impulse level (issue 45; docs/guide/three-dimensions.md).

Model
-----
A cylinder of radius ``r = Block.width / 2`` (the diameter is the block's width; ``depth`` None or the same) and
height ``Block.height``, its centre of mass ``h = Block.h_cm`` above the base centre on the axis; inertia about the
centre of mass ``I_h = m Block.radius_of_gyration²`` about any horizontal axis (without it, a homogeneous solid
cylinder's ``m (r²/4 + H²/12)``) and ``I_z = m r²/2`` about the axis (:func:`~.model.cylinder_properties`;
:func:`~.solver.cylinder_block` builds the block with both, so that its planar ``alpha``, ``R``, ``p`` and ``e_R``
are the cylinder's in a vertical plane through its axis).

Contact. Tilted, the cylinder touches the floor at one point, the lowest point of its rim: its body angle is
recomputed every step, so that the contact point runs round the rim when the cylinder rolls on it (wobbling, the
rocking plane turning) and jumps to the opposite side when the base passes through flat (a landing). With its base
flat (the rim level within ``FLAT_GAP`` contact gaps: at rest, sliding on the full base, landing slowly) the base is
carried by ``rim_points`` points evenly round the rim, the first towards the floor's load, so that the uplift starts
about the rim point the load pushes towards, whatever its direction. A point is in contact while its height
predicted at mid-step is at most the contact gap (``contact_gap (g + peak) dt²``).

Impact and friction. Newton's law with ``e_n = 0`` at the points in contact and isotropic Coulomb friction (stick
inside the static cone ``|P_T| <= mu P_N``, else slip with ``mu_k`` against the slip velocity; ``friction = None``
never slips). On a rim this is **Housner's impact, and no other restitution** (the registry declares it): the
landing rim point, the one opposite the rim point the cylinder rocked on (or, wobbling, wherever the lowest point then
is), takes the whole impulse, sticks, and stops its normal velocity; the angular momentum about it is kept (all three
components: the impulse acts there). For rocking in a vertical plane through the axis this is Housner's ``e_H = 1 -
2 r² / (r_g² + R²)`` on the angular velocity (``Block.e_R`` of :func:`cylinder_block`'s block); for a wobbling
cylinder the same law at the landing point gives what the planar coefficient cannot. A slow landing whose base
meets the floor flat (every rim point within the contact gap) is taken by all rim points: a plastic landing.

Scheme (:mod:`~.step`): ``v_free = v_k + dt (body force, -omega x I omega)``, the impulses at the points in contact
(one point: its exact local solve; the flat base: the lift about the load's rim point, else the closed forms of
:mod:`~.flat`, the base staying down stuck or sliding and twisting on an ellipsoidal limit surface while its centre
of pressure lies in the base, or lifting about one rim point; else nonsmooth Gauss-Seidel with the exact local solve
per point), ``X`` and the quaternion advanced with the theta-blend of the velocities. A cylinder seated on its stuck
base is held at rest in O(1) a step while the floor's load is carried (``g + a_v > 0``, ``|a_h| h <= r (g + a_v)``,
``|a_h| <= mu (g + a_v)``): the uplift threshold ``g r / h`` is exact in every direction. A cylinder rolling
without slip on one rim point (rocking on it, wobbling) for a few steps is crossed by fourth-order Runge-Kutta
sub-steps (:mod:`~.rolling`, ``smooth=True``), its contact force from the no-slip condition at every stage, the
Moreau-Jean steps keeping lift-off, the onset of slip, landings, the base flat, flight and overturning.

Outputs as rigid3d's: ``theta`` the tilt signed by the lean along ``x``; ``plan``
(:class:`~opsrock.result.PlanSummary`): tilt, twist, slide of the base centre, the mechanism of overturning
(``"rim"``: over a rim point that stayed put in the body; ``"rolling"``: after the contact point ran more than
``ROLL_TURN`` round the rim since the cylinder last landed), time on one rim point (``time_rim``), rolling
(``time_rolling``: the contact point turning faster than ``ROLL_RATE p``), sliding and in flight, and the energy
balance; ``plan_history``; ``contact``. Overturning: the tilt reaches ``pi/2``.
"""

from opsrock.solvers.cylinder3d.model import CylinderProperties, cylinder_properties
from opsrock.solvers.cylinder3d.settings import Cylinder3DSettings
from opsrock.solvers.cylinder3d.solver import (SOLVER_NAME, cylinder_block, free_motion, mechanical_energy, solve,
                                               tilted_state)

__all__ = ["SOLVER_NAME", "Cylinder3DSettings", "CylinderProperties", "cylinder_block", "cylinder_properties",
           "free_motion", "mechanical_energy", "solve", "tilted_state"]
