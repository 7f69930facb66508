"""Numerical settings of the Moreau-Jean reference solver."""

from __future__ import annotations

from dataclasses import dataclass

from opsrock.errors import InputError
from opsrock.limits import positive_at_most, positive_finite, real_number
from opsrock.solvers.common import SolverSettings, refuse_value

#: Longest tail after the excitation when ``max_free_time`` is None, in units of ``1/p``.
DEFAULT_TAIL_DTAU: float = 2000.0


@dataclass(frozen=True)
class MoreauJeanSettings(SolverSettings):
    """Numerical settings of :mod:`opsrock.solvers.moreau_jean`: those of
    :class:`~opsrock.solvers.common.SolverSettings` (the block is followed to rest after the excitation:
    ``tail="rest"``, ``stop_at_rest=True``; ``end_time`` only with ``excitation=None``, the span of free
    motion, with no tail) and the following.

    Times are in units of ``1/p`` (``tau = p t``, ``p = sqrt(3 g / 4 R)``), velocities in units of
    ``p R`` (m/s per m/s), so one setting suits every block.

    Parameters
    ----------
    dtau : float
        Time step in units of ``1/p`` (dimensionless), in (0, 0.05]. The step is shortened so that the
        pulse, or each sample interval of a record, holds a whole number of steps. Default 1e-4, from the
        convergence measured in :mod:`opsrock.solvers.moreau_jean` (module docstring): the scheme is
        first order; at 1e-4 the rocking peak ``theta_max / alpha`` is within 6e-5 (one-sine pulse) and
        1e-3 (a FEMA P695 record) of the event-driven Housner solution, slides of a block that cannot rock
        within 1e-7 of Newmark's closed forms, the energy residual is 0.2 % of the input work, and a
        30 s record costs about 0.2 s of CPU (over 100 record-seconds per CPU-second).
    theta_mj : float
        Parameter of the theta-method, in [0.5, 1] (dimensionless): ``q_{k+1} = q_k + dt [(1 -
        theta_mj) v_k + theta_mj v_{k+1}]`` and the forces are evaluated at ``t_k + theta_mj dt``.
        Default 0.5 (the midpoint: no numerical damping of the smooth motion, and the discrete energy
        identity of the module docstring holds exactly).
    local_tol : float
        Slack of the contact laws in the local solver (dimensionless), in (0, 1e-6]: a candidate status
        pair of the two corners is accepted if every inequality (``P_N >= 0``, ``U_N >= 0``, the friction
        cone, the slip direction) holds to ``local_tol`` times the step's velocity scale (the free
        velocity, or ``g dt``). The local problem is solved exactly (a closed form for one contact,
        enumeration of the status pairs for two), so there are no iterations; the slack only absorbs
        round-off. Default 1e-10.
    rest_velocity : float
        After the excitation, the block is at rest when both corners are down without slip and every
        velocity (``|x'|``, ``|y'|``, ``R |theta'|``) is below ``rest_velocity p R`` for ``rest_duration``
        (dimensionless). Default 1e-6. Moreau-Jean brings a seated block to exactly zero velocity
        (the impulses cancel the step's gravity), so any small value works.
    rest_duration : float
        How long (units of ``1/p``) the block must stay at rest for the run to end. Default 1.0.
    max_free_time : float or None
        Longest tail after the excitation (s): a block still moving then is a failed run with its
        reason. None (default): :data:`DEFAULT_TAIL_DTAU` ``/ p`` (a block of R = 1 m: 740 s; measured: free
        rocking from 0.5 alpha comes to rest within 15/p, a record's block within a few 1/p of its end).
    max_steps : int or None
        Steps allowed per run (excitation and tail) before it fails. Default (and None) 200_000_000.
    history_dtau : float
        Spacing of the recorded history (units of ``1/p``); a row every ``max(1, round(history_dtau /
        dtau))`` steps and the last state. Default 0.01. Peaks, ``slide_max`` and the contact summary
        use every step.
    velocity_tol : float
        Contact velocity (units of ``p R``) above which a loaded corner counts as slipping, and an
        unloaded corner as leaving the floor (dimensionless). Default 1e-8. A stuck corner has zero
        tangential velocity up to round-off (the local problem is solved exactly), far below it.
    contact_gap : float
        A corner that had a normal impulse counts as down until it leaves the floor with a positive
        normal velocity or rises more than ``contact_gap (g + max |a_v| + max |a_h|) dt²`` (m;
        ``contact_gap`` dimensionless). Default 20. A rotating pivot constrained at velocity level
        drifts up by about ``h theta'² dt²`` per step; Moreau-Jean then takes one free step and the
        corner falls back (measured gaps of those free steps below ``0.25 g dt²``). Without this margin
        those steps would count as flights and their landings as impacts.
    rocked_theta : float
        The block *rocked* if ``|theta|`` ever exceeds this (rad). Default 1e-9: a seated or sliding
        block keeps ``|theta|`` at round-off level (below 1e-14), one that lifts exceeds it at once.
    """

    max_steps: int | None = 200_000_000
    dtau: float = 1e-4
    theta_mj: float = 0.5
    local_tol: float = 1e-10
    rest_velocity: float = 1e-6
    rest_duration: float = 1.0
    history_dtau: float = 0.01
    velocity_tol: float = 1e-8
    contact_gap: float = 20.0
    rocked_theta: float = 1e-9

    @property
    def step_limit(self) -> int:
        """``max_steps``, 200_000_000 when None."""
        return 200_000_000 if self.max_steps is None else int(self.max_steps)

    def __post_init__(self) -> None:
        super().__post_init__()
        refuse_value("moreau_jean", self, "tail", ("rest",))
        refuse_value("moreau_jean", self, "stop_at_rest", (True,))
        positive_at_most("dtau", self.dtau, 0.05, " (units of 1/p)")
        theta = real_number("theta_mj", self.theta_mj)
        if not 0.5 <= theta <= 1.0:
            raise InputError(f"theta_mj must lie in [0.5, 1], got {self.theta_mj!r}")
        positive_at_most("local_tol", self.local_tol, 1e-6, "")
        positive_at_most("rest_velocity", self.rest_velocity, 1e-3, " (units of p R)")
        positive_at_most("rest_duration", self.rest_duration, 1e3, " (units of 1/p)")
        positive_at_most("history_dtau", self.history_dtau, 10.0, " (units of 1/p)")
        positive_at_most("velocity_tol", self.velocity_tol, 1e-3, " (units of p R)")
        c = positive_finite("contact_gap", self.contact_gap)
        if not 2.0 <= c <= 1e4:
            raise InputError(f"contact_gap must lie in [2, 1e4], got {self.contact_gap!r}")
        positive_at_most("rocked_theta", self.rocked_theta, 1e-3, " rad")


__all__ = ["DEFAULT_TAIL_DTAU", "MoreauJeanSettings"]
