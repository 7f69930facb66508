"""The three-dimensional rigid-block solver ``rigid3d`` (skeleton: the kernel lands with issue 33).

A box of base ``2b x 2d`` and height ``2h`` on a rigid floor with isotropic Coulomb friction at its four base
corners, under two horizontal floor components and a vertical one (:class:`~opsrock.excitations.plan.PlanMotion`),
by Moreau-Jean time stepping (docs/three-dimensions.md).
"""

from opsrock.solvers.rigid3d.settings import Rigid3DSettings
from opsrock.solvers.rigid3d.solver import SOLVER_NAME, solve

__all__ = ["SOLVER_NAME", "Rigid3DSettings", "solve"]
