"""The hybrid strip of an IM (paper Eq. 12): where safe-rocking and overturned cases overlap, its width
W_HS, the ratios to the two ranges and the hybrid ratio HR."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from opsrock.errors import InputError

#: ``W_SAS = W_HS / STANDARD_STRIP_DIVISOR`` (paper Section 4.4: "one-fifth of W_HS").
STANDARD_STRIP_DIVISOR: float = 5.0

#: Number of equal strips over the whole rocking range when an IM has no hybrid strip
#: (``W_HS = 0``): the project's choice, flagged wherever it is used.
FALLBACK_STRIPS: int = 20

#: Bounds on the dispersion ``beta`` in the fits (dimensionless). Below 1e-3 the lognormal

@dataclass(frozen=True)
class HybridStrip:
    """The hybrid strip of one IM and the paper's hybrid ratio (Eq. 12, Table 2).

    Parameters
    ----------
    im : str
        IM name.
    W_HS : float
        Width of the hybrid strip (IM units); 0 when the safe and overturned ranges do not
        overlap (or touch at one value).
    R_S, R_O : float
        Ranges (max - min) of the IM over the safe-rocking and the overturned cases (IM units).
    ratio_S, ratio_O : float
        ``W_HS / R_S`` and ``W_HS / R_O`` (dimensionless); 0 when ``W_HS = 0``.
    HR : float
        Hybrid ratio ``sqrt(ratio_S² + ratio_O²)`` (dimensionless, Eq. 12).
    W_SAS : float
        Standard analysis strip width ``W_HS / 5`` (IM units, Section 4.4).
    overlap_low, overlap_high : float
        Edges of the hybrid strip (IM units); NaN when there is no overlap.
    n_safe, n_overturned : int
        Rocking cases of each kind.
    n_in_strip : int
        Rocking cases whose IM lies in the hybrid strip (edges included).
    decreasing : bool
        Orientation of the IM (True for IM1: overturned cases at low values).
    note : str
        Empty, or why the strip is degenerate (no overlap, a group is empty).
    """

    im: str
    W_HS: float  # noqa: N815
    R_S: float  # noqa: N815
    R_O: float  # noqa: N815
    ratio_S: float  # noqa: N815
    ratio_O: float  # noqa: N815
    HR: float  # noqa: N815
    W_SAS: float  # noqa: N815
    overlap_low: float
    overlap_high: float
    n_safe: int
    n_overturned: int
    n_in_strip: int
    decreasing: bool = False
    note: str = ""

    @property
    def has_overlap(self) -> bool:
        """True if the hybrid strip has a positive width."""
        return self.W_HS > 0.0


def _ratio(w: float, r: float) -> float:
    if w == 0.0:
        return 0.0
    return w / r if r > 0.0 else math.nan


def hybrid_strip(
    values: np.ndarray, overturned: np.ndarray, im: str = "IM", decreasing: bool = False
) -> HybridStrip:
    """Hybrid strip, ranges and hybrid ratio of one IM over rocking cases (Eq. 12).

    Parameters
    ----------
    values : array_like
        IM value of each rocking case (IM units, finite).
    overturned : array_like of bool
        Outcome of each case (True: overturned, False: safe rocking).
    im : str, optional
        IM name for the result.
    decreasing : bool, optional
        IM orientation (True for IM1). The strip is the interval intersection in either
        case; the flag is carried to the fits.

    Returns
    -------
    HybridStrip
    """
    x = np.asarray(values, dtype=float)
    y = np.asarray(overturned, dtype=bool)
    if x.shape != y.shape or x.ndim != 1:
        raise InputError(f"values and overturned must be 1-D of equal length, got {x.shape} and {y.shape}")
    if not np.all(np.isfinite(x)):
        raise InputError(f"values of {im} must be finite, got {x[~np.isfinite(x)][0]!r}")
    xs, xo = x[~y], x[y]
    n_s, n_o = int(xs.size), int(xo.size)
    nan = math.nan
    if n_s == 0 or n_o == 0:
        which = "safe-rocking" if n_s == 0 else "overturned"
        r_s = float(np.ptp(xs)) if n_s else nan
        r_o = float(np.ptp(xo)) if n_o else nan
        return HybridStrip(im, 0.0, r_s, r_o, nan, nan, nan, 0.0, nan, nan, n_s, n_o, 0,
                           decreasing, f"no {which} cases: no hybrid strip can be defined")
    r_s, r_o = float(np.ptp(xs)), float(np.ptp(xo))
    low = max(float(xs.min()), float(xo.min()))
    high = min(float(xs.max()), float(xo.max()))
    w = max(0.0, high - low)
    ratio_s, ratio_o = _ratio(w, r_s), _ratio(w, r_o)
    note = ""
    if w == 0.0:
        note = ("no overlap: the IM separates safe rocking from overturning; "
                f"strips fall back to {FALLBACK_STRIPS} over the rocking range")
        n_in = 0
        low = high = nan
    else:
        n_in = int(np.sum((x >= low) & (x <= high)))
    return HybridStrip(
        im=im, W_HS=w, R_S=r_s, R_O=r_o, ratio_S=ratio_s, ratio_O=ratio_o,
        HR=math.hypot(ratio_s, ratio_o), W_SAS=w / STANDARD_STRIP_DIVISOR,
        overlap_low=low, overlap_high=high, n_safe=n_s, n_overturned=n_o, n_in_strip=n_in,
        decreasing=decreasing, note=note,
    )
