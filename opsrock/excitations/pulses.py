"""Analytic floor-acceleration pulses: the paper's one-sine pulse and the classical pulse family of
the rocking literature.

Every pulse starts at ``t = 0`` from a floor at rest and is zero after its :attr:`duration`:

==============  ==========================================  ===============================  ==========
shape           ``a(t)`` on the pulse                       duration                         ``omega_p``
==============  ==========================================  ===============================  ==========
``rectangular``  ``PFA``                                    ``t_1``                          ``pi / t_1``
``half-sine``    ``PFA sin(omega_p t)``                     ``T_p / 2``                      its own
``one-sine``     ``PFA sin(omega_p t)``                     ``T_p``                          its own
``one-cosine``   ``PFA cos(omega_p t)``                     ``T_p``                          its own
``ricker``       ``PFA (1 - 2 x²) exp(-x²)``,               ``2 t_0``, ``t_0 = 1.6 T_p``     peak of its
                 ``x = omega_p (t - t_0) / 2``                                               Fourier amplitude
==============  ==========================================  ===============================  ==========

with ``T_p = 2 pi / omega_p``. ``omega_p`` is the frequency the dimensionless ratio ``omega_p / p``
(IM1) and the Table 1 intensity measures use: for the rectangular pulse it is the frequency of the
half-sine of the same duration (so ``p t_1 = pi / (omega_p / p)``); for the symmetric Ricker wavelet it
is the frequency at which its Fourier amplitude peaks. The Ricker wavelet has infinite support; it is
cut at ``|t - t_0| = 1.6 T_p``, where it is below ``6e-10 PFA``.

Sign convention (docs/guide/modelling.md section 2): a positive floor acceleration tips the block towards
negative ``theta``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from opsrock.constants import G, PULSE_SHAPE_NAMES
from opsrock.limits import check, one_of, positive_finite, scaled_input

if TYPE_CHECKING:
    from opsrock.block import Block

#: Peak-floor-velocity conventions for IM3 and IM8 (docs/guide/modelling.md section 2).
#: ``"amplitude"``: the harmonic velocity amplitude ``PFA / omega_p``, which the paper's
#: Table 3 medians fit; ``"peak"``: the true peak of the floor velocity from rest (for the one-sine
#: pulse ``2 PFA / omega_p``, reached at ``t = T_p / 2``).
PFV_CONVENTIONS: tuple[str, ...] = ("amplitude", "peak")

#: Half-width of the cut Ricker wavelet, in units of ``T_p``.
RICKER_HALF_WIDTH: float = 1.6


@dataclass(frozen=True)
class Pulse:
    """Base of the analytic pulses: a peak acceleration ``pfa`` and a frequency ``omega_p``.

    Parameters
    ----------
    pfa : float
        Peak floor acceleration ``PFA`` (m/s²), within :data:`opsrock.limits.LIMITS`.
    omega_p : float
        Circular frequency of the pulse ``omega_p`` (rad/s), within :data:`opsrock.limits.LIMITS`;
        its meaning per shape is in the module docstring.
    vertical : float, optional
        A constant vertical floor acceleration ``a_v`` (m/s², positive up) acting over the whole
        run, during the pulse and after it, so the block feels ``g + a_v`` throughout; within
        :data:`opsrock.limits.LIMITS` (``g + a_v > 0``). Default 0. Only the solvers of the
        ``friction`` model take it; the others refuse a non-zero value.
    """

    pfa: float
    omega_p: float
    vertical: float = 0.0
    #: Name of the shape (a key of :data:`PULSE_SHAPES`).
    SHAPE: ClassVar[str] = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "pfa", check("pfa", self.pfa))
        object.__setattr__(self, "omega_p", check("omega_p", self.omega_p))
        object.__setattr__(self, "vertical", check("vertical", self.vertical))

    @classmethod
    def from_ratios(cls, block: "Block", pfa_ratio: float, freq_ratio: float) -> "Pulse":
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
    def from_hz(cls, pfa_g: float, frequency_hz: float) -> "Pulse":
        """Build a pulse from ``PFA`` in g and the pulse frequency ``omega_p / 2 pi`` in Hz."""
        pfa_g = positive_finite("pfa_g", pfa_g)
        frequency_hz = positive_finite("frequency_hz", frequency_hz)
        return cls(pfa=scaled_input("pfa_g", pfa_g, "pfa", G), omega_p=scaled_input("frequency_hz", frequency_hz, "omega_p", 2.0 * math.pi))

    @property
    def shape(self) -> str:
        """Name of the shape (a key of :data:`PULSE_SHAPES`)."""
        return self.SHAPE

    @property
    def T_p(self) -> float:  # noqa: N802  (the paper's symbol)
        """Pulse period ``T_p = 2 pi / omega_p`` (s)."""
        return 2.0 * math.pi / self.omega_p

    @property
    def frequency_hz(self) -> float:
        """Pulse frequency ``omega_p / 2 pi`` (Hz)."""
        return self.omega_p / (2.0 * math.pi)

    @property
    def duration(self) -> float:
        """Time after which the acceleration is zero (s)."""
        raise NotImplementedError

    def peak_velocity(self) -> float:
        """True peak of the floor velocity from rest (m/s)."""
        raise NotImplementedError

    def pfv(self, convention: str = "amplitude") -> float:
        """Peak floor velocity (m/s) under the named convention (see :data:`PFV_CONVENTIONS`)."""
        one_of("convention", convention, PFV_CONVENTIONS)
        return self.pfa / self.omega_p if convention == "amplitude" else self.peak_velocity()

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

    def shape_values(self, t: np.ndarray) -> np.ndarray:
        """``a(t) / PFA`` for times ``t`` (s) inside ``[0, duration]``."""
        raise NotImplementedError

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """Floor acceleration (m/s²) at times ``t`` (s); zero outside ``[0, duration]``."""
        t = np.asarray(t, dtype=float)
        inside = (t >= 0.0) & (t <= self.duration)
        # evaluate the shape inside the pulse only: omega_p t outside it can be arbitrarily large
        return np.where(inside, self.pfa * self.shape_values(np.where(inside, t, 0.0)), 0.0)

    def vertical_acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """Vertical floor acceleration (m/s², positive up) at times ``t`` (s): :attr:`vertical` at all times."""
        return np.full_like(np.asarray(t, dtype=float), self.vertical)

    def breakpoints(self) -> np.ndarray:
        """Start and end of the pulse (s): the acceleration or its slope jumps there."""
        return np.array([0.0, self.duration])


@dataclass(frozen=True)
class HarmonicPulse(Pulse):
    """``a(t) = PFA sin(omega_p t + PHASE)`` for ``0 <= t <= CYCLES T_p``, zero after."""

    #: Phase of the sine at ``t = 0`` (rad).
    PHASE: ClassVar[float] = 0.0
    #: Duration in periods ``T_p``.
    CYCLES: ClassVar[float] = 1.0

    @property
    def duration(self) -> float:
        """Pulse duration ``CYCLES T_p`` (s)."""
        return self.CYCLES * self.T_p

    def shape_values(self, t: np.ndarray) -> np.ndarray:
        """``sin(omega_p t + PHASE)`` (dimensionless)."""
        return np.sin(self.omega_p * t + self.PHASE)

    def peak_velocity(self) -> float:
        """Peak of ``|v(t)|``, ``v = PFA [cos(PHASE) - cos(omega_p t + PHASE)] / omega_p`` (m/s)."""
        # the velocity's extremes are at the zeros of a(t) inside the pulse and at its end
        n = int(round(2.0 * self.CYCLES))
        phases = [k * math.pi for k in range(n + 1)] + [2.0 * math.pi * self.CYCLES + self.PHASE]
        amp = self.pfa / self.omega_p
        end = phases[-1]
        return max(abs(amp * (math.cos(self.PHASE) - math.cos(ph))) for ph in phases if self.PHASE <= ph <= end)


@dataclass(frozen=True)
class OneSinePulse(HarmonicPulse):
    """One full sine cycle of floor acceleration, ``a(t) = PFA sin(omega_p t)`` on ``[0, T_p]``:
    the paper's pulse. ``omega_p`` is its own frequency; the peak velocity is ``2 PFA / omega_p``.

    Parameters
    ----------
    pfa : float
        Peak floor acceleration ``PFA`` (m/s²), within :data:`opsrock.limits.LIMITS`.
    omega_p : float
        Circular frequency of the pulse ``omega_p`` (rad/s), within :data:`opsrock.limits.LIMITS`.
    """

    SHAPE: ClassVar[str] = "one-sine"


@dataclass(frozen=True)
class HalfSinePulse(HarmonicPulse):
    """Half a sine cycle, ``a(t) = PFA sin(omega_p t)`` on ``[0, T_p / 2]``: a one-sided pulse
    (Makris and Roussos 2000). ``omega_p`` is the frequency of the sine; the floor velocity rises
    to ``2 PFA / omega_p`` and stays there.

    Parameters
    ----------
    pfa : float
        Peak floor acceleration ``PFA`` (m/s²).
    omega_p : float
        Circular frequency of the sine (rad/s).
    """

    SHAPE: ClassVar[str] = "half-sine"
    CYCLES: ClassVar[float] = 0.5


@dataclass(frozen=True)
class OneCosinePulse(HarmonicPulse):
    """One full cosine cycle, ``a(t) = PFA cos(omega_p t)`` on ``[0, T_p]`` (Makris and
    Konstantinidis 2003): the acceleration jumps to ``PFA`` at ``t = 0``; the floor velocity peaks
    at ``PFA / omega_p`` and ends at zero.

    Parameters
    ----------
    pfa : float
        Peak floor acceleration ``PFA`` (m/s²).
    omega_p : float
        Circular frequency of the cosine (rad/s).
    """

    SHAPE: ClassVar[str] = "one-cosine"
    PHASE: ClassVar[float] = 0.5 * math.pi


@dataclass(frozen=True)
class RectangularPulse(Pulse):
    """A constant acceleration ``PFA`` for ``0 <= t <= t_1`` (Housner 1963), zero after.

    Parameters
    ----------
    pfa : float
        The acceleration ``PFA`` (m/s²).
    omega_p : float
        ``pi / t_1`` (rad/s): the frequency of the half-sine of the same duration, so that
        ``omega_p / p = pi / (p t_1)``. Build from the duration with :meth:`from_duration`.
    """

    SHAPE: ClassVar[str] = "rectangular"

    @classmethod
    def from_duration(cls, pfa: float, duration: float) -> "RectangularPulse":
        """Build from ``PFA`` (m/s²) and the duration ``t_1`` (s)."""
        duration = check("duration", duration)
        return cls(pfa=pfa, omega_p=scaled_input("duration", math.pi / duration, "omega_p", 1.0))

    @property
    def duration(self) -> float:
        """Pulse duration ``t_1 = pi / omega_p`` (s)."""
        return math.pi / self.omega_p

    def shape_values(self, t: np.ndarray) -> np.ndarray:
        """1 (dimensionless)."""
        return np.ones_like(t)

    def peak_velocity(self) -> float:
        """``PFA t_1`` (m/s): the velocity at the end of the pulse."""
        return self.pfa * self.duration


@dataclass(frozen=True)
class RickerWavelet(Pulse):
    """The symmetric Ricker wavelet ``a(t) = PFA (1 - 2 x²) exp(-x²)``, ``x = omega_p (t - t_0) / 2``,
    centred at ``t_0 = 1.6 T_p`` and cut at ``t = 2 t_0`` (where ``|a| < 6e-10 PFA``).

    The central lobe is positive (``PFA`` at ``t_0``), the two side lobes reach
    ``-2 exp(-3/2) PFA = -0.446 PFA``; the floor velocity ``PFA (t - t_0) exp(-x²)`` peaks at
    ``sqrt(2) exp(-1/2) PFA / omega_p``.

    Parameters
    ----------
    pfa : float
        Peak floor acceleration ``PFA`` (m/s²).
    omega_p : float
        Frequency at which the Fourier amplitude of the wavelet peaks (rad/s).
    """

    SHAPE: ClassVar[str] = "ricker"

    @property
    def t0(self) -> float:
        """Centre of the wavelet (s)."""
        return RICKER_HALF_WIDTH * self.T_p

    @property
    def duration(self) -> float:
        """``2 t_0`` (s)."""
        return 2.0 * self.t0

    def shape_values(self, t: np.ndarray) -> np.ndarray:
        """``(1 - 2 x²) exp(-x²)`` (dimensionless)."""
        x2 = (0.5 * self.omega_p * (t - self.t0)) ** 2
        return (1.0 - 2.0 * x2) * np.exp(-x2)

    def peak_velocity(self) -> float:
        """``sqrt(2) exp(-1/2) PFA / omega_p`` (m/s)."""
        return math.sqrt(2.0) * math.exp(-0.5) * self.pfa / self.omega_p

    def extrema(self) -> np.ndarray:
        """Times of the three extremes of ``a`` (s): side lobes at ``x = -+sqrt(3/2)``, centre."""
        d = 2.0 * math.sqrt(1.5) / self.omega_p
        return np.array([self.t0 - d, self.t0, self.t0 + d])


#: The pulse shapes by name.
_BY_SHAPE: dict[str, type[Pulse]] = {
    cls.SHAPE: cls for cls in (RectangularPulse, HalfSinePulse, OneSinePulse, OneCosinePulse, RickerWavelet)
}
PULSE_SHAPES: dict[str, type[Pulse]] = {name: _BY_SHAPE[name] for name in PULSE_SHAPE_NAMES}


def pulse_class(shape: str) -> type[Pulse]:
    """The pulse class of ``shape``, one of :data:`PULSE_SHAPES` (the message names ``shape``)."""
    one_of("shape", shape, tuple(PULSE_SHAPES))
    return PULSE_SHAPES[shape]
