"""Numerical settings of the three-dimensional cylinder solver ``cylinder3d``."""

from __future__ import annotations

from dataclasses import dataclass

from opsrock.errors import InputError
from opsrock.limits import int_at_least, positive_at_most, positive_finite, real_number
from opsrock.solvers.common import SolverSettings, refuse_value

#: Longest tail after the excitation when ``max_free_time`` is None, in units of ``1/p`` (a fortieth of rigid3d's,
#: about eight rocking periods of small amplitude: a cylinder may go on wobbling on its rim without end, nothing in
#: the rigid model resisting rolling, and the tail then ends with the verdict known from its energy:
#: :mod:`opsrock.solvers.cylinder3d`).
DEFAULT_TAIL_DTAU: float = 50.0


@dataclass(frozen=True)
class Cylinder3DSettings(SolverSettings):
    """Numerical settings of :mod:`opsrock.solvers.cylinder3d`: those of
    :class:`~opsrock.solvers.common.SolverSettings` (the cylinder is followed to rest after the excitation:
    ``tail="rest"``, ``stop_at_rest=True``; ``end_time`` only with ``excitation=None``) and the following. Times are
    in units of ``1/p`` and velocities in units of ``p R`` of the cylinder rocking in a vertical plane through its
    axis (``R = hypot(r, h_cm)``, ``p = sqrt(g R / (r_g² + R²))``).

    Parameters
    ----------
    dtau : float
        Time step in units of ``1/p`` (dimensionless), in (0, 0.05]; shortened so that the pulse, or each sample
        interval of a record, holds a whole number of steps. Default 1e-4 (as rigid3d: its planar-limit study).
    theta_mj : float
        Parameter of the theta-method, in [0.5, 1]. Default 0.5.
    rim_points : int
        Points round the rim that carry the base while it is flat (at rest, sliding on the full base), in [3, 64]:
        spaced evenly from the lowest rim point (or, the base flat, from the rim point the floor's load pushes
        towards). Default 16.
    nsgs_tol : float
        Convergence tolerance of nonsmooth Gauss-Seidel on the flat base's rim points (dimensionless, relative to
        ``g dt``), in (0, 1e-4]. Default 1e-9.
    nsgs_max_sweeps : int
        Sweeps allowed per step (>= 1). Default 300.
    nsgs_fail_steps : int
        Consecutive unconverged steps after which the run fails (>= 1). Default 500.
    rest_velocity : float
        After the excitation the cylinder is at rest when it stands on its base without slip and every velocity is
        below ``rest_velocity p R`` for ``rest_duration`` (dimensionless). Default 1e-6.
    rest_duration : float
        How long (units of ``1/p``) it must stay at rest for the run to end. Default 1.0.
    max_steps : int or None
        Steps allowed per run (excitation and tail). Default (and None) 200_000_000.
    history_dtau : float
        Spacing of the recorded history (units of ``1/p``). Default 0.01.
    velocity_tol : float
        Speed (units of ``p R``) below which a cylinder on its stuck base is seated (the rest skip holds it while
        the floor's load is carried). Default 1e-8.
    contact_gap : float
        A rim point is in contact while its predicted height is at most ``contact_gap (g + max |a_v| + max |a_h|)
        dt²`` (m; dimensionless factor), in [2, 1e4]. Default 20 (rigid3d's).
    rocked_theta : float
        The cylinder *rocked* if its tilt ever exceeds this (rad). Default 1e-9.
    smooth : bool
        Cross the phase in which the cylinder rolls without slip on one rim point (rocking on it, wobbling) with
        fourth-order Runge-Kutta sub-steps of up to ``5e-3/p`` (:mod:`opsrock.solvers.cylinder3d.rolling`), the
        Moreau-Jean steps keeping landings, lift-off, the onset of slip, the base flat, flight and overturning
        (True, default); False: Moreau-Jean steps throughout.
    """

    max_steps: int | None = 200_000_000
    dtau: float = 1e-4
    theta_mj: float = 0.5
    rim_points: int = 16
    nsgs_tol: float = 1e-9
    nsgs_max_sweeps: int = 300
    nsgs_fail_steps: int = 500
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
        refuse_value("cylinder3d", self, "tail", ("rest",))
        refuse_value("cylinder3d", self, "stop_at_rest", (True,))
        positive_at_most("dtau", self.dtau, 0.05, " (units of 1/p)")
        theta = real_number("theta_mj", self.theta_mj)
        if not 0.5 <= theta <= 1.0:
            raise InputError(f"theta_mj must lie in [0.5, 1], got {self.theta_mj!r}")
        int_at_least("rim_points", self.rim_points, 3)
        if self.rim_points > 64:
            raise InputError(f"rim_points must lie in [3, 64], got {self.rim_points!r}")
        positive_at_most("nsgs_tol", self.nsgs_tol, 1e-4, "")
        int_at_least("nsgs_max_sweeps", self.nsgs_max_sweeps, 1)
        int_at_least("nsgs_fail_steps", self.nsgs_fail_steps, 1)
        positive_at_most("rest_velocity", self.rest_velocity, 1e-3, " (units of p R)")
        positive_at_most("rest_duration", self.rest_duration, 1e3, " (units of 1/p)")
        positive_at_most("history_dtau", self.history_dtau, 10.0, " (units of 1/p)")
        positive_at_most("velocity_tol", self.velocity_tol, 1e-3, " (units of p R)")
        c = positive_finite("contact_gap", self.contact_gap)
        if not 2.0 <= c <= 1e4:
            raise InputError(f"contact_gap must lie in [2, 1e4], got {self.contact_gap!r}")
        positive_at_most("rocked_theta", self.rocked_theta, 1e-3, " rad")


__all__ = ["DEFAULT_TAIL_DTAU", "Cylinder3DSettings"]
