"""Every figure and table of Liu, Huang & Liu (2023) from one command: ``opsrock reproduce``.

The pipeline follows the paper's workflow, validation first:

1. **validation gate**: a fixed subset of the paper's pulses runs through the OpenSees model and
   the independent scipy SDOF solver (validation case 2); if the agreement targets are not
   met the run stops with a short report of the disagreeing cases (``--ignore-gate`` goes on,
   and the report says so on its first line);
2. **campaign**: the paper's 400 cases (the shipped scene ``paper``) with the chosen solver,
   resumable, into ``DIR/cases.csv``;
3. **dense spectrum** (Figure 6b): the rigid-body equation on the dense grid of
   the shipped scene ``spectrum`` with the compiled solver's batch entry point (the SDOF model
   would take minutes for the same picture), the campaign's verdicts drawn over it;
4. **fragility**: hybrid strips, Table 2, strip fractions and lognormal fits, Table 3, with the
   paper's values side by side;
5. **figures** 3, 4, 6a, 6b, 8-12 and the published-threshold charts into ``DIR/figures/`` and ``DIR/report.md``.
"""

from __future__ import annotations

import contextlib
import json
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import pandas as pd

    from opsrock.validation.sdof_agreement import Agreement

from opsrock._files import atomic_csv, atomic_text, read_table
from opsrock.data import scene_file

#: The shipped scenes of the campaign and of the dense spectrum.
PAPER_SCENE = scene_file("paper")
SPECTRUM_SCENE = scene_file("spectrum")


@dataclass(frozen=True)
class GateReport:
    """Outcome of the validation gate (:func:`opsrock.report.paper.gate_text` writes it out).

    Parameters
    ----------
    passed : bool
        Agreement targets of validation case 2 met on the subset.
    overridden : bool
        The gate failed and ``--ignore-gate`` let the run go on.
    summary : Agreement
        The agreement figures (:class:`opsrock.validation.sdof_agreement.Agreement`).
    disagreements : pandas.DataFrame
        Disagreeing cases with their distance to the overturning boundary.
    """

    passed: bool
    overridden: bool
    summary: Agreement
    disagreements: pd.DataFrame


@dataclass(frozen=True)
class Reproduction:
    """What :func:`reproduce` computed and wrote.

    Parameters
    ----------
    gate : GateReport or None
        The validation gate (None when the campaign solver is not the OpenSees model).
    stopped : bool
        The gate failed and the run stopped before the campaign; the fields below are then empty.
    timings : dict of str to float
        Wall time of each step (s), by name (``validation_gate_s``, ``campaign_s``, ..., ``total_s``).
    campaign : CampaignSummary or None
        The campaign's summary (:func:`opsrock.campaign.run_campaign`).
    figures : dict of str to pathlib.Path
        Figure name -> PNG.
    report : pathlib.Path or None
        ``report.md``.
    table2, table3, ranking : pandas.DataFrame or None
        Table 2, Table 3 and the IM ranking.
    """

    gate: GateReport | None
    stopped: bool
    timings: dict[str, float]
    campaign: Any = None
    figures: dict[str, Path] = field(default_factory=dict)
    report: Path | None = None
    table2: pd.DataFrame | None = None
    table3: pd.DataFrame | None = None
    ranking: pd.DataFrame | None = None


#: Block sets of the ranking-robustness study in the report (seeded; issue: the paper's blocks are
#: unknown, so is its IM ranking a property of the IMs or of its blocks?).
ROBUSTNESS_SETS: int = 200


def validation_gate(ignore: bool = False, workers: int | None = None) -> GateReport:
    """Run validation case 2 on its fixed 24-pulse subset (6 per block)."""
    from opsrock.validation.sdof_agreement import compare, disagreements, paper_cases, summarize

    cases = paper_cases(quick=True)
    df = compare(cases, workers=workers)
    agreement = summarize(df)
    bad = disagreements(df, cases)
    return GateReport(passed=agreement.passed, overridden=ignore and not agreement.passed,
                      summary=agreement, disagreements=bad)


@dataclass(frozen=True)
class ReproduceSettings:
    """What :func:`reproduce` runs.

    Parameters
    ----------
    solver : str
        Solver of the campaign (default the OpenSees model, as in the paper).
    ignore_gate : bool
        Go on when the validation gate fails (the report says so on its first line).
    force : bool
        Discard stored campaign results of other settings in the output folder.
    paper_scene, spectrum_scene : path
        Scenes of the campaign and of the dense spectrum (None skips the spectrum).
    robustness_sets : int
        Block sets of the ranking-robustness study (count; 0 skips it); ``robustness.csv``.
    seed : int
        Seed of the block-set draws (no unit).
    """

    solver: str = "opensees"
    ignore_gate: bool = False
    force: bool = False
    paper_scene: str | os.PathLike = PAPER_SCENE
    spectrum_scene: str | os.PathLike | None = SPECTRUM_SCENE
    robustness_sets: int = ROBUSTNESS_SETS
    seed: int = 0


def reproduce(out_dir: str | os.PathLike, settings: ReproduceSettings | None = None, *, workers: int | None = None,
              progress: bool = True) -> Reproduction:
    """Run the whole pipeline into ``out_dir``; return what was computed and written.

    Parameters
    ----------
    out_dir : path
        Output folder (created): ``cases.csv``, ``table2.csv/.md``, ``table3.csv/.md``,
        ``figures/``, ``report.md``, ``validation_gate.md``.
    settings : ReproduceSettings, optional
        What to run (default: the paper's workflow with the OpenSees model).
    workers : int, optional
        Local worker processes (default all cores).
    progress : bool
        Progress bars on stderr.
    """
    # pandas, scipy and the solvers only when the pipeline runs (the command line's parser reads this module)
    from opsrock.report.paper import PaperReport, gate_text, write_report
    from opsrock.validation.experiments import headline

    t_start = time.perf_counter()
    st = settings or ReproduceSettings()
    solver = st.solver
    out = Path(out_dir)
    (out / "figures").mkdir(parents=True, exist_ok=True)
    timer = _Timings()
    with timer("validation_gate_s"):
        gate = validation_gate(ignore=st.ignore_gate, workers=workers) if solver == "opensees" else None
    if gate is not None:
        atomic_text(out / "validation_gate.md", gate_text(gate))
        if not gate.passed and not st.ignore_gate:
            return Reproduction(gate=gate, stopped=True, timings=timer.seconds)
    with timer("campaign_s"):
        scene, summary, cases = _campaign(out, st.paper_scene, solver, workers, st.force, progress)
    spectrum = None
    if st.spectrum_scene is not None:
        with timer("spectrum_s"):
            spectrum = _spectrum(out, st.spectrum_scene, workers)
    with timer("fragility_s"):
        analysis, t2, t3, ranking = _fragility(out, cases, scene.pfv_convention, workers)
    robustness = None
    if st.robustness_sets:
        with timer("robustness_s"):
            robustness = _robustness(out, st.robustness_sets, st.seed, workers, progress)
    with timer("figures_s"):
        figures = make_figures(cases, analysis, out / "figures", spectrum=spectrum, solver=solver, scene=scene,
                               workers=workers)
    restitution = headline()  # section 7b: the shipped free-rocking data, 200 trial resamples
    timings = timer.seconds
    timings["total_s"] = time.perf_counter() - t_start
    report = write_report(out, PaperReport(cases=cases, analysis=analysis, table3=t3, ranking=ranking, gate=gate,
                                           figures=figures, timings=timings, solver=solver, campaign=summary,
                                           pfv_convention=scene.pfv_convention, robustness=robustness,
                                           restitution=restitution))
    atomic_text(out / "timings.json", json.dumps(timings, indent=2) + "\n")
    return Reproduction(gate=gate, stopped=False, timings=timings, campaign=summary, figures=figures, report=report,
                        table2=t2, table3=t3, ranking=ranking)


class _Timings:
    """Wall time of each step of the pipeline (s), by name: ``with timer("campaign_s"): ...``."""

    def __init__(self) -> None:
        self.seconds: dict[str, float] = {}

    @contextlib.contextmanager
    def __call__(self, name: str):
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self.seconds[name] = time.perf_counter() - t0


def _campaign(out: Path, paper_scene, solver: str, workers, force: bool, progress: bool):
    """Step 2: the paper's 400 cases with the chosen solver, resumable; returns the scene, the campaign's
    summary and its ``cases.csv``."""
    from opsrock.campaign import run_campaign
    from opsrock.campaign.cases import units_row
    from opsrock.campaign.scene import load_scene

    scene = load_scene(paper_scene)
    if solver != scene.solver:
        scene = scene.with_solver(solver)
    summary = run_campaign(scene, out, workers=workers, force=force, progress=progress)
    return scene, summary, read_table(summary.cases_csv, skiprows=units_row(summary.cases_csv))


def _spectrum(out: Path, spectrum_scene, workers) -> pd.DataFrame:
    """Step 3: the dense spectrum (Figure 6b), ``spectrum/spectrum.csv``."""
    from opsrock.campaign.scene import load_scene

    spectrum = dense_spectrum(load_scene(spectrum_scene), workers=workers)
    (out / "spectrum").mkdir(exist_ok=True)
    atomic_csv(out / "spectrum" / "spectrum.csv", spectrum)
    return spectrum


def _fragility(out: Path, cases: pd.DataFrame, pfv_convention: str, workers: int | None = None):
    """Step 4: hybrid strips, Table 2, strip fractions and fits, Table 3, the IM ranking."""
    from opsrock import fragility

    analysis = fragility.analyse_fragility(cases, workers=workers or os.cpu_count() or 1)
    t2 = fragility.table2(analysis)
    t3 = fragility.table3(analysis)
    atomic_csv(out / "table2.csv", t2)
    atomic_csv(out / "table3.csv", t3)
    atomic_text(out / "table2.md", fragility.table2_markdown(t2, pfv_convention) + "\n")
    atomic_text(out / "table3.md", fragility.table3_markdown(t3, pfv_convention) + "\n")
    ranking = fragility.rank_ims(analysis)
    atomic_csv(out / "im_ranking.csv", ranking.reset_index())
    return analysis, t2, t3, ranking


def _robustness(out: Path, n_sets: int, seed: int, workers, progress: bool):
    """Step 4b: is the ranking robust to the (unknown) blocks? ``robustness.csv``."""
    from opsrock.analysis.robustness import ranking_robustness

    robustness = ranking_robustness(n_sets, seed=seed, workers=workers or os.cpu_count() or 1, progress=progress)
    atomic_csv(out / "robustness.csv", robustness.shares)
    return robustness


def dense_spectrum(scene, workers: int | None = None) -> pd.DataFrame:
    """Overturning spectrum of every block of ``scene`` on its grid, with the compiled
    rigid-body solver's batch entry point (one call per block, no per-case overhead).

    Returns one row a case: ``block, freq_ratio, pfa_ratio, theta_max_over_alpha, verdict, status``.
    """
    import numpy as np
    import pandas as pd

    from opsrock.solvers.housner_fast import solve_grid

    frames = []
    fr, ar = np.meshgrid(np.asarray(scene.grid.freq_ratio), np.asarray(scene.grid.pfa_ratio), indexing="ij")
    for spec in scene.blocks:
        b = spec.block
        res = solve_grid(b.alpha, b.e, ar.ravel(), fr.ravel(), threads=workers)
        frames.append(pd.DataFrame({
            "block": spec.name, "freq_ratio": fr.ravel(), "pfa_ratio": ar.ravel(),
            "theta_max_over_alpha": res.theta_max.ravel() / b.alpha, "verdict": res.verdict.ravel(),
            "status": np.where(res.ok.ravel(), "ok", "failed"),
        }))
    return pd.concat(frames, ignore_index=True)


#: Free rocking drawn after the pulse in Figure 4 (s): the whole decay to rest, as the paper shows.
FIG4_TAIL_S: float = 8.0


def _figure4_history(case, solver: str, simulate):
    """One Figure 4 history of the campaign solver, run past the pulse through the decay to rest
    (OpenSees: every step kept, not stopped at the first post-pulse peak; scipy solvers: dense
    output every T_p/200)."""
    if solver == "opensees":
        return simulate(case.block, case.pulse, solver=solver, stop_at_rest=False,
                        end_time=case.pulse.duration + FIG4_TAIL_S)
    if solver in ("housner", "sdof"):
        return simulate(case.block, case.pulse, solver=solver, tail="rest", max_free_time=FIG4_TAIL_S,
                        dense_step=case.pulse.duration / 200)
    return simulate(case.block, case.pulse, solver=solver)


def make_figures(cases: pd.DataFrame, analysis, fig_dir: Path, *, spectrum: pd.DataFrame | None,
                 solver: str, scene, workers: int | None = None) -> dict[str, Path]:
    """Figures 3, 4, 6a, 6b, 8-12 into ``fig_dir``; returns name -> path.

    ``scene`` is the campaign's scene: Figures 3 and 4 re-run a few of its cases with full
    histories (the campaign stores peaks and verdicts only). The figures are independent: with
    ``workers`` > 1 the paper's figures and the threshold charts are drawn by a pool of processes
    (the longest first) while this process re-runs and draws Figures 3 and 4.
    """
    from opsrock.plots import fragility as fplots

    workers = workers or os.cpu_count() or 1
    jobs = fplots.paper_figure_jobs(cases, analysis, fig_dir, spectrum)
    # beyond the paper: the minimum-overturning charts of the rocking literature (validation case 7)
    jobs["thresholds"] = (threshold_charts_figure, (fig_dir / "thresholds.png",))
    order = sorted(jobs, key=lambda k: -THRESHOLDS_COST if k == "thresholds" else -fplots.FIGURE_COST.get(k, 1.0))
    figs: dict[str, Path] = {}
    pool = None
    if workers > 1:
        from opsrock.plots import figure_pool

        pool = figure_pool(min(workers, len(jobs)))
    try:
        futures = {}
        if pool is not None:
            from opsrock._pool import deferred_interrupts

            with deferred_interrupts():  # the workers are forked at the first submit
                futures = {k: pool.submit(jobs[k][0], *jobs[k][1]) for k in order}
        figs.update(_history_figures(cases, fig_dir, solver, scene))
        for k in order:
            figs[k] = futures[k].result() if pool is not None else jobs[k][0](*jobs[k][1])
    finally:
        if pool is not None:
            pool.shutdown(cancel_futures=True)
    keys = ("fig3", "fig4", "fig6a", "fig6b", "fig8", "fig9", "fig10", "fig11", "fig12", "thresholds")
    return {k: figs[k] for k in keys if k in figs}


#: Relative cost of the threshold-charts job (the charts are computed there: the longest job).
THRESHOLDS_COST: float = 4.0


def threshold_charts_figure(path: str | os.PathLike) -> Path:
    """One job of :func:`make_figures`: compute :func:`opsrock.analysis.charts.literature_charts` and draw them
    with :func:`opsrock.plots.thresholds.plot_threshold_charts` into ``path`` (PNG); returns its path."""
    from opsrock.analysis.charts import literature_charts
    from opsrock.plots.thresholds import plot_threshold_charts  # matplotlib: only when figures are drawn

    return plot_threshold_charts(literature_charts(), path)


def _history_figures(cases: pd.DataFrame, fig_dir: Path, solver: str, scene) -> dict[str, Path]:
    """Figures 3 and 4: a few of the campaign's cases re-run with full histories."""
    from opsrock.plots.response import plot_histories, plot_response
    from opsrock.solvers import simulate

    figs: dict[str, Path] = {}
    by_id = {c.case_id: c for c in scene.cases()}
    ok = cases[cases["status"] == "ok"]
    safe = ok[ok["verdict"] == "safe"].sort_values("theta_max_over_alpha")
    over = ok[ok["verdict"] == "overturned"].sort_values("pfa_ratio")

    # Figure 3: hysteresis of the model for the largest safe response (OpenSees, with moments)
    if len(safe):
        c = by_id[safe["case_id"].iloc[-1]]
        res = simulate(c.block, c.pulse, solver="opensees")
        figs["fig3"] = plot_response(res, c.block, c.pulse, fig_dir / "fig3_hysteresis.png")

    # Figure 4: three safe, three overturning histories; the paper compares with experiments
    # (not available here), so the independent scipy SDOF solver is drawn under the model.
    def spread(df: pd.DataFrame) -> list[str]:
        if len(df) <= 3:
            return list(df["case_id"])
        idx = [0, len(df) // 2, len(df) - 1]
        return [df["case_id"].iloc[i] for i in idx]

    chosen = spread(safe) + spread(over)
    if chosen:
        res_a, res_b, titles = [], [], []
        for cid in chosen:
            c = by_id[cid]
            res_a.append(_figure4_history(c, solver, simulate))
            # the independent scipy SDOF solver, from its dense output, down to rest
            res_b.append(simulate(c.block, c.pulse, solver="sdof", tail="rest", max_free_time=FIG4_TAIL_S,
                                  dense_step=c.pulse.duration / 200))
            titles.append(f"{cid}  " + r"$\omega_p/p$" + f"={c.freq_ratio:.3g}, " + r"PFA/g tan$\alpha$" + f"={c.pfa_ratio:.3g}")
        figs["fig4"] = plot_histories(res_a, titles, fig_dir / "fig4_histories.png", references=res_b,
                                      reference_label="independent scipy SDOF")
    return figs
