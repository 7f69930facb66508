"""Floor motion in plan: two horizontal components (and the first one's vertical motion) and the block's
orientation in plan, for the three-dimensional solver ``rigid3d``.

Frames (docs/guide/three-dimensions.md)
---------------------------------
The *motion axes* 1 and 2 are those of the records (a building's two horizontal directions; a recording's two
components). The *block frame* has ``x`` along the block's width (``2b``), ``y`` along its depth (``2d``) and
``z`` up. ``azimuth`` is the angle (deg) from motion axis 1 to the block's ``x`` axis, counter-clockwise seen
from above; the floor acceleration in the block frame is therefore::

    a_x =  a_1 cos(azimuth) + a_2 sin(azimuth)
    a_y = -a_1 sin(azimuth) + a_2 cos(azimuth)

A single horizontal motion along the block's direction ``phi`` (deg, from ``x`` towards ``y``) is
``PlanMotion(motion, azimuth=-phi)`` (:meth:`PlanMotion.along`). With ``second=None`` and ``azimuth=0`` the
motion is the planar solvers' motion along the block's width, with their sign convention (a positive floor
acceleration tips the block towards negative ``theta``).

The vertical floor motion is the first component's (``first.vertical``, as every planar excitation carries
it); ``second`` must carry none.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from opsrock.constants import G
from opsrock.errors import InputError, InputTypeError
from opsrock.excitations.base import Excitation, has_vertical
from opsrock.limits import real_number


@dataclass(frozen=True)
class PlanMotion:
    """Two horizontal floor-motion components and the block's orientation in plan.

    Parameters
    ----------
    first : Excitation
        The component along motion axis 1 (m/s²), with the vertical floor motion if any.
    second : Excitation or None
        The component along motion axis 2 (m/s²), with no vertical motion of its own. None: none.
    azimuth : float
        Angle from motion axis 1 to the block's width axis ``x`` (deg), counter-clockwise seen from above, in
        [-360, 360]. Default 0.
    """

    first: Excitation
    second: Excitation | None = None
    azimuth: float = 0.0

    def __post_init__(self) -> None:
        for name in ("first", "second"):
            value = getattr(self, name)
            if value is None and name == "second":
                continue
            if isinstance(value, PlanMotion) or not isinstance(value, Excitation):
                raise InputTypeError(f"{name} must be a floor motion (a pulse or a record), got {value!r}")
        if self.second is not None and has_vertical(self.second):
            raise InputError("second must carry no vertical motion (the vertical floor motion is the first "
                             "component's)", argument="second")
        az = real_number("azimuth", self.azimuth)
        if not (math.isfinite(az) and -360.0 <= az <= 360.0):
            raise InputError(f"azimuth must lie in [-360, 360] deg, got {self.azimuth!r}", argument="azimuth")
        object.__setattr__(self, "azimuth", az)

    @classmethod
    def along(cls, motion: Excitation, phi: float) -> "PlanMotion":
        """``motion`` along the block's plan direction ``phi`` (deg, from its width axis ``x`` towards ``y``)."""
        return cls(motion, None, -real_number("phi", phi))

    @property
    def planar(self) -> bool:
        """True if the motion is the planar solvers' own: one component along the block's width (``azimuth`` a
        multiple of 360 deg, no second component)."""
        return self.second is None and self.azimuth % 360.0 == 0.0

    @property
    def vertical(self):
        """The first component's vertical motion (as :attr:`Record.vertical` or :attr:`Pulse.vertical`)."""
        return getattr(self.first, "vertical", None)

    @property
    def duration(self) -> float:
        """Time after which both components are zero (s)."""
        return max(self.first.duration, 0.0 if self.second is None else self.second.duration)

    @property
    def pfa(self) -> float:
        """Peak of the first component (m/s²): the quantity a campaign scales, as for a planar motion."""
        return self.first.pfa

    def scaled(self, factor: float) -> "PlanMotion":
        """Both horizontal components times ``factor`` (dimensionless), the vertical floor motion unchanged: the
        copy :func:`opsrock.analysis.sensitivity.amplitude_sensitivity` scales."""
        return PlanMotion(_scaled_horizontal(self.first, factor),
                          None if self.second is None else _scaled_horizontal(self.second, factor), self.azimuth)

    def components(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Floor acceleration ``(a_x, a_y)`` in the block frame at times ``t`` (m/s²)."""
        a1 = np.asarray(self.first.acceleration(t), dtype=float)
        a2 = np.zeros_like(a1) if self.second is None else np.asarray(self.second.acceleration(t), dtype=float)
        c, s = math.cos(math.radians(self.azimuth)), math.sin(math.radians(self.azimuth))
        return c * a1 + s * a2, -s * a1 + c * a2

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """Magnitude of the horizontal floor acceleration at times ``t`` (m/s²)."""
        ax, ay = self.components(t)
        return np.hypot(ax, ay)

    def uplift_ratio(self, tan_x: float, tan_y: float) -> float:
        """The peak over time of ``max(|a_x| / (g tan_x), |a_y| / (g tan_y))`` (dimensionless): the floor
        acceleration over the smallest one that uplifts a rigid box in its direction (``tan_x = b / h_cm``,
        ``tan_y = d / h_cm`` of the box; the resultant of weight and inertia leaves the base when either term
        passes 1; the vertical floor motion left out). One component at ``azimuth`` psi: ``PFA / (g min(tan_x /
        |cos psi|, tan_y / |sin psi|))``; two: at the samples of sampled components (their acceleration is
        piecewise linear, so the peak is at one of them), else at 20,001 times over the duration."""
        c, s = math.cos(math.radians(self.azimuth)), math.sin(math.radians(self.azimuth))
        if self.second is None:
            return self.first.pfa * max(abs(c) / (G * tan_x), abs(s) / (G * tan_y))
        sampled = all(hasattr(m, "values") for m in (self.first, self.second))
        t = self.breakpoints() if sampled else np.linspace(0.0, self.duration, 20_001)
        ax, ay = self.components(t)
        return float(np.max(np.maximum(np.abs(ax) / (G * tan_x), np.abs(ay) / (G * tan_y))))

    def breakpoints(self) -> np.ndarray:
        """Times where either component is not smooth (s)."""
        parts = [self.first.breakpoints()] + ([] if self.second is None else [self.second.breakpoints()])
        return np.unique(np.concatenate(parts))


def _scaled_horizontal(motion: Excitation, factor: float) -> Excitation:
    """``motion``'s horizontal acceleration times ``factor``, its vertical motion unchanged (a record's
    ``scaled`` scales both: its vertical samples are put back)."""
    if hasattr(motion, "scaled"):
        return motion.scaled(factor).with_vertical(getattr(motion, "vertical", None))
    return dataclasses.replace(motion, pfa=motion.pfa * real_number("factor", factor))


__all__ = ["PlanMotion"]
