"""Fast rigid-body rocking solver for dense overturning spectra (numba-compiled).

Solves the same exact rigid-body equation as :mod:`opsrock.solvers.housner` (paper Eq. 1-3,
docs/guide/modelling.md section 2), written in the dimensionless time ``tau = p t``::

    d²theta/dtau² = -[ sin(alpha s - theta) + (a(t)/g) cos(alpha s - theta) ],   s = sgn(theta)

with uplift from rest only when ``|a| > g tan(alpha)`` (Eq. 4), towards ``s = -sgn(a)``;
instantaneous impacts at ``theta = 0`` that multiply the angular velocity by ``e``
(Housner's coefficient times the restitution factor); overturning at ``|theta| >= pi/2``
(Eq. 11).

Method
------
* While the pulse lasts: classical fourth-order Runge-Kutta with a fixed step
  ``h = min(max_dtau, 2 pi / (omega_p/p) / steps_per_pulse)`` (in units of ``1/p``), landing
  exactly on the end of the pulse (where ``a(t)`` has a kink). Impacts and peaks inside a
  step are located by a safeguarded Newton iteration *on the Runge-Kutta map itself* (the
  step length is the unknown), so the event time is consistent with the integrator to
  round-off. After an impact the first step is shortened to the predicted half-excursion
  ``|omega| / |theta''|`` (halved again if it still overshoots), so chattering sequences are
  resolved impact by impact with geometrically shrinking steps.
* Coming to rest (impacts accumulating): once an impact leaves less than ``rest_velocity``
  (dimensionless, ``theta' / p``) and the rotational acceleration on the new side points back
  to ``theta = 0``, the block is seated. The excursions that are dropped are smaller than
  ``rest_velocity² / (2 |theta''|)``. A seated block lifts off again, in closed form for the
  sine pulse, when ``|a|`` next exceeds ``g tan(alpha)``.
* After the pulse (``a = 0``) nothing is integrated: the energy
  ``E = omega²/2 + cos(alpha - |theta|) - cos(alpha)`` (per ``m g R``) is conserved between
  impacts and multiplied by ``e²`` at each one, so the block overturns if and only if it
  heads over the barrier ``1 - cos(alpha)`` with more energy than that, and otherwise its
  next peak is ``alpha - arccos(E + cos alpha)``, after which every impact lowers the energy
  and ``theta_max`` can no longer grow. A block beyond the hump (``|theta| > alpha``) at the
  end of the pulse overturns if it heads out, or heads in without the energy to recross the
  hump; with that energy it falls back to ``theta = 0``, impacts, and the same rules apply.
  This is exact, not an approximation.

Records
-------
A :class:`~opsrock.excitations.Record` is integrated segment by segment: its acceleration is
linear between samples, every step ends on a sample (no step straddles a kink), steps are also
bounded by ``max_dtau``, and a seated block's uplift is found in closed form on the segment where
``|a|`` first exceeds ``g tan(alpha)``. Impacts and peaks are located exactly as for the pulse,
and after the last sample the same exact energy verdict applies. On FEMA P695 floor motions it
matches the event-driven ``housner`` solver to 1.1e-5 alpha (validation case 8) at about a
millisecond per record (``opsrock bench --only records``).

Why numba: a per-case ``solve_ivp`` loop costs milliseconds per case (Python overhead per
step and per restart at every impact), too slow for 40,000-case spectra; a numpy-vectorised
fixed-step integrator over all cases wastes work on cases that have already settled or
overturned and handles per-case events clumsily. A compiled per-case integrator with a
thread pool over chunks of cases has neither problem. Measured by
``opsrock bench --only housner_fast`` on the 2-core project machine while it was shared
(load average 8-11): 40,000 cases in 2.4-3.7 s, 25-90 µs per case against 23-77 ms per
case for a per-case ``solve_ivp`` loop (x250-x2000), with ``|d theta_max| / alpha`` below
1e-8 of the converged answer. The kernel is compiled once and cached (``cache=True``, in
``__pycache__``): about 16-20 s for a cold compile on that machine, 2-4 s to load the
cache in a new process.
"""

from opsrock.solvers.housner_fast.grid import GridResult, solve_grid, solve_pulses
from opsrock.solvers.housner_fast.kernel import (
    STATUS_EVENT_FAILED,
    STATUS_MAX_IMPACTS,
    STATUS_MAX_STEPS,
    STATUS_NONFINITE,
    STATUS_OK,
    STATUS_REASONS,
)
from opsrock.solvers.housner_fast.settings import HousnerFastSettings
from opsrock.solvers.housner_fast.solver import SOLVER_NAME, solve

__all__ = ["GridResult", "HousnerFastSettings", "SOLVER_NAME", "STATUS_EVENT_FAILED", "STATUS_MAX_IMPACTS",
           "STATUS_MAX_STEPS", "STATUS_NONFINITE", "STATUS_OK", "STATUS_REASONS", "solve",
           "solve_grid", "solve_pulses"]
