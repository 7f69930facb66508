"""The paper's equivalent SDOF model (Eq. 5-8) integrated by scipy, region by region.

    I_O theta'' + f_d(theta, theta') + M_s(theta) = -Lambda a(t)

solved with the same model as the OpenSees solver (:class:`opsrock.model.SDOFModel`: the
*tabulated* spring ``spring_table``, stiff branch and all; the damper ``c_D`` of
``damping_coefficient``; the lever ``lever_arm``) but none of its numerics:

* the rotation axis is cut at every kink of the spring table and at the damper band edges
  ``±delta alpha``; inside one region the equation is linear with constant coefficients and
  :func:`scipy.integrate.solve_ivp` integrates it with tight tolerances, stopping on a
  terminal event at the region's edges, at ``|theta| = pi/2`` (overturning, Eq. 11) and at
  every excitation breakpoint (pulse start and end, record samples);
* the damper is armed at the start of every passage through the band (on entering it, at a
  turning point inside it, and at the start from a state inside it) by the model's damper law
  (:meth:`opsrock.model.SDOFModel.arm_damper`: by default so that a free passage keeps ``e²`` of
  the energy; ``damper="entry_velocity"`` is Eq. 8 on entry only), and off when it is left. Before
  the first passage, and while the block is seated, ``c_D = 0``;
* the stiff branch ``|theta| <= theta_e`` (slope ``k_e = M_s(theta_e) / theta_e``, natural
  frequency ``omega_e = sqrt(k_e / I_O)``, about ``p sqrt(1 / theta_e_ratio)``: 1000 p by
  default) is integrated with an implicit method (``stiff_method``). A block that sits in it
  is handled as **seated**: the exact solution there is the quasi-static deflection
  ``theta_qs = -Lambda a(t) / k_e`` plus a free oscillation of amplitude ``A`` at
  ``omega_e``; once ``|theta_qs| + A < theta_e`` the solver drops the oscillation and follows
  ``theta_qs`` until ``Lambda |a(t)| > M_s(theta_e)``, where the block leaves the branch
  (for ``lever="housner"`` this is ``|a| > g tan(alpha - theta_e) / tan(alpha) · g tan(alpha)``,
  i.e. Eq. 4 to within ``theta_e``). The error of this treatment is below ``theta_e`` in
  rotation (1e-6 alpha by default) and ``k_e theta_e² / 2`` in energy; a block starting from
  rest is seated from the start.
"""

from opsrock.solvers.sdof.settings import SDOFSettings
from opsrock.solvers.sdof.solver import SOLVER_NAME, solve, table_potential

__all__ = ["SDOFSettings", "SOLVER_NAME", "solve", "table_potential"]
