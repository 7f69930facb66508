"""Solvers behind one entry point, :func:`simulate`.

Each solver is a module with a ``solve(block, excitation, **settings) -> RockingResult``
function and a frozen settings dataclass:

* ``opensees``: the paper's equivalent SDOF model built literally in OpenSeesPy (the only
  module that touches OpenSees state);
* ``sdof``: the same SDOF equations integrated by scipy, sharing no numerics with OpenSees;
* ``housner``: the exact rigid-body equation with instantaneous impacts, event-driven;
* ``housner_fast``: the same rigid-body equation, compiled, for dense spectra.
"""

from __future__ import annotations

import importlib
from typing import Any

from opsrock._checks import one_of
from opsrock.block import Block
from opsrock.excitations import Excitation
from opsrock.result import RockingResult

#: Solver names accepted by :func:`simulate` and the command line.
SOLVERS: tuple[str, ...] = ("opensees", "sdof", "housner", "housner_fast")


def get_solver(name: str):
    """Return the solver module called ``name`` (one of :data:`SOLVERS`)."""
    one_of("solver", name, SOLVERS)
    return importlib.import_module(f"opsrock.solvers.{name}")


def simulate(block: Block, excitation: Excitation, solver: str = "opensees", **settings: Any) -> RockingResult:
    """Solve the rocking response of ``block`` to ``excitation``.

    Parameters
    ----------
    block : Block
        The block.
    excitation : Excitation
        A :class:`~opsrock.excitations.OneSinePulse`, :class:`~opsrock.excitations.Record`, or
        anything with ``duration``, ``pfa``, ``acceleration(t)`` and ``breakpoints()``.
    solver : str
        One of :data:`SOLVERS`.
    **settings
        Keyword settings of that solver's ``solve`` (model and numerics).
    """
    if not isinstance(block, Block):
        raise TypeError(f"block must be a Block, got {block!r}")
    if not isinstance(excitation, Excitation):
        raise TypeError(f"excitation must be an Excitation (OneSinePulse, Record), got {excitation!r}")
    return get_solver(solver).solve(block, excitation, **settings)
