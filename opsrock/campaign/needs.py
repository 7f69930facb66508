"""A scene states what it needs; ``solver = "auto"`` picks the cheapest solver whose measured error meets it.

A scene's optional ``[needs]`` table::

    [needs]
    answer = "verdicts"     # verdicts | theta_max | histories | hysteresis
    tolerance = 0.01        # largest numerical error of theta_max accepted, in alpha
    model = "either"        # rigid (the rigid body) | sdof (the paper's SDOF model) | either

With ``[solver] name = "auto"`` the campaign runs the cheapest solver (most record-seconds per
CPU-second) of the model asked whose measured numerical error meets the tolerance; the hysteresis of
the model exists only in the SDOF model; a block with friction or a floor that moves vertically needs
the rigid block with friction (solver ``friction``); a scene that turns a block in plan or gives a second
horizontal component needs three dimensions: the box of solver ``rigid3d``, the only solver in plan (its
verdicts checked against the planar solvers and Siconos, docs/guide/three-dimensions.md; the evidence table has no
row of it yet, so ``tolerance`` is not checked against a measured error). The evidence is shipped with opsrock
(``opsrock/data/evidence/solvers.csv``, derived from the validation cases' and benchmarks' outputs by
``tools/evidence.py``), and the choice with the evidence row goes into the campaign's manifest. With a
named solver, ``[needs]`` is checked against it. A need that no solver meets is refused before anything
runs, with the reason.
"""

from __future__ import annotations

import csv
import functools
import math
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from opsrock.errors import InputError
from opsrock.solvers.registry import FRICTION_MODEL, METHODS, RIGID_MODEL, SDOF_MODEL, plan_solver, screen_solver

#: What a scene may ask for.
ANSWERS: tuple[str, ...] = ("verdicts", "theta_max", "histories", "hysteresis")
#: The answers that need the solver's time histories (its registry entry's ``histories``).
HISTORY_ANSWERS: tuple[str, ...] = ("histories", "hysteresis")
#: The models an answer may come from.
NEEDED_MODELS: tuple[str, ...] = (RIGID_MODEL, SDOF_MODEL, "either")
#: The evidence table shipped in the package.
EVIDENCE_FILE: str = "evidence/solvers.csv"


@dataclass(frozen=True)
class Needs:
    """What a scene asks for.

    Parameters
    ----------
    answer : str
        One of :data:`ANSWERS`.
    tolerance : float
        Largest numerical error of theta_max accepted (alpha, dimensionless), > 0.
    model : str
        One of :data:`NEEDED_MODELS`.
    """

    answer: str = "verdicts"
    tolerance: float = 0.01
    model: str = "either"

    def __post_init__(self) -> None:
        if self.answer not in ANSWERS:
            raise InputError(f"needs.answer must be one of {', '.join(ANSWERS)}, got {self.answer!r}")
        if self.model not in NEEDED_MODELS:
            raise InputError(f"needs.model must be one of {', '.join(NEEDED_MODELS)}, got {self.model!r}")
        t = self.tolerance
        if isinstance(t, bool) or not isinstance(t, (int, float)) or not (math.isfinite(t) and t > 0):
            raise InputError(f"needs.tolerance must be a positive number (alpha), got {t!r}")


#: Cases from which the SDOF model's verdicts are asked for at scale: the scene is screened by the rigid
#: body and only the cases whose verdict can differ go to the SDOF model (:mod:`opsrock.campaign.multifidelity`).
MULTIFIDELITY_MIN_CASES: int = 500


@dataclass(frozen=True)
class Choice:
    """The solver chosen for a need, and why; ``strategy`` ``"multifidelity"``: screen with ``screen`` and
    run ``solver`` only where the answer can differ (:class:`opsrock.campaign.multifidelity.MultiFidelity`, which
    :func:`opsrock.campaign.workflow.run_campaign` runs for it)."""

    solver: str
    reason: str
    evidence: dict[str, Any] = field(default_factory=dict)
    strategy: str = "single"
    screen: str = ""

    def manifest(self) -> dict[str, Any]:
        """As JSON data for the manifest."""
        return {"solver": self.solver, "reason": self.reason, "evidence": dict(self.evidence),
                "strategy": self.strategy, "screen": self.screen}


def _evidence_path() -> Path:
    return Path(str(resources.files("opsrock.data"))) / EVIDENCE_FILE


@functools.lru_cache(maxsize=1)
def evidence() -> tuple[dict[str, Any], ...]:
    """The shipped evidence rows (numbers as floats)."""
    with open(_evidence_path(), newline="") as fh:
        rows = list(csv.DictReader(fh))
    for r in rows:
        for k in ("numerical_error_alpha", "record_seconds_per_cpu_second", "model_form_p95_alpha",
                  "model_form_verdict_agreement"):
            r[k] = float(r[k])
    return tuple(rows)


def _candidates(needs: Needs, friction: bool) -> list[dict]:
    """The evidence rows of the solvers whose model may answer ``needs``."""
    if friction:
        if needs.model == SDOF_MODEL:
            raise InputError(f"needs.model = {SDOF_MODEL!r}: the paper's SDOF model has no friction and no vertical "
                             "motion, and the scene's blocks slide or its floor moves vertically; use model "
                             f"{RIGID_MODEL!r} or 'either'")
        models = {FRICTION_MODEL}
    else:
        models = {RIGID_MODEL, SDOF_MODEL} if needs.model == "either" else {needs.model}
    if needs.answer == "hysteresis":
        if SDOF_MODEL not in models:
            raise InputError(f"needs.answer = 'hysteresis' exists only in the paper's SDOF model (spring and damper), "
                             f"not in model {needs.model!r}" + (" with friction" if friction else ""))
        models = {SDOF_MODEL}
    return [r for r in evidence() if r["model"] in models]


def _plan_choice(needs: Needs) -> Choice:
    """The solver in plan (:func:`opsrock.solvers.registry.plan_solver`) for a scene in three dimensions, or
    :class:`InputError` if ``needs`` asks what it has not."""
    solver = plan_solver()
    if needs.model == SDOF_MODEL or needs.answer == "hysteresis":
        raise InputError(f"needs.model = {needs.model!r}, answer {needs.answer!r}: the scene turns a block in plan or "
                         f"gives a second horizontal component, and only the rigid box of solver {solver!r} moves in "
                         f"plan (no SDOF model, no hysteresis); use model {RIGID_MODEL!r} or 'either'")
    return Choice(solver, f"{solver}: the scene needs three dimensions (a block turned in plan or a second "
                               "horizontal component) and it is the only solver in plan; no measured error of it in "
                               "the evidence table yet")


def choose(needs: Needs, *, friction: bool = False, n_cases: int = 0, plan: bool = False) -> Choice:
    """The cheapest solver meeting ``needs`` (``friction``: the scene's blocks slide or its floor moves
    vertically; ``plan``: the scene needs three dimensions, :func:`opsrock.solvers.registry.plan_solver`); the SDOF model's verdicts for
    :data:`MULTIFIDELITY_MIN_CASES` cases or more (``n_cases``) are asked of a multi-fidelity campaign.

    Raises
    ------
    InputError
        If no solver meets the need, naming the closest one and its measured error.
    """
    if plan:
        return _plan_choice(needs)
    rows = _candidates(needs, friction)
    ok = [r for r in rows if r["numerical_error_alpha"] <= needs.tolerance]
    if not ok:
        best = min(rows, key=lambda r: r["numerical_error_alpha"])
        raise InputError(f"needs.tolerance = {needs.tolerance!r} alpha: no solver of model {needs.model!r} meets it; "
                         f"the most accurate, {best['solver']}, has a measured error of "
                         f"{best['numerical_error_alpha']:.3g} alpha ({best['source']})")
    pick = max(ok, key=lambda r: r["record_seconds_per_cpu_second"])
    reason = (f"{pick['solver']}: model {pick['model']}, measured error {pick['numerical_error_alpha']:.3g} alpha <= "
              f"{needs.tolerance:g}, {pick['record_seconds_per_cpu_second']:.4g} record-seconds per CPU-second, the "
              f"cheapest of {', '.join(r['solver'] for r in ok)}")
    if pick["model"] == SDOF_MODEL and needs.answer == "verdicts" and n_cases >= MULTIFIDELITY_MIN_CASES:
        screen = screen_solver()
        return Choice(pick["solver"], reason + f"; {n_cases} cases: screened by {screen}, {pick['solver']} "
                      "where the verdict can differ (multi-fidelity)", pick, "multifidelity", screen)
    return Choice(pick["solver"], reason, pick)


def check(solver: str, needs: Needs, *, friction: bool = False, plan: bool = False) -> Choice:
    """A named ``solver`` against ``needs`` (``plan``: the scene needs three dimensions): its evidence row, or
    :class:`InputError` saying why it cannot answer."""
    entry = METHODS.get(solver)
    if plan or (entry is not None and entry.plan):
        if entry is None or not entry.plan:
            raise InputError(f"solver {solver!r} is planar and the scene needs three dimensions (a block turned in "
                             f"plan or a second horizontal component): use {plan_solver()!r} or 'auto'")
        return _plan_choice(needs)
    rows = {r["solver"]: r for r in _candidates(needs, friction)}
    if solver not in rows:
        raise InputError(f"solver {solver!r} cannot answer the scene's needs (answer {needs.answer!r}, model "
                         f"{needs.model!r}); candidates: {', '.join(rows) or 'none'}")
    r = rows[solver]
    if r["numerical_error_alpha"] > needs.tolerance:
        raise InputError(f"solver {solver!r} has a measured error of {r['numerical_error_alpha']:.3g} alpha, above "
                         f"needs.tolerance = {needs.tolerance!r} ({r['source']})")
    return Choice(solver, f"{solver}: named by the scene; measured error {r['numerical_error_alpha']:.3g} alpha <= "
                          f"{needs.tolerance:g}", r)


__all__ = ["ANSWERS", "Choice", "EVIDENCE_FILE", "HISTORY_ANSWERS", "MULTIFIDELITY_MIN_CASES", "NEEDED_MODELS", "Needs", "check",
           "choose",
           "evidence"]
