"""The inventory study run by stages, in the shape of pelicun's ``Assessment`` and its stage models: one
:class:`Assessment` holds the design and where it writes, and four stages with one job each run it in
order, each reading what the one before left on the assessment:

1. :class:`DemandStage`: each floor motion's measures (:func:`opsrock.inventory.campaigns.cached_demands`);
2. :class:`CampaignStage`: every group's campaign, run or resumed on one pool of workers
   (:func:`opsrock.inventory.campaigns.run_groups`), the scenes built (and every input checked) first;
3. :class:`FitStage`: the fragility tables of the model choice;
4. :class:`OutputStage`: the tables, the report, the figures and (planar) the pelicun folder, written
   together through a staging folder (a failed or interrupted run changes nothing).

What differs between the model choices (planar per axis, or every item a box in three dimensions under
both directions at once: :mod:`opsrock.inventory.three_d`) is a :class:`Route`: how its scenes are built,
how it fits and what it writes. The solver's registry entry picks the route (``plan``), never its name.
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import pandas as pd

from opsrock.inventory.outputs import InventoryStudy, workers_of


@dataclass(frozen=True)
class Route:
    """What a model choice brings to the stages.

    Parameters
    ----------
    name : str
        ``"planar"`` or ``"3d"`` (progress lines).
    scenes : callable
        ``scenes(design) -> list[GroupScene]``: the campaigns, every input checked before anything is written.
    fit : callable
        ``fit(assessment) -> dict[str, DataFrame]``: the tables written (key -> table), from
        ``assessment.cases`` and ``assessment.demands``.
    write : callable
        ``write(assessment, stage) -> (paths, pelicun, report)``: the tables, figures, pelicun folder and report
        written into the staging folder ``stage``; ``paths`` key -> CSV path, ``pelicun`` key -> path.
    outputs : tuple of str
        Globs (relative to the output folder) of the files it writes (:func:`opsrock._files.staged_folder`).
    """

    name: str
    scenes: Callable[[Any], list]
    fit: Callable[["Assessment"], dict[str, pd.DataFrame]]
    write: Callable[["Assessment", Path], tuple[dict[str, Path], dict[str, Path], Path]]
    outputs: tuple[str, ...]


@dataclass
class Assessment:
    """One inventory study being run: its design, where it writes, and what each stage leaves for the next.

    Parameters
    ----------
    design : InventoryDesign
        The inventory, the motions and how to run and fit them.
    route : Route
        The model choice.
    out : Path
        The output folder.
    store : Path
        Where the campaigns keep their stores.
    workers : int or None
        Processes (None: every core).
    progress : bool
        Progress on stderr.
    force : bool
        Delete stored results of other settings in the campaigns' folders instead of refusing them.
    case_timeout : float or None
        Wall-clock budget of one case (s); None: the campaigns' default. Cases stored as timed out are computed
        again (:func:`opsrock.inventory.campaigns.run_groups`).
    """

    design: Any
    route: Route
    out: Path
    store: Path
    workers: int | None = None
    progress: bool = True
    force: bool = False
    case_timeout: float | None = None
    scenes: list = field(default_factory=list, repr=False)
    demands: pd.DataFrame | None = field(default=None, repr=False)
    cases: pd.DataFrame | None = field(default=None, repr=False)
    tables: dict[str, pd.DataFrame] = field(default_factory=dict, repr=False)
    n_computed: int = 0
    n_retried: int = 0
    timings: dict[str, float] = field(default_factory=dict)
    t_start: float = field(default_factory=time.perf_counter)

    def say(self, text: str) -> None:
        """One progress line on stderr (when :attr:`progress`)."""
        if self.progress:
            print(f"contents: {text}", file=sys.stderr, flush=True)

    def run(self) -> InventoryStudy:
        """Every stage in order; the study as written."""
        self.scenes = self.route.scenes(self.design)  # every input checked before anything is written
        for stage in (DemandStage(), CampaignStage(), FitStage()):
            stage.run(self)
        return OutputStage().run(self)


class DemandStage:
    """Each floor motion's measures (pfa m/s², pfv m/s, ...), cached in the store."""

    def run(self, a: Assessment) -> None:
        from opsrock.inventory.campaigns import cached_demands

        t0 = time.perf_counter()
        a.demands = cached_demands(a.design.motions, a.store, workers_of(a.workers))
        a.timings["demands_s"] = time.perf_counter() - t0


class CampaignStage:
    """Every group's campaign, run or resumed on one pool of workers; refuses a study whose every case
    failed (:func:`opsrock.fragility.cases.check_some_finished`)."""

    def run(self, a: Assessment) -> None:
        from opsrock.fragility.cases import check_some_finished
        from opsrock.inventory.campaigns import run_groups

        a.say(f"{sum(s.scene.n_cases for s in a.scenes)} cases in {len(a.scenes)} campaigns ({a.route.name}) into "
              f"{a.store}")
        a.cases, t = run_groups(a.scenes, a.store, a.demands, workers=a.workers, progress=a.progress,
                                force=a.force, case_timeout=a.case_timeout)
        a.timings["campaigns_s"], a.n_computed = t["campaigns_s"], int(t["n_computed"])
        a.n_retried = int(t["n_retried"])
        if a.n_retried:
            a.say(f"{a.n_retried} cases stored as timed out were computed again")
        check_some_finished(a.cases, str(a.store))


class FitStage:
    """The route's fragility tables."""

    def run(self, a: Assessment) -> None:
        t0 = time.perf_counter()
        a.say(f"fits ({a.design.n_boot} record resamples each)")
        a.tables = a.route.fit(a)
        a.timings["fits_s"] = time.perf_counter() - t0


class OutputStage:
    """The route's tables, figures, pelicun folder and report, all or nothing."""

    def run(self, a: Assessment) -> InventoryStudy:
        from opsrock._files import staged_folder

        t0 = time.perf_counter()
        with staged_folder(a.out, a.route.outputs) as stage:
            paths, pel, report = a.route.write(a, stage)
            final = {p: a.out / Path(p).relative_to(stage) for p in [report, *paths.values(), *pel.values()]}
        a.timings.setdefault("outputs_s", time.perf_counter() - t0)
        a.timings.setdefault("total_s", time.perf_counter() - a.t_start)
        a.say(f"done in {a.timings['total_s']:.1f} s: {final[report]}")
        return InventoryStudy(design=a.design, out_dir=str(a.out), tables={k: str(final[p]) for k, p in paths.items()},
                              pelicun={k: str(final[p]) for k, p in pel.items()}, report=str(final[report]),
                              n_cases=len(a.cases), n_computed=a.n_computed,
                              n_failed=int((a.cases["status"] != "ok").sum()), timings=a.timings)


__all__ = ["Assessment", "CampaignStage", "DemandStage", "FitStage", "OutputStage", "Route"]
