"""What every floor motion offers the solvers: the :class:`Excitation` protocol.

Sign convention (docs/guide/modelling.md section 2): a positive floor acceleration tips the block towards
negative ``theta``. A vertical floor acceleration ``a_v`` (m/s², positive up), where an excitation
carries one (:attr:`Pulse.vertical`, :attr:`Record.vertical`), adds to gravity: the block feels
``g + a_v``.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np


@runtime_checkable
class Excitation(Protocol):
    """What every solver needs from a floor motion."""

    @property
    def duration(self) -> float:
        """Time after which the acceleration is zero (s)."""

    @property
    def pfa(self) -> float:
        """Peak absolute floor acceleration (m/s²)."""

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """Floor acceleration at times ``t`` (m/s²); zero before 0 and after ``duration``."""

    def breakpoints(self) -> np.ndarray:
        """Times where the acceleration is not smooth (s), for event-driven solvers."""


def has_vertical(excitation: object) -> bool:
    """True if ``excitation`` carries a vertical floor motion that is not identically zero."""
    vertical = getattr(excitation, "vertical", None)
    if vertical is None:
        return False
    return bool(np.any(np.asarray(vertical, dtype=float) != 0.0))
