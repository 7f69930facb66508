"""IDA curves and resurrection: a record that overturns the block at one level and not at a higher one.

A rocking block is not a structure that degrades monotonically: a stronger scaling of the same
record can change the timing of the impacts so that the block survives (the safe windows of the
pulse thresholds are the same phenomenon). Each (block, record, floor) is one IDA curve; sorted by
level, its first overturning level is the curve's *first exceedance*, and every safe level above
it is a *resurrection*.

Two outcome conventions for the fits, both offered and reported:

* ``"as_simulated"``: each case's own verdict (a resurrected case counts as safe);
* ``"first_exceedance"``: a case counts as overturned if its curve overturned at this level or
  any lower one (the IDA "collapse at first exceedance" convention; the curve is made monotone).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import pandas as pd

from opsrock.campaign.cases import as_bool
from opsrock.errors import InputError

#: Columns that identify one IDA curve.
CURVE_KEYS: tuple[str, ...] = ("block", "record", "floor")
#: Outcome conventions of the fits (module notes).
OUTCOMES: tuple[str, ...] = ("as_simulated", "first_exceedance")


def _ok(cases: pd.DataFrame) -> pd.DataFrame:
    """The finished cases (failed ones are never a verdict), sorted along each curve."""
    ok = cases[cases["status"] == "ok"].copy()
    ok["overturned"] = as_bool(ok["overturned"], "overturned")  # the case reader's parser: anything else refused
    return ok.sort_values([*CURVE_KEYS, "level"], kind="stable")


def outcomes(cases: pd.DataFrame, convention: str = "as_simulated") -> pd.Series:
    """Overturned (bool) per finished case under ``convention`` (one of :data:`OUTCOMES`), indexed
    like ``cases``."""
    if convention not in OUTCOMES:
        raise InputError(f"convention must be one of {', '.join(OUTCOMES)}; got {convention!r}")
    ok = _ok(cases)
    if convention == "as_simulated":
        return ok["overturned"]
    return ok.groupby(list(CURVE_KEYS), sort=False)["overturned"].cummax()


def resurrections(cases: pd.DataFrame) -> pd.DataFrame:
    """One row per IDA curve: ``n_levels``, ``n_overturned``, ``first_overturned_level`` (level
    index, 0 if never), ``first_overturned_value`` (the scene's measure there), ``n_resurrected``
    (safe levels above the first overturning one) and ``resurrected`` (bool)."""
    ok = _ok(cases)
    rows = []
    for key, g in ok.groupby(list(CURVE_KEYS), sort=False):
        over = g["overturned"].to_numpy(bool)
        first = int(np.argmax(over)) if over.any() else -1
        n_res = int((~over[first + 1:]).sum()) if first >= 0 else 0
        rows.append({**dict(zip(CURVE_KEYS, key)), "n_levels": len(g), "n_overturned": int(over.sum()),
                     "first_overturned_level": int(g["level"].iloc[first]) if first >= 0 else 0,
                     "first_overturned_value": float(g["level_value"].iloc[first]) if first >= 0 else np.nan,
                     "n_resurrected": n_res, "resurrected": n_res > 0})
    import pandas as pd

    return pd.DataFrame(rows)


def resurrection_summary(table: pd.DataFrame) -> dict[str, float]:
    """Counts of :func:`resurrections`: curves, curves that overturn, curves with a resurrection and
    the resurrected cases (safe cases above a first overturning level)."""
    n_over = int((table["n_overturned"] > 0).sum())
    return {"n_curves": len(table), "n_curves_overturning": n_over,
            "n_curves_resurrected": int(table["resurrected"].sum()),
            "share_of_overturning_curves": float(table["resurrected"].sum() / n_over) if n_over else np.nan,
            "n_resurrected_cases": int(table["n_resurrected"].sum())}
