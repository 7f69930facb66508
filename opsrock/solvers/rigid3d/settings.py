"""Numerical settings of the three-dimensional solver ``rigid3d``."""

from __future__ import annotations

from dataclasses import dataclass

from opsrock.errors import InputError
from opsrock.limits import int_at_least, positive_at_most, positive_finite, real_number
from opsrock.solvers.common import SolverSettings, refuse_value

#: Longest tail after the excitation when ``max_free_time`` is None, in units of ``1/p`` of the weaker axis.
DEFAULT_TAIL_DTAU: float = 2000.0


@dataclass(frozen=True)
class Rigid3DSettings(SolverSettings):
    """Numerical settings of :mod:`opsrock.solvers.rigid3d`: those of
    :class:`~opsrock.solvers.common.SolverSettings` (the block is followed to rest after the excitation:
    ``tail="rest"``, ``stop_at_rest=True``; ``end_time`` only with ``excitation=None``, the span of free motion)
    and the following.

    Times are in units of ``1/p`` and velocities in units of ``p R`` of the weaker axis (the smaller of
    ``alpha``, ``alpha_depth``; ``p = sqrt(g R / (r² + R²))`` for rocking in that plane, with ``R`` and ``r``
    that plane's: :attr:`Block.p` when the width is the weaker axis).

    Parameters
    ----------
    dtau : float
        Time step in units of ``1/p`` (dimensionless), in (0, 0.05]. The step is shortened so that the pulse,
        or each sample interval of a record, holds a whole number of steps. Default 1e-4 (the convergence
        study of :mod:`opsrock.solvers.rigid3d`).
    theta_mj : float
        Parameter of the theta-method, in [0.5, 1] (dimensionless). Default 0.5 (the midpoint).
    nsgs_tol : float
        Convergence tolerance of the nonsmooth Gauss-Seidel contact solver (dimensionless), in (0, 1e-4]: a
        step's sweeps stop when no impulse changes by more than ``nsgs_tol`` times the step's velocity scale
        (``g dt`` or the free velocity, whichever is larger). Default 1e-10.
    nsgs_max_sweeps : int
        Sweeps over the active corners allowed per step (>= 1); a step that needs more is counted as
        unconverged (``diagnostics["nsgs_unconverged_steps"]``) and keeps its last sweep. Default 500.
    nsgs_fail_steps : int
        Consecutive unconverged steps after which the run fails with its reason (>= 1). Default 500 (dtau 0.05 at
        the default step): with infinite friction (``friction=None``) a corner whose load vanishes can make the
        contact problem have no solution for a while (the infinite-friction limit slides it with a vanishing
        normal impulse); in a run of the directionality study 27 of 4,160 cases met 50 such steps in a row and
        failed, and three of them rerun went through 108 to 223 such steps in all (their runs of them shorter
        than 500) and overturned; with the closed form for two corners in the infinite-friction limit
        (``diagnostics["edge_slip_steps"]``) none of the study's 6,240 cases meets 500 in a row (3 did without
        it); a step that does not converge keeps its last sweep and is counted
        (``diagnostics["nsgs_unconverged_steps"]``).
    nsgs_loose_tol : float
        A step that has not met ``nsgs_tol`` in ``nsgs_max_sweeps`` sweeps goes on for up to
        ``nsgs_extra_sweeps`` sweeps more to this looser tolerance, in [nsgs_tol, 1e-4] (dimensionless; counted
        in ``diagnostics["nsgs_loose_steps"]``): a block at the stick-slip limit on three or four corners, whose
        impulses are statically indeterminate, makes Gauss-Seidel converge slowly (by 0.3 % a sweep in the
        cases seen), not diverge. Default 1e-5; in the cases seen the body's velocity then moved by about 1e-4
        of ``g dt`` a sweep's worth of the remaining iterations (2e-8 m/s): the slowly converging part of the
        impulses is mostly the indeterminate one, which does not move the block.
    nsgs_extra_sweeps : int
        Those further sweeps (>= 0; at least one is taken, to measure the change). Default 20: more cost more
        than they save (500 made a case of corner rocking 13 times slower and rescued no run).
    rest_velocity : float
        After the excitation, the block is at rest when its corners are down without slip and every velocity
        (``|V|``, ``R |omega|``) is below ``rest_velocity p R`` for ``rest_duration`` (dimensionless). Default 1e-6.
    rest_duration : float
        How long (units of ``1/p``) the block must stay at rest for the run to end. Default 1.0.
    max_free_time : float or None
        Longest tail after the excitation (s): a block still moving then is a failed run with its reason.
        None (default): :data:`DEFAULT_TAIL_DTAU` ``/ p``.
    max_steps : int or None
        Steps allowed per run (excitation and tail, the rest skip's included) before it fails. Default (and
        None) 200_000_000.
    history_dtau : float
        Spacing of the recorded history (units of ``1/p``). Default 0.01.
    velocity_tol : float
        Contact velocity (units of ``p R``) above which a loaded corner counts as slipping and an unloaded one
        as leaving the floor, and below which a block on its four stuck corners is seated (the rest skip then
        holds it while the floor's load is carried) (dimensionless). Default 1e-8.
    contact_gap : float
        A corner that had a normal impulse counts as down until it leaves the floor with a positive normal
        velocity or rises more than ``contact_gap (g + max |a_v| + max |a_h|) dt²`` (m; dimensionless
        factor), as in ``moreau_jean``. Default 20.
    rocked_theta : float
        The block *rocked* if its tilt ever exceeds this (rad). Default 1e-9.
    smooth : bool
        Cross the phases in which the block turns about one or two stuck corners
        (:mod:`opsrock.solvers.rigid3d.pivot`), or rocks on one or two corners of which one slips (the contact
        forces at acceleration level), with
        fourth-order Runge-Kutta steps of up to a sample interval, the Moreau-Jean steps keeping impacts, lift-off,
        the onset and end of slip, flight and overturning (True, default); False: Moreau-Jean steps throughout.

    The tail rule ``tail="peak"`` ends the run after the excitation once the block's energy can no longer bring
    its tilt to ``theta_max`` (an energy bound with a factor-2 margin, the base slower than 1 mm/s): the verdict
    and ``theta_max`` are then final, the end state is not a state of rest.
    """

    max_steps: int | None = 200_000_000
    dtau: float = 1e-4
    theta_mj: float = 0.5
    nsgs_tol: float = 1e-10
    nsgs_max_sweeps: int = 500
    nsgs_fail_steps: int = 500
    nsgs_loose_tol: float = 1e-5
    nsgs_extra_sweeps: int = 20
    rest_velocity: float = 1e-6
    rest_duration: float = 1.0
    history_dtau: float = 0.01
    velocity_tol: float = 1e-8
    contact_gap: float = 20.0
    rocked_theta: float = 1e-9
    smooth: bool = True

    @property
    def step_limit(self) -> int:
        """``max_steps``, 200_000_000 when None."""
        return 200_000_000 if self.max_steps is None else int(self.max_steps)

    def __post_init__(self) -> None:
        super().__post_init__()
        refuse_value("rigid3d", self, "tail", ("rest", "peak"))
        if not isinstance(self.smooth, bool):
            raise InputError(f"smooth must be True or False, got {self.smooth!r}")
        refuse_value("rigid3d", self, "stop_at_rest", (True,))
        positive_at_most("dtau", self.dtau, 0.05, " (units of 1/p)")
        theta = real_number("theta_mj", self.theta_mj)
        if not 0.5 <= theta <= 1.0:
            raise InputError(f"theta_mj must lie in [0.5, 1], got {self.theta_mj!r}")
        positive_at_most("nsgs_tol", self.nsgs_tol, 1e-4, "")
        int_at_least("nsgs_max_sweeps", self.nsgs_max_sweeps, 1)
        int_at_least("nsgs_fail_steps", self.nsgs_fail_steps, 1)
        loose = positive_at_most("nsgs_loose_tol", self.nsgs_loose_tol, 1e-4, "")
        if loose < self.nsgs_tol:
            raise InputError(f"nsgs_loose_tol must be >= nsgs_tol ({self.nsgs_tol!r}), got {self.nsgs_loose_tol!r}")
        int_at_least("nsgs_extra_sweeps", self.nsgs_extra_sweeps, 0)
        positive_at_most("rest_velocity", self.rest_velocity, 1e-3, " (units of p R)")
        positive_at_most("rest_duration", self.rest_duration, 1e3, " (units of 1/p)")
        positive_at_most("history_dtau", self.history_dtau, 10.0, " (units of 1/p)")
        positive_at_most("velocity_tol", self.velocity_tol, 1e-3, " (units of p R)")
        c = positive_finite("contact_gap", self.contact_gap)
        if not 2.0 <= c <= 1e4:
            raise InputError(f"contact_gap must lie in [2, 1e4], got {self.contact_gap!r}")
        positive_at_most("rocked_theta", self.rocked_theta, 1e-3, " rad")


__all__ = ["DEFAULT_TAIL_DTAU", "Rigid3DSettings"]
