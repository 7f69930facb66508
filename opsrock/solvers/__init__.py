"""Solvers behind one entry point, :func:`simulate`, and their registry :data:`METHODS`.

Every solver is a package with ``settings.py``, ``solver.py`` (and, compiled, ``kernel.py``) whose
``solve(block, excitation, settings=None, **overrides) -> RockingResult`` keeps one written contract
(the docstring of :mod:`opsrock.solvers.common`: the shared settings base, statuses, result fields and
errors; tests/model/solvers/test_contract.py checks every registered solver against it). They share
:mod:`~opsrock.solvers.common` and :mod:`~opsrock.solvers.status` and never each other's code:

* ``opensees``: the paper's equivalent SDOF model built literally in OpenSeesPy (the only
  solver that touches OpenSees state; OpenSeesPy is loaded when first used);
* ``sdof``: the same SDOF equations integrated by scipy, sharing no numerics with OpenSees;
* ``housner``: the exact rigid-body equation with instantaneous impacts, event-driven;
* ``housner_fast``: the same rigid-body equation, compiled, for dense spectra and campaigns;
* ``friction``: the rigid block on a floor with Coulomb friction and vertical motion (rest, slide,
  rock, slide-rock), event-driven and compiled;
* ``moreau_jean``: the same block by Moreau-Jean time stepping with contact and friction as
  complementarity conditions: the reference of a different formulation for ``friction``;
* ``rigid3d``: a rigid box on its four base corners in three dimensions (two horizontal components and a
  vertical one, isotropic Coulomb friction, Housner's impact), compiled; the only solver in plan.

The registry (:mod:`~opsrock.solvers.registry`) declares what each solver models and needs
(:class:`SolverInfo`: planar or in plan, the restitution it models, the result columns it writes, what it
needs of a scene's blocks); :func:`solver_names` and :func:`capabilities` read it for the command line, the
campaign and the studies, which choose a solver by what it declares, never by its name;
:func:`check_model` refuses what a solver does not model.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from opsrock.block import Block
from opsrock.errors import InputTypeError
from opsrock.solvers.registry import METHODS, SOLVERS, SolverInfo, capabilities, check_model, info, solver_names

if TYPE_CHECKING:  # the excitations and results load numpy: the command line's parser reads the registry without
    from opsrock.excitations import Excitation
    from opsrock.excitations.plan import PlanMotion
    from opsrock.result import RockingResult


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


def warm_up(solver: str) -> None:
    """Make the compiled kernel of ``solver`` (one of :data:`SOLVERS`) ready in this process: compiled, or loaded
    from numba's cache, by one short solve of a small block under a one-sine pulse (in plan for a solver in plan,
    on a slipping base for one with friction). Nothing for a solver that is not compiled (registry ``compiled``).
    A campaign calls it before its first case, so that no case's time budget pays for a compile; when the cache is
    cold the solver says so on standard error with the expected duration
    (:func:`opsrock.solvers._compile.announce_compile`). A solver whose kernel compiles a path only when a case first
    needs it (``friction``'s free flight) makes that path ready too, by its ``warm_up_paths``."""
    entry = info(solver)
    if not entry.compiled:
        return
    from opsrock.excitations.plan import PlanMotion
    from opsrock.excitations.pulses import OneSinePulse

    block = Block(0.3, 1.2, restitution_factor=1.0, depth=0.6 if "depth" in entry.block_needs else None,
                  friction=0.5 if entry.friction else None)
    pulse = OneSinePulse.from_ratios(Block(0.3, 1.2, restitution_factor=1.0), 1.35, 3.0)
    simulate(block, PlanMotion.along(pulse, 30.0) if entry.plan else pulse, solver=solver)
    paths = getattr(get_solver(solver), "warm_up_paths", None)
    if paths is not None:
        paths()


def simulate(block: Block, excitation: Excitation | PlanMotion | None, solver: str = "opensees",
             **settings: Any) -> RockingResult:
    """Solve the rocking response of ``block`` to ``excitation``.

    A :class:`~opsrock.excitations.plan.PlanMotion` goes as it is to a solver that models motion in plan
    (registry ``plan``: ``rigid3d``); a planar one (:attr:`PlanMotion.planar`: one component along the block's
    width) goes to a planar solver as its first component, and any other is refused for it
    (:func:`check_model`).

    Parameters
    ----------
    block : Block
        The block.
    excitation : Excitation or PlanMotion or None
        A :class:`~opsrock.excitations.OneSinePulse`, :class:`~opsrock.excitations.Record`, or
        anything with ``duration``, ``pfa``, ``acceleration(t)`` and ``breakpoints()`` (m/s²); a
        :class:`~opsrock.excitations.plan.PlanMotion` (two horizontal components, m/s², and the block's
        azimuth, deg); None: a still floor (free rocking from the settings' ``theta0``, ``theta_dot0``).
    solver : str
        One of :data:`SOLVERS`.
    **settings
        Keyword settings of that solver's ``solve`` (model and numerics).

    Examples
    --------
    A 0.4 m x 1.6 m block under a one-sine pulse of 3 times its frequency parameter and twice its uplift
    acceleration, by the event-driven rigid-body solver:

    >>> import opsrock
    >>> block = opsrock.Block(width=0.4, height=1.6)
    >>> pulse = opsrock.OneSinePulse.from_ratios(block, 3.0, 2.0)
    >>> result = opsrock.simulate(block, pulse, solver="housner")
    >>> result.status, result.overturned
    ('ok', True)
    """
    if not isinstance(block, Block):
        raise InputTypeError(f"block must be a Block, got {block!r}")
    from opsrock.excitations import Excitation
    from opsrock.excitations.plan import PlanMotion

    if excitation is not None and not isinstance(excitation, (Excitation, PlanMotion)):
        raise InputTypeError(f"excitation must be an Excitation (OneSinePulse, Record) or a PlanMotion, got "
                             f"{excitation!r}")
    check_model(solver, block, excitation)
    return get_solver(solver).solve(block, planar_excitation(solver, excitation), **settings)


def planar_excitation(solver: str, excitation: Excitation | PlanMotion | None) -> Excitation | PlanMotion | None:
    """What ``solver`` is given for ``excitation``: a planar :class:`~opsrock.excitations.plan.PlanMotion` as its
    first component for a planar solver (registry ``plan`` False); anything else as it is (a non-planar
    plan motion is refused for a planar solver by :func:`check_model`, not here)."""
    from opsrock.excitations.plan import PlanMotion

    if isinstance(excitation, PlanMotion) and excitation.planar and not info(solver).plan:
        return excitation.first
    return excitation


__all__ = ["METHODS", "SOLVERS", "SolverInfo", "capabilities", "check_model", "check_settings", "get_solver", "info",
           "planar_excitation", "settings_class", "simulate", "solver_names", "warm_up"]
