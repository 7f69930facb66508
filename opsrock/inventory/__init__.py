"""The contents study (``opsrock contents``): items of contents on floor motions, into each item's fragility per
floor, tables, a report and a pelicun assessment, run by the stages of one
:class:`~opsrock.inventory.stages.Assessment` (demands, campaigns, fits, outputs) in one of its configurations
(:class:`~opsrock.inventory.stages.Route`):

* the user's inventory (:mod:`opsrock.inventory.items`) on the user's own floor motions
  (:mod:`opsrock.inventory.motions`) or the shipped building's, planar per axis or every item a box in three
  dimensions (:mod:`opsrock.inventory.study`, :mod:`opsrock.inventory.three_d`;
  ``opsrock contents --inventory FILE --motions FILE [--solver rigid3d]``);
* FEMA P-58's nine unanchored items in the shipped building beside FEMA's fragilities (:mod:`opsrock.inventory.fema`;
  ``opsrock contents``);
* both models side by side, in three dimensions and in the plane of the weaker axis
  (:mod:`opsrock.inventory.directionality`; ``opsrock contents --model both``, alias ``opsrock directionality``).

Layers, each importing only those before it: readers (:mod:`~opsrock.inventory.readers`), the model (items,
friction, motions, sources), the campaigns (:mod:`~opsrock.inventory.campaigns`), the fits and tables, the outputs
(:mod:`~opsrock.inventory.outputs`), the stages (:mod:`~opsrock.inventory.stages`), the configurations.
"""
