"""The solver registry as the campaign and the command line read it, in one place.

Every name, model and capability of a solver that :mod:`opsrock.campaign` and :mod:`opsrock.cli` use is
read from :mod:`opsrock.solvers`' registry through :func:`solver_info` (and :func:`solver_names`); neither
keeps its own list, and a change of the registry's form is met here only.
"""

from __future__ import annotations

from opsrock.solvers import METHODS, SOLVERS, SolverInfo


def solver_names() -> tuple[str, ...]:
    """Every registered solver's name, in the registry's order."""
    return tuple(SOLVERS)


def solver_info(name: str) -> SolverInfo | None:
    """The registry's entry of solver ``name`` (its ``model``: ``"rigid"``, ``"sdof"`` or ``"friction"``),
    or None for a name it does not hold."""
    return METHODS.get(name)


__all__ = ["solver_info", "solver_names"]
