"""Markdown renderings of Tables 2 and 3, ours beside the paper's."""

from __future__ import annotations

import math

import pandas as pd

from opsrock.fragility.analysis import TABLE2_COLUMNS
from opsrock.published.liu_huang_liu_2023 import TABLE2, TABLE3


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
