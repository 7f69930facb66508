"""The campaign engine: run every case of a scene, store each result as it finishes, resume after a stop.

:class:`Stage` is the engine, written once; :func:`opsrock.campaign.workflow.run_campaign` runs it, or a
policy over it that the scene's ``[needs]`` chose (the multi-fidelity campaign of
:mod:`opsrock.campaign.multifidelity` runs the screen as one stage on every case and the expensive
solver as another on the selected case ids). A stage:

1. the scene is validated (:func:`opsrock.campaign.scene.load_scene`) before anything is written;
2. the output folder's store (:mod:`opsrock.campaign.store`) is opened and locked; its manifest must
   match the scene's digest (blocks, design, solver, settings), or the run is refused unless
   ``force=True``, which clears the old results: results of different settings never mix;
3. a record scene's floor motions are computed by the executor, or read from the folder's cache
   (:mod:`opsrock.campaign.motions`);
4. cases already stored are reused; the others are sent in batches to an executor
   (:mod:`opsrock.campaign.executors`) and every batch's results are committed as soon as it returns;
5. ``cases.csv`` is assembled from the store, in the scene's case order (:mod:`opsrock.campaign.cases`),
   and written atomically (temporary file + ``os.replace``), with ``manifest.json`` beside it.

So an interrupted run (Ctrl-C, ``kill -9``, a dead worker, a power cut) loses at most the
batches being computed, and re-running the same command computes only the missing cases and
ends with the same ``cases.csv`` as an uninterrupted run, column for column, except
``wall_time_s`` and ``cpu_time_s``, which are measured (:data:`~opsrock.campaign.cases.IDENTITY_EXCLUDED`).

A case whose solver raises, runs past its budget, or returns ``status="failed"``, is stored as failed with
its reason: a result, never given a verdict other than ``"failed"``, and reused by a resume (use
``force=True`` to recompute everything). A case lost to the infrastructure (its worker process died while
it ran alone, its Dask worker was lost) is stored failed too, with a reason that starts with
:data:`~opsrock.campaign.executors.LOST_PREFIX`; it is not a result: a resume computes it again
(:meth:`~opsrock.campaign.store.ResultStore.done_ids`), and so does one of a store written before the
prefix (reason ``"worker process died ..."``). The summary counts them (``n_lost``).

A campaign never re-runs the user's script: started from a script without an ``if __name__ ==
"__main__":`` guard, or with several workers inside a worker process, it stops with
:class:`~opsrock.errors.UnguardedScriptError` naming the fix (:func:`opsrock._pool.pool_allowed`). The
command line is ``opsrock run`` (:mod:`opsrock.cli`).
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import hashlib
import json
import math
import os
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Collection, Iterator, Mapping, Sequence

from opsrock import __version__
from opsrock._files import atomic_write
from opsrock._pool import leave_if_reimported, pool_allowed
from opsrock.campaign.advice import sliding_warnings
from opsrock.campaign.cases import CASES_FILE, IDENTITY_EXCLUDED, case_table, failed_row, result_row, write_cases_csv
from opsrock.campaign.executors import Executor, LocalPool, batch_size, is_lost, make_batches
from opsrock.campaign.motions import MOTIONS_FILE, cached_motions, compute_motions
from opsrock.campaign.scene import MAX_CASES, Scene
from opsrock.campaign.store import DISK_ERRNOS, MANIFEST_FILE, STORE_FILE, ResultStore, disk_fault
from opsrock.campaign.timeout import DEFAULT_CASE_TIMEOUT, time_limit
from opsrock.errors import AllCasesLostError, CampaignConflictError, CaseTimeout, InputTypeError, UsageError
from opsrock.limits import check
from opsrock.result import RockingResult
from opsrock.solvers import get_solver, simulate, warm_up
from opsrock.solvers.registry import METHODS

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
    warnings : tuple of str
        Where the no-slip model may not hold (:func:`opsrock.campaign.advice.sliding_warnings`).
    choice : str
        Why the solver was chosen for (or checked against) the scene's ``[needs]``; empty without needs.
    n_lost : int
        Cases of the final table lost to the infrastructure (their worker died:
        :data:`~opsrock.campaign.executors.LOST_PREFIX`), counted in ``n_failed`` too; running the same
        campaign again computes them.
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
    warnings: tuple[str, ...] = ()
    choice: str = ""
    n_lost: int = 0

    def lines(self) -> list[str]:
        """The report a command line prints, one line each."""
        head = (f"{self.n_cases} cases ({self.n_computed} computed, {self.n_reused} reused) with {self.solver} in "
                f"{self.wall_time_s:.1f} s -> {self.cases_csv}")
        lost = ([f"{self.n_lost} cases lost to the infrastructure (a worker process died), stored failed: run the "
                 "same campaign again to compute them"] if self.n_lost else [])
        return [head] + ([f"solver chosen for the scene's needs: {self.choice}"] if self.choice else []) + lost


# --- work done in the workers -------------------------------------------------------------------
def solve_batch(
    cases: Sequence,
    *,
    solver: str,
    settings: Mapping[str, Any],
    solve_fn: Callable[..., RockingResult] | None = None,
    case_timeout: float | None = DEFAULT_CASE_TIMEOUT,
) -> list[dict[str, Any]]:
    """Solve cases one after the other; never raises for a bad case.

    Parameters
    ----------
    cases : sequence of PulseCase or RecordCase
    solver : str
        Solver name passed to ``solve_fn``.
    settings : dict
        Keyword settings of the solver (as the scene gives them, checked when the scene was made).
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
    if solve_fn is None and METHODS.get(solver) is not None:
        get_solver(solver)  # import the solver module (and compile it, in a fresh clone) outside the budget
    with _SOLVE_LOCK:
        return [_solve_one(case, fn, solver, settings, case_timeout) for case in cases]


def _solve_one(case, fn: Callable, solver: str, settings: Mapping[str, Any], case_timeout: float | None) -> dict:
    """The stored row of ``case`` solved by ``fn`` in this process, with the wall and CPU times (s) of the call
    (the CPU time of this thread: the case's own, whatever else the machine runs)."""
    t0, c0 = time.perf_counter(), time.thread_time()
    if case.problem:
        return failed_row(case.case_id, solver, case.problem, 0.0, 0.0)
    try:
        with time_limit(case_timeout):
            result = fn(case.block, case.excitation, solver=solver, **settings)
        if not isinstance(result, RockingResult):
            raise InputTypeError(f"solver returned {type(result).__name__}, not a RockingResult")
        return result_row(case.case_id, result, *_spent(t0, c0))
    except CaseTimeout as exc:
        reason = str(exc) or f"timeout: no answer within the case budget of {case_timeout:g} s"
        return failed_row(case.case_id, solver, reason, *_spent(t0, c0))
    except Exception as exc:  # noqa: BLE001  (a bad case must not stop the campaign)
        return failed_row(case.case_id, solver, f"{type(exc).__name__}: {exc}", *_spent(t0, c0))


def _spent(t0: float, c0: float) -> tuple[float, float]:
    """Wall and thread CPU time (s) since ``time.perf_counter() == t0`` and ``time.thread_time() == c0`` (the CPU
    time read first: it can then never exceed the wall time)."""
    c1 = time.thread_time()
    return time.perf_counter() - t0, c1 - c0


def lost_row(case, reason: str, *, solver: str) -> dict[str, Any]:
    """The stored row of a case the executor could not solve alone, failed with ``reason``: its worker died
    (a reason starting :data:`~opsrock.campaign.executors.LOST_PREFIX`: a resume computes it again) or it ran
    past its budget (``"timeout..."``: the solver's failure, a result)."""
    return failed_row(case.case_id, solver, reason)


def _lost_motion(item: Any, reason: str) -> str:
    return reason


# --- the campaign ------------------------------------------------------------------------------
def _manifest(scene: Scene, digest: str, solve_fn: Callable | None) -> dict[str, Any]:
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
        "needs": None if scene.needs is None else dataclasses.asdict(scene.needs),
        "choice": None if scene.choice is None else scene.choice.manifest(),
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


#: Environment variable: seconds between two plain progress lines when stderr is not a terminal.
PROGRESS_INTERVAL_ENV: str = "OPSROCK_PROGRESS_INTERVAL"
#: Default of :data:`PROGRESS_INTERVAL_ENV` (s): a run shorter than this prints no progress line.
PROGRESS_INTERVAL: float = 30.0


def progress_bar(total: int, description: str, progress: bool):
    """The progress of ``total`` cases on stderr when ``progress``: a bar on a terminal, else (a pipe, a
    file, CI, ``nohup``) a plain line every :data:`PROGRESS_INTERVAL` seconds (cases done, rate, time
    left: :class:`PlainProgress`). Either has ``update(n)`` and is a context manager."""
    if progress and not sys.stderr.isatty():
        return PlainProgress(total, description, progress_interval())
    from tqdm import tqdm

    return tqdm(total=total, desc=description, unit="case", file=sys.stderr,
                disable=not (progress and sys.stderr.isatty()), dynamic_ncols=True)


def progress_interval() -> float:
    """Seconds between plain progress lines: :data:`PROGRESS_INTERVAL_ENV` if set to a positive number,
    else :data:`PROGRESS_INTERVAL`."""
    try:
        value = float(os.environ.get(PROGRESS_INTERVAL_ENV, ""))
    except ValueError:
        return PROGRESS_INTERVAL
    return value if math.isfinite(value) and value > 0 else PROGRESS_INTERVAL


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.0f} s"
    return f"{seconds / 60:.1f} min" if seconds < 7200 else f"{seconds / 3600:.1f} h"


class PlainProgress:
    """Progress as plain lines on stderr, for a stderr that is not a terminal: every ``interval`` seconds
    (from a daemon thread, so a long batch is told too) one line ``"<description>: 120/250000 cases (0.0 %)
    in 30 s, 4.0 cases/s; about 17.4 h left"``; nothing for a run shorter than ``interval``.

    Parameters
    ----------
    total : int
        Cases to do.
    description : str
        What they are (the scene's name).
    interval : float
        Seconds between two lines (> 0).
    """

    def __init__(self, total: int, description: str, interval: float) -> None:
        self.total, self.description, self.interval = total, description, interval
        self.done, self.t0 = 0, time.monotonic()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._tick, daemon=True, name="opsrock-progress")

    def __enter__(self) -> PlainProgress:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()

    def update(self, n: int) -> None:
        """``n`` more cases done."""
        self.done += n

    def line(self) -> str:
        """The progress line now."""
        elapsed = time.monotonic() - self.t0
        head = f"opsrock: {self.description}: {self.done}/{self.total} cases"
        if not self.done:
            return f"{head} in {_duration(elapsed)}; no case finished yet (the estimate comes with the first batch)"
        rate = self.done / elapsed
        left = (self.total - self.done) / rate
        return (f"{head} ({100 * self.done / max(self.total, 1):.1f} %) in {_duration(elapsed)}, {rate:.3g} cases/s; "
                f"about {_duration(left)} left")

    def _tick(self) -> None:
        while not self._stop.wait(self.interval):
            try:
                print(self.line(), file=sys.stderr, flush=True)
            except (OSError, ValueError):  # stderr closed or full: progress is not worth a failure
                return


@dataclass
class _Run:
    """One campaign under way: the scene, its folder and store, the executor, and what it did."""

    scene: Scene
    out: Path
    digest: str
    executor: Executor | None
    progress: bool
    n_computed: int = 0
    n_reused: int = 0

    def summary(self, table: list, wall_time_s: float) -> CampaignSummary:
        out = self.out
        return CampaignSummary(
            n_cases=len(table), n_computed=self.n_computed, n_reused=self.n_reused,
            n_failed=sum(r["status"] == "failed" for r in table), wall_time_s=wall_time_s, out_dir=str(out),
            n_lost=sum(r["status"] == "failed" and is_lost(r["reason"]) for r in table),
            store_path=str(out / STORE_FILE), cases_csv=str(out / CASES_FILE), manifest_path=str(out / MANIFEST_FILE),
            digest=self.digest, solver=self.scene.solver, warnings=tuple(sliding_warnings(self.scene.blocks, table, solver=self.scene.solver)),
            choice=self.scene.choice.reason if self.scene.choice is not None else "")

    def open(self, store: ResultStore, manifest: dict, force: bool) -> None:
        """Check the folder's manifest against this run's, or start the store afresh."""
        old = store.manifest()
        if old and old.get("digest") != self.digest and not force:
            raise CampaignConflictError(_conflict_message(self.out, old, manifest))
        if force or not old:
            store.clear()
            (self.out / CASES_FILE).unlink(missing_ok=True)
            store.write_manifest(manifest)
        atomic_write(self.out / MANIFEST_FILE, lambda fh: json.dump(manifest, fh, indent=2, sort_keys=True))

    def cases(self) -> list:
        """The scene's cases; a record scene's floor motions by the executor (or the folder's cache)."""
        if self.scene.records is None:
            return self.scene.cases()
        items = self.scene.records.motion_items()
        fresh: list[bool] = []
        motions = cached_motions(self.out, self.digest, items, lambda todo: fresh.append(True) or
                                 self._compute_motions(todo))
        if not fresh and any(isinstance(m, str) and is_lost(m) for m in motions.values()):
            # a cached motion lost to the infrastructure is not a result: compute the motions again
            (self.out / MOTIONS_FILE).unlink(missing_ok=True)
            motions = cached_motions(self.out, self.digest, items, self._compute_motions)
        return self.scene.cases(motions)

    def _compute_motions(self, items: list) -> list:
        results: list[Any] = [None] * len(items)
        size = max(1, math.ceil(len(items) / (4 * self.executor.workers)))
        with progress_bar(len(items), f"{self.scene.name}: floor motions", self.progress) as bar:
            for k, res in self.executor.map_batches(compute_motions, make_batches(items, size), _lost_motion):
                results[k * size : k * size + len(res)] = res
                bar.update(len(res))
        return results

    def solve(self, store: ResultStore, cases: list, solve: Callable, batch: int | None) -> None:
        """Solve the cases the store does not hold yet, committing every batch as it returns."""
        done = store.done_ids()
        todo = [c for c in cases if c.case_id not in done]
        self.n_reused = len(cases) - len(todo)
        if not todo:
            return
        size = batch or batch_size(len(todo), self.executor.workers)
        lost = functools.partial(lost_row, solver=self.scene.solver)
        name = self.scene.name
        with progress_bar(len(todo), f"{name} ({self.n_reused} reused)" if self.n_reused else name,
                           self.progress) as bar:
            for _, rows in self.executor.map_batches(solve, make_batches(todo, size), lost):
                store.append(rows)
                self.n_computed += len(rows)
                bar.update(len(rows))


def campaign_identity(scene: Scene, solve_fn: Callable | None) -> tuple[str, dict[str, Any]]:
    """The digest of what determines the results (a custom ``solve_fn`` included) and the manifest."""
    digest = scene.digest()
    if solve_fn is not None:
        digest = hashlib.sha256(f"{digest}|{_callable_name(solve_fn)}".encode()).hexdigest()
    return digest, _manifest(scene, digest, solve_fn)


def case_budget(scene: Scene, case_timeout: float | None) -> float:
    if case_timeout is None:
        case_timeout = scene.case_timeout if scene.case_timeout is not None else DEFAULT_CASE_TIMEOUT
    return check("case_timeout", case_timeout)


@dataclass(frozen=True)
class Execution:
    """Where and how a campaign's cases run: the same for every stage of a policy.

    Parameters
    ----------
    workers : int or None
        Processes of the default :class:`~opsrock.campaign.executors.LocalPool` (None: all cores);
        ignored when ``executor`` is given.
    executor : Executor or None
        Where to run; the caller closes it. None: each stage makes a local pool and closes it.
    force : bool
        Delete a stage folder's stored results first, even of other settings.
    progress : bool
        Progress bars on stderr (only when stderr is a terminal).
    batch : int or None
        Cases per batch (None: :func:`opsrock.campaign.executors.batch_size`).
    case_timeout : float
        Wall-clock budget of one case (s), already checked.
    """

    workers: int | None
    executor: Executor | None
    force: bool
    progress: bool
    batch: int | None
    case_timeout: float


@dataclass(frozen=True)
class Stage:
    """The campaign engine, written once: one store, one solve loop, one case budget for every workflow.

    A stage runs (or resumes) cases of a scene into one folder: it opens and locks the folder's store
    (refusing other settings unless ``force``), computes or reads the floor motions, solves the cases the
    store lacks in batches, commits each batch as it returns, and writes ``cases.csv`` and
    ``manifest.json``. A policy (:data:`opsrock.campaign.workflow.POLICIES`) runs its stages through it.

    Parameters
    ----------
    how : Execution
        Where and how the cases run.
    solve_fn : callable or None
        Replaces :func:`opsrock.solvers.simulate` (see :class:`opsrock.campaign.workflow.CampaignOptions`).
    """

    how: Execution
    solve_fn: Callable[..., RockingResult] | None = None

    def __call__(self, scene: Scene, out_dir: str | os.PathLike, *, only: Collection[str] | None = None,
                 cases: list | None = None) -> tuple[CampaignSummary, list]:
        """Run the cases of ``scene`` (only those of ``only``, by case id, if given) into ``out_dir``.

        ``cases`` are the scene's cases when the caller has them already (their floor motions computed
        by an earlier stage). Returns the summary and the scene's cases (all of them, in its order).
        """
        t_start = time.perf_counter()
        leave_if_reimported()  # a worker re-running an unguarded script: before the folder is touched
        _within_limit(scene)
        if self.how.executor is None:
            pool_allowed(self.how.workers)  # several workers inside a worker: refused before anything is written
        how, out = self.how, Path(out_dir)
        digest, manifest = campaign_identity(scene, self.solve_fn)
        solve = functools.partial(solve_batch, solver=scene.solver, settings=dict(scene.solver_settings),
                                  solve_fn=self.solve_fn, case_timeout=how.case_timeout)
        with ResultStore(out / STORE_FILE) as store, _disk_faults(out):
            run = _Run(scene, out, digest, how.executor, how.progress)
            run.open(store, manifest, how.force)
            if how.executor is None:  # made once the folder is known to be ours
                warm_up(scene.solver)  # compiled here once (announced), loaded by each worker: no case pays for it
                run.executor = LocalPool(how.workers, item_timeout=how.case_timeout, warm=(scene.solver,))
            try:
                cases = run.cases() if cases is None else cases
                chosen = cases if only is None else [c for c in cases if c.case_id in only]
                run.solve(store, chosen, solve, how.batch)
            finally:
                if how.executor is None:
                    run.executor.close()
            table = case_table(chosen, store.rows())
            write_cases_csv(out / CASES_FILE, table, scene.columns, scene.units)
        summary = run.summary(table, time.perf_counter() - t_start)
        _some_computed(summary, table)
        return summary, cases


def _within_limit(scene: Scene) -> None:
    """Refuse, before anything is computed or written, a campaign of more than :data:`MAX_CASES` cases: a scene
    file's parser refuses it already; a campaign built in code (a contents study of a 200-storey building on every
    floor: 3.8 million cases) went on computing floor motions, with days of work ahead."""
    if scene.n_cases > MAX_CASES:
        raise UsageError(f"campaign {scene.name}: {len(scene.blocks)} blocks x {scene.design.n_per_block} cases per "
                         f"block = {scene.n_cases} cases, more than the {MAX_CASES} a campaign takes (MAX_CASES): "
                         "ask for fewer blocks, records, levels or floors")


def _some_computed(summary: CampaignSummary, table: list) -> None:
    """Raise :class:`AllCasesLostError` when this run tried cases and every case of the table was lost to the
    infrastructure: a run that computed nothing must not return as if it had (a script read from standard input
    once lost all 1,760 cases, its workers unable to import it, and returned normally)."""
    if summary.n_computed == 0 or summary.n_lost < summary.n_cases:
        return
    first = next(r["reason"] for r in table if is_lost(r["reason"]))
    raise AllCasesLostError(f"no case could be computed: all {summary.n_cases} cases were lost to the infrastructure "
                            f"(first: {first}); they are stored as lost in {summary.store_path}: fix the cause and "
                            "run the same campaign again (or pass workers=1 to run the cases in this process)")


@contextlib.contextmanager
def _disk_faults(out: Path) -> Iterator[None]:
    """A campaign file (``manifest.json``, ``cases.csv``, the motion cache) the file system would not write:
    :func:`opsrock.campaign.store.disk_fault`, naming the file (the store itself tells its own faults)."""
    try:
        yield
    except OSError as exc:
        if exc.errno not in DISK_ERRNOS:
            raise
        raise disk_fault(exc.filename or out, exc) from None


__all__ = ["CASES_FILE", "CampaignSummary", "Execution", "IDENTITY_EXCLUDED", "MANIFEST_FILE", "PROGRESS_INTERVAL",
           "PROGRESS_INTERVAL_ENV", "PlainProgress", "Stage",
           "campaign_identity", "case_budget", "lost_row", "progress_bar", "progress_interval", "solve_batch"]
