"""The contents study: each FEMA P-58 unanchored item's overturning fragility on the floors of one
building, beside FEMA P-58's, ready for a pelicun assessment.

:func:`run_contents_study` runs it end to end (resumable campaigns, maximum-likelihood fits with
record-bootstrap intervals, tables, figures, the report and pelicun's damage-model files);
:mod:`~opsrock.contents.design` holds what a study computes (building, floors, records, IDA levels,
items, variants), :mod:`~opsrock.contents.campaigns` runs the campaigns, :mod:`~opsrock.contents.fits`
fits, :mod:`~opsrock.contents.tables` and :mod:`~opsrock.contents.drivers` measure, and
:mod:`~opsrock.contents.pelicun` writes pelicun's files. FEMA's own rule is
:mod:`opsrock.published.fema_p58`.
"""

from opsrock.contents.design import DEFAULT_FRICTION, DEFAULT_LEVELS, SWEEP_BUILDINGS, VARIANTS, ContentsDesign
from opsrock.contents.study import TABLES, ContentsStudy, StudySummary, run_contents_study

__all__ = ["DEFAULT_FRICTION", "DEFAULT_LEVELS", "SWEEP_BUILDINGS", "TABLES", "VARIANTS", "ContentsDesign",
           "run_contents_study", "ContentsStudy", "StudySummary"]
