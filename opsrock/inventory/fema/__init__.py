"""FEMA P-58's nine unanchored items on the floors of the shipped building, beside FEMA P-58's fragilities, ready
for a pelicun assessment: a configuration of the contents study (``opsrock contents``, the route
:data:`~opsrock.inventory.fema.study.FEMA_NINE` of :class:`opsrock.inventory.stages.Assessment`).

:func:`opsrock.run_study` (with no inventory and no motions) runs it end to end (resumable campaigns, maximum-likelihood fits with
record-bootstrap intervals, tables, figures, the report and pelicun's damage-model files);
:mod:`~opsrock.inventory.fema.design` holds what it computes (building, floors, records, IDA levels, items,
variants), :mod:`~opsrock.inventory.fema.campaigns` runs the campaigns, :mod:`~opsrock.inventory.fema.fits`
fits, :mod:`~opsrock.inventory.fema.tables` and :mod:`~opsrock.inventory.fema.drivers` measure, and
:mod:`~opsrock.inventory.fema.pelicun` hands the default variant to the study's one pelicun writer. FEMA's own
rule is :mod:`opsrock.published.fema_p58`.
"""

from opsrock.inventory.fema.design import DEFAULT_FRICTION, DEFAULT_LEVELS, SWEEP_BUILDINGS, VARIANTS, ContentsDesign
from opsrock.inventory.fema.study import FEMA_NINE, TABLES, StudySummary

__all__ = ["DEFAULT_FRICTION", "DEFAULT_LEVELS", "FEMA_NINE", "SWEEP_BUILDINGS", "TABLES", "VARIANTS", "ContentsDesign",
           "StudySummary"]
