"""Sliding as a damage mode of its own: the fragility of sliding beyond a distance, beside overturning.

A block that slides may walk into a wall, off a platform or into a doorway; the distance that matters
is the room's. For a campaign solved with friction (``cases.csv`` with the contact columns: solvers of
the ``friction`` model), the outcome of a case is ``slid beyond d``: its peak slide (``slide_max``,
m) or its residual slide (``|slide_residual|``, m) exceeds ``d``; a block that overturned counts as
beyond every distance (it has left its place). ``P(slid beyond d | demand)`` is fitted as a lognormal
by maximum likelihood over every finished case, with bootstrap intervals that resample whole records,
in PFA (m/s²) and in PFV (m/s), and exported to pelicun beside the overturning components
(ID ``opsrock.<block>.SLIDE<d in mm>MM.<PFA|PFV>``, one limit state).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from opsrock.campaign.cases import as_bool
from opsrock.errors import InputError

#: What a slide is measured by: the peak, or the residual, displacement of the base on the floor.
SLIDE_MEASURES: tuple[str, ...] = ("slide_max", "slide_residual")
#: Default distances (m) of the report: a few centimetres (a cabinet against a wall) to half a metre.
DEFAULT_DISTANCES: tuple[float, ...] = (0.05, 0.2, 0.5)


@dataclass(frozen=True)
class SlidingFit:
    """One sliding fragility: block, distance (m), slide measure, demand, and the lognormal fit (median in
    the demand's unit: m/s² for PFA, m/s for PFV) with its record-bootstrap interval."""

    block: str
    distance: float
    measure: str
    demand: str
    median: float
    median_lo: float
    median_hi: float
    beta: float
    beta_lo: float
    beta_hi: float
    n_cases: int
    n_beyond: int
    success: bool
    message: str

    def row(self) -> dict:
        """The fit as a table row."""
        return dict(self.__dict__)


def slid_beyond(cases: pd.DataFrame, distance: float, measure: str = "slide_max") -> np.ndarray:
    """Per finished case: did the block slide beyond ``distance`` (m) by ``measure``, or overturn?

    Raises
    ------
    InputError
        If ``cases`` has no slide columns (not a campaign solved with friction), ``measure`` is unknown
        or ``distance`` is not positive.
    """
    if measure not in SLIDE_MEASURES:
        raise InputError(f"measure must be one of {', '.join(SLIDE_MEASURES)}, got {measure!r}")
    if not (isinstance(distance, (int, float)) and math.isfinite(distance) and distance > 0):
        raise InputError(f"distance must be a positive length in m, got {distance!r}")
    if measure not in cases:
        raise InputError(f"the cases have no {measure} column: sliding needs a campaign solved with friction "
                         "(solver friction)")
    slide = np.abs(pd.to_numeric(cases[measure], errors="coerce").to_numpy(float))
    over = as_bool(cases["overturned"], "overturned")
    return over | (slide > distance)


def fit_sliding(cases: pd.DataFrame, block: str, distance: float, *, measure: str = "slide_max",
                demand: str = "pfa", n_boot: int = 200, seed: int = 0) -> SlidingFit:
    """The fragility of ``block`` sliding beyond ``distance`` (m) in ``demand`` (``pfa`` or ``pfv``
    column of ``cases``), from its finished cases."""
    head, plan = _sliding_plan(cases, block, distance, measure, demand, n_boot, seed)
    return _sliding_fit(head, plan.finish(plan.draws()) if plan is not None else None)


def _sliding_plan(cases: pd.DataFrame, block: str, distance: float, measure: str, demand: str, n_boot: int,
                  seed: int):
    """The head of a :class:`SlidingFit` (what it is, the counts) and the MLE plan of its fit (None: no
    transition, nothing to fit); :func:`_sliding_fit` finishes it."""
    from opsrock.fragility.mle import plan_mle

    sel = cases[(cases["block"] == block) & (cases["status"] == "ok")]
    y = slid_beyond(sel, distance, measure)
    x = pd.to_numeric(sel[demand], errors="coerce").to_numpy(float)
    head = dict(block=block, distance=float(distance), measure=measure, demand=demand, n_cases=int(len(sel)),
                n_beyond=int(y.sum()))
    if y.sum() == 0 or y.all():
        return head, None
    groups = sel["record"].to_numpy() if "record" in sel else None
    return head, plan_mle(x, y, n_boot=n_boot, seed=seed, groups=groups)


def _sliding_fit(head: dict, fit) -> SlidingFit:
    """The :class:`SlidingFit` of ``head`` from its MLE fit (None: no transition)."""
    if fit is None:
        nan = math.nan
        return SlidingFit(**head, median=nan, median_lo=nan, median_hi=nan, beta=nan, beta_lo=nan, beta_hi=nan,
                          success=False, message="no transition: every case on one side")
    return SlidingFit(**head, median=fit.mu, median_lo=fit.mu_lo, median_hi=fit.mu_hi, beta=fit.beta,
                      beta_lo=fit.beta_lo, beta_hi=fit.beta_hi, success=bool(fit.success), message=fit.message)


def sliding_table(cases: pd.DataFrame, distances=DEFAULT_DISTANCES, *, measure: str = "slide_max",
                  demands=("pfa", "pfv"), n_boot: int = 200, seed: int = 0, workers: int = 1) -> pd.DataFrame:
    """Every block's sliding fragility at every distance and demand, one row each (blocks sorted, then
    distances, then demands): :func:`fit_sliding` of each, the bootstrap resamples of all of them shared
    among ``workers`` processes (the same numbers whatever ``workers``)."""
    from opsrock.fragility.mle import fit_plans

    parts = [_sliding_plan(cases, b, d, measure, dem, n_boot, seed)
             for b in sorted(cases["block"].unique()) for d in distances for dem in demands]
    fits = iter(fit_plans([plan for _, plan in parts if plan is not None], workers))
    rows = [_sliding_fit(head, next(fits) if plan is not None else None).row() for head, plan in parts]
    return pd.DataFrame(rows, columns=list(SlidingFit.__dataclass_fields__))


def has_slides(cases: pd.DataFrame) -> bool:
    """True if ``cases`` is a table of a campaign solved with friction: it has every contact column
    (:data:`opsrock.campaign.cases.CONTACT_COLUMNS`), the slides among them."""
    from opsrock.campaign.cases import CONTACT_COLUMNS

    return all(c in cases.columns for c in CONTACT_COLUMNS)


def sliding_component_id(block: str, distance: float, demand: str) -> str:
    """``opsrock.<block>.SLIDE<d in mm>MM.<PFA|PFV>``."""
    return f"opsrock.{block}.SLIDE{round(distance * 1000)}MM.{demand.upper()}"


def sliding_components(table: pd.DataFrame):
    """The successful fits of :func:`sliding_table` as pelicun components
    (:class:`opsrock.fragility.pelicun_export.ComponentFragility`), and the skipped ones with why."""
    from opsrock.fragility.pelicun_export import ComponentFragility

    out, skipped = [], []
    for _, r in table.iterrows():
        cid = sliding_component_id(r["block"], r["distance"], r["demand"])
        if r["success"] and math.isfinite(r["median"]) and r["beta"] > 0:
            out.append(ComponentFragility(cid, r["demand"], float(r["median"]), float(r["beta"])))
        else:
            skipped.append(f"{cid}: {r['message']}")
    return out, skipped


__all__ = ["DEFAULT_DISTANCES", "SLIDE_MEASURES", "SlidingFit", "fit_sliding", "has_slides", "slid_beyond",
           "sliding_component_id", "sliding_components", "sliding_table"]
