"""Analytic floor-acceleration pulses: the one-sine pulse of the paper.

Sign convention (docs/modelling.md section 2): a positive floor acceleration tips the block towards
negative ``theta``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from opsrock._checks import one_of, positive_finite
from opsrock.constants import G
from opsrock.limits import check, scaled_input

if TYPE_CHECKING:
    from opsrock.block import Block

#: Peak-floor-velocity conventions for IM3 and IM8 (docs/modelling.md section 2).
#: ``"amplitude"``: the harmonic velocity amplitude ``PFA / omega_p``, which the paper's
#: Table 3 medians fit; ``"peak"``: the true peak of the floor velocity from rest,
#: ``2 PFA / omega_p``, reached at ``t = T_p / 2``.
PFV_CONVENTIONS: tuple[str, ...] = ("amplitude", "peak")


@dataclass(frozen=True)
class OneSinePulse:
    """One full sine cycle of floor acceleration, ``a(t) = PFA sin(omega_p t)`` on ``[0, T_p]``.

    Parameters
    ----------
    pfa : float
        Peak floor acceleration ``PFA`` (m/s²), within :data:`opsrock.limits.LIMITS`.
    omega_p : float
        Circular frequency of the pulse ``omega_p`` (rad/s), within :data:`opsrock.limits.LIMITS`.
    """

    pfa: float
    omega_p: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "pfa", check("pfa", self.pfa))
        object.__setattr__(self, "omega_p", check("omega_p", self.omega_p))

    @classmethod
    def from_ratios(cls, block: "Block", pfa_ratio: float, freq_ratio: float) -> "OneSinePulse":
        """Build a pulse from the dimensionless pair of the overturning spectrum.

        Parameters
        ----------
        block : Block
            The block that sets the scales ``g tan(alpha)`` and ``p``.
        pfa_ratio : float
            ``PFA / (g tan alpha)`` (dimensionless, IM2), > 0.
        freq_ratio : float
            ``omega_p / p`` (dimensionless, IM1), > 0.
        """
        pfa_ratio = positive_finite("pfa_ratio", pfa_ratio)
        freq_ratio = positive_finite("freq_ratio", freq_ratio)
        return cls(
            pfa=scaled_input("pfa_ratio", pfa_ratio, "pfa", block.uplift_acceleration),
            omega_p=scaled_input("freq_ratio", freq_ratio, "omega_p", block.p),
        )

    @classmethod
    def from_hz(cls, pfa_g: float, frequency_hz: float) -> "OneSinePulse":
        """Build a pulse from ``PFA`` in g and the pulse frequency in Hz."""
        pfa_g = positive_finite("pfa_g", pfa_g)
        frequency_hz = positive_finite("frequency_hz", frequency_hz)
        return cls(pfa=scaled_input("pfa_g", pfa_g, "pfa", G), omega_p=scaled_input("frequency_hz", frequency_hz, "omega_p", 2.0 * math.pi))

    @property
    def T_p(self) -> float:  # noqa: N802  (the paper's symbol)
        """Pulse period ``T_p = 2 pi / omega_p`` (s)."""
        return 2.0 * math.pi / self.omega_p

    @property
    def duration(self) -> float:
        """Pulse duration, equal to ``T_p`` (s)."""
        return self.T_p

    @property
    def frequency_hz(self) -> float:
        """Pulse frequency ``omega_p / 2 pi`` (Hz)."""
        return self.omega_p / (2.0 * math.pi)

    def pfv(self, convention: str = "amplitude") -> float:
        """Peak floor velocity (m/s) under the named convention (see :data:`PFV_CONVENTIONS`)."""
        one_of("convention", convention, PFV_CONVENTIONS)
        amplitude = self.pfa / self.omega_p
        return amplitude if convention == "amplitude" else 2.0 * amplitude

    @property
    def PFV(self) -> float:  # noqa: N802
        """Peak floor velocity in the paper's convention, ``PFA / omega_p`` (m/s)."""
        return self.pfv("amplitude")

    def pfa_ratio(self, block: "Block") -> float:
        """``PFA / (g tan alpha)`` for ``block`` (dimensionless)."""
        return self.pfa / block.uplift_acceleration

    def freq_ratio(self, block: "Block") -> float:
        """``omega_p / p`` for ``block`` (dimensionless)."""
        return self.omega_p / block.p

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """Floor acceleration (m/s²) at times ``t`` (s); zero outside ``[0, T_p]``."""
        t = np.asarray(t, dtype=float)
        inside = (t >= 0.0) & (t <= self.T_p)
        # evaluate the sine inside the pulse only: omega_p t outside it can be arbitrarily large
        return np.where(inside, self.pfa * np.sin(self.omega_p * np.where(inside, t, 0.0)), 0.0)

    def breakpoints(self) -> np.ndarray:
        """Start and end of the pulse (s): the acceleration's slope jumps there."""
        return np.array([0.0, self.T_p])
