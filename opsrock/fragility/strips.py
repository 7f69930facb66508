"""Analysis strips (paper Eq. 13): the overturned fraction per strip of width W_AS = factor W_SAS."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from opsrock.errors import InputError
from opsrock.fragility.hybrid_strip import FALLBACK_STRIPS, HybridStrip
from opsrock.limits import one_of, positive_finite

#: Strip extents (see the module notes).
STRIP_EXTENTS: tuple[str, ...] = ("hybrid", "range")

# Relative tolerance used to put a case that sits on a strip edge (up to rounding) into the
# strip above it, and the hybrid strip's top edge into the last strip.
_EDGE_RTOL = 1e-9


@dataclass(frozen=True)
class StripFractions:
    """Overturning fraction per analysis strip of one IM (Eq. 13).

    Parameters
    ----------
    im : str
        IM name.
    factor : float
        ``W_AS / W_SAS`` (Table 3 uses 0.5, 1, 2).
    width : float
        Strip width ``W_AS`` (IM units).
    extent : str
        ``"hybrid"`` or ``"range"`` (see the module notes).
    low, high, centre : ndarray
        Strip edges and centres (IM units), non-empty strips only, ascending.
    n_cases, n_overturned : ndarray of int
        Rocking cases and overturned cases in each strip.
    fallback : bool
        True if the IM had no hybrid strip and the strips were laid over the whole rocking
        range instead (``FALLBACK_STRIPS`` of them).
    """

    im: str
    factor: float
    width: float
    extent: str
    low: np.ndarray = field(repr=False)
    high: np.ndarray = field(repr=False)
    centre: np.ndarray = field(repr=False)
    n_cases: np.ndarray = field(repr=False)
    n_overturned: np.ndarray = field(repr=False)
    fallback: bool = False

    @property
    def fraction(self) -> np.ndarray:
        """Overturning fraction ``P_ro`` per strip (Eq. 13), dimensionless."""
        return self.n_overturned / self.n_cases

    @property
    def n_strips(self) -> int:
        """Number of non-empty strips."""
        return int(self.centre.size)

    def to_frame(self) -> pd.DataFrame:
        """One row a strip: ``im, factor, low, high, centre, n_cases, n_overturned, fraction``."""
        return pd.DataFrame({
            "im": self.im, "factor": self.factor, "low": self.low, "high": self.high,
            "centre": self.centre, "n_cases": self.n_cases, "n_overturned": self.n_overturned,
            "fraction": self.fraction,
        })


def strip_fractions(
    values: np.ndarray,
    overturned: np.ndarray,
    strip: HybridStrip,
    factor: float = 1.0,
    extent: str = "range",
) -> StripFractions:
    """Overturning fraction in analysis strips of width ``factor · W_SAS`` (Eq. 13).

    Parameters
    ----------
    values : array_like
        IM value of each rocking case (IM units).
    overturned : array_like of bool
        Outcome of each rocking case.
    strip : HybridStrip
        The IM's hybrid strip (from :func:`hybrid_strip` on the same cases).
    factor : float, optional
        ``W_AS / W_SAS`` (dimensionless, > 0).
    extent : {"range", "hybrid"}, optional
        Strips over the whole rocking range (default), or over the hybrid strip only.

    Returns
    -------
    StripFractions
    """
    factor = positive_finite("factor", factor)
    one_of("extent", extent, STRIP_EXTENTS)
    x = np.asarray(values, dtype=float)
    y = np.asarray(overturned, dtype=bool)
    if x.size == 0:
        raise InputError("values is empty: no rocking cases")
    fallback = not strip.has_overlap
    if fallback:
        span = float(np.ptp(x))
        width = span / FALLBACK_STRIPS if span > 0 else 1.0
        anchor, top, use_extent = float(x.min()), float(x.max()), "range"
    else:
        width = factor * strip.W_SAS
        anchor, top, use_extent = strip.overlap_low, strip.overlap_high, extent
    # strip index of each case: [anchor + k w, anchor + (k+1) w)
    k = np.floor((x - anchor) / width + _EDGE_RTOL).astype(int)
    n_hybrid = max(1, math.ceil((top - anchor) / width - _EDGE_RTOL))
    on_top = np.abs(x - top) <= _EDGE_RTOL * max(1.0, abs(top))
    k = np.where(on_top & (k >= n_hybrid), n_hybrid - 1, k)
    if use_extent == "hybrid":
        keep = (k >= 0) & (k < n_hybrid)
    else:
        keep = np.ones_like(k, dtype=bool)
    k, yk = k[keep], y[keep]
    idx = np.unique(k)
    n_cases = np.array([np.sum(k == i) for i in idx], dtype=int)
    n_over = np.array([np.sum(yk[k == i]) for i in idx], dtype=int)
    low = anchor + idx * width
    high = low + width
    centre = 0.5 * (np.maximum(low, 0.0) + high)
    return StripFractions(strip.im, factor, width, use_extent, low, high, centre, n_cases,
                          n_over, fallback)
