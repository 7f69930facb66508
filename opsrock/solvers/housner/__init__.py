"""The exact rigid-body rocking equation with instantaneous impacts (paper Eq. 1-4, 9-11).

Between impacts the block pivots about one base corner (``s = sgn(theta)``)::

    theta'' = -p² [ sin(alpha s - theta) + a(t)/g cos(alpha s - theta) ]

with a positive floor acceleration ``a`` tipping the block towards negative ``theta``. The
solver is event-driven:

* **seated** while ``|a(t)| <= g tan(alpha)`` (Eq. 4); the first time ``|a|`` exceeds that
  level the block uplifts about the corner set by the sign of ``a`` (``s = -sgn(a)``);
* **impact** when ``theta`` returns to zero: ``theta' -> e theta'`` (Housner's instantaneous
  impact, ``e = block.e``) and the block goes on about the other corner;
* **rest** when the velocity after an impact falls below ``rest_velocity_ratio · p · alpha``:
  the remaining bounces ("chattering") form a geometric series ``e, e², ...`` of vanishing
  duration (at most ``2 |theta'| / ((1 - e) p² alpha)`` in free rocking), so the block is
  set down as seated; it lifts off again if ``|a|`` still exceeds ``g tan(alpha)``;
* **overturning** when ``|theta|`` reaches ``pi/2`` (Eq. 11), a terminal event.

With ``equations="linearised"`` the small-angle form of the classical rocking papers is solved
instead, ``theta'' = -p² [(alpha s - theta) + a/g]`` with uplift when ``|a| > g alpha``
(:data:`opsrock.constants.EQUATIONS`); overturning is still ``|theta| = pi/2``.

The lever here is the exact ``cos(alpha s - theta)`` of Eq. 1; the SDOF model of Eq. 6 keeps
it constant at ``cos(alpha)`` (see :mod:`opsrock.solvers.sdof`): one of the model-form
differences measured by ``validation/model_form``.
"""

from opsrock.solvers.housner.settings import HousnerSettings
from opsrock.solvers.housner.solver import SOLVER_NAME, solve

__all__ = ["HousnerSettings", "SOLVER_NAME", "solve"]
