"""``opsrock fragility``'s ``report.md``, written from the study computed beforehand
(:func:`opsrock.analysis.record_report.write_record_report`)."""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pandas as pd

from opsrock._files import atomic_text
from opsrock.intensity.table1 import IMS
from opsrock.inventory.report import DEFINITIONS, FAILURE_HEADERS, footnotes, formatted_table, method_lines
from opsrock.report.markdown import markdown_table


@dataclass(frozen=True)
class RecordReport:
    """What :func:`opsrock.analysis.record_report.write_record_report` computed and wrote (``report.md`` is
    written from it).

    Parameters
    ----------
    study : RecordStudy
        :func:`opsrock.fragility.record_study.record_fragility` of the cases.
    robustness : pandas.DataFrame or None
        Shares of the pulse study over seeded block sets (``robustness.csv``); None: not run.
    robustness_sets : int
        Block sets of that study (count; 0: not run).
    sliding : pandas.DataFrame or None
        The sliding fragilities (``sliding.csv``) of a campaign solved with friction; None for another.
    slide_distances : tuple of float
        Distances of the sliding section (m).
    pelicun : pathlib.Path
        ``fragility_pelicun.csv``.
    skipped : list of str
        Blocks and demands not exported (no finite fit), with the reason.
    figures : dict of str to pathlib.Path
        Figure name -> PNG.
    timings : dict of str to float
        ``fits_s`` and ``total_s`` (s).
    source : str
        Where the cases came from (a campaign folder or a ``cases.csv``).
    table : pandas.DataFrame
        :func:`opsrock.inventory.summary.item_floor_table` of the per-block, per-floor fits (PFV m/s, PFA g).
    findings : tuple of Finding
        :func:`opsrock.inventory.summary.floor_findings` of ``table``.
    failures : pandas.DataFrame
        :func:`opsrock.inventory.summary.failure_table` of the cases (``code, n_failed, first_reason``).
    measure : str
        The scene's measure (:data:`opsrock.analysis.record_report.MEASURE_LABELS` key: ``pfa_g``,
        ``pfa_ratio``, ``""`` for a cloud, ``unknown``).
    method : str
        ``"ida"``, ``"msa"`` or ``"cloud"``.
    """

    study: Any
    robustness: pd.DataFrame | None
    robustness_sets: int
    sliding: pd.DataFrame | None
    slide_distances: tuple[float, ...]
    pelicun: Path
    skipped: list[str]
    figures: dict[str, Path]
    timings: dict[str, float]
    source: str
    table: pd.DataFrame = field(repr=False)
    findings: tuple
    failures: pd.DataFrame = field(repr=False)
    measure: str
    method: str


def _percent(share: float) -> str:
    return f"{100 * share:.1f} %" if math.isfinite(share) else "n/a"


def _rank(value) -> str:
    return f"{int(value)}" if isinstance(value, (int, float)) and math.isfinite(value) else "n/a (no fit)"


def _conclusion(ims: pd.DataFrame, freq: pd.DataFrame, robust: pd.DataFrame | None) -> list[str]:
    if not ims["beta"].notna().any():
        n, k = int(ims["n_cases"].max()), int(ims["n_overturned"].max())
        return [f"**No fragility curve can be fitted**: of the {n} finished cases {k} overturned "
                f"({'none' if k == 0 else 'all' if k == n else 'too few'}), so there is no transition for an IM "
                "to describe. The counts and the tables below are written; the fits are empty (NaN) and say why "
                "in `mle_message`."]
    by = {c: ims.loc[ims[c].idxmin(), "im"] if ims[c].notna().any() else "n/a" for c in ("beta", "HR", "cv_percent")}
    im9 = ims.set_index("im").loc["IM9"] if "IM9" in set(ims["im"]) else None
    lines = [f"On these floor motions the smallest dispersion beta is **{by['beta']}**, the smallest hybrid ratio "
             f"**{by['HR']}**, the smallest CV **{by['cv_percent']}**."]
    if im9 is not None:
        lines.append(f"The paper's recommendation, IM9, ranks {_rank(im9['rank_beta'])} of {len(ims)} by beta "
                     f"({im9['beta']:.3g}), {_rank(im9['rank_HR'])} by HR and {_rank(im9['rank_cv_percent'])} by CV.")
    top = freq.sort_values("share_beta", ascending=False).iloc[0]
    if int(top["n_resamples"]) > 0:
        lines.append(f"Over {int(top['n_resamples'])} record resamples, {top['im']} has the smallest beta in "
                     f"{100 * top['share_beta']:.0f} % of them [{100 * top['share_beta_lo']:.0f}, "
                     f"{100 * top['share_beta_hi']:.0f}] %.")
    if robust is not None:
        for c, name in (("HR", "HR"), ("cv_percent", "CV"), ("beta", "beta")):
            t = robust.sort_values(f"share_{c}", ascending=False).iloc[0]
            lines.append(f"Pulse study over the block sets: {t['im']} wins by {name} in {100 * t[f'share_{c}']:.0f} % "
                         f"[{100 * t[f'share_{c}_lo']:.0f}, {100 * t[f'share_{c}_hi']:.0f}] % of the sets.")
    return lines


def _sliding_lines(sliding: pd.DataFrame, distances: tuple[float, ...], figure: str) -> list[str]:
    """The report's sliding section: one table per block, the figure."""
    lines = ["## Sliding beyond a distance", "",
             "The campaign was solved with friction: a case *slid beyond d* when its peak slide of the base on the "
             "floor (`slide_max`) exceeds d, and an overturned case counts as beyond every distance. "
             f"P(slid beyond d | demand) is fitted as a lognormal by MLE over every finished case of the block on one "
             "floor, for "
             f"d = {', '.join(f'{100 * d:g}' for d in distances)} cm, in PFA (m/s²) and PFV (m/s), with the "
             "same record-bootstrap intervals as above (`sliding.csv`); the fits are exported to "
             "`fragility_pelicun.csv` as `opsrock.<block>.<floor>.SLIDE<d in mm>MM.<PFA|PFV>`, one per block and floor.",
             ""]
    table = sliding.assign(distance_cm=100 * sliding["distance"])  # its unit column: the demand's
    cols = ["distance_cm", "demand", "unit", "median", "median_lo", "median_hi", "beta", "beta_lo", "beta_hi",
            "n_beyond", "n_cases"]
    for (block, floor), rows in table.groupby(["block", "floor"], sort=False):
        lines += [f"### {block}, floor {floor}", "", markdown_table(rows[cols], ".4g"), ""]
        failed = rows[~rows["success"].astype(bool)]
        if len(failed):
            lines += ["No fit: " + "; ".join(f"{100 * r.distance:g} cm, {r.demand}: {r.message}"
                                               for r in failed.itertuples()), ""]
    return lines + [f"![Sliding]({figure})", ""]


def _solver_lines(source: str, cases: pd.DataFrame) -> list[str]:
    """Which solver made the cases, and why when a scene's ``[needs]`` chose it (the campaign's
    ``manifest.json`` beside ``cases.csv``, where there is one)."""
    solvers = sorted(str(x) for x in cases["solver"].dropna().unique()) if "solver" in cases else []
    line = f"Solver: {', '.join(f'`{x}`' for x in solvers) or 'not recorded'}"
    p = Path(source) if source else None
    manifest = (p if p is not None and p.is_dir() else (p.parent if p is not None else Path("."))) / "manifest.json"
    try:
        choice = json.loads(manifest.read_text()).get("choice") if source and manifest.is_file() else None
    except (OSError, ValueError, AttributeError):
        choice = None
    if isinstance(choice, dict) and choice.get("reason"):
        line += f", chosen by `solver = \"auto\"` for the scene's needs: {choice['reason']}"
    return [line + ".", ""]


#: The scene's measure (:data:`opsrock.analysis.record_report.MEASURE_LABELS` key) defined, for the report.
MEASURE_DEFINITIONS: dict[str, str] = {
    "pfa_g": "the scene's measure is **PFA in g**: each motion is scaled so that its PFA equals the level",
    "pfa_ratio": "the scene's measure is **PFA / (g tan alpha)** (dimensionless): each motion is scaled so that "
                 "its PFA equals the level times the block's uplift acceleration g tan alpha (alpha: the block's "
                 "slenderness angle, rad), so a level of 1 just lifts the block",
    "": "the motions are taken as recorded (a cloud: no levels)",
    "unknown": "the scene's measure could not be recognised from the cases (its `level_value` is neither PFA in g "
               "nor PFA / (g tan alpha)); see the scene file",
}
#: What the paper's nine IMs mean on a floor motion, and the symbols they use (all nine are dimensionless).
IM_SYMBOLS: str = ("Symbols: PFA (m/s²) and PFV (m/s) of the floor motion; T_m its mean period (s), which stands for "
                   "the pulse period T_p, and omega_p = 2 pi / T_m (rad/s); the block's p (its frequency parameter, "
                   "rad/s), alpha (slenderness angle, rad), R (half-diagonal, m) and e_R (Housner's restitution, "
                   "dimensionless); g = 9.81 m/s². Every IM is dimensionless.")


def _im_definitions(ims: pd.DataFrame) -> list[str]:
    """The table defining each IM the ranking shows, before the ranking."""
    table = pd.DataFrame([{"IM": im.name, "definition": f"`{im.formula}`", "meaning": im.meaning, "unit": "-",
                           "proposed by": im.reference} for im in IMS if im.name in set(ims["im"])])
    return ["## The paper's nine intensity measures (IMs)", "",
            "Each IM combines the floor motion with the block (Liu, Huang & Liu 2023, Table 1, here on floor motions). "
            + IM_SYMBOLS, "", markdown_table(table), ""]


def _head(report: RecordReport) -> list[str]:
    study, s, source = report.study, report.study.settings, report.source
    return [
        "# Overturning fragility from floor motions", "",
        f"Cases: `{source}`; {len(study.cases)} finished cases ({study.n_failed} failed, excluded and never a "
        f"verdict), {int(study.cases['y'].sum())} overturned. Demands: " + "; ".join(DEFINITIONS.values())
        + f"; {MEASURE_DEFINITIONS[report.measure]}. Intervals: {s.n_boot} resamples of the records (seed {s.seed}, "
        f"{100 * s.confidence:.0f} %). Outcome convention of the fits: `{s.outcome}`. "
        f"Wall time {report.timings['total_s']:.1f} s.", ""]


def _block_lines(out: Path, report: RecordReport) -> list[str]:
    """The per-block, per-floor table first, its notes, the pelicun IDs, the method, what the floors show and
    each block's figure."""
    t, conf = report.table, report.study.settings.confidence
    lines = ["## Per block and floor, for loss assessment", "",
             markdown_table(formatted_table(t, "overturned", conf, "block")) if len(t) else "(no block was fitted)", "",
             *(footnotes(t, "overturned") if len(t) else []),
             "Exported to `fragility_pelicun.csv` in the FEMA P-58 / pelicun damage-model form, one component per "
             "block and floor, `opsrock.<block>.<floor>.<PFA|PFV>` (a pelicun component has one fragility wherever "
             "it stands, and a block's differs by floor), medians in pelicun's SI units (PFA in m/s², PFV in m/s); "
             "the per-floor fits are in `blocks.csv`.", ""]
    if report.skipped:
        lines += ["Not exported (no finite fit): " + "; ".join(report.skipped), ""]
    lines += method_lines(report.method, conf)
    if report.findings:
        lines += ["## What the floors show", "", *(f"- {f.text}" for f in report.findings), ""]
    for key, path in report.figures.items():
        if key.startswith("fragility:"):
            lines += [f"![{key.split(':', 1)[1]}: overturning fragility per floor]({os.path.relpath(path, out)})", ""]
    return lines


def _case_lines(report: RecordReport) -> list[str]:
    lines = [*_solver_lines(report.source, report.study.cases)]
    if len(report.failures):
        n = int(report.failures["n_failed"].sum())
        lines += [f"{n} case{'s' if n != 1 else ''} failed (excluded from every fit, never counted as a verdict); "
                  f"{'their reasons' if n != 1 else 'its reason'}:", "", markdown_table(report.failures.rename(columns=FAILURE_HEADERS)), ""]
    return lines


def _resurrection_lines(out: Path, report: RecordReport) -> list[str]:
    rs, figs = report.study.resurrection_summary, report.figures
    return ["## Resurrection", "",
            f"{rs['n_curves']} IDA curves (block x record x floor), {rs['n_curves_overturning']} overturn at some level; "
            f"**{rs['n_curves_resurrected']}** of those ({_percent(rs['share_of_overturning_curves'])}) are safe again at "
            f"a higher level ({rs['n_resurrected_cases']} resurrected cases; `resurrections.csv`). `as_simulated` counts "
            "each case's own verdict; `first_exceedance` counts a curve as overturned from its first overturning level "
            "on. The scene's measure fitted both ways, every block and floor together (`measure_fits.csv`: a "
            "comparison of the two conventions, not the fragility of any block; the per-block, per-floor fits are "
            "above):", "",
            markdown_table(report.study.measure_fits, ".4g") if len(report.study.measure_fits) else "(a cloud: no levels)",
            "", f"![IDA curves]({os.path.relpath(figs['ida'], out)})", ""]


def _ranking_lines(out: Path, report: RecordReport) -> list[str]:
    study, robust = report.study, report.robustness
    ims = study.ims[["im", "n_cases", "n_overturned", "mu", "mu_lo", "mu_hi", "beta", "beta_lo", "beta_hi", "HR",
                     "cv_percent", "loglik_per_case", "logistic_mu", "logistic_beta_equivalent", "rank_beta"]]
    return [*_im_definitions(study.ims),
            "## Conclusion: which IM describes overturning best", "", *_conclusion(study.ims, study.frequencies, robust), "",
            "### The nine IMs, ranked as the paper ranks them", "",
            "MLE (probit on ln IM, every finished case; mu the median IM, dimensionless), its interval by record, the "
            "paper's HR (rocking cases) and CV = 100 beta/mu, the log-likelihood per case, and a logistic regression "
            "beside the probit:", "",
            markdown_table(ims, ".3g"), "",
            "How often each IM wins when the records are resampled:", "",
            markdown_table(study.frequencies[["im", "share_beta", "share_beta_lo", "share_beta_hi", "share_HR",
                                              "share_cv_percent"]], ".2f"), "",
            f"![IM ranking]({os.path.relpath(report.figures['ranking'], out)})", ""]


def write_markdown(out: Path, report: RecordReport) -> None:
    """Write ``out/report.md`` atomically from ``report``: the per-block, per-floor table first, then the
    method, the floors, the figures, the cases, the resurrections, the IMs defined and then ranked, the
    robustness, the sufficiency and the sliding.

    Parameters
    ----------
    out : pathlib.Path
        The report's folder (figure links are relative to it).
    report : RecordReport
        What :func:`opsrock.analysis.record_report.write_record_report` computed.
    """
    study, robust, s = report.study, report.robustness, report.study.settings
    lines = [*_head(report), *_block_lines(out, report), *_case_lines(report), *_resurrection_lines(out, report),
             *_ranking_lines(out, report)]
    if robust is not None:
        lines += ["## Is the paper's ranking robust? The pulse study over block sets", "",
                  f"{report.robustness_sets} sets of four blocks (alpha uniform in 0.15-0.45 rad, R in 0.5-1.5 m, seed {s.seed}), "
                  "each on the paper's 10 x 10 one-sine grid (`housner_fast`), ranked by HR, CV and beta of the "
                  "least-squares fit at W_SAS; share of sets each IM wins, with 95 % Wilson intervals:", "",
                  markdown_table(robust[["im", "share_HR", "share_HR_lo", "share_HR_hi", "share_cv_percent",
                                         "share_beta"]], ".2f"), ""]
    lines += ["## Sufficiency", "",
              "Probit on ln IM and a standardised covariate; the covariate's coefficient, its cluster-robust standard "
              "error (records as clusters) and the two-sided p-value of the Wald test (a small p-value: the IM does "
              "not carry all the information about overturning):", "",
              markdown_table(study.sufficiency[["im", "covariate", "coefficient", "std_error", "p_value"]], ".3g")
              if len(study.sufficiency) else "(no covariate varies)", ""]
    if report.sliding is not None:
        lines += _sliding_lines(report.sliding, report.slide_distances, os.path.relpath(report.figures["sliding"], out))
    atomic_text(out / "report.md", "\n".join(lines))


__all__ = ["RecordReport", "write_markdown"]
