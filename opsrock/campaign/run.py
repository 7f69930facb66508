"""Campaigns: run every case of a scene, store each result as it finishes, resume after a stop.

:func:`run_campaign` is the whole workflow:

1. the scene is validated (:func:`opsrock.campaign.scene.load_scene`) before anything is written;
2. the output folder's store (:mod:`opsrock.campaign.store`) is opened and locked; its manifest must
   match the scene's digest (blocks, grid, solver, settings), or the run is refused unless
   ``force=True``, which clears the old results: results of different settings never mix;
3. cases already stored are reused; the others are sent in batches to an executor
   (:mod:`opsrock.campaign.executors`) and every batch's results are committed as soon as it returns;
4. ``cases.csv`` is assembled from the store, in the scene's case order, and written
   atomically (temporary file + ``os.replace``), with ``manifest.json`` beside it.

So an interrupted run (Ctrl-C, ``kill -9``, a dead worker, a power cut) loses at most the
batches being computed, and re-running the same command computes only the missing cases and
ends with the same ``cases.csv`` as an uninterrupted run, column for column, except
``wall_time_s``, which is measured (see :data:`IDENTITY_EXCLUDED`).

A case whose solver raises, or returns ``status="failed"``, is stored as failed with its
reason; so is a case whose worker process dies while it runs alone. Failed cases are never
given a verdict other than ``"failed"``, and are not retried by a resume (they are results);
use ``force=True`` to recompute everything.

Command line (wired into ``opsrock run`` by :mod:`opsrock.cli`, also ``python -m
opsrock.campaign``)::

    opsrock run SCENE.toml --out DIR [--solver NAME] [--workers N]
                [--scheduler tcp://HOST:PORT | --dask-local N] [--force] [--no-progress]

:func:`run_command` returns the exit status: 0 done (failed cases are reported on stderr but
are results, not errors), 2 usage error (bad scene, refused settings change, folder in use,
Dask missing; a one-line message on stderr and nothing written), 130 interrupted.
"""

from __future__ import annotations

import csv
import functools
import json
import math
import os
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Mapping, Sequence

from opsrock._files import atomic_write
from opsrock.campaign.executors import (
    Executor,
    LocalPool,
    batch_size,
    make_batches,
)
from opsrock.campaign.scene import Case, Scene, SceneError, load_scene
from opsrock.campaign.store import STORE_FILE, ResultStore
from opsrock.campaign.timeout import DEFAULT_CASE_TIMEOUT, CaseTimeout, time_limit
from opsrock.errors import CampaignConflictError, InputError, InputTypeError
from opsrock.result import RockingResult
from opsrock.solvers import SOLVERS, check_settings, get_solver, simulate

#: Name of the assembled table in the output folder.
CASES_FILE: str = "cases.csv"

#: Name of the human-readable copy of the run manifest.
MANIFEST_FILE: str = "manifest.json"

#: Columns of ``cases.csv``, in order. Inputs (block, pulse, intensity measures) come from the
#: scene; the rest from the store. Units: m, rad, m/s², rad/s, s, m/s; ratios dimensionless.
CASES_COLUMNS: tuple[str, ...] = (
    "case_id",
    "block", "width", "height", "alpha", "R", "p", "e", "e_R",
    "pfa", "omega_p", "T_p", "pfv", "freq_ratio", "pfa_ratio",
    "IM1", "IM2", "IM3", "IM4", "IM5", "IM6", "IM7", "IM8", "IM9",
    "theta_max", "theta_max_over_alpha", "overturned", "rocked",
    "status", "reason", "verdict", "solver", "wall_time_s",
)  # fmt: skip

#: Columns that differ between two runs of the same campaign: measured, not computed. Two
#: ``cases.csv`` of the same scene and settings agree in every other column, whatever the
#: executor, the worker count and the interruptions.
IDENTITY_EXCLUDED: tuple[str, ...] = ("wall_time_s",)

#: Longest failure reason kept (characters); a reason is also folded onto one line.
MAX_REASON: int = 500

#: One solve at a time per process: OpenSeesPy keeps one global model per interpreter, and a
#: Dask worker may run several threads.
_SOLVE_LOCK = threading.Lock()


@dataclass(frozen=True)
class CampaignSummary:
    """What a campaign did.

    Parameters
    ----------
    n_cases : int
        Cases in the scene.
    n_computed : int
        Cases solved by this run.
    n_reused : int
        Cases found in the store from an earlier (interrupted) run.
    n_failed : int
        Cases of the final table with ``status == "failed"`` (computed now or earlier).
    wall_time_s : float
        Wall-clock time of this run (s).
    out_dir : str
        Output folder.
    store_path : str
        The SQLite store.
    cases_csv : str
        The assembled table.
    manifest_path : str
        JSON copy of the run manifest.
    digest : str
        Digest of what determines the results (scene, solver, settings).
    solver : str
        Solver that ran.
    """

    n_cases: int
    n_computed: int
    n_reused: int
    n_failed: int
    wall_time_s: float
    out_dir: str
    store_path: str
    cases_csv: str
    manifest_path: str
    digest: str
    solver: str


# --- work done in the workers -------------------------------------------------------------------
def _one_line(text: str) -> str:
    text = " ".join(str(text).split())
    return text if len(text) <= MAX_REASON else text[: MAX_REASON - 3] + "..."


def failed_row(case_id: str, solver: str, reason: str, wall_time_s: float = math.nan) -> dict[str, Any]:
    """A store row for a case that produced no result (status ``"failed"``, verdict ``"failed"``)."""
    return {
        "case_id": case_id,
        "status": "failed",
        "reason": _one_line(reason) or "failed without a reason",
        "verdict": "failed",
        "theta_max": math.nan,
        "theta_max_over_alpha": math.nan,
        "overturned": False,
        "rocked": False,
        "solver": solver,
        "wall_time_s": wall_time_s,
        "n_steps": None,
        "n_impacts": None,
    }


def result_row(case_id: str, result: RockingResult, wall_time_s: float) -> dict[str, Any]:
    """A store row from a solver's result."""
    s = result.summary()
    return {
        "case_id": case_id,
        "status": s["status"],
        "reason": _one_line(s["reason"]),
        "verdict": s["verdict"],
        "theta_max": s["theta_max"],
        "theta_max_over_alpha": s["theta_max_over_alpha"],
        "overturned": s["overturned"],
        "rocked": s["rocked"],
        "solver": s["solver"],
        "wall_time_s": wall_time_s,
        "n_steps": s["n_steps"],
        "n_impacts": s["n_impacts"],
    }


def solve_batch(
    cases: Sequence[Case],
    *,
    solver: str,
    settings: Mapping[str, Any],
    solve_fn: Callable[..., RockingResult] | None = None,
    case_timeout: float | None = DEFAULT_CASE_TIMEOUT,
) -> list[dict[str, Any]]:
    """Solve cases one after the other; never raises for a bad case.

    Parameters
    ----------
    cases : sequence of Case
    solver : str
        Solver name passed to ``solve_fn``.
    settings : dict
        Keyword settings of the solver (as the scene gives them, checked by
        :func:`opsrock.solvers.check_settings`).
    solve_fn : callable, optional
        ``solve_fn(block, excitation, solver=..., **settings) -> RockingResult``. Default
        :func:`opsrock.solvers.simulate`. Must be picklable (a module-level function).
    case_timeout : float or None
        Wall-clock budget of each case (s); a case past it is a failed row whose reason
        starts with ``"timeout"`` (:func:`opsrock.campaign.timeout.time_limit`). None: no budget.

    Returns
    -------
    list of dict
        One store row per case: the result's scalars, or a failed row whose reason is the
        exception (type and message) if the solve raised or returned something else.
    """
    fn = simulate if solve_fn is None else solve_fn
    if solve_fn is None and solver in SOLVERS:
        get_solver(solver)  # import the solver module (and compile it, in a fresh clone) outside the budget
    rows = []
    with _SOLVE_LOCK:
        for case in cases:
            t0 = time.perf_counter()
            if getattr(case, "problem", ""):
                rows.append(failed_row(case.case_id, solver, case.problem, 0.0))
                continue
            try:
                with time_limit(case_timeout):
                    result = fn(case.block, case.excitation, solver=solver, **settings)
                if not isinstance(result, RockingResult):
                    raise InputTypeError(f"solver returned {type(result).__name__}, not a RockingResult")
                rows.append(result_row(case.case_id, result, time.perf_counter() - t0))
            except CaseTimeout as exc:
                reason = str(exc) or f"timeout: no answer within the case budget of {case_timeout:g} s"
                rows.append(failed_row(case.case_id, solver, reason, time.perf_counter() - t0))
            except Exception as exc:  # noqa: BLE001  (a bad case must not stop the campaign)
                rows.append(failed_row(case.case_id, solver, f"{type(exc).__name__}: {exc}", time.perf_counter() - t0))
    return rows


def _lost_row(case: Case, reason: str, *, solver: str) -> dict[str, Any]:
    return failed_row(case.case_id, solver, reason)


def _columns(scene: Scene) -> tuple[str, ...]:
    if scene.records is None:
        return CASES_COLUMNS
    from opsrock.campaign.records import RECORD_CASES_COLUMNS

    return RECORD_CASES_COLUMNS


#: Floor motions of a record scene, cached in its output folder (computed once, reused on resume).
MOTIONS_FILE: str = "floor_motions.pickle"


def _floor_motions(scene: Scene, out: Path, digest: str, executor: Executor, progress: bool) -> dict:
    """The scene's floor motions and their measures: from the folder's cache when it was written for
    this digest, else computed by ``executor`` (one item per record and building) and cached."""
    import pickle

    from opsrock.campaign.records import assemble_motions, compute_motions, motion_items

    spec = scene.records
    items = motion_items(spec)
    cache = out / MOTIONS_FILE
    try:
        with open(cache, "rb") as fh:
            saved = pickle.load(fh)
        if saved.get("digest") == digest and len(saved["results"]) == len(items):
            return assemble_motions(spec, items, saved["results"])
    except (OSError, EOFError, pickle.UnpicklingError, AttributeError, KeyError, TypeError):
        pass
    results: list[Any] = [None] * len(items)
    size = max(1, math.ceil(len(items) / (4 * executor.workers)))
    batches = make_batches(items, size)
    bar = _progress_bar(len(items), scene, 0, progress)
    bar.set_description(f"{scene.name}: floor motions")
    with bar:
        for k, res in executor.map_batches(compute_motions, batches, _lost_motion):
            results[k * size : k * size + len(res)] = res
            bar.update(len(res))
    atomic_write(cache, lambda fh: pickle.dump({"digest": digest, "results": results}, fh), binary=True)
    return assemble_motions(spec, items, results)


def _lost_motion(item: Any, reason: str) -> str:
    return reason


# --- the campaign ------------------------------------------------------------------------------
def _manifest(scene: Scene, digest: str, solve_fn: Callable | None) -> dict[str, Any]:
    from opsrock import __version__

    return {
        "digest": digest,
        "scene_name": scene.name,
        "scene_path": scene.path,
        "blocks_path": scene.blocks_path,
        "solver": scene.solver,
        "solver_settings": dict(scene.solver_settings),
        "solve_fn": None if solve_fn is None else _callable_name(solve_fn),
        "pfv_convention": scene.pfv_convention,
        "n_cases": scene.n_cases,
        "opsrock_version": __version__,
    }


def _callable_name(fn: Callable) -> str:
    if isinstance(fn, functools.partial):
        return f"partial({_callable_name(fn.func)}, {fn.args!r}, {sorted(fn.keywords.items())!r})"
    # A callable instance is named by its class: its repr may hold a memory address.
    name = getattr(fn, "__qualname__", None) or type(fn).__qualname__
    return f"{getattr(fn, '__module__', '?')}.{name}"


def _conflict_message(out_dir: Path, old: Mapping[str, Any], new: Mapping[str, Any]) -> str:
    diffs = [
        f"{k}: stored {old.get(k)!r}, now {new.get(k)!r}"
        for k in ("solver", "solver_settings", "solve_fn", "pfv_convention", "n_cases", "scene_path")
        if old.get(k) != new.get(k)
    ]
    detail = "; ".join(diffs) if diffs else "the blocks or the grid differ"
    return (
        f"{out_dir} holds results of other settings ({detail}); refusing to mix them. "
        "Use another --out folder, or --force to delete the old results and start over."
    )





def _format(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "True" if value else "False"
    if isinstance(value, float):
        return repr(value)  # shortest repr that round-trips: exact, and identical run to run
    return str(value)


def case_table(scene: Scene, rows: Mapping[str, Mapping[str, Any]], cases: Sequence | None = None) -> list[dict[str, Any]]:
    """The rows of ``cases.csv``: scene inputs and intensity measures joined to stored results.

    Parameters
    ----------
    scene : Scene
    rows : dict
        Stored rows keyed by ``case_id`` (:meth:`opsrock.campaign.store.ResultStore.rows`); every case
        of the scene must be there.

    Returns
    -------
    list of dict
        One dict per case, keys :data:`CASES_COLUMNS`, in the scene's case order.
    """
    from opsrock.intensity import (
        intensity_measures,  # lazily: written alongside this module
    )

    cases = scene.cases() if cases is None else cases
    if scene.records is not None:
        return _record_case_table(cases, rows)
    table = []
    for case in cases:
        if case.case_id not in rows:
            raise KeyError(f"case {case.case_id!r} has no stored result")
        b, pulse, stored = case.block, case.pulse, rows[case.case_id]
        ims = intensity_measures(b, pulse, pfv_convention=scene.pfv_convention)
        rec = {
            "case_id": case.case_id,
            "block": b.name,
            "width": b.width,
            "height": b.height,
            "alpha": b.alpha,
            "R": b.R,
            "p": b.p,
            "e": b.e,
            "e_R": b.e_R,
            "pfa": pulse.pfa,
            "omega_p": pulse.omega_p,
            "T_p": pulse.T_p,
            "pfv": pulse.pfv(scene.pfv_convention),
            "freq_ratio": case.freq_ratio,
            "pfa_ratio": case.pfa_ratio,
            **{f"IM{k}": ims[f"IM{k}"] for k in range(1, 10)},
        }
        for col in CASES_COLUMNS[len(rec) :]:
            rec[col] = stored[col]
        table.append(rec)
    return table


def _record_case_table(cases: Sequence, rows: Mapping[str, Mapping[str, Any]]) -> list[dict[str, Any]]:
    from opsrock.campaign.records import RECORD_CASES_COLUMNS, record_case_row

    table = []
    for case in cases:
        if case.case_id not in rows:
            raise KeyError(f"case {case.case_id!r} has no stored result")
        rec = record_case_row(case)
        for col in RECORD_CASES_COLUMNS[len(rec):]:
            rec[col] = rows[case.case_id][col]
        table.append(rec)
    return table


def write_cases_csv(path: str | Path, table: Sequence[Mapping[str, Any]],
                    columns: Sequence[str] = CASES_COLUMNS) -> None:
    """Write a case table atomically (temporary file, fsync, ``os.replace``), columns ``columns``."""

    def write(fh):
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(columns)
        for rec in table:
            w.writerow([_format(rec[c]) for c in columns])

    atomic_write(Path(path), write)


def _progress_bar(total: int, scene: Scene, reused: int, progress: bool):
    from tqdm import tqdm

    return tqdm(
        total=total,
        desc=f"{scene.name} ({reused} reused)" if reused else scene.name,
        unit="case",
        file=sys.stderr,
        disable=not (progress and sys.stderr.isatty()),
        dynamic_ncols=True,
    )


def run_campaign(
    scene: Scene | str | os.PathLike,
    out_dir: str | os.PathLike,
    *,
    solver: str | None = None,
    workers: int | None = None,
    executor: Executor | None = None,
    force: bool = False,
    progress: bool = True,
    solve_fn: Callable[..., RockingResult] | None = None,
    batch: int | None = None,
    case_timeout: float | None = None,
) -> CampaignSummary:
    """Run (or resume) every case of a scene into ``out_dir``.

    Parameters
    ----------
    scene : Scene or path
        The scene, or its TOML file (validated first: :class:`~opsrock.campaign.scene.SceneError`
        before anything is written).
    out_dir : str or Path
        Output folder: ``results.sqlite`` (the store), ``cases.csv``, ``manifest.json``.
    solver : str, optional
        Run with this solver instead of the scene's; the scene's settings are dropped if they
        belong to another solver (:meth:`Scene.with_solver`).
    workers : int, optional
        Worker processes of the default :class:`~opsrock.campaign.executors.LocalPool` (default: all
        available cores). Ignored when ``executor`` is given.
    executor : Executor, optional
        Where to run (:class:`~opsrock.campaign.executors.LocalPool`,
        :class:`~opsrock.campaign.executors.DaskExecutor`); the caller closes it.
    force : bool, optional
        Delete the folder's stored results first, even if they were computed with other
        settings. Default False: resume, and refuse a folder of other settings.
    progress : bool, optional
        Show a progress bar on stderr (only when stderr is a terminal). Default True.
    solve_fn : callable, optional
        Replace :func:`opsrock.solvers.simulate` (tests, custom solvers):
        ``solve_fn(block, excitation, solver=..., **settings) -> RockingResult``, picklable.
        Its name enters the manifest, so its results never mix with a real solver's.
    batch : int, optional
        Cases per batch. Default :func:`opsrock.campaign.executors.batch_size`.
    case_timeout : float, optional
        Wall-clock budget of one case (s). Default: the scene's ``[solver] case_timeout``, else
        :data:`opsrock.campaign.timeout.DEFAULT_CASE_TIMEOUT`. A case past it is stored failed with a
        reason starting ``"timeout"`` and the campaign goes on; the local executor also kills a
        worker stuck in native code (:class:`opsrock.campaign.executors.LocalPool`).

    Returns
    -------
    CampaignSummary

    Raises
    ------
    SceneError
        Invalid scene or solver settings (nothing written).
    CampaignConflictError
        ``out_dir`` holds results of other settings and ``force`` is False.
    StoreError
        Another run holds ``out_dir``.
    """
    t_start = time.perf_counter()
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    if solver is not None:
        scene = scene.with_solver(solver)
    settings = dict(scene.solver_settings)
    try:
        check_settings(scene.solver, settings)
    except (ImportError, KeyError, TypeError, ValueError) as exc:  # a Scene built in code
        raise SceneError(scene.path or "<scene>", "solver.settings", dict(scene.solver_settings), str(exc)) from None
    digest = scene.digest()
    if solve_fn is not None:
        import hashlib

        digest = hashlib.sha256(f"{digest}|{_callable_name(solve_fn)}".encode()).hexdigest()
    if case_timeout is None:
        case_timeout = scene.case_timeout if scene.case_timeout is not None else DEFAULT_CASE_TIMEOUT
    if isinstance(case_timeout, bool) or not isinstance(case_timeout, (int, float)) or not case_timeout > 0:
        raise InputError(f"case_timeout must be a positive number of seconds, got {case_timeout!r}")
    manifest = _manifest(scene, digest, solve_fn)
    cases = scene.cases() if scene.records is None else None
    out = Path(out_dir)
    own_executor = executor is None

    with ResultStore(out / STORE_FILE) as store:
        old = store.manifest()
        if old and old.get("digest") != digest and not force:
            raise CampaignConflictError(_conflict_message(out, old, manifest))
        if force or not old:
            store.clear()
            (out / CASES_FILE).unlink(missing_ok=True)
            store.write_manifest(manifest)
        atomic_write(out / MANIFEST_FILE, lambda fh: json.dump(manifest, fh, indent=2, sort_keys=True))

        if own_executor:
            executor = LocalPool(workers, item_timeout=case_timeout)
        try:
            if cases is None:
                cases = scene.cases(_floor_motions(scene, out, digest, executor, progress))
            done = store.done_ids()
            todo = [c for c in cases if c.case_id not in done]
            n_reused = len(cases) - len(todo)
            n_computed = 0
            if todo:
                size = batch or batch_size(len(todo), executor.workers)
                batches = make_batches(todo, size)
                fn = functools.partial(solve_batch, solver=scene.solver, settings=settings, solve_fn=solve_fn,
                                       case_timeout=case_timeout)
                lost = functools.partial(_lost_row, solver=scene.solver)
                with _progress_bar(len(todo), scene, n_reused, progress) as bar:
                    for _, rows in executor.map_batches(fn, batches, lost):
                        store.append(rows)
                        n_computed += len(rows)
                        bar.update(len(rows))
        finally:
            if own_executor:
                executor.close()

        table = case_table(scene, store.rows(), cases)
        write_cases_csv(out / CASES_FILE, table, _columns(scene))
    return CampaignSummary(
        n_cases=len(cases),
        n_computed=n_computed,
        n_reused=n_reused,
        n_failed=sum(r["status"] == "failed" for r in table),
        wall_time_s=time.perf_counter() - t_start,
        out_dir=str(out),
        store_path=str(out / STORE_FILE),
        cases_csv=str(out / CASES_FILE),
        manifest_path=str(out / MANIFEST_FILE),
        digest=digest,
        solver=scene.solver,
    )
