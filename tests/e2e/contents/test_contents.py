"""The FEMA P-58 contents: the shipped blocks library, the study's design checks, a quick study end to end
(its files, the resume, the pelicun export's round trip), and ``opsrock contents``: its refusals of bad
input (the promise of tests/e2e/inputs/test_hostile_inputs.py: exit status 2, one line naming the argument, no
traceback, nothing written) and an interruption that loses nothing."""

from __future__ import annotations

import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pandas as pd
import pytest

from opsrock._files import read_units
from opsrock.inventory.columns import read_table as study_table
from opsrock.campaign import run_campaign
from opsrock.campaign.scene import load_blocks, load_scene
from opsrock.constants import DEFAULT_RESTITUTION_FACTOR, G
from opsrock.inventory.fema import DEFAULT_FRICTION, ContentsDesign
from opsrock.inventory.fema.columns import read_fema_table, units_of
from opsrock.inventory.run import StudyOptions, run_design
from opsrock.inventory.fema.design import DEFAULT_FRICTION_KINETIC, campaign_scenes, library_friction, quick
from opsrock.data import block_library, block_library_names
from opsrock.errors import InputError
from opsrock.fragility.pelicun_export import read_pelicun_csv
from opsrock.published import fema_p58
from _support import OPSROCK

LIBRARY = "fema-p58-contents"


def test_library_is_shipped_with_the_nine_items():
    assert LIBRARY in block_library_names()
    blocks = load_blocks(block_library(LIBRARY))
    assert [b.name for b in blocks] == [it.fema_id for it in fema_p58.ITEMS]
    for b, it in zip(blocks, fema_p58.ITEMS):
        # width = depth (the overturning direction), height = height, exactly the described inches
        assert b.width == pytest.approx(it.depth_in * 0.0254, rel=1e-12)
        assert b.height == pytest.approx(it.height_in * 0.0254, rel=1e-12)
        assert b.friction is None and b.restitution is None
        assert b.restitution_factor == DEFAULT_RESTITUTION_FACTOR
        assert it.fema_id in b.reason


def test_library_states_the_friction_the_study_assumes():
    text = block_library(LIBRARY).read_text()
    found = re.search(r"friction default: mu_s = ([\d.]+), mu_k = ([\d.]+)", text)
    assert found and (float(found.group(1)), float(found.group(2))) == library_friction() == (0.4, 0.4)
    assert (DEFAULT_FRICTION, DEFAULT_FRICTION_KINETIC) == library_friction()
    assert "ASSUMPTION" in text and "MCEER-07-0001" in text  # its source: an assumption, and why
    notes = block_library(LIBRARY).with_suffix(".md").read_text()
    assert "assumption, not a measurement" in notes and "BSD 3-Clause" in notes
    for it in fema_p58.ITEMS:  # the notes tabulate every item with its metres
        assert f"| {it.fema_id} |" in notes and f"{it.depth_in * 0.0254:.6g}" in notes


def test_a_scene_names_the_library_and_any_solver_takes_it(tmp_path):
    scene = tmp_path / "scene.toml"
    scene.write_text(f'blocks = "{LIBRARY}"\nselect = ["E.20.22.106a", "E.20.22.112a"]\n[solver]\nname = '
                     '"housner_fast"\n[grid.freq_ratio]\nvalues = [2.0]\n[grid.pfa_ratio]\nvalues = [1.5, 4.0]\n')
    s = load_scene(scene)
    assert [b.name for b in s.blocks] == ["E.20.22.106a", "E.20.22.112a"]
    summary = run_campaign(s, tmp_path / "out", workers=1, progress=False)
    assert summary.n_cases == 4 and summary.n_failed == 0


@pytest.mark.parametrize("kwargs, needle", [
    ({"variants": ("default", "rigid")}, "variants"), ({"variants": ()}, "variants"),
    ({"floors": ("ground", 9)}, "floor"), ({"floors": ("roof", 8)}, "twice"), ({"floors": ()}, "floors"),
    ({"levels": (1.0, -2.0)}, "levels"), ({"friction": 0.0}, "friction"), ({"friction": 1.5}, "friction"),
    ({"friction": True}, "friction"), ({"period": 0.0}, "period"), ({"floors": ("ground", "attic")}, "floors"),
])
def test_design_refuses_bad_input(kwargs, needle):
    with pytest.raises(InputError, match=needle):
        ContentsDesign(**{"period": 1.0, "storeys": 8, **kwargs})


@pytest.mark.usefixtures("record_library")
def test_variants_share_campaigns_by_solver():
    design = quick(ContentsDesign(period=1.0, storeys=8, items=("E.20.22.104a",)))
    scenes = campaign_scenes(design)
    assert set(scenes) == {"rocking", "friction"}
    rocking = {b.name: b for b in scenes["rocking"].blocks}
    assert rocking["E.20.22.104a-default"].restitution_factor == DEFAULT_RESTITUTION_FACTOR
    assert rocking["E.20.22.104a-housner"].restitution_factor == 1.0
    assert all(b.friction is None for b in scenes["rocking"].blocks)
    (fric,) = scenes["friction"].blocks
    assert (fric.friction, fric.friction_kinetic, scenes["friction"].solver) == (*library_friction(), "friction")
    assert scenes["rocking"].records.fingerprint() == scenes["friction"].records.fingerprint()
    (own,) = campaign_scenes(quick(ContentsDesign(period=1.0, storeys=8, items=("E.20.22.104a",), friction=0.3,
                                                  variants=("friction",))))["friction"].blocks
    assert (own.friction, own.friction_kinetic) == (0.3, 0.3)


@pytest.mark.parametrize("kwargs, needle", [
    ({"names": ("NOPE",)}, "records"), ({"names": ("NORTHR_MUL009", "NORTHR_MUL009")}, "twice"),
    ({"items": ("E.20.22.104b",)}, "items"), ({"items": ("E.20.22.104a", "E.20.22.104a")}, "twice"),
    ({"record_set": "fema-p695:mid-field"}, "record_set"), ({"record_set": "fema-p695:far-field/NORTHR_MUL009"},
                                                            "record_set"),
])
@pytest.mark.usefixtures("record_library")
def test_study_refuses_bad_records_and_items_before_writing(tmp_path, kwargs, needle):
    with pytest.raises(InputError, match=needle):
        run_design(quick(ContentsDesign(period=1.0, storeys=8, **kwargs)), tmp_path / "out",
                   StudyOptions(progress=False))
    assert not (tmp_path / "out").exists()


@pytest.fixture(scope="module")
def study(record_library, tmp_path_factory):
    out = tmp_path_factory.mktemp("contents")
    items = ("E.20.22.102a", "E.20.22.106a", "E.20.22.124a")
    design = ContentsDesign(period=1.0, storeys=8, items=items)
    first = run_design(quick(design), out, StudyOptions(workers=1, progress=False))
    ratios_text = (out / "ratios.csv").read_text()
    again = run_design(quick(design), out, StudyOptions(workers=1, progress=False))
    return out, first, again, ratios_text


def test_quick_study_writes_its_files(study):
    out, first, _, _ = study
    for name in ("report.md", "fragility.csv", "ratios.csv", "rule_reproduction.csv", "paired_variants.csv",
                 "figures/E.20.22.106a.png", "figures/fema_rule.png", "pelicun/fragility.csv", "pelicun/config.json",
                 "pelicun/mapping.csv", "pelicun/demands.csv", "pelicun/inventory.csv"):
        assert (out / name).is_file(), name
    assert first.summary.n_cases == 3 * 3 * 6 * 2 * 8 and first.summary.n_failed == 0  # items x variants x records x floors x levels
    assert first.summary.timings["friction_motions_seeded"] is True
    report = (out / "report.md").read_text()
    assert "## What drives the differences (measured)" in report and "E.20.22.124a" in report


def test_quick_study_resumes_and_repeats_itself(study):
    out, first, again, ratios_text = study
    assert again.summary.timings["rocking_computed"] == 0 and again.summary.timings["friction_computed"] == 0
    assert again.summary.ratio_range == first.summary.ratio_range
    assert (out / "ratios.csv").read_text() == ratios_text  # seeded bootstraps: the same intervals


def test_ratio_table_against_the_database(study):
    out, _, _, _ = study
    ratios = read_fema_table(out / "ratios.csv")
    header, units = read_units(out / "ratios.csv")  # the units row, each column's from its one definition
    assert units == units_of(header) and dict(zip(header, units))["median_pfv"] == "m/s"
    assert set(ratios["variant"]) == {"default", "housner", "friction"}
    assert set(ratios["floor"]) == {"ground", "f8"}
    ok = ratios.dropna(subset=["median_pfv"])
    assert list(ratios.columns[:8]) == ["item", "kind", "b_over_h", "R", "floor", "floor_number", "variant",
                                        "median_pfv"]
    assert {"fema_median_pfv", "ratio_fema", "ratio_fema_lo", "ratio_fema_hi", "rule_pfv", "ratio_rule",
            "median_pfa_g", "ratio_pfa_rule", "n_cases", "n_overturned"} <= set(ratios.columns)
    for _, r in ok.iterrows():
        it = fema_p58.item(r["item"])
        # the file keeps every digit: the ratio read back is the quotient of the medians read back
        assert r["ratio_fema"] == pytest.approx(r["median_pfv"] / it.median_mps, rel=1e-15)
        assert r["fema_median_pfv"] == it.median_mps
        assert r["median_pfv_lo"] <= r["median_pfv_hi"]
        if r["median_pfa_g"] == r["median_pfa_g"]:  # in PFA an IDA has few values: a fit may be separated
            assert r["ratio_pfa_rule"] >= 1.0  # nothing overturns before it can rock (PFA above g b/h)
    default = ratios[ratios["variant"] == "default"]
    assert default["median_pfv"].notna().all() and (default["ratio_fema"] > 1.0).all()
    # with mu = 0.4 below its b/h = 0.435 the 2-shelf bookcase slides and never overturns
    fric = ratios[(ratios["variant"] == "friction") & (ratios["item"] == "E.20.22.102a")]
    assert fric["median_pfv"].isna().all() and (fric["n_overturned"] == 0).all()


def test_pelicun_export_round_trips(study):
    # the study's one pelicun writer: each item on each floor one non-directional component (each unit once), the
    # default variant's PFV fit (one direction: the direction's own lognormal, through the writer's quantile match)
    out, _, _, _ = study
    fits = read_fema_table(out / "fragility.csv")  # every float exactly as written, on every pandas
    mapping, units = study_table(out / "pelicun" / "mapping.csv", dtype={"floor": str})
    assert units["median_ds1"] == "m/s"
    comps = {c.component_id: c for c in read_pelicun_csv(out / "pelicun" / "fragility.csv")}
    assert set(comps) == set(mapping["pelicun_id"]) and (mapping["status"] == "ok").all()
    assert (mapping["quantity"] == 1).all() and len(mapping) == 3 * 2  # three items, ground and roof
    assert (pd.read_csv(out / "pelicun" / "fragility.csv")["Demand-Directional"] == 0).all()
    for _, m in mapping.iterrows():
        number = 0 if m["floor"] == "ground" else int(m["floor"])
        f = fits[(fits["campaign"] == "rocking") & (fits["variant"] == "default") & (fits["item"] == m["fema_id"])
                 & (fits["floor_number"] == number) & (fits["demand"] == "pfv")].iloc[0]
        c = comps[m["pelicun_id"]]
        assert c.component_id == f"opsrock.{m['fema_id']}.{m['floor']}"
        # one lognormal matched at 21 of its own quantiles (brentq to 1e-12 in ln x, a least-squares line): the fit
        # itself to round-off; 1e-9 leaves that room and fails on any other curve
        assert c.median == pytest.approx(f["median"], rel=1e-9) and c.beta == pytest.approx(f["beta"], rel=1e-9)
        assert c.median == m["median_ds1"]


# --- opsrock contents on the command line ------------------------------------------------------------------
QUICK = ("contents", "--quick", "--no-progress", "--out", "out")

#: Bad input and the words its one line must hold (the first: the option's name).
REFUSED: list[tuple[tuple[str, ...], tuple[str, ...]]] = [
    (("--period", "nan"), ("--period",)), (("--storeys", "1e40"), ("--storeys",)), (("--damping", "-1"), ("--damping",)),
    (("--floors", "ground,9"), ("--floors", "9")), (("--floors", "roof,8"), ("--floors", "twice")),
    (("--floors", ""), ("--floors",)), (("--floors", "ground,attic"), ("--floors", "attic")),
    (("--records", "NOPE"), ("--records", "NOPE")), (("--record-set", "fema-p695:mid"), ("--record-set", "mid")),
    (("--items", "E.20.22.999a"), ("--items", "E.20.22.999a")), (("--items", ""), ("--items",)),
    (("--variants", "default,rigid"), ("--variants", "rigid")), (("--friction", "0"), ("--friction",)),
    (("--friction", "2"), ("--friction",)),
    (("--n-boot", "-1"), ("--n-boot",)), (("--seed", "-1"), ("--seed",)), (("--workers", "0"), ("--workers",)),
    (("--out", ""), ("--out",)), (("--store", "/dev/null"), ("--store",)),
]


def _refusal(args: tuple[str, ...], needles: tuple[str, ...], work: Path) -> str | None:
    cwd = work / str(abs(hash(args)))
    cwd.mkdir()
    cmd = [str(OPSROCK), *QUICK, *args] if OPSROCK.exists() else [sys.executable, "-m", "opsrock.cli", *QUICK, *args]
    proc = subprocess.run(cmd, check=False, cwd=cwd, capture_output=True, text=True, timeout=120)
    lines = proc.stderr.splitlines()
    problems = [p for p, bad in (
        (f"exit {proc.returncode}", proc.returncode != 2), (f"{len(lines)} stderr lines", len(lines) != 1),
        ("traceback", "Traceback" in proc.stderr), ("stdout", bool(proc.stdout)),
        (f"wrote {[p.name for p in cwd.iterdir()]}", any(cwd.iterdir())),
        (f"lacks {needles}", not lines or not all(n in lines[0] for n in needles))) if bad]
    return f"{args}: {'; '.join(problems)} | {proc.stderr.strip()[:200]}" if problems else None


@pytest.mark.usefixtures("record_library")
def test_contents_refuses_bad_input_in_one_line_and_writes_nothing(tmp_path):
    with ThreadPoolExecutor(max_workers=4) as pool:
        broken = [r for r in pool.map(lambda c: _refusal(*c, tmp_path), REFUSED) if r]
    assert not broken, "\n".join(broken)


@pytest.mark.usefixtures("record_library")
def test_contents_interrupted_keeps_its_cases_and_resumes(tmp_path, monkeypatch, capsys):
    from opsrock.cli import main
    from opsrock.inventory.fema import report

    args = ["contents", "--quick", "--items", "E.20.22.105a", "--variants", "default", "--records",
            "NORTHR_MUL009,KOBE_NIS000,HECTOR_HEC000", "--no-progress", "--no-sweep", "--workers", "1",
            "--out", str(tmp_path / "out")]

    def interrupt(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(report, "write_report", interrupt)  # Ctrl-C while the outputs are written
    assert main(args) == 130
    err = capsys.readouterr().err
    assert "interrupted" in err and "run the same command again" in err
    left = sorted(p.name for p in (tmp_path / "out").iterdir())
    assert left == ["campaigns"]  # the cases are kept; no table, figure or report half-written
    monkeypatch.undo()
    assert main(args) == 0
    out = capsys.readouterr().out
    assert re.search(r"^opsrock contents: 48 cases \(0 failed\) in [\d.]+ s; .*report\.md$", out.strip())
    assert (tmp_path / "out" / "report.md").is_file() and (tmp_path / "out" / "pelicun" / "mapping.csv").is_file()
