"""Overturning fragility from a table of simulated cases (paper Section 4, Eq. 12-16).

The input is a pandas DataFrame of cases, one row a (block, pulse) simulation, with the
columns of the campaign's ``cases.csv`` (``status``, ``rocked``, ``overturned``, ``IM1`` ..
``IM9``, ...). No solver runs here.

Choices (docs/guide/modelling.md section 2 "Fragility layer"; each is where the paper is silent or loose):

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

The layer is a package of one method a module:

* :mod:`~opsrock.fragility.cases`: which cases count (:func:`split_cases`);
* :mod:`~opsrock.fragility.hybrid_strip`: Eq. 12 (:func:`hybrid_strip`);
* :mod:`~opsrock.fragility.strips`: Eq. 13 (:func:`strip_fractions`);
* :mod:`~opsrock.fragility.lognormal`: Eq. 14 and the fit result (:class:`LognormalFit`);
* :mod:`~opsrock.fragility.least_squares`: Eq. 15-16 (:func:`fit_lognormal_least_squares`);
* :mod:`~opsrock.fragility.mle`: the maximum-likelihood fit (:func:`fit_lognormal_mle`);
* :mod:`~opsrock.fragility.analysis`: the paper's whole analysis, Tables 2-3, the IM ranking;
* :mod:`~opsrock.fragility.tables`: Markdown renderings beside the paper.
"""

from __future__ import annotations

from opsrock.fragility.analysis import (
    TABLE2_COLUMNS,
    FragilityAnalysis,
    FragilitySettings,
    IMFragility,
    analyse_fragility,
    best_ims,
    rank_ims,
    table2,
    table3,
)
from opsrock.fragility.cases import CaseSplit, split_cases
from opsrock.fragility.hybrid_strip import FALLBACK_STRIPS, STANDARD_STRIP_DIVISOR, HybridStrip, hybrid_strip
from opsrock.fragility.least_squares import LS_MAX_EVALUATIONS, fit_lognormal_least_squares
from opsrock.fragility.lognormal import BETA_BOUNDS, LognormalFit, fragility_probability
from opsrock.fragility.mle import MLEFit, fit_lognormal_mle
from opsrock.fragility.strips import STRIP_EXTENTS, StripFractions, strip_fractions
from opsrock.fragility.tables import table2_markdown, table3_markdown

__all__ = [
    "BETA_BOUNDS", "CaseSplit", "FALLBACK_STRIPS", "FragilityAnalysis", "FragilitySettings", "HybridStrip",
    "IMFragility", "LS_MAX_EVALUATIONS", "LognormalFit", "MLEFit", "STANDARD_STRIP_DIVISOR", "STRIP_EXTENTS",
    "StripFractions", "TABLE2_COLUMNS", "analyse_fragility", "best_ims", "fit_lognormal_least_squares",
    "fit_lognormal_mle", "fragility_probability", "hybrid_strip", "rank_ims", "split_cases", "strip_fractions",
    "table2", "table2_markdown", "table3", "table3_markdown",
]
