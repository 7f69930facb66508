"""Validation case ``experiments``: measured free rocking of limestone blocks against Housner's
restitution and against the free-rocking decay each solver predicts.

Data: Colombo, C. et al., *Experimental dataset on the free-rocking response of masonry blocks*,
University of Minho, DOI 10.60756/uminho-jh25, CC BY 4.0; shipped in ``opsrock/data/experiments/``
(its ``SOURCE.md`` says how the tables were derived). 12 geometries (B = 0.05 m, H = 0.20-0.75 m),
134 distinct trials, 7,519 impacts, each with its measured angular-velocity ratio after/before.

Two parts (``validation/experiments/README.md`` derives the relations and tolerances):

1. **Restitution.** The measured ratio against Housner's ``e_R = 1 - 1.5 sin²(alpha)`` and against the
   paper's ``0.95 e_R``, per geometry and per impact number (bias, RMSE, medians); the factor
   ``f = measured / e_R`` fitted on the data (median over all impacts) with variants that drop or
   weight impacts differently, and tests of whether ``f`` drifts with the impact number or with
   the slenderness. Every interval is a bootstrap that resamples whole trials within each geometry
   (impacts of one trial are correlated), seeded.
2. **Decay of free rocking.** The running product of the measured ratios of each trial (the
   velocity after ``n`` impacts over that before the first), median and spread per geometry, against
   the rigid body with ``e_R``, with the fitted ``f e_R`` and with ``0.95 e_R`` (``housner``) and the
   paper's SDOF model at default settings (``sdof``, ``opensees``) released from rest at stated
   fractions of alpha (the experiments' release angles are not in the data).

``run(out_dir, quick)`` writes the tables and figures and returns the summary with ``"passed"``:
the data's own consistency, the intervals containing their estimates, the rigid body reproducing
``e^n`` and both SDOF implementations reproducing the model's closed-form decay.

The package, by role: :mod:`~.constants` (the fixed choices), :mod:`~.checks` (data, intervals, runs
against closed forms), :mod:`~.statistics` (restitution, factor, drift, bootstrap, headline, decay),
:mod:`~.runs` (the solver runs), :mod:`~.closed_forms`, :mod:`~.tables`, :mod:`~.figures` and
:mod:`~opsrock.validation.experiments.summary` (the summary and :func:`run`).
"""

from opsrock.published.colombo_limestone import (
    DATA_FILES,
    EventArrays,
    analysis_arrays,
    data_file,
    load_events,
    load_trials,
)
from opsrock.validation.experiments.checks import data_checks, interval_checks, model_checks
from opsrock.validation.experiments.closed_forms import sdof_closed_form
from opsrock.validation.experiments.constants import (
    MODELS,
    N_BOOT,
    N_BOOT_QUICK,
    PAPER_FACTOR,
    QUICK_GROUPS,
    RELEASE_RATIOS,
    SEED,
)
from opsrock.validation.experiments.runs import DecayRun, free_rocking, predict_decay
from opsrock.validation.experiments.statistics import (
    FACTOR_VARIANTS,
    Headline,
    bootstrap,
    decay_errors,
    headline,
    headline_stats,
    measured_decay,
    statistics,
    trial_resamples,
)
from opsrock.validation.experiments.summary import run, summarise

__all__ = ["DATA_FILES", "FACTOR_VARIANTS", "MODELS", "N_BOOT", "N_BOOT_QUICK", "PAPER_FACTOR", "QUICK_GROUPS",
           "RELEASE_RATIOS", "SEED", "DecayRun", "EventArrays", "Headline", "analysis_arrays", "bootstrap", "data_checks",
           "data_file", "decay_errors", "free_rocking", "headline", "headline_stats", "interval_checks",
           "load_events", "load_trials", "measured_decay", "model_checks", "predict_decay", "run",
           "sdof_closed_form", "statistics", "summarise", "trial_resamples"]
