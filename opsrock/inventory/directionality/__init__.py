"""Both models side by side: the same contents items under the same record pairs in three dimensions (both
horizontal components at once) and in the plane of the weaker axis, beside pelicun's non-directional factor: a
configuration of the contents study (``opsrock contents --model both``; ``opsrock directionality`` is its alias),
the route :data:`~opsrock.inventory.directionality.study.BOTH` of :class:`opsrock.inventory.stages.Assessment`.

:mod:`~opsrock.inventory.directionality.study` holds the design and runs it,
:mod:`~opsrock.inventory.directionality.cases` builds the motions and cases,
:mod:`~opsrock.inventory.directionality.summary` computes the tables,
:mod:`~opsrock.inventory.directionality.columns` defines their columns and writes and reads them, and
:mod:`~opsrock.inventory.directionality.report` writes the report and figures.
"""
