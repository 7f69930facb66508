"""Which cases enter the fragility statistics: rocking cases only (Eq. 13); no-uplift and failed
cases counted and reported, never a verdict.

A campaign whose every case failed has nothing to fit: every entry point that fits a campaign
(``opsrock fragility``, :func:`opsrock.fragility.record_study.record_fragility`, ``opsrock contents``) refuses
it in one line through :func:`check_some_finished`; a group (a block, an item on a floor) whose every case
failed is skipped, with the reason :func:`failed_groups` gives."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from opsrock.campaign.cases import as_bool
from opsrock.campaign.executors import is_lost
from opsrock.errors import AllCasesFailedError, InputError


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
        raise InputError(f"column 'status' must be 'ok' or 'failed', got {status[bad][0]!r}")
    ok = status == "ok"
    rocked = as_bool(cases["rocked"], "rocked")
    overturned = as_bool(cases["overturned"], "overturned")
    rocking = ok & rocked
    if np.any(ok & ~rocked & overturned):
        i = int(np.flatnonzero(ok & ~rocked & overturned)[0])
        raise InputError(f"case at row {i} is marked overturned but not rocked")
    if "verdict" in cases.columns:
        expected = np.where(~ok, "failed", np.where(~rocked, "no_uplift",
                                                    np.where(overturned, "overturned", "safe")))
        verdict = cases["verdict"].astype(str).to_numpy()
        wrong = verdict != expected
        if wrong.any():
            i = int(np.flatnonzero(wrong)[0])
            raise InputError(
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


def _why_failed(cases: pd.DataFrame) -> str:
    """``"N cases; first reason: ..."`` of failed cases, and what to do about those lost to the infrastructure."""
    reasons = cases["reason"].fillna("").astype(str).tolist() if "reason" in cases.columns else []
    text = f"{len(cases)} cases" + (f"; first reason: {reasons[0]}" if reasons and reasons[0] else "")
    n_lost = sum(map(is_lost, reasons))
    if n_lost:
        text += (f"; {n_lost} of them were lost to the infrastructure (a worker process died): run the campaign "
                 "again to compute them")
    return text


def count_failed(cases: pd.DataFrame) -> int:
    """How many of ``cases`` did not finish (``status`` other than ``"ok"``: stored failed with their reason)."""
    return int((cases["status"] != "ok").sum())


def check_some_finished(cases: pd.DataFrame, source: str) -> None:
    """Refuse a campaign's cases of which none finished: nothing to fit.

    Parameters
    ----------
    cases : pandas.DataFrame
        Its case table: column ``status`` (``"ok"`` for a finished case) and, when present, ``reason``.
    source : str
        The campaign (its folder or table), named in the message.

    Raises
    ------
    AllCasesFailedError
        ``"every case of <source> failed (N cases; first reason: ...): nothing to fit"`` (an
        :class:`~opsrock.errors.InputError`: exit 2), with what to do when cases were lost to the infrastructure.
    """
    if len(cases) and not (cases["status"].astype(str) == "ok").any():
        raise AllCasesFailedError(f"every case of {source} failed ({_why_failed(cases)}): nothing to fit")


def failed_groups(cases: pd.DataFrame, by: str | list[str]) -> dict:
    """The groups of ``cases`` (by the column or columns ``by``: a block, an item and its floor) of which no case
    finished, each with why: ``{group key: "every case failed (N cases; first reason: ...)"}``, in the table's
    order. A fit skips them and says so."""
    out = {}
    for key, sub in cases.groupby(by, sort=False):
        if not (sub["status"].astype(str) == "ok").any():
            out[key] = f"every case failed ({_why_failed(sub)})"
    return out
