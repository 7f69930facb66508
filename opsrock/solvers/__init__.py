"""Solvers behind one entry point, :func:`simulate`, and their registry :data:`METHODS`.

Every solver is a package with ``settings.py``, ``solver.py`` (and, compiled, ``kernel.py``) whose
``solve(block, excitation, settings=None, **overrides) -> RockingResult`` keeps one written contract
(the docstring of :mod:`opsrock.solvers.common`: the shared settings base, statuses, result fields and
errors; tests/solvers/test_contract.py checks every registered solver against it). They share
:mod:`~opsrock.solvers.common` and :mod:`~opsrock.solvers.status` and never each other's code:

* ``opensees``: the paper's equivalent SDOF model built literally in OpenSeesPy (the only
  solver that touches OpenSees state; OpenSeesPy is loaded when first used);
* ``sdof``: the same SDOF equations integrated by scipy, sharing no numerics with OpenSees;
* ``housner``: the exact rigid-body equation with instantaneous impacts, event-driven;
* ``housner_fast``: the same rigid-body equation, compiled, for dense spectra and campaigns;
* ``friction``: the rigid block on a floor with Coulomb friction and vertical motion (rest, slide,
  rock, slide-rock), event-driven and compiled;
* ``moreau_jean``: the same block by Moreau-Jean time stepping with contact and friction as
  complementarity conditions: the reference of a different formulation for ``friction``.

The registry (:mod:`~opsrock.solvers.registry`) declares what each solver models and needs
(:class:`SolverInfo`); :func:`solver_names` and :func:`capabilities` read it for the command line and
the campaign, :func:`check_model` refuses what a solver does not model.
"""

from __future__ import annotations

from typing import Any

from opsrock.block import Block
from opsrock.errors import InputTypeError
from opsrock.excitations import Excitation
from opsrock.result import RockingResult
from opsrock.solvers.registry import METHODS, SOLVERS, SolverInfo, capabilities, check_model, info, solver_names


def get_solver(name: str):
    """Return the solver module called ``name`` (one of :data:`SOLVERS`)."""
    return info(name).load()


def settings_class(name: str) -> type:
    """The settings dataclass of the solver ``name`` (one of :data:`SOLVERS`)."""
    return info(name).settings_class()


def check_settings(name: str, settings: dict[str, Any]) -> Any:
    """The settings object the solver ``name`` would run with under ``settings`` (keyword overrides),
    built now so that a bad name or value is refused before any work.

    Raises
    ------
    InputError, InputTypeError
        Naming the setting: unknown to the solver, or refused by it.
    """
    from opsrock.solvers.common import make_settings

    return make_settings(settings_class(name), None, dict(settings))


def simulate(block: Block, excitation: Excitation | None, solver: str = "opensees", **settings: Any) -> RockingResult:
    """Solve the rocking response of ``block`` to ``excitation``.

    Parameters
    ----------
    block : Block
        The block.
    excitation : Excitation or None
        A :class:`~opsrock.excitations.OneSinePulse`, :class:`~opsrock.excitations.Record`, or
        anything with ``duration``, ``pfa``, ``acceleration(t)`` and ``breakpoints()``; None: a still
        floor (free rocking from the settings' ``theta0``, ``theta_dot0``).
    solver : str
        One of :data:`SOLVERS`.
    **settings
        Keyword settings of that solver's ``solve`` (model and numerics).
    """
    if not isinstance(block, Block):
        raise InputTypeError(f"block must be a Block, got {block!r}")
    if excitation is not None and not isinstance(excitation, Excitation):
        raise InputTypeError(f"excitation must be an Excitation (OneSinePulse, Record), got {excitation!r}")
    check_model(solver, block, excitation)
    return get_solver(solver).solve(block, excitation, **settings)


__all__ = ["METHODS", "SOLVERS", "SolverInfo", "capabilities", "check_model", "check_settings", "get_solver", "info",
           "settings_class", "simulate", "solver_names"]
