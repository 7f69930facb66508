"""Numerical settings of the event-driven rigid-body solver."""

from __future__ import annotations

from dataclasses import dataclass

from opsrock.constants import EQUATIONS
from opsrock.limits import one_of, positive_finite
from opsrock.solvers.common import ScipySettings


@dataclass(frozen=True)
class HousnerSettings(ScipySettings):
    """Numerical settings of the rigid-body solver (the model has no free parameter): those of
    :class:`~opsrock.solvers.common.ScipySettings` and

    Parameters
    ----------
    atol : float
        Absolute tolerance on ``theta`` (rad). Default 1e-12 rad, far below any rotation of interest
        (alpha is 0.1-0.5 rad).
    rest_velocity_ratio : float
        After an impact the block is set down as seated if ``|theta'| < rest_velocity_ratio · p · alpha``
        (dimensionless). Default 1e-6: the bounces left would rise to ``~(1e-6)² alpha / 2`` at most.
    equations : str
        Form of the equation of motion, one of :data:`opsrock.constants.EQUATIONS`. Default ``"exact"``
        (Eq. 1); ``"linearised"`` for the small-angle form of the classical papers.
    """

    atol: float = 1e-12
    rest_velocity_ratio: float = 1e-6
    equations: str = "exact"

    def __post_init__(self) -> None:
        super().__post_init__()
        one_of("equations", self.equations, EQUATIONS)
        positive_finite("rest_velocity_ratio", self.rest_velocity_ratio)


__all__ = ["HousnerSettings"]
