"""The paper's equivalent SDOF model (Eq. 5-8): its parameters and its spring table.

This module holds the *model* both SDOF solvers share (the OpenSees one and the scipy one),
never their numerics: the damper band ``delta``, the stiff branch ``theta_e``, the spring
table and the excitation lever ``Lambda``.

    I_O theta'' + f_d(theta, theta') + M_s(theta) = -Lambda a(t)

* ``M_s(theta) = m g R sin(alpha sgn(theta) - theta)`` (Eq. 5), tabulated piecewise-linearly with a
  stiff branch of half-width ``theta_e`` through zero;
* ``f_d = c_D theta'`` while ``|theta| <= delta alpha``, zero outside, with
  ``c_D = I_O (1 - e) |theta'_1| / (2 delta alpha)`` set on entering the band (Eq. 7-8);
* ``Lambda = m R cos(alpha)`` (``lever="housner"``, default) or the paper's printed
  ``I_O cos(alpha) / R`` (``lever="printed"``); docs/modelling.md section 2 explains the choice.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from opsrock._checks import in_open_interval, int_at_least, one_of
from opsrock.block import Block
from opsrock.constants import G

#: Excitation lever options: ``"housner"`` = ``m R cos(alpha)`` (agrees with Eq. 1 and the
#: uplift threshold Eq. 4), ``"printed"`` = ``I_O cos(alpha) / R`` as printed in Eq. 6.
LEVERS: tuple[str, ...] = ("housner", "printed")

#: Default damper band ``delta`` (fraction of alpha). Chosen by the model-form convergence
#: study (validation/model_form): see the README's validation section.
DEFAULT_DELTA: float = 0.005

#: Default stiff-branch half-width ``theta_e / alpha``. docs/modelling.md section 4: 1e-6 alpha matched
#: the rigid-body first peak to 0.04 %, 1e-4 alpha gave 0.9 % high, 1e-2 alpha 10 % low.
DEFAULT_THETA_E_RATIO: float = 1e-6

#: Default number of table points per side beyond the stiff branch. docs/modelling.md section 4:
#: about 30 points give 0.1-0.2 % of ``m g R sin(alpha)``.
DEFAULT_TABLE_POINTS: int = 30

#: The table extends this far beyond ``pi/2 + alpha`` (rad), so an overturning block never
#: runs off the table before the overturning check stops the analysis.
TABLE_MARGIN: float = 0.2


@dataclass(frozen=True)
class SDOFModel:
    """Parameters of the equivalent SDOF model (not of any solver's numerics).

    Parameters
    ----------
    delta : float
        Half-width of the damper band as a fraction of ``alpha`` (dimensionless, in (0, 1)).
    theta_e_ratio : float
        Half-width of the stiff spring branch, ``theta_e / alpha`` (dimensionless, in (0, delta)).
    table_points : int
        Number of tabulated points per side beyond the stiff branch (>= 4).
    lever : str
        Excitation lever, one of :data:`LEVERS`.
    """

    delta: float = DEFAULT_DELTA
    theta_e_ratio: float = DEFAULT_THETA_E_RATIO
    table_points: int = DEFAULT_TABLE_POINTS
    lever: str = "housner"

    def __post_init__(self) -> None:
        object.__setattr__(self, "delta", in_open_interval("delta", self.delta, 0.0, 1.0))
        object.__setattr__(self, "theta_e_ratio", in_open_interval("theta_e_ratio", self.theta_e_ratio, 0.0, 1.0))
        if self.theta_e_ratio >= self.delta:
            # name delta when theta_e_ratio is at its default: delta is what the caller changed
            changed = "delta" if self.theta_e_ratio == DEFAULT_THETA_E_RATIO else "theta_e_ratio"
            value = self.delta if changed == "delta" else self.theta_e_ratio
            raise ValueError(
                f"{changed} = {value!r}: the stiff branch must lie inside the damper band, i.e. "
                f"theta_e_ratio < delta; got theta_e_ratio = {self.theta_e_ratio:g}, delta = {self.delta:g}"
            )
        int_at_least("table_points", self.table_points, 4)
        one_of("lever", self.lever, LEVERS)

    # --- derived, per block ----------------------------------------------------------------
    def theta_e(self, block: Block) -> float:
        """Stiff-branch half-width ``theta_e`` (rad)."""
        return self.theta_e_ratio * block.alpha

    def band(self, block: Block) -> float:
        """Damper band half-width ``delta alpha`` (rad)."""
        return self.delta * block.alpha

    def lever_arm(self, block: Block) -> float:
        """Excitation lever ``Lambda`` (kg m): moment per unit floor acceleration."""
        return lever_coefficient(block, self.lever)

    def damping_coefficient(self, block: Block, entry_velocity: float) -> float:
        """``c_D = I_O (1 - e) |theta'_1| / (2 delta alpha)`` (N m s/rad), Eq. 8.

        Parameters
        ----------
        block : Block
        entry_velocity : float
            Angular velocity on entering the band, ``theta'_1`` (rad/s).
        """
        return block.I_O * (1.0 - block.e) * abs(entry_velocity) / (2.0 * self.band(block))

    def spring_table(self, block: Block) -> tuple[np.ndarray, np.ndarray]:
        """Tabulated restoring moment, symmetric about zero.

        Returns
        -------
        theta : ndarray
            Rotations (rad), increasing: ``-theta_end .. -theta_e, theta_e .. theta_end``
            with ``theta_end = pi/2 + alpha + TABLE_MARGIN``.
        moment : ndarray
            ``M_s = m g R sin(alpha sgn(theta) - theta)`` at those rotations (N m). Between
            ``-theta_e`` and ``theta_e`` the table is a straight stiff branch through zero.
        """
        theta_e = self.theta_e(block)
        theta_end = 0.5 * math.pi + block.alpha + TABLE_MARGIN
        pos = np.linspace(theta_e, theta_end, self.table_points + 1)
        m_pos = block.mass * G * block.R * np.sin(block.alpha - pos)
        theta = np.concatenate([-pos[::-1], pos])
        moment = np.concatenate([-m_pos[::-1], m_pos])
        return theta, moment


def lever_coefficient(block: Block, lever: str = "housner") -> float:
    """Excitation lever ``Lambda`` (kg m) for the named option (see :data:`LEVERS`)."""
    one_of("lever", lever, LEVERS)
    if lever == "housner":
        return block.mass * block.R * math.cos(block.alpha)
    return block.I_O * math.cos(block.alpha) / block.R


#: Relative round-off allowance of the uplift test: ``PFA = 1.0 g tan(alpha)`` computed in floating
#: point may exceed the peak restoring moment by an ulp or two.
UPLIFT_RTOL: float = 1e-9


def can_uplift(block: Block, model: "SDOFModel", pfa: float) -> bool:
    """Eq. 4 for the SDOF model: can a floor motion of peak ``pfa`` (m/s²) uplift the block from rest?

    True when the peak excitation moment ``|Lambda| PFA`` exceeds the peak restoring moment
    ``m g R sin(alpha)`` (beyond a round-off allowance :data:`UPLIFT_RTOL`). With the housner
    lever this is ``PFA > g tan(alpha)``; with the printed lever ``PFA > 0.75 g tan(alpha)``.

    The SDOF model's stiff branch is finite, so at exactly the threshold it sits at neutral
    equilibrium and can tip numerically (measured in OpenSees: up to 0.03 alpha in 6 of the 40
    threshold cases of the paper grid); the solvers use this test instead (``uplift_check``).
    """
    return abs(model.lever_arm(block)) * pfa > block.overturning_rotation_moment * (1.0 + UPLIFT_RTOL)


def restoring_moment(block: Block, theta: np.ndarray | float) -> np.ndarray:
    """Exact restoring moment ``m g R sin(alpha sgn(theta) - theta)`` (N m), Eq. 5."""
    theta = np.asarray(theta, dtype=float)
    return block.mass * G * block.R * np.sin(block.alpha * np.sign(theta) - theta)


__all__ = [
    "DEFAULT_DELTA",
    "DEFAULT_TABLE_POINTS",
    "DEFAULT_THETA_E_RATIO",
    "LEVERS",
    "SDOFModel",
    "UPLIFT_RTOL",
    "can_uplift",
    "lever_coefficient",
    "restoring_moment",
]
