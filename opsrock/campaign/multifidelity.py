"""Multi-fidelity campaigns: the rigid body screens every case, the paper's SDOF model runs only where
its verdict can differ from the screen's, plus a seeded random audit of the rest.

:class:`MultiFidelity` is the workflow, a policy over the one campaign engine
(:class:`opsrock.campaign.run.Stage`): :func:`~opsrock.campaign.workflow.run_campaign` runs it when the scene's
``[needs]`` chose it (or when given as ``policy=``), resumable in the same way:

1. **Screen.** The whole scene is a stage of the screen solver (default ``housner_fast``, the rigid
   body) in ``out_dir/screen``.
2. **Escalation.** Each screened case is kept or sent to the expensive solver (default ``opensees``)
   by an :class:`EscalationRule` (:func:`escalation_reason`):

   * ``screen_failed``: the screen has no verdict;
   * ``overturned``: the screen overturned it. Once the rigid body overturns, its ``theta_max`` is the
     limit ``pi/2``, whatever the margin by which it went over: the screen cannot place the case
     against the boundary, and the validation cases show the SDOF model safe in 17-21 % of them
     (:data:`EVIDENCE`), far above what a margin at the 95th percentile leaves;
   * ``near_overturning``: safe with ``theta_max / alpha >= 1 - margin``: within the model-form
     error of the boundary, the SDOF model may overturn;
   * ``near_uplift``: safe with ``theta_max / alpha < uplift_q``, or ``no_uplift`` with the floor at or
     above the uplift threshold (``pfa_ratio >= 1``). Both models lift the block at
     ``PFA = g tan alpha`` (Eq. 4, the default ``housner`` lever), but the SDOF model calls a block
     rocked only past ``ROCKED_THETA_E_MULTIPLE theta_e`` (``1e-5 alpha`` by default); a rigid body
     lifted by less reads ``no_uplift`` there. ``uplift_q`` is ten times that threshold.

   The margin is a percentile (default the 95th) of the measured model-form error
   ``|theta_max(SDOF) - theta_max(rigid)| / alpha`` on records (:data:`EVIDENCE`, validation case 9),
   unless given.
3. **Audit.** A seeded random ``audit_fraction`` of the kept cases also runs with the expensive solver;
   its agreement with the screen's verdict, with a Wilson interval, measures what the rule lets
   through.
4. The escalated and audited cases are solved in ``out_dir/escalated``, a stage of the same engine with
   the expensive solver on those case ids only (``only=``): same store, same manifest (digest) as a full
   campaign of it, so its rows are reused whatever the margin or the audit of a later run, and
   ``run_campaign`` could complete it; its ``cases.csv`` holds those cases.
5. ``out_dir/cases.csv``: one row per case, in the scene's order, with the columns of a normal campaign
   of the scene with the expensive solver, plus ``source`` (``screen``, ``escalated`` or ``audit``);
   the ``solver`` column names the solver that produced the row. ``out_dir/manifest.json`` holds the
   rule, its evidence, the audit and the counts.

An interrupted run loses at most the batches in flight (the screen's and the escalated store commit
every batch); the same call again resumes both.
"""

from __future__ import annotations

import csv
import dataclasses
import json
import math
import time
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from opsrock import __version__
from opsrock._files import atomic_write
from opsrock.campaign.cases import CASES_FILE, SOURCE_COLUMN, UNITS, case_table, write_cases_csv
from opsrock.campaign.run import Stage
from opsrock.campaign.scene import Scene
from opsrock.campaign.store import MANIFEST_FILE, read_rows
from opsrock.errors import InputError
from opsrock.solvers import check_settings
from opsrock.solvers.registry import METHODS, RIGID_MODEL, SDOF_MODEL, reference_sdof_solver, solver_names
from opsrock.solvers.registry import screen_solver as default_screen

#: Sub-folders of a multi-fidelity run: the screen's campaign and the expensive solver's partial one.
SCREEN_DIR: str = "screen"
ESCALATED_DIR: str = "escalated"

#: Values of the ``source`` column of ``cases.csv``.
SOURCES: tuple[str, ...] = ("screen", "escalated", "audit")

#: Why a case is escalated (:func:`escalation_reason`), in the order the rule tests them.
REASONS: tuple[str, ...] = ("screen_failed", "overturned", "near_overturning", "near_uplift")

#: Default share of the kept cases audited by the expensive solver.
DEFAULT_AUDIT_FRACTION: float = 0.02

#: Default percentile of the measured model-form error that sets the margin.
DEFAULT_PERCENTILE: int = 95

#: ``uplift_q`` is this multiple of the SDOF model's own rocking threshold
#: (``ROCKED_THETA_E_MULTIPLE * theta_e_ratio``, 1e-5 by default). On the 44 FEMA roof motions of
#: ``fema-far-field-ida-b3`` x its 4 blocks scaled to 0.9-1.1 g tan alpha, the rigid body and the OpenSees model
#: differed (safe / no_uplift) on 164 of the 176 cases at 1.005 g tan alpha, all with a rigid ``theta_max / alpha``
#: <= 8.4e-6, and on none at 0.9-0.995 or 1.02-1.1 (``studies/multifidelity/uplift_probe.csv``).
UPLIFT_SAFETY: float = 10.0


@dataclass(frozen=True)
class ModelFormEvidence:
    """Measured model-form error of an expensive solver against the rigid-body screen, as published by
    the validation cases of the repository and shipped as data (``opsrock/data/evidence/model_form.csv``,
    derived from the validation outputs by ``tools/evidence.py``).

    Parameters
    ----------
    solver : str
        The expensive solver the numbers are for.
    screen_solvers : tuple of str
        Screens the numbers hold for.
    abs_error : dict
        ``{percentile: |theta_max(solver) - theta_max(rigid)| / alpha}`` over the cases safe in both.
    n_safe_both : int
        Cases the percentiles are taken over.
    n_screen_overturned, n_overturned_to_safe : int
        Cases the rigid body overturned, and of them those the solver found safe.
    n_screen_safe, n_safe_to_overturned : int
        Cases the rigid body found safe, and of them those the solver overturned.
    min_q_safe_to_overturned : float
        Smallest rigid ``theta_max / alpha`` of those (NaN if none).
    source : str
        Where each number comes from.
    rows : dict
        ``{percentile: "file, row"}`` of each ``abs_error`` value.
    cross_check : str
        The same measurement elsewhere, not used by the rule.
    """

    solver: str
    screen_solvers: tuple[str, ...]
    abs_error: Mapping[int, float]
    n_safe_both: int
    n_screen_overturned: int
    n_overturned_to_safe: int
    n_screen_safe: int
    n_safe_to_overturned: int
    min_q_safe_to_overturned: float
    source: str
    rows: Mapping[int, str] = field(default_factory=dict)
    cross_check: str = ""

    @property
    def overturned_flip_rate(self) -> float:
        """Share of the rigid body's overturned cases the solver found safe."""
        return self.n_overturned_to_safe / self.n_screen_overturned if self.n_screen_overturned else math.nan


def _load_evidence() -> dict[str, ModelFormEvidence]:
    """The measured model-form error by expensive solver, from the table shipped in the package
    (``opsrock/data/evidence/model_form.csv``, written by ``tools/evidence.py`` from the validation cases'
    outputs; a test keeps the two equal)."""
    from importlib import resources

    path = Path(str(resources.files("opsrock.data"))) / "evidence" / "model_form.csv"
    out = {}
    with open(path, newline="") as fh:
        table = list(csv.DictReader(fh))
    for r in table:
        pct = {p: float(r[f"p{p}"]) for p in (50, 90, 95) if r[f"p{p}"] != "nan"}
        out[r["solver"]] = ModelFormEvidence(
            solver=r["solver"], screen_solvers=tuple(r["screen_solvers"].split()), abs_error=pct,
            n_safe_both=int(r["n_safe_both"]), n_screen_overturned=int(r["n_screen_overturned"]),
            n_overturned_to_safe=int(r["n_overturned_to_safe"]), n_screen_safe=int(r["n_screen_safe"]),
            n_safe_to_overturned=int(r["n_safe_to_overturned"]),
            min_q_safe_to_overturned=float(r["min_q_safe_to_overturned"]), source=r["source"],
            rows={p: r[f"row_p{p}"] for p in pct})
    return out


#: The measured model-form error by expensive solver (see :class:`ModelFormEvidence`), from the package's data.
EVIDENCE: dict[str, ModelFormEvidence] = _load_evidence()


@dataclass(frozen=True)
class EscalationRule:
    """Which screened cases go to the expensive solver (:func:`escalation_reason`).

    Parameters
    ----------
    margin : float
        A safe screen case with ``theta_max / alpha >= 1 - margin`` is escalated.
    escalate_overturned : bool
        Escalate every case the screen overturned.
    uplift_q : float
        A safe screen case with ``theta_max / alpha`` below it is escalated (0: none).
    margin_source : str
        Where the margin comes from.
    evidence : ModelFormEvidence or None
        The measurement the rule was derived from (None: none applies).
    """

    margin: float
    escalate_overturned: bool
    uplift_q: float
    margin_source: str
    evidence: ModelFormEvidence | None = None

    def __post_init__(self) -> None:
        if not (isinstance(self.margin, (int, float)) and 0.0 <= self.margin <= 1.0):
            raise InputError(f"margin must be a number in [0, 1] (of theta_max / alpha), got {self.margin!r}")
        if not (isinstance(self.uplift_q, (int, float)) and 0.0 <= self.uplift_q < 1.0):
            raise InputError(f"uplift_q must be a number in [0, 1), got {self.uplift_q!r}")


def escalation_reason(rule: EscalationRule, row: Mapping[str, Any]) -> str:
    """Why a screened case goes to the expensive solver (one of :data:`REASONS`), or ``""`` (kept).

    ``row`` is a row of the screen's ``cases.csv`` (or table): ``status``, ``verdict``,
    ``theta_max_over_alpha`` and ``pfa_ratio`` (``PFA / (g tan alpha)`` of the floor motion) are read.
    """
    verdict = str(row["verdict"])
    if str(row["status"]) != "ok" or verdict == "failed":
        return "screen_failed"
    if verdict == "overturned":
        return "overturned" if rule.escalate_overturned else ""
    q = float(row["theta_max_over_alpha"])
    if not math.isfinite(q):
        return "screen_failed"
    if verdict == "safe":
        if q >= 1.0 - rule.margin:
            return "near_overturning"
        return "near_uplift" if q < rule.uplift_q else ""
    pfa_ratio = float(row["pfa_ratio"])  # no_uplift
    return "near_uplift" if rule.uplift_q > 0.0 and not pfa_ratio < 1.0 else ""


def _sdof_model(solver: str, settings: Mapping[str, Any]):
    """The SDOF model the expensive solver runs (None for a solver of another model)."""
    if METHODS.get(solver).model != SDOF_MODEL:
        return None
    return check_settings(solver, dict(settings)).model


def derive_rule(solver: str, screen_solver: str, settings: Mapping[str, Any] | None = None, *,
                margin: float | None = None, percentile: int = DEFAULT_PERCENTILE,
                escalate_overturned: bool | None = None) -> EscalationRule:
    """The escalation rule for ``solver`` (with ``settings``) screened by ``screen_solver``.

    Parameters
    ----------
    solver, screen_solver : str
        The expensive solver and the screen (a solver of the rigid-body model).
    settings : dict, optional
        The expensive solver's settings: the evidence holds for its default model only.
    margin : float, optional
        Margin on ``theta_max / alpha``. Default: the ``percentile`` of :data:`EVIDENCE` for the pair.
    percentile : int
        Which measured percentile sets the margin (those :data:`EVIDENCE` holds: 50, 90, 95).
    escalate_overturned : bool, optional
        Default: when the evidence's share of rigid-overturned cases found safe exceeds
        ``1 - percentile / 100`` (and always when there is no evidence).

    Raises
    ------
    InputError
        A screen that is not a rigid-body solver; no margin and no evidence for the pair (or for the
        expensive solver's model when its settings change it); a percentile the evidence lacks.
    """
    for name in (solver, screen_solver):
        if METHODS.get(name) is None:
            raise InputError(f"unknown solver {name!r} (known: {', '.join(solver_names())})")
    if METHODS.get(screen_solver).model != RIGID_MODEL:
        raise InputError(f"screen_solver must solve the rigid body ({', '.join(solver_names(model=RIGID_MODEL))}), "
                         f"got {screen_solver!r}")
    model = _sdof_model(solver, settings or {})
    uplift_q = 0.0
    if model is not None:
        from opsrock.solvers.opensees.settings import ROCKED_THETA_E_MULTIPLE

        uplift_q = UPLIFT_SAFETY * ROCKED_THETA_E_MULTIPLE * model.theta_e_ratio
    ev = _evidence(solver, screen_solver, model, needed=margin is None)
    if margin is None and ev is not None:
        if percentile not in ev.abs_error:
            raise InputError(f"percentile must be one of {sorted(ev.abs_error)} (measured for {solver!r}), "
                             f"got {percentile!r}")
        margin = ev.abs_error[percentile]
        source = f"p{percentile} of |theta_max({solver}) - theta_max(rigid)| / alpha on records: {ev.rows[percentile]}"
    else:
        source = "given"
    if escalate_overturned is None:
        escalate_overturned = ev is None or not ev.overturned_flip_rate <= 1.0 - percentile / 100.0
    return EscalationRule(margin=float(margin), escalate_overturned=bool(escalate_overturned),
                          uplift_q=uplift_q, margin_source=source, evidence=ev)


def _evidence(solver: str, screen_solver: str, model, *, needed: bool) -> ModelFormEvidence | None:
    ev = EVIDENCE.get(solver)
    problem = ""
    if ev is None or screen_solver not in ev.screen_solvers:
        problem = f"no measured model-form error for {solver!r} screened by {screen_solver!r}"
    elif model is not None and model != type(model)():
        problem = f"the evidence is for the default SDOF model; the settings give {model}"
    if problem and needed:
        raise InputError(f"{problem}: give margin= (of theta_max / alpha)")
    return None if problem else ev


# --- selection ----------------------------------------------------------------------------------
@dataclass(frozen=True)
class Selection:
    """What the expensive solver runs: escalated cases with their reason, and the audit."""

    escalated: Mapping[str, str]
    audited: tuple[str, ...]
    n_cases: int

    @property
    def ids(self) -> set[str]:
        """Every case id the expensive solver runs."""
        return set(self.escalated) | set(self.audited)

    def source(self, case_id: str) -> str:
        """``escalated``, ``audit`` or ``screen``."""
        return "escalated" if case_id in self.escalated else "audit" if case_id in self.audited else "screen"


def select_cases(screen: Sequence[Mapping[str, Any]], rule: EscalationRule, *,
                 audit_fraction: float = DEFAULT_AUDIT_FRACTION, seed: int = 0) -> Selection:
    """Escalated cases (:func:`escalation_reason`) and a seeded random audit of the others.

    The audit draws ``ceil(audit_fraction * kept)`` of the kept cases without replacement from
    ``numpy.random.default_rng(seed)``, in the table's order: the same screen, fraction and seed give
    the same audit.
    """
    import numpy as np

    if not (isinstance(audit_fraction, (int, float)) and 0.0 <= audit_fraction <= 1.0):
        raise InputError(f"audit_fraction must be a number in [0, 1], got {audit_fraction!r}")
    escalated, kept = {}, []
    for row in screen:
        reason = escalation_reason(rule, row)
        if reason:
            escalated[str(row["case_id"])] = reason
        else:
            kept.append(str(row["case_id"]))
    n_audit = min(len(kept), math.ceil(audit_fraction * len(kept) - 1e-9))
    picks = np.random.default_rng(seed).choice(len(kept), size=n_audit, replace=False) if n_audit else []
    return Selection(escalated=escalated, audited=tuple(kept[k] for k in sorted(int(p) for p in picks)),
                     n_cases=len(screen))


# --- the summary --------------------------------------------------------------------------------
@dataclass(frozen=True)
class MultiFidelitySummary:
    """What a multi-fidelity campaign did.

    Parameters
    ----------
    n_cases : int
        Cases in the scene (all screened).
    n_screened : int
        Cases whose row in ``cases.csv`` is the screen's (not run by the expensive solver).
    n_escalated, n_audited : int
        Cases run by the expensive solver because of the rule, and as the audit.
    n_solves_saved : int
        Expensive solves a full campaign would have made and this one did not:
        ``n_cases - n_escalated - n_audited``.
    escalated_by_reason : dict
        ``{reason: count}`` (:data:`REASONS`).
    audited : tuple of str
        The audited case ids, in the scene's order.
    n_audit_compared, n_audit_agree : int
        Audited cases both solvers finished, and of them those with the same verdict.
    audit_agreement : float
        ``n_audit_agree / n_audit_compared`` (NaN without any).
    audit_interval : tuple of float
        95 % Wilson interval of the agreement.
    audit_disagreements : tuple of str
        Audited case ids whose verdicts differ.
    margin : float
        Margin on ``theta_max / alpha``.
    margin_source : str
        Where it comes from.
    rule : EscalationRule
    screen_solver, solver : str
    n_computed, n_reused : int
        Expensive solves made by this call, and found in the store.
    n_failed : int
        Rows of ``cases.csv`` with ``status == "failed"``.
    screen_wall_time_s, expensive_wall_time_s, wall_time_s : float
        Wall-clock time of the screen, of the expensive solves, of the whole call (s).
    out_dir, cases_csv, manifest_path, screen_dir, escalated_dir : str
        Output paths.
    warnings : tuple of str
        Where the no-slip model may not hold (the screen's, :func:`opsrock.campaign.advice.sliding_warnings`).
    choice : str
        Why the scene's ``[needs]`` chose this workflow; empty when the policy was given.
    """

    n_cases: int
    n_screened: int
    n_escalated: int
    n_audited: int
    n_solves_saved: int
    escalated_by_reason: Mapping[str, int]
    audited: tuple[str, ...]
    n_audit_compared: int
    n_audit_agree: int
    audit_agreement: float
    audit_interval: tuple[float, float]
    audit_disagreements: tuple[str, ...]
    margin: float
    margin_source: str
    rule: EscalationRule
    screen_solver: str
    solver: str
    n_computed: int
    n_reused: int
    n_failed: int
    screen_wall_time_s: float
    expensive_wall_time_s: float
    wall_time_s: float
    out_dir: str
    cases_csv: str
    manifest_path: str
    screen_dir: str
    escalated_dir: str
    warnings: tuple[str, ...] = field(default=())
    choice: str = ""

    def lines(self) -> list[str]:
        """The report a command line prints, one line each."""
        n_x = self.n_escalated + self.n_audited
        ratio = self.n_cases / n_x if n_x else math.inf
        reasons = ", ".join(f"{k} {v}" for k, v in self.escalated_by_reason.items() if v) or "none"
        lo, hi = self.audit_interval
        audit = (f"{self.n_audit_agree}/{self.n_audit_compared} same verdict ({100 * self.audit_agreement:.1f} %, "
                 f"95 % Wilson interval {100 * lo:.1f}-{100 * hi:.1f} %)" if self.n_audit_compared else "none compared")
        return [
            (f"{self.n_cases} cases screened with {self.screen_solver} in {self.screen_wall_time_s:.1f} s -> "
             f"{self.screen_dir}"),
            (f"escalated to {self.solver}: {self.n_escalated} ({reasons}); margin {self.margin:.4g} alpha "
             f"({self.margin_source})"),
            f"audit: {self.n_audited} of the {self.n_cases - self.n_escalated} kept cases; {audit}",
            (f"{self.solver} solves: {n_x} of {self.n_cases} ({self.n_computed} computed, {self.n_reused} reused) "
             f"in {self.expensive_wall_time_s:.1f} s; {self.n_solves_saved} saved ({ratio:.2f}x fewer)"),
            (f"{self.n_cases} cases ({self.n_screened} screen, {self.n_escalated} escalated, {self.n_audited} audit) "
             f"in {self.wall_time_s:.1f} s -> {self.cases_csv}"),
        ] + ([f"solver chosen for the scene's needs: {self.choice}"] if self.choice else [])


# --- the policy ----------------------------------------------------------------------------------
def _read_table(path: str | Path) -> list[dict[str, str]]:
    """The screen's ``cases.csv`` as text rows (its units row skipped)."""
    from opsrock._files import read_units

    units = read_units(path)[1]
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))[units is not None:]


def _audit(selection: Selection, screen_rows: Mapping, rows: Mapping) -> tuple[int, int, tuple[str, ...]]:
    """Audited cases both solvers finished, those with the same verdict, and the others' ids."""
    compared, differ = 0, []
    for cid in selection.audited:
        a, b = screen_rows[cid], rows[cid]
        if a["status"] != "ok" or b["status"] != "ok":
            continue
        compared += 1
        if a["verdict"] != b["verdict"]:
            differ.append(cid)
    return compared, compared - len(differ), tuple(differ)


def _write_table(out: Path, scene_x: Scene, cases: Sequence, selection: Selection, screen_rows: Mapping,
                 rows: Mapping) -> list[dict[str, Any]]:
    merged = {c.case_id: rows[c.case_id] if c.case_id in rows else screen_rows[c.case_id] for c in cases}
    table = case_table(cases, merged)
    audited = set(selection.audited)
    for rec in table:
        cid = rec["case_id"]
        rec[SOURCE_COLUMN] = "escalated" if cid in selection.escalated else "audit" if cid in audited else "screen"
    write_cases_csv(out / CASES_FILE, table, (*scene_x.columns, SOURCE_COLUMN),
                    (*scene_x.units, UNITS[SOURCE_COLUMN]))
    return table


@dataclass(frozen=True)
class MultiFidelity:
    """The multi-fidelity policy over the campaign engine (:func:`opsrock.campaign.workflow.run_campaign`).

    The screen runs as one stage on every case in ``out_dir/screen``; the escalated and audited cases run as
    a second stage of the same engine, the expensive solver on those case ids only, in ``out_dir/escalated``
    (a partial campaign of the scene: same store and manifest as a full one, so its rows are reused whatever
    the margin or the audit of a later run); then ``out_dir/cases.csv`` and ``out_dir/manifest.json``.

    Parameters
    ----------
    screen_solver, solver : str
        The screen (a rigid-body solver; default the registry's first compiled one) and the expensive solver
        (default the registry's SDOF model in OpenSees). A solver that is the scene's own keeps the scene's
        settings; another runs with its defaults (:meth:`Scene.with_solver`).
    margin : float or None
        Margin on ``theta_max / alpha`` (dimensionless); None: the ``percentile`` of :data:`EVIDENCE`
        (:func:`derive_rule`).
    percentile : int
        Which measured percentile sets the margin (%).
    escalate_overturned : bool or None
        Escalate every case the screen overturned (None: as the evidence says, :func:`derive_rule`).
    audit_fraction : float
        Share of the kept cases also run by ``solver`` (dimensionless, default 0.02), drawn with ``seed``.
    seed : int
        Seed of the audit.
    """

    screen_solver: str = field(default_factory=default_screen)
    solver: str = field(default_factory=reference_sdof_solver)
    margin: float | None = None
    percentile: int = DEFAULT_PERCENTILE
    escalate_overturned: bool | None = None
    audit_fraction: float = DEFAULT_AUDIT_FRACTION
    seed: int = 0

    @classmethod
    def from_choice(cls, choice) -> MultiFidelity:
        """The policy of a scene whose ``[needs]`` chose it (:class:`opsrock.campaign.needs.Choice`)."""
        return cls(screen_solver=choice.screen, solver=choice.solver)

    def _check(self, scene: Scene) -> EscalationRule:
        info = METHODS.get(self.solver)
        if info is None or info.friction or self.screen_solver == self.solver:
            raise InputError(f"solver must be a no-slip solver other than the screen ({self.screen_solver!r}), "
                             f"got {self.solver!r}")
        return derive_rule(self.solver, self.screen_solver, scene.with_solver(self.solver).solver_settings,
                           margin=self.margin, percentile=self.percentile,
                           escalate_overturned=self.escalate_overturned)

    def run(self, scene: Scene, out: Path, stage: Stage) -> MultiFidelitySummary:
        """Screen, select, solve the selection, merge (see the class); ``stage`` is the campaign engine
        (:class:`opsrock.campaign.run.Stage`), whose ``solve_fn`` serves the expensive solver only.

        Raises
        ------
        InputError
            An invalid solver pair or rule (nothing written).
        """
        t0 = time.perf_counter()
        choice = scene.choice.reason if scene.choice is not None else ""
        # the scene's [needs] chose this strategy; its two stages run named solvers
        scene = dataclasses.replace(scene, needs=None, choice=None)
        rule = self._check(scene)
        scene_x = scene.with_solver(self.solver)
        screen, cases = dataclasses.replace(stage, solve_fn=None)(scene.with_solver(self.screen_solver),
                                                                   out / SCREEN_DIR)
        selection = select_cases(_read_table(screen.cases_csv), rule, audit_fraction=self.audit_fraction,
                                 seed=self.seed)
        expensive, _ = stage(scene_x, out / ESCALATED_DIR, only=selection.ids, cases=cases)
        screen_rows = read_rows(out / SCREEN_DIR)
        rows = {k: v for k, v in read_rows(out / ESCALATED_DIR).items() if k in selection.ids}
        table = _write_table(out, scene_x, cases, selection, screen_rows, rows)
        audit = _audit(selection, screen_rows, rows)
        summary = _summary(selection, rule, (screen, expensive), table, audit, out,
                           (screen.wall_time_s, expensive.wall_time_s, time.perf_counter() - t0), choice)
        _write_manifest(summary, scene, scene_x, screen, rule, self)
        return summary


def _summary(selection: Selection, rule: EscalationRule, stages: tuple, table: list,
             audit: tuple[int, int, tuple[str, ...]], out: Path, times: tuple[float, float, float],
             choice: str) -> MultiFidelitySummary:
    """The summary of a run; ``stages`` are the screen's and the expensive solver's stage summaries."""
    from opsrock.stats import wilson_interval

    screen, expensive = stages
    compared, agree, differ = audit
    n_esc, n_aud = len(selection.escalated), len(selection.audited)
    by_reason = {r: sum(v == r for v in selection.escalated.values()) for r in REASONS}
    return MultiFidelitySummary(
        n_cases=selection.n_cases, n_screened=selection.n_cases - n_esc - n_aud, n_escalated=n_esc,
        n_audited=n_aud, n_solves_saved=selection.n_cases - n_esc - n_aud, escalated_by_reason=by_reason,
        audited=selection.audited,
        n_audit_compared=compared, n_audit_agree=agree, audit_agreement=agree / compared if compared else math.nan,
        audit_interval=wilson_interval(agree, compared), audit_disagreements=differ, margin=rule.margin,
        margin_source=rule.margin_source, rule=rule, screen_solver=screen.solver, solver=expensive.solver,
        n_computed=expensive.n_computed, n_reused=expensive.n_reused, n_failed=sum(r["status"] == "failed" for r in table),
        screen_wall_time_s=times[0], expensive_wall_time_s=times[1], wall_time_s=times[2], out_dir=str(out),
        cases_csv=str(out / CASES_FILE), manifest_path=str(out / MANIFEST_FILE), screen_dir=str(out / SCREEN_DIR),
        escalated_dir=str(out / ESCALATED_DIR), warnings=screen.warnings, choice=choice)


def _json_safe(value: Any) -> Any:
    """``value`` with every non-finite float as None (strict JSON)."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, Mapping):
        return {str(k): _json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(v) for v in value]
    return value


def _write_manifest(s: MultiFidelitySummary, scene: Scene, scene_x: Scene, screen, rule: EscalationRule,
                    policy: MultiFidelity) -> None:
    manifest = {
        "kind": "multifidelity", "scene_name": scene.name, "scene_path": scene.path, "n_cases": s.n_cases,
        "solver": s.solver, "solver_settings": dict(scene_x.solver_settings), "digest": scene_x.digest(),
        "screen_solver": s.screen_solver, "screen_digest": screen.digest,
        "rule": {**asdict(rule), "percentile": policy.percentile},
        "audit": {"fraction": policy.audit_fraction, "seed": policy.seed, "n": s.n_audited, "compared": s.n_audit_compared,
                  "agree": s.n_audit_agree, "agreement": s.audit_agreement, "wilson_95": s.audit_interval,
                  "disagreements": s.audit_disagreements, "cases": s.audited},
        "counts": {"cases": s.n_cases, "screen": s.n_screened, "escalated": s.n_escalated, "audited": s.n_audited,
                   "solves_saved": s.n_solves_saved, "by_reason": s.escalated_by_reason, "failed": s.n_failed},
        "opsrock_version": __version__,
    }
    text = json.dumps(_json_safe(manifest), indent=2, sort_keys=True, allow_nan=False)
    atomic_write(Path(s.manifest_path), lambda fh: fh.write(text))


__all__ = [
    "DEFAULT_AUDIT_FRACTION",
    "DEFAULT_PERCENTILE",
    "ESCALATED_DIR",
    "EVIDENCE",
    "REASONS",
    "SCREEN_DIR",
    "SOURCES",
    "EscalationRule",
    "ModelFormEvidence",
    "MultiFidelity",
    "MultiFidelitySummary",
    "Selection",
    "derive_rule",
    "escalation_reason",
    "select_cases",
]
