"""The user's building: an inventory of contents (:mod:`opsrock.inventory.items`) on the user's own floor
motions (:mod:`opsrock.inventory.motions`), into each item's fragility per floor and a pelicun assessment
(:mod:`opsrock.inventory.study`, ``opsrock contents --inventory FILE --motions FILE``)."""
