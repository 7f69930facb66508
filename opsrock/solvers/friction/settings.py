"""Numerical settings of the compiled friction solver."""

from __future__ import annotations

from dataclasses import dataclass

from opsrock.limits import bool_fields, compiled_stepping, positive_finite


@dataclass(frozen=True)
class FrictionSettings:
    """Numerical settings of the event-driven rigid block with friction (all dimensionless).

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
    max_steps : int
        Steps allowed per case (integrator steps and departures from rest) before it is reported as
        failed. Default 10**7.
    max_tail : float
        How long, in units of ``1/p``, the block is followed after the excitation ends before a case
        still moving is reported as failed. Default 10000 (a block of ``p = 3 rad/s`` for 55 min).
    """

    max_dtau: float = 0.02
    steps_per_pulse: int = 200
    rest_velocity: float = 1e-7
    max_impacts: int = 100_000
    max_steps: int = 10_000_000
    max_tail: float = 10_000.0

    def __post_init__(self) -> None:
        bool_fields(self)
        compiled_stepping(self)
        positive_finite("max_tail", self.max_tail)


__all__ = ["FrictionSettings"]
