"""Numerical settings of the three-dimensional solver ``rigid3d``."""

from __future__ import annotations

from dataclasses import dataclass

from opsrock.solvers.common import SolverSettings, refuse_value


@dataclass(frozen=True)
class Rigid3DSettings(SolverSettings):
    """Numerical settings of :mod:`opsrock.solvers.rigid3d`: those of
    :class:`~opsrock.solvers.common.SolverSettings` (the block is followed to rest after the excitation) and
    the following. Times are in units of ``1/p`` of the weaker axis.

    Parameters
    ----------
    dtau : float
        Time step in units of ``1/p`` (dimensionless). Default 1e-4.
    theta_mj : float
        Parameter of the theta-method, in [0.5, 1] (dimensionless). Default 0.5.
    history_dtau : float
        Spacing of the recorded history (units of ``1/p``). Default 0.01.
    """

    max_steps: int | None = 200_000_000
    dtau: float = 1e-4
    theta_mj: float = 0.5
    history_dtau: float = 0.01

    def __post_init__(self) -> None:
        super().__post_init__()
        refuse_value("rigid3d", self, "tail", ("rest",))
        refuse_value("rigid3d", self, "stop_at_rest", (True,))


__all__ = ["Rigid3DSettings"]
