"""Overturning fragility from a table of simulated cases (paper Section 4, Eq. 12-16).

The input is a pandas DataFrame of cases, one row a (block, pulse) simulation, with the
columns of the campaign's ``cases.csv`` (``status``, ``rocked``, ``overturned``, ``IM1`` ..
``IM9``, ...). No solver runs here.

Choices (docs/modelling.md section 2 "Fragility layer"; each is where the paper is silent or loose):

* **Which cases count.** Only rocking cases (``status == "ok"`` and ``rocked``) enter any
  statistic: Eq. 13 divides by "the total number of rocking simulations". Cases below the
  uplift threshold (``no_uplift``) are counted and reported, not treated as safe. Failed
  cases are excluded and counted; they never become a verdict (:func:`split_cases`).
* **Hybrid strip** (Eq. 12). The interval intersection of the IM ranges of the safe-rocking
  and the overturned cases, whatever the IM's orientation: for IM1 (decreasing) the
  overturned cases sit at low IM1 and the intersection is ``[min safe, max overturned]``.
  ``W_HS`` is its width (0 when the ranges do not overlap: the IM separates the two states
  perfectly), ``W_SAS = W_HS / 5`` (Section 4.4, Table 2's last column).
* **Analysis strips** (Eq. 13). Strips of width ``W_AS = factor · W_SAS`` are laid on a
  grid anchored at the lower edge of the hybrid strip, so that ``W_SAS`` cuts the hybrid
  strip into exactly five. Default ``extent="range"``: the strips tile the whole rocking
  range of the IM, so the fit also sees the strips outside the hybrid strip, whose fraction
  is exactly 0 or 1 by definition. ``extent="hybrid"`` keeps only the strips over the hybrid
  strip (a literal reading of Section 4.4, "within the specific IM value in Figure 8"); when
  ``W_HS / W_AS`` is not an integer (``2 W_SAS`` gives 2.5 strips) its last strip is kept
  full width and reaches past the hybrid strip. Why "range" is the default: on the project's
  400-case campaign (housner_fast solver) the hybrid-only fits are not robust to the strip
  width (IM4: beta 1.21 / 0.94 / 0.27 for W_SAS/2, W_SAS, 2 W_SAS), contradicting the
  paper's Section 4.5 finding, whereas whole-range strips give 0.01-0.25 and medians and
  dispersions near Table 3 for IM3, IM6 and IM7 (e.g. IM3 mu 1.44, beta 0.15 against the
  paper's 1.36, 0.14), and Figure 10 of the paper shows fractions of 0 and 1. A strip is
  ``[low, high)``; the top edge of the hybrid strip belongs to the strip below it. Empty
  strips are dropped. The x of a strip is its centre.
* **No overlap.** When ``W_HS = 0`` the paper's strip width is 0. Then the strips fall back
  to ``FALLBACK_STRIPS`` equal strips over the whole rocking range, flagged
  ``fallback=True`` in every result and table. Both fits then see a step: the least-squares
  fit drives ``beta`` to its lower bound and the MLE has no finite optimum; both say so in
  ``success``/``message`` and are never silently reported as a good fit.
* **Fragility of a decreasing IM** (IM1): ``P(overturn | IM = x) = Phi(ln(mu / x) / beta)``,
  the mirror of Eq. 14, so that ``mu`` is still the 50 % IM and ``beta`` the dispersion.
* **CV.** The paper's ``CV = beta / mu`` (in %) is kept for comparison, but it is not
  scale-free (multiply an IM by 10 and CV falls tenfold). ``beta`` is scale-free (but not
  power-free: ``beta`` of ``IM^k`` is ``k beta``). The ranking also reports two measures that
  are invariant under any monotone change of the IM: the MLE log-likelihood per case and the
  fraction of rocking cases that fall in the hybrid strip.
* **Beside the paper's least-squares fit**, a maximum-likelihood fit on the raw 0/1 outcomes
  of the rocking cases (Bernoulli likelihood, probit on ``ln IM``) with seeded percentile
  bootstrap confidence intervals.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np
import pandas as pd
from scipy import optimize, special

from opsrock._checks import int_at_least, one_of, positive_finite
from opsrock.intensity import IM_NAMES, add_intensity_measures, get_im
from opsrock.excitations import PFV_CONVENTIONS
from opsrock.paper_values import STRIP_FACTORS, TABLE2, TABLE3

#: ``W_SAS = W_HS / STANDARD_STRIP_DIVISOR`` (paper Section 4.4: "one-fifth of W_HS").
STANDARD_STRIP_DIVISOR: float = 5.0

#: Number of equal strips over the whole rocking range when an IM has no hybrid strip
#: (``W_HS = 0``): the project's choice, flagged wherever it is used.
FALLBACK_STRIPS: int = 20

#: Bounds on the dispersion ``beta`` in the fits (dimensionless). Below 1e-3 the lognormal
#: CDF is a step at the resolution of any IM table; above 20 it is flat over 10 decades.
BETA_BOUNDS: tuple[float, float] = (1e-3, 20.0)

#: Cap on residual evaluations per least-squares start (a step-like data set otherwise
#: crawls towards the ``beta`` bound for hundreds of iterations).
LS_MAX_EVALUATIONS: int = 300

#: Strip extents (see the module notes).
STRIP_EXTENTS: tuple[str, ...] = ("hybrid", "range")

# Relative tolerance used to put a case that sits on a strip edge (up to rounding) into the
# strip above it, and the hybrid strip's top edge into the last strip.
_EDGE_RTOL = 1e-9


# ---------------------------------------------------------------------------------------
# Case selection
# ---------------------------------------------------------------------------------------
def _as_bool(series: pd.Series, name: str) -> np.ndarray:
    if series.dtype == bool:
        return series.to_numpy()
    mapping = {"true": True, "false": False, "1": True, "0": False, "1.0": True, "0.0": False}
    out = series.astype(str).str.strip().str.lower().map(mapping)
    if out.isna().any():
        bad = series[out.isna()].iloc[0]
        raise ValueError(f"column {name!r} must hold booleans, got {bad!r}")
    return out.to_numpy(dtype=bool)


@dataclass(frozen=True)
class CaseSplit:
    """The cases table split into what enters the fragility statistics and what does not.

    Parameters
    ----------
    rocking : pandas.DataFrame
        The rocking cases (``status == "ok"`` and ``rocked``), with a boolean column
        ``overturned``: the only rows any fragility statistic uses.
    n_total, n_rocking, n_safe, n_overturned, n_no_uplift, n_failed : int
        Counts. ``n_total = n_rocking + n_no_uplift + n_failed`` and
        ``n_rocking = n_safe + n_overturned``.
    """

    rocking: pd.DataFrame = field(repr=False)
    n_total: int
    n_rocking: int
    n_safe: int
    n_overturned: int
    n_no_uplift: int
    n_failed: int

    def counts(self) -> dict[str, int]:
        """The counts as a dict (for tables and reports)."""
        return {k: getattr(self, k) for k in
                ("n_total", "n_rocking", "n_safe", "n_overturned", "n_no_uplift", "n_failed")}


def split_cases(cases: pd.DataFrame) -> CaseSplit:
    """Keep the rocking cases, count the no-uplift and failed ones (Eq. 13).

    Parameters
    ----------
    cases : pandas.DataFrame
        Needs columns ``status`` (``"ok"``/``"failed"``), ``rocked`` and ``overturned``
        (booleans). If a ``verdict`` column is present it must agree with them.

    Returns
    -------
    CaseSplit
    """
    missing = [c for c in ("status", "rocked", "overturned") if c not in cases.columns]
    if missing:
        raise KeyError(f"cases lacks the column(s) {missing}")
    status = cases["status"].astype(str).to_numpy()
    bad = ~np.isin(status, ("ok", "failed"))
    if bad.any():
        raise ValueError(f"column 'status' must be 'ok' or 'failed', got {status[bad][0]!r}")
    ok = status == "ok"
    rocked = _as_bool(cases["rocked"], "rocked")
    overturned = _as_bool(cases["overturned"], "overturned")
    rocking = ok & rocked
    if np.any(ok & ~rocked & overturned):
        i = int(np.flatnonzero(ok & ~rocked & overturned)[0])
        raise ValueError(f"case at row {i} is marked overturned but not rocked")
    if "verdict" in cases.columns:
        expected = np.where(~ok, "failed", np.where(~rocked, "no_uplift",
                                                    np.where(overturned, "overturned", "safe")))
        verdict = cases["verdict"].astype(str).to_numpy()
        wrong = verdict != expected
        if wrong.any():
            i = int(np.flatnonzero(wrong)[0])
            raise ValueError(
                f"case at row {i}: verdict {verdict[i]!r} disagrees with status/rocked/overturned "
                f"({expected[i]!r})"
            )
    table = cases.loc[rocking].copy()
    table["overturned"] = overturned[rocking]
    n_over = int(np.sum(overturned[rocking]))
    return CaseSplit(
        rocking=table.reset_index(drop=True),
        n_total=int(len(cases)),
        n_rocking=int(rocking.sum()),
        n_safe=int(rocking.sum()) - n_over,
        n_overturned=n_over,
        n_no_uplift=int(np.sum(ok & ~rocked)),
        n_failed=int(np.sum(~ok)),
    )


# ---------------------------------------------------------------------------------------
# Hybrid strip (Eq. 12)
# ---------------------------------------------------------------------------------------
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
        raise ValueError(f"values and overturned must be 1-D of equal length, got {x.shape} and {y.shape}")
    if not np.all(np.isfinite(x)):
        raise ValueError(f"values of {im} must be finite, got {x[~np.isfinite(x)][0]!r}")
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


# ---------------------------------------------------------------------------------------
# Analysis strips (Eq. 13)
# ---------------------------------------------------------------------------------------
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
        raise ValueError("values is empty: no rocking cases")
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


# ---------------------------------------------------------------------------------------
# Lognormal fragility fits (Eq. 14-16 and MLE)
# ---------------------------------------------------------------------------------------
def fragility_probability(
    x: np.ndarray | float, mu: float, beta: float, decreasing: bool = False
) -> np.ndarray:
    """Lognormal overturning fragility (Eq. 14), mirrored for a decreasing IM.

    Parameters
    ----------
    x : array_like
        IM values (IM units, > 0).
    mu : float
        Median (IM units): the IM of 50 % overturning probability.
    beta : float
        Logarithmic standard deviation (dimensionless); 0 gives a step at ``mu``.
    decreasing : bool, optional
        True for IM1: ``Phi(ln(mu / x) / beta)``; else ``Phi(ln(x / mu) / beta)``.

    Returns
    -------
    ndarray
        ``P(overturning | IM = x)``.
    """
    x = np.asarray(x, dtype=float)
    s = -1.0 if decreasing else 1.0
    z = s * np.log(x / mu)
    if beta == 0.0:
        return np.where(z > 0, 1.0, np.where(z < 0, 0.0, 0.5))
    return special.ndtr(z / beta)


@dataclass(frozen=True)
class LognormalFit:
    """A lognormal fragility fit (Eq. 14): median ``mu``, dispersion ``beta``.

    Parameters
    ----------
    mu : float
        Median (IM units).
    beta : float
        Dispersion (dimensionless).
    cv_percent : float
        The paper's ``CV = 100 beta / mu`` (% per IM unit; not scale-free).
    method : str
        ``"least_squares"`` (Eq. 15-16 on strip fractions) or ``"mle"``.
    n_points : int
        Strips (least squares) or cases (MLE) fitted.
    decreasing : bool
        Orientation (see :func:`fragility_probability`).
    success : bool
        False when the fit is not to be trusted (too few points, ``beta`` at a bound,
        perfectly separated outcomes, optimiser failure); ``message`` says why.
    message : str
        Diagnostic.
    objective : float
        Sum of squared errors (Eq. 15) or negative log-likelihood at the optimum.
    """

    mu: float
    beta: float
    cv_percent: float
    method: str
    n_points: int
    decreasing: bool = False
    success: bool = True
    message: str = ""
    objective: float = math.nan

    def probability(self, x: np.ndarray | float) -> np.ndarray:
        """Fitted ``P(overturning | IM = x)``."""
        return fragility_probability(x, self.mu, self.beta, self.decreasing)


def _failed_fit(method: str, n: int, decreasing: bool, message: str) -> LognormalFit:
    return LognormalFit(math.nan, math.nan, math.nan, method, n, decreasing, False, message)


def fit_lognormal_least_squares(
    x: np.ndarray, fraction: np.ndarray, decreasing: bool = False
) -> LognormalFit:
    """Least-squares lognormal fit to strip fractions (paper Eq. 15-16).

    Minimises ``sum (P_i - Phi(s ln(x_i / mu) / beta))²`` over ``mu`` and ``beta``
    (``s = -1`` for a decreasing IM), from several starting ``beta`` values, keeping the best.

    Parameters
    ----------
    x : array_like
        Strip centres (IM units, > 0).
    fraction : array_like
        Overturning fraction in each strip (dimensionless, in [0, 1]).
    decreasing : bool, optional
        IM orientation.

    Returns
    -------
    LognormalFit
    """
    x = np.asarray(x, dtype=float)
    f = np.asarray(fraction, dtype=float)
    method = "least_squares"
    if x.shape != f.shape or x.ndim != 1:
        raise ValueError(f"x and fraction must be 1-D of equal length, got {x.shape} and {f.shape}")
    if np.any(~np.isfinite(x) | (x <= 0)):
        raise ValueError(f"x must be positive and finite, got {x[~np.isfinite(x) | (x <= 0)][0]!r}")
    if np.any((f < 0) | (f > 1) | ~np.isfinite(f)):
        raise ValueError("fraction must lie in [0, 1]")
    if x.size < 2:
        return _failed_fit(method, int(x.size), decreasing, f"{x.size} strip(s): need at least 2")
    if np.all(f == 0) or np.all(f == 1):
        return _failed_fit(method, int(x.size), decreasing,
                           "every strip fraction is %d: no transition to fit" % f[0])
    if np.all((f == 0) | (f == 1)):
        return _failed_fit(method, int(x.size), decreasing,
                           "every strip fraction is 0 or 1: the strip fractions are a step and "
                           "beta is not identified")
    s = -1.0 if decreasing else 1.0
    lx = np.log(x)

    def residual(q: np.ndarray) -> np.ndarray:
        return f - special.ndtr(s * (lx - q[0]) / q[1])

    def jacobian(q: np.ndarray) -> np.ndarray:
        z = s * (lx - q[0]) / q[1]
        phi = np.exp(-0.5 * z**2) / math.sqrt(2.0 * math.pi)
        return np.stack([phi * s / q[1], phi * z / q[1]], axis=1)

    # start the median where the fractions cross 1/2 (nearest strip), beta from the spread
    m0 = float(lx[np.argmin(np.abs(f - 0.5))])
    spread = float(np.ptp(lx)) if np.ptp(lx) > 0 else 1.0
    lo = [lx.min() - 3 * spread, BETA_BOUNDS[0]]
    hi = [lx.max() + 3 * spread, BETA_BOUNDS[1]]
    best = None
    for b0 in (0.05, 0.2, 0.5, 1.5):
        q0 = [m0, float(np.clip(b0 * max(spread, 0.1), *BETA_BOUNDS))]
        res = optimize.least_squares(residual, q0, jac=jacobian, bounds=(lo, hi), method="trf",
                                     x_scale=[1.0, 0.1], xtol=1e-10, ftol=1e-12, gtol=1e-12,
                                     max_nfev=LS_MAX_EVALUATIONS)
        if best is None or res.cost < best.cost:
            best = res
    mu, beta = math.exp(best.x[0]), float(best.x[1])
    sse = 2.0 * float(best.cost)
    ok, msg = bool(best.success), str(best.message)
    if beta <= BETA_BOUNDS[0] * (1 + 1e-6):
        ok, msg = False, "beta at its lower bound: the strip fractions are a step"
    elif beta >= BETA_BOUNDS[1] * (1 - 1e-6):
        ok, msg = False, "beta at its upper bound: no transition in the data"
    elif not (lo[0] < best.x[0] < hi[0]) or abs(best.x[0] - lo[0]) < 1e-9 or abs(best.x[0] - hi[0]) < 1e-9:
        ok, msg = False, "median at its bound: outside the data"
    elif ok:
        # Resolution: the fitted curve rises from 16 % to 84 % over about 2 beta mu (IM units).
        # If that is narrower than one strip, the strip fractions cannot tell beta = 0.02 from
        # 0.002: the data are a step at strip resolution and beta is not identified.
        spacing = float(np.median(np.diff(np.sort(x))))
        if 2.0 * beta * mu < spacing:
            ok, msg = False, (f"beta = {beta:.3g} below the strip resolution: the fitted transition "
                              f"2 beta mu = {2 * beta * mu:.3g} is narrower than one strip ({spacing:.3g})")
    return LognormalFit(mu, beta, 100.0 * beta / mu, method, int(x.size), decreasing, ok, msg, sse)


@dataclass(frozen=True)
class MLEFit(LognormalFit):
    """Maximum-likelihood lognormal fit on 0/1 outcomes, with bootstrap intervals.

    Parameters
    ----------
    mu_lo, mu_hi, beta_lo, beta_hi : float
        Percentile-bootstrap confidence bounds of ``mu`` (IM units) and ``beta``.
    confidence : float
        Confidence level of the bounds (e.g. 0.95).
    n_boot : int
        Bootstrap resamples drawn.
    n_boot_used : int
        Resamples that gave a finite MLE (resamples with perfectly separated outcomes have
        none and are left out; if many are, the bounds are optimistic).
    seed : int
        Seed of ``numpy.random.default_rng`` for the resampling.
    loglik_per_case : float
        Maximum log-likelihood divided by the number of cases: invariant under any
        monotone power-law change of the IM, so comparable between IMs.
    """

    mu_lo: float = math.nan
    mu_hi: float = math.nan
    beta_lo: float = math.nan
    beta_hi: float = math.nan
    confidence: float = 0.95
    n_boot: int = 0
    n_boot_used: int = 0
    seed: int = 0
    loglik_per_case: float = math.nan


def _separated(u: np.ndarray, y: np.ndarray) -> bool:
    """True if every overturned case has a larger (oriented) IM than every safe one."""
    return bool(y.any() and (~y).any() and u[~y].max() <= u[y].min())


def _mle_core(u: np.ndarray, y: np.ndarray, q0: np.ndarray | None = None
              ) -> tuple[np.ndarray, float, bool, str]:
    """Probit MLE in ``u = s ln x``: returns ((m, ln beta), nll, success, message).

    Fitted as ``P = Phi(a + b v)`` on the standardised ``v = (u - mean) / sd``, whose
    log-likelihood is concave in ``(a, b)`` (probit regression), so the optimiser cannot
    wander off; then ``beta = sd / b`` and ``m = mean - a sd / b``. ``q0`` (a previous
    ``(m, ln beta)``) only seeds the start.
    """
    centre, sd = float(np.mean(u)), float(np.std(u)) or 1.0
    v = (u - centre) / sd
    if q0 is not None:
        b0 = sd / math.exp(q0[1])
        start = np.array([-(q0[0] - centre) / sd * b0, b0])
    else:
        start = np.array([0.0, 1.0])

    def nll(ab: np.ndarray) -> tuple[float, np.ndarray]:
        z = ab[0] + ab[1] * v
        lp, lq = special.log_ndtr(z), special.log_ndtr(-z)
        value = -float(np.sum(np.where(y, lp, lq)))
        log_phi = -0.5 * z**2 - 0.5 * math.log(2 * math.pi)
        # d(-loglik)/dz: -phi/Phi(z) for y = 1, +phi/Phi(-z) for y = 0
        dz = np.where(y, -np.exp(log_phi - lp), np.exp(log_phi - lq))
        return value, np.array([np.sum(dz), np.sum(dz * v)])

    res = optimize.minimize(nll, start, jac=True, method="BFGS", options={"gtol": 1e-8})
    a, b = res.x
    ok = bool(res.success) or res.status == 2  # status 2: precision loss at the optimum
    msg = str(res.message)
    if not b > 0:
        return np.array([math.nan, math.nan]), float(res.fun), False, (
            "overturning does not grow with the (oriented) IM: slope b = %.3g <= 0" % b)
    beta = sd / b
    m = centre - a * sd / b
    if not BETA_BOUNDS[0] < beta < BETA_BOUNDS[1]:
        ok, msg = False, f"beta = {beta:.3g} outside {BETA_BOUNDS}"
    return np.array([m, math.log(beta)]), float(res.fun), ok, msg


def fit_lognormal_mle(
    values: np.ndarray,
    overturned: np.ndarray,
    decreasing: bool = False,
    n_boot: int = 200,
    confidence: float = 0.95,
    seed: int = 0,
) -> MLEFit:
    """Maximum-likelihood lognormal fragility on the raw outcomes of rocking cases.

    Maximises ``sum y ln P + (1 - y) ln(1 - P)`` with ``P = Phi(s ln(x / mu) / beta)``
    (a probit regression on ``ln x``), then resamples the cases with replacement ``n_boot``
    times for percentile confidence bounds.

    Parameters
    ----------
    values : array_like
        IM value of each rocking case (IM units, > 0).
    overturned : array_like of bool
        Outcome of each case.
    decreasing : bool, optional
        IM orientation (True for IM1).
    n_boot : int, optional
        Bootstrap resamples (0: no intervals).
    confidence : float, optional
        Confidence level of the bounds, in (0, 1).
    seed : int, optional
        Seed of the resampling.

    Returns
    -------
    MLEFit
    """
    x = np.asarray(values, dtype=float)
    y = np.asarray(overturned, dtype=bool)
    if x.shape != y.shape or x.ndim != 1:
        raise ValueError(f"values and overturned must be 1-D of equal length, got {x.shape} and {y.shape}")
    if np.any(~np.isfinite(x) | (x <= 0)):
        raise ValueError(f"values must be positive and finite, got {x[~np.isfinite(x) | (x <= 0)][0]!r}")
    n_boot = int_at_least("n_boot", n_boot, 0)
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must lie in (0, 1), got {confidence!r}")
    s = -1.0 if decreasing else 1.0
    u = s * np.log(x)
    n = int(x.size)
    common = dict(method="mle", n_points=n, decreasing=decreasing, confidence=confidence,
                  n_boot=n_boot, seed=seed)
    if n == 0 or y.all() or (~y).all():
        return MLEFit(math.nan, math.nan, math.nan, success=False,
                      message="outcomes are all one kind: no fragility to fit", **common)
    if _separated(u, y):
        gap_mid = 0.5 * (u[~y].max() + u[y].min())
        mu = math.exp(s * gap_mid)
        return MLEFit(mu, 0.0, 0.0, success=False, objective=0.0, loglik_per_case=0.0,
                      message="outcomes perfectly separated by the IM: no finite MLE "
                              "(beta -> 0); mu is the middle of the gap", **common)
    q, value, ok, msg = _mle_core(u, y)
    with np.errstate(over="ignore"):
        mu, beta = float(np.exp(s * q[0])), float(np.exp(q[1]))
    if not (math.isfinite(mu) and mu > 0.0 and math.isfinite(beta)):
        # the optimiser ran off to a median of 0 or infinity: too few or too one-sided outcomes
        return MLEFit(math.nan, math.nan, math.nan, success=False, objective=value,
                      message=f"no finite MLE: the median ran off to {mu!r} (too few transitional "
                              "outcomes)", **common)
    lo = hi = (math.nan, math.nan)
    used = 0
    if n_boot:
        rng = np.random.default_rng(seed)
        draws = []
        for _ in range(n_boot):
            idx = rng.integers(0, n, n)
            ub, yb = u[idx], y[idx]
            if yb.all() or (~yb).all() or _separated(ub, yb):
                continue
            qb, _, okb, _ = _mle_core(ub, yb, q if ok else None)
            if okb:
                draws.append((math.exp(s * qb[0]), math.exp(qb[1])))
        used = len(draws)
        if used >= 2:
            arr = np.array(draws)
            tail = 50.0 * (1.0 - confidence)
            lo = tuple(np.percentile(arr, tail, axis=0))
            hi = tuple(np.percentile(arr, 100.0 - tail, axis=0))
    return MLEFit(mu, beta, 100.0 * beta / mu, success=ok, message=msg, objective=value,
                  mu_lo=float(lo[0]), mu_hi=float(hi[0]), beta_lo=float(lo[1]),
                  beta_hi=float(hi[1]), n_boot_used=used, loglik_per_case=-value / n, **common)


# ---------------------------------------------------------------------------------------
# Whole analysis and tables
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class FragilitySettings:
    """Settings of :func:`analyse_fragility`.

    Parameters
    ----------
    ims : tuple of str, optional
        IMs to analyse (default all nine).
    strip_factors : tuple of float, optional
        ``W_AS / W_SAS`` values (default Table 3's 0.5, 1, 2).
    extent : {"hybrid", "range"}, optional
        Where the analysis strips go (module notes).
    n_boot : int, optional
        Bootstrap resamples of the MLE (0: no intervals).
    confidence : float, optional
        Confidence level of the MLE bounds.
    seed : int, optional
        Bootstrap seed.
    pfv_convention : {"amplitude", "peak"} or None, optional
        If given, IM1..IM9 are recomputed from the block and pulse columns with this PFV;
        if None, the table's IM columns are used (computed with "amplitude" if absent).
    """

    ims: tuple[str, ...] = IM_NAMES
    strip_factors: tuple[float, ...] = STRIP_FACTORS
    extent: str = "range"
    n_boot: int = 200
    confidence: float = 0.95
    seed: int = 0
    pfv_convention: str | None = None

    def __post_init__(self) -> None:
        for im in self.ims:
            one_of("ims", im, IM_NAMES)
        for f in self.strip_factors:
            positive_finite("strip_factors", f)
        one_of("extent", self.extent, STRIP_EXTENTS)
        int_at_least("n_boot", self.n_boot, 0)
        if self.pfv_convention is not None:
            one_of("pfv_convention", self.pfv_convention, PFV_CONVENTIONS)


@dataclass(frozen=True)
class IMFragility:
    """Everything the fragility layer computes for one IM.

    Parameters
    ----------
    im : str
        IM name.
    hybrid : HybridStrip
        Hybrid strip and ratio.
    strips : Mapping[float, StripFractions]
        Strip fractions per strip factor.
    ls_fits : Mapping[float, LognormalFit]
        Least-squares fit per strip factor (Eq. 15-16).
    mle : MLEFit
        Maximum-likelihood fit on the rocking cases.
    """

    im: str
    hybrid: HybridStrip
    strips: Mapping[float, StripFractions] = field(repr=False)
    ls_fits: Mapping[float, LognormalFit]
    mle: MLEFit


@dataclass(frozen=True)
class FragilityAnalysis:
    """Result of :func:`analyse_fragility`: the case split and one :class:`IMFragility` per IM."""

    split: CaseSplit
    results: Mapping[str, IMFragility]
    settings: FragilitySettings

    def __getitem__(self, im: str) -> IMFragility:
        return self.results[im]


def _with_ims(cases: pd.DataFrame, pfv_convention: str | None) -> pd.DataFrame:
    if pfv_convention is not None or any(im not in cases.columns for im in IM_NAMES):
        return add_intensity_measures(cases, pfv_convention or "amplitude")
    return cases


def analyse_fragility(
    cases: pd.DataFrame, settings: FragilitySettings | None = None
) -> FragilityAnalysis:
    """Hybrid strips, strip fractions, least-squares and MLE fits for every IM.

    Parameters
    ----------
    cases : pandas.DataFrame
        Cases table (columns of ``cases.csv``).
    settings : FragilitySettings, optional
        Defaults to ``FragilitySettings()``.

    Returns
    -------
    FragilityAnalysis
    """
    settings = settings or FragilitySettings()
    split = split_cases(_with_ims(cases, settings.pfv_convention))
    y = split.rocking["overturned"].to_numpy(bool)
    results = {}
    for im in settings.ims:
        dec = get_im(im).decreasing
        x = split.rocking[im].to_numpy(float)
        hs = hybrid_strip(x, y, im, dec)
        strips, fits = {}, {}
        for fac in settings.strip_factors:
            if hs.n_safe == 0 or hs.n_overturned == 0:
                fits[fac] = _failed_fit("least_squares", 0, dec, hs.note)
                continue
            st = strip_fractions(x, y, hs, fac, settings.extent)
            strips[fac] = st
            fit = fit_lognormal_least_squares(st.centre, st.fraction, dec)
            if st.fallback:
                fit = LognormalFit(fit.mu, fit.beta, fit.cv_percent, fit.method, fit.n_points,
                                   dec, False, "fallback strips (no hybrid strip); " + fit.message,
                                   fit.objective)
            fits[fac] = fit
        mle = fit_lognormal_mle(x, y, dec, settings.n_boot, settings.confidence, settings.seed) \
            if x.size else MLEFit(math.nan, math.nan, math.nan, "mle", 0, dec, False, "no rocking cases")
        results[im] = IMFragility(im, hs, strips, fits, mle)
    return FragilityAnalysis(split, results, settings)


def _analysis(cases_or_analysis, settings: FragilitySettings | None) -> FragilityAnalysis:
    if isinstance(cases_or_analysis, FragilityAnalysis):
        return cases_or_analysis
    return analyse_fragility(cases_or_analysis, settings)


#: Columns of :func:`table2`, exactly those of the paper's Table 2.
TABLE2_COLUMNS: tuple[str, ...] = ("im", "W_HS", "R_S", "R_O", "W_HS_over_R_S", "W_HS_over_R_O",
                                   "HR", "W_SAS")


def table2(cases_or_analysis, settings: FragilitySettings | None = None) -> pd.DataFrame:
    """The paper's Table 2 (hybrid strip parameters per IM) from a cases table.

    Parameters
    ----------
    cases_or_analysis : pandas.DataFrame or FragilityAnalysis
        Cases table, or an analysis already computed.
    settings : FragilitySettings, optional
        Used when a cases table is given.

    Returns
    -------
    pandas.DataFrame
        Columns ``im, W_HS, R_S, R_O, W_HS_over_R_S, W_HS_over_R_O, HR, W_SAS`` (IM units
        and dimensionless ratios), one row per IM.
    """
    if not isinstance(cases_or_analysis, FragilityAnalysis):
        settings = FragilitySettings(**{**vars(settings or FragilitySettings()), "n_boot": 0})
    an = _analysis(cases_or_analysis, settings)
    rows = []
    for im, r in an.results.items():
        h = r.hybrid
        rows.append({"im": im, "W_HS": h.W_HS, "R_S": h.R_S, "R_O": h.R_O,
                     "W_HS_over_R_S": h.ratio_S, "W_HS_over_R_O": h.ratio_O, "HR": h.HR,
                     "W_SAS": h.W_SAS})
    return pd.DataFrame(rows, columns=list(TABLE2_COLUMNS))


def table3(cases_or_analysis, settings: FragilitySettings | None = None) -> pd.DataFrame:
    """The paper's Table 3 (least-squares fits per strip width) plus the MLE beside it.

    Parameters
    ----------
    cases_or_analysis : pandas.DataFrame or FragilityAnalysis
        Cases table, or an analysis already computed.
    settings : FragilitySettings, optional
        Used when a cases table is given.

    Returns
    -------
    pandas.DataFrame
        One row per (IM, strip factor): ``im, strip_factor, W_AS, n_strips, mu, beta,
        cv_percent, ls_success, ls_message, fallback, mle_mu, mle_beta, mle_cv_percent,
        mle_mu_lo, mle_mu_hi, mle_beta_lo, mle_beta_hi, mle_success, mle_loglik_per_case,
        n_rocking, n_safe, n_overturned, n_no_uplift, n_failed``. ``mu`` in IM units,
        ``beta`` dimensionless, ``cv_percent`` = 100 beta / mu.
    """
    an = _analysis(cases_or_analysis, settings)
    counts = an.split.counts()
    rows = []
    for im, r in an.results.items():
        m = r.mle
        for fac, fit in r.ls_fits.items():
            st = r.strips.get(fac)
            rows.append({
                "im": im, "strip_factor": fac,
                "W_AS": st.width if st is not None else math.nan,
                "n_strips": st.n_strips if st is not None else 0,
                "mu": fit.mu, "beta": fit.beta, "cv_percent": fit.cv_percent,
                "ls_success": fit.success, "ls_message": fit.message,
                "fallback": bool(st.fallback) if st is not None else True,
                "mle_mu": m.mu, "mle_beta": m.beta, "mle_cv_percent": m.cv_percent,
                "mle_mu_lo": m.mu_lo, "mle_mu_hi": m.mu_hi,
                "mle_beta_lo": m.beta_lo, "mle_beta_hi": m.beta_hi,
                "mle_success": m.success, "mle_loglik_per_case": m.loglik_per_case,
                "n_rocking": counts["n_rocking"], "n_safe": counts["n_safe"],
                "n_overturned": counts["n_overturned"], "n_no_uplift": counts["n_no_uplift"],
                "n_failed": counts["n_failed"],
            })
    return pd.DataFrame(rows)


def rank_ims(analysis: FragilityAnalysis, strip_factor: float = 1.0) -> pd.DataFrame:
    """Rank the IMs by the paper's criteria (HR, CV) and by scale-free ones.

    Parameters
    ----------
    analysis : FragilityAnalysis
        A computed analysis.
    strip_factor : float, optional
        Which least-squares fit supplies ``cv_percent`` and ``beta``.

    Returns
    -------
    pandas.DataFrame
        Indexed by IM: ``HR``, ``cv_percent``, ``beta`` (NaN, so unranked, when the
        least-squares fit is flagged unreliable, e.g. a perfectly separating IM: HR and
        ``fraction_in_hybrid`` rank those), ``mle_beta``,
        ``mle_loglik_per_case`` (higher is better; invariant under power laws of the IM),
        ``fraction_in_hybrid`` (rocking cases in the hybrid strip; invariant under any
        monotone change of the IM), and a ``rank_<criterion>`` column for each (1 = best).
    """
    n = max(analysis.split.n_rocking, 1)
    rows = {}
    for im, r in analysis.results.items():
        fit = r.ls_fits.get(strip_factor)
        usable = fit is not None and fit.success
        rows[im] = {
            "HR": r.hybrid.HR,
            "cv_percent": fit.cv_percent if usable else math.nan,
            "beta": fit.beta if usable else math.nan,
            "mle_beta": r.mle.beta if r.mle.success else math.nan,
            "mle_loglik_per_case": r.mle.loglik_per_case,
            "fraction_in_hybrid": r.hybrid.n_in_strip / n,
        }
    df = pd.DataFrame.from_dict(rows, orient="index")
    df.index.name = "im"
    for col in list(df.columns):
        df[f"rank_{col}"] = df[col].rank(ascending=col != "mle_loglik_per_case", method="min")
    return df


def best_ims(ranking: pd.DataFrame) -> dict[str, str]:
    """The best IM under each criterion of a :func:`rank_ims` table (NaNs skipped)."""
    out = {}
    for col in ranking.columns:
        if col.startswith("rank_") or ranking[col].isna().all():
            continue
        out[col] = str(ranking[col].idxmax() if col == "mle_loglik_per_case" else ranking[col].idxmin())
    return out


# ---------------------------------------------------------------------------------------
# Markdown renderers, ours beside the paper's
# ---------------------------------------------------------------------------------------
def _md(header: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines)


def _f(v: float, nd: int = 2) -> str:
    return "n/a" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.{nd}f}"


def table2_markdown(ours: pd.DataFrame, pfv_convention: str = "amplitude") -> str:
    """Render :func:`table2` output beside the paper's Table 2, as "ours (paper)".

    Parameters
    ----------
    ours : pandas.DataFrame
        Output of :func:`table2`.
    pfv_convention : str, optional
        Stated in the caption (IM3 and IM8 depend on it).
    """
    cols = list(TABLE2_COLUMNS[1:])
    rows = []
    for _, r in ours.iterrows():
        paper = TABLE2.get(r["im"])
        rows.append([r["im"]] + [
            f"{_f(r[c])} ({_f(getattr(paper, c)) if paper else 'n/a'})" for c in cols])
    caption = ("Table 2, ours (paper). Rocking cases only; IM3 and IM8 with PFV convention "
               f"'{pfv_convention}'. The paper's blocks are not listed, so values differ; "
               "compare the ranking.")
    return caption + "\n\n" + _md(["IM"] + cols, rows)


def table3_markdown(ours: pd.DataFrame, pfv_convention: str = "amplitude") -> str:
    """Render :func:`table3` output beside the paper's Table 3, plus the MLE columns.

    Parameters
    ----------
    ours : pandas.DataFrame
        Output of :func:`table3`.
    pfv_convention : str, optional
        Stated in the caption.
    """
    factors = sorted(ours["strip_factor"].unique())
    header = ["IM"]
    for fac in factors:
        header += [f"mu ({fac:g} W_SAS)", f"beta ({fac:g} W_SAS)", f"CV % ({fac:g} W_SAS)"]
    header += ["MLE mu [CI]", "MLE beta [CI]"]
    rows = []
    for im, g in ours.groupby("im", sort=False):
        row = [im]
        for fac in factors:
            r = g[g["strip_factor"] == fac].iloc[0]
            p = TABLE3.get(im, {}).get(float(fac))
            flag = "" if r["ls_success"] else "*"
            row += [f"{_f(r['mu'])}{flag} ({_f(p.mu) if p else 'n/a'})",
                    f"{_f(r['beta'])}{flag} ({_f(p.beta) if p else 'n/a'})",
                    f"{_f(r['cv_percent'])} ({_f(p.cv_percent) if p else 'n/a'})"]
        r = g.iloc[0]
        row += [f"{_f(r['mle_mu'])} [{_f(r['mle_mu_lo'])}, {_f(r['mle_mu_hi'])}]",
                f"{_f(r['mle_beta'])} [{_f(r['mle_beta_lo'])}, {_f(r['mle_beta_hi'])}]"]
        rows.append(row)
    caption = ("Table 3, least-squares lognormal fits on strip fractions, ours (paper); "
               "* = fit flagged unreliable (see ls_message). MLE on the raw outcomes of the "
               f"rocking cases, percentile-bootstrap bounds. PFV convention '{pfv_convention}'.")
    return caption + "\n\n" + _md(header, rows)
