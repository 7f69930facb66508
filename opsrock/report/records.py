"""``opsrock fragility``: the record fragility report of a record campaign.

    opsrock fragility RUN_DIR|cases.csv --out DIR [--n-boot N] [--seed S] [--outcome as_simulated|first_exceedance]
                      [--robustness-sets N] [--workers N]

Reads the ``cases.csv`` of a record scene's run, fits every IM (:mod:`opsrock.fragility.record_study`),
and writes into ``DIR``: ``report.md``, ``ims.csv``, ``measure_fits.csv``, ``resurrections.csv``,
``sufficiency.csv``, ``frequencies.csv``, ``blocks.csv``, ``fragility_pelicun.csv`` (FEMA P-58 /
pelicun damage model) and ``figures/``; with ``--robustness-sets N`` also the pulse study over N
seeded block sets (``robustness.csv``). A campaign solved with friction (its table has the contact
columns) also gets the fragility of sliding beyond :data:`SLIDE_DISTANCES` (:mod:`opsrock.fragility.sliding`):
``sliding.csv``, ``figures/sliding.png``, a section of the report and the ``SLIDE`` components in
``fragility_pelicun.csv``; any other campaign's outputs are as they were.
"""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path

import pandas as pd

from opsrock._files import atomic_csv, atomic_text
from opsrock.errors import InputError
from opsrock.fragility.sliding import DEFAULT_DISTANCES
from opsrock.report.markdown import markdown_table

#: Distances (m) of the sliding section: 5 cm (a cabinet against a wall), 20 cm and 50 cm.
SLIDE_DISTANCES: tuple[float, ...] = DEFAULT_DISTANCES


def read_cases(source: str | Path) -> pd.DataFrame:
    """The ``cases.csv`` of a record campaign, checked: ``source`` is the campaign's folder or the file.

    Refused, with the file and the reason (:class:`~opsrock.errors.InputError`): a file that is not a
    table, a table of a pulse campaign, missing columns, text in a number column, no rows, and a table
    shorter than the campaign it came from (its ``manifest.json`` beside it says how many cases).
    """
    p = Path(source)
    csv_path = p / "cases.csv" if p.is_dir() else p
    if not csv_path.is_file():
        raise InputError(f"cases: no cases.csv at {source!s} (give the --out folder of `opsrock run` or a cases.csv)")
    try:
        cases = pd.read_csv(csv_path)
    except (ValueError, UnicodeDecodeError, pd.errors.ParserError) as exc:
        raise InputError(f"cases: {csv_path} cannot be read as a table: {str(exc).splitlines()[0]}") from None
    if "record" not in cases.columns:
        raise InputError(f"cases: {csv_path} is not from a record scene (no 'record' column); "
                         "pulse campaigns go through `opsrock reproduce`")
    _check_table(csv_path, cases)
    _check_complete(csv_path, len(cases))
    return cases


#: Columns of a record campaign's table the study reads, and those of them that must hold numbers.
_STUDY_COLUMNS = ("block", "record", "floor", "level", "level_value", "status", "overturned", "rocked",
                  "theta_max_over_alpha", "pfa", "pfv", "magnitude", "distance_km", "building_period",
                  *(f"IM{k}" for k in range(1, 10)))
_NUMBER_COLUMNS = ("level", "level_value", "theta_max_over_alpha", "pfa", "pfv", "magnitude", "distance_km",
                   "building_period", *(f"IM{k}" for k in range(1, 10)))
#: Number columns of a campaign solved with friction that the sliding section reads (when present).
_SLIDE_NUMBER_COLUMNS = ("slide_max", "slide_residual")


def _check_table(csv_path: Path, cases: pd.DataFrame) -> None:
    missing = [c for c in _STUDY_COLUMNS if c not in cases.columns]
    if missing:
        raise InputError(f"cases: {csv_path} lacks the column(s) {', '.join(missing)} of a record campaign's table")
    if cases.empty:
        raise InputError(f"cases: {csv_path} holds no cases (a header only)")
    for col in (*_NUMBER_COLUMNS, *(c for c in _SLIDE_NUMBER_COLUMNS if c in cases.columns)):
        if not pd.api.types.is_numeric_dtype(cases[col]):
            bad = pd.to_numeric(cases[col], errors="coerce").isna() & cases[col].notna()
            row = int(bad.to_numpy().nonzero()[0][0]) if bad.any() else 0
            raise InputError(f"cases: {csv_path}, column {col!r}, row {row + 2}: "
                             f"{str(cases[col].iloc[row])!r} is not a number")
    if not cases["status"].isin(("ok", "failed")).all():
        bad = cases.loc[~cases["status"].isin(("ok", "failed")), "status"].iloc[0]
        raise InputError(f"cases: {csv_path}, column 'status': {bad!r} is neither 'ok' nor 'failed'")


def _check_complete(csv_path: Path, n_rows: int) -> None:
    """A ``cases.csv`` beside its campaign's manifest must hold every case of the campaign."""
    manifest = csv_path.parent / "manifest.json"
    if not manifest.is_file():
        return
    try:
        n_cases = int(json.loads(manifest.read_text())["n_cases"])
    except (OSError, ValueError, KeyError, TypeError):
        return
    if n_rows != n_cases:
        raise InputError(f"cases: {csv_path} holds {n_rows} of the {n_cases} cases of its campaign "
                         f"({manifest}); re-run `opsrock run` on the campaign to rebuild it")


def _exports(blocks: pd.DataFrame):
    from opsrock.fragility.pelicun_export import ComponentFragility, component_id

    out, skipped = [], []
    for _, r in blocks.iterrows():
        if r["success"] and math.isfinite(r["mu"]) and r["beta"] > 0:
            out.append(ComponentFragility(component_id(r["block"], r["demand"]), r["demand"], float(r["mu"]), float(r["beta"])))
        else:
            skipped.append(f"{r['block']}/{r['demand']}: {r['message']}")
    return out, skipped


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


def write_record_report(cases: pd.DataFrame, out: Path, *, n_boot: int = 200, seed: int = 0,
                        outcome: str = "as_simulated", robustness_sets: int = 0, workers: int = 1,
                        source: str = "") -> dict:
    """Run the study on ``cases`` and write every output into ``out``; returns paths and timings."""
    from opsrock.fragility.pelicun_export import write_pelicun_csv
    from opsrock.fragility.record_study import RecordStudySettings, record_fragility
    from opsrock.plots import record_fragility as rplots

    t0 = time.perf_counter()
    out.mkdir(parents=True, exist_ok=True)
    study = record_fragility(cases, RecordStudySettings(n_boot=n_boot, seed=seed, outcome=outcome), workers=workers)
    t_fit = time.perf_counter() - t0
    robust = None
    if robustness_sets:
        from opsrock.analysis.robustness import ranking_robustness

        robust = ranking_robustness(robustness_sets, seed=seed, workers=workers).shares
        atomic_csv(out / "robustness.csv", robust)
    for name in ("ims", "measure_fits", "resurrections", "sufficiency", "frequencies", "blocks"):
        atomic_csv(out / f"{name}.csv", getattr(study, name))
    comps, skipped = _exports(study.blocks)
    sliding = _sliding(cases, out, n_boot, seed, workers)
    if sliding is not None:
        from opsrock.fragility.sliding import sliding_components

        slide_comps, slide_skipped = sliding_components(sliding)
        comps, skipped = comps + slide_comps, skipped + slide_skipped
    pel = write_pelicun_csv(comps, out / "fragility_pelicun.csv")
    fig = out / "figures"
    jobs = {"ida": (rplots.plot_ida_curves, (study.cases, fig / "ida_curves.png", "scene measure (level value)")),
            "fragility": (rplots.plot_measure_fragility, (study.cases, study.measure_fits, fig / "fragility.png",
                                                          "scene measure (level value)")),
            "ranking": (rplots.plot_im_ranking, (study.ims, study.frequencies, fig / "im_ranking.png", robust))}
    if sliding is not None:
        jobs["sliding"] = (rplots.plot_sliding_fragility, (cases, sliding, fig / "sliding.png"))
    if workers > 1:  # independent figures: drawn at once
        from opsrock._pool import deferred_interrupts
        from opsrock.plots import figure_pool

        with figure_pool(min(workers, len(jobs))) as pool:
            with deferred_interrupts():
                futures = {k: pool.submit(fn, *args) for k, (fn, args) in jobs.items()}
            figs = {k: f.result() for k, f in futures.items()}
    else:
        figs = {k: fn(*args) for k, (fn, args) in jobs.items()}
    timings = {"fits_s": t_fit, "total_s": time.perf_counter() - t0}
    _write_markdown(out, study, robust, figs, skipped, timings, source, robustness_sets, sliding)
    return {"study": study, "pelicun": pel, "figures": figs, "timings": timings, "sliding": sliding}


def _sliding(cases: pd.DataFrame, out: Path, n_boot: int, seed: int, workers: int) -> pd.DataFrame | None:
    """The sliding fragilities of a campaign solved with friction (``sliding.csv``), None for another."""
    from opsrock.fragility.sliding import has_slides, sliding_table

    if not has_slides(cases):
        return None
    table = sliding_table(cases, SLIDE_DISTANCES, n_boot=n_boot, seed=seed, workers=workers)
    atomic_csv(out / "sliding.csv", table)
    return table


def _sliding_lines(sliding: pd.DataFrame, figure: str) -> list[str]:
    """The report's sliding section: one table per block, the figure."""
    lines = ["## Sliding beyond a distance", "",
             "The campaign was solved with friction: a case *slid beyond d* when its peak slide of the base on the "
             "floor (`slide_max`) exceeds d, and an overturned case counts as beyond every distance. "
             f"P(slid beyond d | demand) is fitted as a lognormal by MLE over every finished case of the block, for "
             f"d = {', '.join(f'{100 * d:g}' for d in SLIDE_DISTANCES)} cm, in PFA (m/s²) and PFV (m/s), with the "
             "same record-bootstrap intervals as above (`sliding.csv`); the fits are exported to "
             "`fragility_pelicun.csv` as `opsrock.<block>.SLIDE<d in mm>MM.<PFA|PFV>`.", ""]
    table = sliding.assign(distance_cm=100 * sliding["distance"],
                           unit=sliding["demand"].map({"pfa": "m/s2", "pfv": "m/s"}))
    cols = ["distance_cm", "demand", "unit", "median", "median_lo", "median_hi", "beta", "beta_lo", "beta_hi",
            "n_beyond", "n_cases"]
    for block, rows in table.groupby("block", sort=False):
        lines += [f"### {block}", "", markdown_table(rows[cols], ".4g"), ""]
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


def _write_markdown(out, study, robust, figs, skipped, timings, source, n_sets, sliding=None) -> None:
    s, rs = study.settings, study.resurrection_summary
    ims = study.ims[["im", "n_cases", "n_overturned", "mu", "mu_lo", "mu_hi", "beta", "beta_lo", "beta_hi", "HR",
                     "cv_percent", "loglik_per_case", "logistic_mu", "logistic_beta_equivalent", "rank_beta"]]
    lines = [
        "# Overturning fragility from floor motions", "",
        f"Cases: `{source}`; {len(study.cases)} finished cases ({study.n_failed} failed, excluded and never a "
        f"verdict), {int(study.cases['y'].sum())} overturned. Intervals: {s.n_boot} resamples of the records "
        f"(seed {s.seed}, {100 * s.confidence:.0f} %). Outcome convention of the fits: `{s.outcome}`. "
        f"Wall time {timings['total_s']:.1f} s.", "",
        *_solver_lines(source, study.cases),
        "## Conclusion", "", *_conclusion(study.ims, study.frequencies, robust), "",
        "## Resurrection", "",
        f"{rs['n_curves']} IDA curves (block x record x floor), {rs['n_curves_overturning']} overturn at some level; "
        f"**{rs['n_curves_resurrected']}** of those ({_percent(rs['share_of_overturning_curves'])}) are safe again at a "
        f"higher level ({rs['n_resurrected_cases']} resurrected cases; `resurrections.csv`). `as_simulated` counts each "
        "case's own verdict; `first_exceedance` counts a curve as overturned from its first overturning level on. "
        "The scene's measure fitted both ways:", "",
        markdown_table(study.measure_fits, ".4g") if len(study.measure_fits) else "(a cloud: no levels)", "",
        f"![IDA curves]({os.path.relpath(figs['ida'], out)})", "",
        f"![Fragility]({os.path.relpath(figs['fragility'], out)})", "",
        "## The nine IMs, ranked as the paper ranks them", "",
        "MLE (probit on ln IM, every finished case), its interval by record, the paper's HR (rocking cases) and "
        "CV = 100 beta/mu, the log-likelihood per case, and a logistic regression beside the probit:", "",
        markdown_table(ims, ".3g"), "",
        "How often each IM wins when the records are resampled:", "",
        markdown_table(study.frequencies[["im", "share_beta", "share_beta_lo", "share_beta_hi", "share_HR",
                                          "share_cv_percent"]], ".2f"), "",
        f"![IM ranking]({os.path.relpath(figs['ranking'], out)})", "",
    ]
    if robust is not None:
        lines += ["## Is the paper's ranking robust? The pulse study over block sets", "",
                  f"{n_sets} sets of four blocks (alpha uniform in 0.15-0.45 rad, R in 0.5-1.5 m, seed {s.seed}), "
                  "each on the paper's 10 x 10 one-sine grid (`housner_fast`), ranked by HR, CV and beta of the "
                  "least-squares fit at W_SAS; share of sets each IM wins, with 95 % Wilson intervals:", "",
                  markdown_table(robust[["im", "share_HR", "share_HR_lo", "share_HR_hi", "share_cv_percent",
                                         "share_beta"]], ".2f"), ""]
    lines += ["## Sufficiency", "",
              "Probit on ln IM and a standardised covariate; the covariate's coefficient, its cluster-robust standard "
              "error (records as clusters) and the two-sided p-value of the Wald test (a small p-value: the IM does "
              "not carry all the information about overturning):", "",
              markdown_table(study.sufficiency[["im", "covariate", "coefficient", "std_error", "p_value"]], ".3g")
              if len(study.sufficiency) else "(no covariate varies)", "",
              "## Per block, for loss assessment", "",
              "MLE on PFA (m/s²) and PFV (m/s) of every case of each block (all floors), interval by record; exported "
              "to `fragility_pelicun.csv` in the FEMA P-58 / pelicun damage-model form.", "",
              markdown_table(study.blocks[["block", "demand", "unit", "mu", "mu_lo", "mu_hi", "beta", "n_cases"]], ".4g"), ""]
    if skipped:
        lines += ["Not exported (no finite fit): " + "; ".join(skipped), ""]
    if sliding is not None:
        lines += _sliding_lines(sliding, os.path.relpath(figs["sliding"], out))
    atomic_text(out / "report.md", "\n".join(lines))
