"""The contents study run by stages, in the shape of pelicun's ``Assessment`` and its stage models: one
:class:`Assessment` holds the design and where it writes, and four stages with one job each run it in
order, each reading what the one before left on the assessment:

1. :class:`DemandStage`: the floor motions' measures;
2. :class:`CampaignStage`: every campaign, run or resumed (the scenes built, and every input checked, first);
3. :class:`FitStage`: the fragility tables;
4. :class:`OutputStage`: the tables, the report, the figures and the pelicun folder, written together through a
   staging folder (a failed or interrupted run changes nothing).

What a configuration of the study brings to the stages is a :class:`Route` (its stage models): the user's
inventory planar per axis (:data:`opsrock.inventory.study.PLANAR`) or every item a box in three dimensions
(:data:`opsrock.inventory.three_d.THREE_D`; the solver's registry entry picks it, ``plan``, never its name),
FEMA P-58's nine in the shipped building beside FEMA's fragilities (:data:`opsrock.inventory.fema.study.FEMA_NINE`),
and both models side by side (:data:`opsrock.inventory.directionality.study.BOTH`).
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import pandas as pd

from opsrock.inventory.campaigns import StudyOptions
from opsrock.inventory.outputs import InventoryStudy, Written, workers_of


def inventory_demands(a: "Assessment") -> pd.DataFrame:
    """Each motion's measures of the user's motion set (:func:`opsrock.inventory.campaigns.cached_demands`)."""
    from opsrock.inventory.campaigns import cached_demands

    return cached_demands(a.design.motions, a.store, workers_of(a.options.workers))


def inventory_jobs(a: "Assessment") -> list:
    """Every group's campaign (:func:`opsrock.inventory.campaigns.group_jobs`)."""
    from opsrock.inventory.campaigns import group_jobs

    return group_jobs(a.scenes, a.demands)


@dataclass(frozen=True)
class Route:
    """What a configuration of the study brings to the stages: one function per stage (its stage models).

    Parameters
    ----------
    name : str
        ``"planar"``, ``"3d"``, ``"fema-p58"`` or ``"both"`` (progress lines).
    scenes : callable
        ``scenes(design)``: the campaigns' scenes (or what they are built from), every input checked before
        anything is written.
    fit : callable
        ``fit(assessment) -> dict[str, DataFrame]``: the tables (key -> table), from ``assessment.cases`` and
        ``assessment.demands``.
    write : callable
        ``write(assessment, stage) -> Written``: the tables, figures, pelicun folder and report written into
        the staging folder ``stage``.
    outputs : tuple of str
        Globs (relative to the output folder) of the files it writes (:func:`opsrock._files.staged_folder`).
    demands : callable
        ``demands(assessment)``: the floor motions' measures (default :func:`inventory_demands`).
    jobs : callable
        ``jobs(assessment) -> list of CampaignJob``: the campaigns (:class:`opsrock.inventory.campaigns.CampaignJob`),
        which the study's one runner (:func:`opsrock.inventory.campaigns.run_campaigns`) runs or resumes in order
        (default :func:`inventory_jobs`).
    """

    name: str
    scenes: Callable[[Any], Any]
    fit: Callable[["Assessment"], dict[str, pd.DataFrame]]
    write: Callable[["Assessment", Path], Written]
    outputs: tuple[str, ...]
    demands: Callable[["Assessment"], Any] = inventory_demands
    jobs: Callable[["Assessment"], list] = inventory_jobs


@dataclass
class Assessment:
    """One inventory study being run: its design, where it writes, and what each stage leaves for the next.

    Parameters
    ----------
    design : object
        The study's design (:class:`opsrock.inventory.study.InventoryDesign`, or the design of its route).
    route : Route
        The configuration.
    out : Path
        The output folder.
    store : Path
        Where the campaigns keep their stores.
    options : StudyOptions
        How it runs: processes, progress, force, the case budget (s)
        (:class:`opsrock.inventory.campaigns.StudyOptions`; its ``store_dir`` is already ``store``).
    """

    design: Any
    route: Route
    out: Path
    store: Path
    options: StudyOptions = field(default_factory=StudyOptions)
    scenes: Any = field(default=None, repr=False)
    demands: Any = field(default=None, repr=False)
    cases: pd.DataFrame | None = field(default=None, repr=False)
    tables: dict[str, pd.DataFrame] = field(default_factory=dict, repr=False)
    runs: tuple = ()
    n_computed: int = 0
    n_retried: int = 0
    timings: dict[str, float] = field(default_factory=dict)
    t_start: float = field(default_factory=time.perf_counter)

    def say(self, text: str) -> None:
        """One progress line on stderr (when :attr:`progress`)."""
        if self.options.progress:
            print(f"contents: {text}", file=sys.stderr, flush=True)

    def run(self) -> InventoryStudy:
        """Every stage in order; the study as written."""
        self.scenes = self.route.scenes(self.design)  # every input checked before anything is written
        for stage in (DemandStage(), CampaignStage(), FitStage()):
            stage.run(self)
        return OutputStage().run(self)


class DemandStage:
    """Each floor motion's measures (pfa m/s², pfv m/s, ...), as the route reads them (cached in the store)."""

    def run(self, a: Assessment) -> None:
        t0 = time.perf_counter()
        a.demands = a.route.demands(a)
        a.timings["demands_s"] = time.perf_counter() - t0


class CampaignStage:
    """Every campaign of the route (its :attr:`Route.jobs`), run or resumed by the study's one runner
    (:func:`opsrock.inventory.campaigns.run_campaigns`); refuses a study whose every case failed
    (:func:`opsrock.fragility.cases.check_some_finished`). Leaves each campaign's record in ``runs``."""

    def run(self, a: Assessment) -> None:
        from opsrock.fragility.cases import check_some_finished
        from opsrock.inventory.campaigns import run_campaigns

        t0 = time.perf_counter()
        jobs = a.route.jobs(a)
        a.say(f"{sum(j.scene.n_cases for j in jobs)} cases in {len(jobs)} campaigns ({a.route.name}) into {a.store}")
        a.cases, a.runs = run_campaigns(jobs, a.store, a.options)
        a.n_computed = sum(r.n_computed for r in a.runs)
        a.n_retried = sum(r.n_retried for r in a.runs)
        a.timings["campaigns_s"] = time.perf_counter() - t0
        if a.n_retried:
            a.say(f"{a.n_retried} cases stored as timed out were computed again")
        check_some_finished(a.cases, str(a.store))


class FitStage:
    """The route's fragility tables (and the tables computed from them)."""

    def run(self, a: Assessment) -> None:
        t0 = time.perf_counter()
        a.say(f"fits ({a.design.n_boot} record resamples each)")
        a.tables = a.route.fit(a)
        a.timings["fits_s"] = time.perf_counter() - t0


class OutputStage:
    """The route's tables, figures, pelicun folder and report, all or nothing."""

    def run(self, a: Assessment) -> InventoryStudy:
        from opsrock._files import staged_folder
        from opsrock.fragility.cases import count_failed

        t0 = time.perf_counter()
        with staged_folder(a.out, a.route.outputs) as stage:
            w = a.route.write(a, stage)
            final = {p: str(a.out / Path(p).relative_to(stage))
                     for p in [w.report, *w.tables.values(), *w.pelicun.values(), *w.figures]}
        a.timings.setdefault("outputs_s", time.perf_counter() - t0)
        a.timings.setdefault("total_s", time.perf_counter() - a.t_start)
        a.say(f"done in {a.timings['total_s']:.1f} s: {final[w.report]}")
        return InventoryStudy(design=a.design, out_dir=str(a.out), tables={k: final[p] for k, p in w.tables.items()},
                              pelicun={k: final[p] for k, p in w.pelicun.items()}, report=final[w.report],
                              n_cases=len(a.cases), n_computed=a.n_computed,
                              n_failed=count_failed(a.cases), timings=a.timings,
                              figures=[final[p] for p in w.figures], summary=w.summary)


__all__ = ["Assessment", "CampaignStage", "DemandStage", "FitStage", "OutputStage", "Route", "inventory_demands",
           "inventory_jobs"]
