"""Numerical settings of the compiled friction solver."""

from __future__ import annotations

from dataclasses import dataclass

from opsrock.limits import compiled_stepping
from opsrock.solvers.common import SolverSettings, refuse_value

#: Longest follow-up after the excitation when ``max_free_time`` is None, in units of ``1/p``
#: (a block of ``p = 3 rad/s`` for 55 min).
DEFAULT_TAIL_DTAU: float = 10_000.0


@dataclass(frozen=True)
class FrictionSettings(SolverSettings):
    """Numerical settings of the event-driven rigid block with friction: those of
    :class:`~opsrock.solvers.common.SolverSettings` (this solver follows the block to rest after the
    excitation: ``tail="rest"``, ``stop_at_rest=True``; ``end_time`` only with ``excitation=None``, where it
    is the span of the still floor, after which the block is followed to rest as always) and

    Parameters
    ----------
    max_dtau : float
        Largest Runge-Kutta step in units of ``1/p`` (``tau = p t``), during the excitation and after
        it. Default 0.02, as ``housner_fast`` (whose measurements justify it for the rocking mode; the
        sliding modes' equations are no stiffer).
    steps_per_pulse : int
        Minimum number of steps per pulse period (dimensionless count). Default 200.
    rest_velocity : float
        Rotation rate, in units of ``p``, below which a block leaving an impact towards a restoring
        acceleration is seated (and the base's slip rate below which it stops with it). Default 1e-7,
        as ``housner_fast``.
    max_impacts : int
        Impacts allowed per case before it is reported as failed. Default 100000.
    max_steps : int or None
        Steps allowed per case (integrator steps and departures from rest) before it is reported as
        failed. Default (and None) 10**7.
    max_free_time : float or None
        How long (s) the block is followed after the excitation ends before a case still moving is
        reported as failed; a pure slide whose friction cannot stop it within this time (none on a
        frictionless floor) ends at once with status ok and its slip velocity (docs/guide/friction.md, the
        ending rule). None (default): :data:`DEFAULT_TAIL_DTAU` ``/ p``.
    """

    max_steps: int | None = 10_000_000
    max_dtau: float = 0.02
    steps_per_pulse: int = 200
    rest_velocity: float = 1e-7
    max_impacts: int = 100_000

    @property
    def step_limit(self) -> int:
        """``max_steps``, 10**7 when None."""
        return 10_000_000 if self.max_steps is None else int(self.max_steps)

    def __post_init__(self) -> None:
        super().__post_init__()
        refuse_value("friction", self, "tail", ("rest",))
        refuse_value("friction", self, "stop_at_rest", (True,))
        compiled_stepping(self)


__all__ = ["DEFAULT_TAIL_DTAU", "FrictionSettings"]
