"""The paper's equivalent SDOF model (Eq. 5-8) built literally in OpenSeesPy.

OpenSees state is owned by :mod:`opsrock.opensees_session`: every model here is built inside its
``fresh_model()`` context, which wipes OpenSees before and after (also on errors), so no state
leaks from one run into the next.

Model (docs/guide/modelling.md sections 2 and 4)
------------------------------------------------
One rotational degree of freedom (a 1-D model, ``ndm=1, ndf=1``: the node's single dof *is*
the block rotation ``theta``), rotational mass ``I_O``, and two ``zeroLength`` elements between
a fixed node and the free one:

* the spring, ``uniaxialMaterial ElasticMultiLinear`` with the table of
  :meth:`opsrock.model.SDOFModel.spring_table` (path-independent; its negative slopes are the
  rocking instability); ``MultiLinear``/``Hysteretic`` would be hysteretic and wrong here;
* the damper, ``uniaxialMaterial Viscous C 1.0`` whose ``C`` is changed through
  ``parameter``/``updateParameter``: ``c_D`` set by the model's damper law at the start of every
  passage through the band ``|theta| <= delta alpha`` (on entering it, at the first step after a
  turning point inside it; :meth:`opsrock.model.SDOFModel.arm_damper`), zero outside (Eq. 7) and
  while the block is seated. The change takes effect from the next step.

With an implicit integrator a block seated in the stiff branch is treated as the scipy solver treats
it (:class:`opsrock.model.Seat`): its free oscillation at ``omega_e`` is dropped once it fits in the branch, and with
adaptive Newmark under a record it is carried along its quasi-static deflection without steps up to the samples at
which the floor can lift it, where a step lands on the uplift instant.

The floor acceleration enters as the nodal moment ``-Lambda a(t)`` (``Lambda`` =
:meth:`~opsrock.model.SDOFModel.lever_arm`): a ``Trig`` time series for a one-sine pulse (exact
at every step, whatever the step), a ``Path`` series for a sampled :class:`~opsrock.excitations.Record`.

The transient loop stops when ``|theta| >= pi/2`` (overturned: OpenSees never fails by itself,
theta just grows), when the block can no longer exceed its peak after the excitation ended
(its energy below the barrier at ``theta_max + rest_tolerance alpha``), or at a hard end time (a
*failed* run: the answer is unknown).

:func:`solve_lumped_mass` builds the lumped-mass form of the paper's Figure 2b (a pivot, a rigid
link of length ``R`` and the mass ``m`` with ``I_CM = m R^2 / 3``) for the validation of the
excitation lever.

The package: :mod:`~opsrock.solvers.opensees.settings` (every numerical choice, named and justified),
:mod:`~opsrock.solvers.opensees.build` (the models), :mod:`~opsrock.solvers.opensees.stepper` (the
transient loop: step policy, guards, the seat, damper switching, stopping) and
:mod:`~opsrock.solvers.opensees.solver` (the entry points).
"""

import importlib

from opsrock.solvers.opensees.settings import (
    ALGORITHMS,
    INTEGRATORS,
    ROCKED_THETA_E_MULTIPLE,
    SOLVER_NAME,
    OpenSeesSettings,
    critical_time_step,
)

#: Names whose modules import OpenSeesPy, loaded when first used (PEP 562): ``import opsrock.solvers`` and
#: this package's settings work without OpenSeesPy's system BLAS; the first ``solve`` loads it.
_LAZY: dict[str, str] = {
    "solve": "opsrock.solvers.opensees.solver",
    "solve_lumped_mass": "opsrock.solvers.opensees.solver",
    "opensees_log_path": "opsrock.opensees_session",
}


def __getattr__(name: str):
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["ALGORITHMS", "INTEGRATORS", "OpenSeesSettings", "ROCKED_THETA_E_MULTIPLE", "SOLVER_NAME",
           "critical_time_step", "opensees_log_path", "solve", "solve_lumped_mass"]
