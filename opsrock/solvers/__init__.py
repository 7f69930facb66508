"""Solvers behind one entry point, :func:`simulate`, and their registry :data:`METHODS`.

Each solver is a module (or a package of one method a module) with a
``solve(block, excitation, *, settings=None, **overrides) -> RockingResult`` function and a frozen
settings dataclass; they share :mod:`~opsrock.solvers.common` and never each other's code:

* ``opensees``: the paper's equivalent SDOF model built literally in OpenSeesPy (the only
  solver that touches OpenSees state);
* ``sdof``: the same SDOF equations integrated by scipy, sharing no numerics with OpenSees;
* ``housner``: the exact rigid-body equation with instantaneous impacts, event-driven;
* ``housner_fast``: the same rigid-body equation, compiled, for dense spectra and campaigns;
* ``friction``: the rigid block on a floor with Coulomb friction and vertical motion (rest, slide,
  rock, slide-rock), event-driven and compiled;
* ``moreau_jean``: the same block by Moreau-Jean time stepping with contact and friction as
  complementarity conditions: the reference of a different formulation for ``friction``.

A solver module is imported when first used (OpenSeesPy and numba are costly to import), so the
registry names modules and settings classes instead of holding them.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import Any

from opsrock.block import Block
from opsrock.errors import InputError, InputTypeError
from opsrock.excitations import Excitation
from opsrock.excitations.base import has_vertical
from opsrock.limits import one_of
from opsrock.result import RockingResult


@dataclass(frozen=True)
class SolverInfo:
    """One entry of the registry.

    Parameters
    ----------
    name : str
        The solver's name (``--solver``, ``[solver] name``).
    module : str
        Module whose ``solve`` runs it.
    settings : str
        ``"module:Class"`` of its frozen settings dataclass.
    model : str
        What it solves: ``"rigid"`` (the rigid-body equation, Eq. 1-3, no slip, horizontal motion),
        ``"sdof"`` (the paper's equivalent SDOF model, Eq. 5-8) or ``"friction"`` (the rigid block
        with Coulomb friction under horizontal and vertical floor motion, docs/friction.md).
    """

    name: str
    module: str
    settings: str
    model: str

    def load(self):
        """The solver module."""
        return importlib.import_module(self.module)

    def settings_class(self) -> type:
        """The solver's settings dataclass."""
        module, _, attr = self.settings.partition(":")
        return getattr(importlib.import_module(module), attr)


#: The registry: every solver by name (as scipy's ``solve_ivp`` keeps its ``METHODS``).
METHODS: dict[str, SolverInfo] = {
    "opensees": SolverInfo("opensees", "opsrock.solvers.opensees",
                           "opsrock.solvers.opensees.settings:OpenSeesSettings", "sdof"),
    "sdof": SolverInfo("sdof", "opsrock.solvers.sdof", "opsrock.solvers.sdof.settings:SDOFSettings", "sdof"),
    "housner": SolverInfo("housner", "opsrock.solvers.housner", "opsrock.solvers.housner:HousnerSettings", "rigid"),
    "housner_fast": SolverInfo("housner_fast", "opsrock.solvers.housner_fast",
                               "opsrock.solvers.housner_fast.settings:HousnerFastSettings", "rigid"),
    "friction": SolverInfo("friction", "opsrock.solvers.friction",
                           "opsrock.solvers.friction.settings:FrictionSettings", "friction"),
    "moreau_jean": SolverInfo("moreau_jean", "opsrock.solvers.moreau_jean",
                              "opsrock.solvers.moreau_jean.settings:MoreauJeanSettings", "friction"),
}

#: Solver names accepted by :func:`simulate` and the command line.
SOLVERS: tuple[str, ...] = tuple(METHODS)


def get_solver(name: str):
    """Return the solver module called ``name`` (one of :data:`SOLVERS`)."""
    return METHODS[one_of("solver", name, SOLVERS)].load()


def settings_class(name: str) -> type:
    """The settings dataclass of the solver ``name`` (one of :data:`SOLVERS`)."""
    return METHODS[one_of("solver", name, SOLVERS)].settings_class()


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


def check_model(name: str, block: Block, excitation: object) -> None:
    """Refuse a block with friction, or a floor motion with a vertical component, for a solver whose
    model has neither (every model but ``"friction"``).

    Raises
    ------
    InputError
        Naming the solver and what it cannot model.
    """
    info = METHODS[one_of("solver", name, SOLVERS)]
    if info.model == "friction":
        return
    if block.slips:
        raise InputError(f"solver {name!r} models no-slip rocking; block {block.name or '<unnamed>'} has "
                         f"friction = {block.friction!r}: use solver 'friction' (or drop friction)")
    if has_vertical(excitation):
        raise InputError(f"solver {name!r} takes horizontal floor motion only; the excitation has a vertical "
                         "component: use solver 'friction' (or drop the vertical motion)")


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
        raise InputTypeError(f"block must be a Block, got {block!r}")
    if not isinstance(excitation, Excitation):
        raise InputTypeError(f"excitation must be an Excitation (OneSinePulse, Record), got {excitation!r}")
    check_model(solver, block, excitation)
    return get_solver(solver).solve(block, excitation, **settings)


__all__ = ["METHODS", "SOLVERS", "SolverInfo", "check_model", "check_settings", "get_solver", "settings_class",
           "simulate"]
