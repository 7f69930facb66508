"""Units that cannot silently be wrong (issue 32), through the real console script.

The table: values beyond a plausibility bound (:data:`opsrock.limits.PLAUSIBLE`: a floor motion above 10 g,
a block larger than 10 m) at every user boundary of ``simulate``, ``threshold``, ``run`` (blocks and record
files of a scene) and ``records show|plot`` on the user's file, each refused with exit 2, one line naming the
argument (or the file and field) and the unit the value looks like given the units declared, nothing written
(the promise of ``_hostile``). Then the confirmation (``--accept-implausible``, ``accept_implausible = true``)
accepted, and ``records show|plot`` on the user's own file in three formats (``.AT2`` in g, a two-column CSV in
cm/s², a one-column text in m/s² with a ``dt =`` line), checked against the closed forms of one sine cycle.
"""

from __future__ import annotations

import json
import math
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from _hostile import Case, sweep
from _support import BLOCKS, run_opsrock, without_compile_notice

from opsrock.campaign.scene import load_scene
from opsrock.constants import G
from opsrock.errors import ImplausibleInputError

SIM = ("simulate", "--width", "0.4", "--height", "2.2", "--solver", "housner_fast")
PULSE = ("--pfa", "0.5", "--freq", "1")

#: The motion of every record file here: one cycle of a 1-Hz sine of amplitude A = 0.3 g, then 1 s at rest,
#: sampled at 0.005 s.
AMPLITUDE_G, FREQ, DT = 0.3, 1.0, 0.005


def _samples() -> np.ndarray:
    t = np.arange(int(round(2.0 / DT)) + 1) * DT
    return np.where(t <= 1.0 / FREQ, AMPLITUDE_G * np.sin(2 * math.pi * FREQ * t), 0.0)


def _at2(path: Path, values_in_file: np.ndarray) -> None:
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", "Synthetic sine, 1 Hz, H1",
             "ACCELERATION TIME SERIES IN UNITS OF G", f"NPTS= {values_in_file.size}, DT= {DT:.4f} SEC"]
    lines += [" ".join(f"{v:.7E}" for v in values_in_file[i:i + 5]) for i in range(0, values_in_file.size, 5)]
    path.write_text("\n".join(lines) + "\n")


SCENE = """name = "{name}"
blocks = "{blocks}"
{extra}
[solver]
name = "housner_fast"
[records]
files = ["{record}"]
units = "{units}"
ground = true
"""

BIG_BLOCKS = """[[block]]
name = "cabinet_mm"
width = 400
height = 600
reason = "a cabinet of 400 x 600 mm, given in millimetres"
"""


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> Path:
    """The sine cycle in three formats and units; the same numbers in the wrong units; scenes of them."""
    b = tmp_path_factory.mktemp("units_inputs")
    a_g = _samples()
    t = np.arange(a_g.size) * DT
    _at2(b / "sine.AT2", a_g)
    (b / "sine_cm.csv").write_text("time,acc\n" + "\n".join(f"{ti:.3f},{100 * G * a:.6f}" for ti, a in zip(t, a_g)))
    (b / "sine_ms2.txt").write_text(f"# synthetic sine\ndt = {DT} s\n" + "\n".join(f"{G * a:.8f}" for a in a_g))
    _at2(b / "sine_cm.AT2", 100 * G * a_g)  # a header that says g over samples in cm/s²
    (b / "blocks_mm.toml").write_text(BIG_BLOCKS)
    for name, blocks, record, units, extra in (
            ("big_block", "blocks_mm.toml", "sine.AT2", "g", ""),
            ("cm_as_g", BLOCKS, "sine_cm.csv", "g", ""),
            ("cm_as_g_confirmed", BLOCKS, "sine_cm.csv", "g", "accept_implausible = true"),
            ("big_block_confirmed", "blocks_mm.toml", "sine.AT2", "g", "accept_implausible = true"),
            ("confirm_not_bool", BLOCKS, "sine.AT2", "g", 'accept_implausible = "yes"')):
        (b / f"{name}.toml").write_text(SCENE.format(name=name, blocks=blocks, record=b / record, units=units,
                                                     extra=extra))
    return b


def units_cases(b: Path) -> list[Case]:
    """Every implausible value at every boundary, refused naming the argument and the likely unit."""
    rec_g = ("--record", f"{b}/sine.AT2")
    return [
        # block sizes in millimetres
        Case("simulate --width 400 --height 600", ("simulate", "--width", "400", "--height", "600", *PULSE),
             ("--width", "400", "millimetres", "--accept-implausible")),
        Case("simulate --width 2500 (mm, beyond the limit)", ("simulate", "--width", "2500", "--height", "2.2", *PULSE),
             ("--width", "millimetres", "2.5 m")),
        Case("threshold --width 400 --height 600", ("threshold", "--width", "400", "--height", "600", "--freq", "2"),
             ("--width", "millimetres", "--accept-implausible")),
        # a pulse beyond 10 g
        Case("simulate --pfa 300 (cm/s² meant)", (*SIM, "--pfa", "300", "--freq", "1"), ("--pfa", "300", "cm/s²")),
        # record files: the values look like cm/s²
        Case("simulate cm/s² file declared g", (*SIM, "--record", f"{b}/sine_cm.csv", "--units", "g"),
             ("--record", "sine_cm.csv", "cm/s² declared as g", "--units cm/s2", "--accept-implausible")),
        Case("simulate cm/s² file declared m/s2", (*SIM, "--record", f"{b}/sine_cm.csv", "--units", "m/s2"),
             ("--record", "sine_cm.csv", "cm/s² declared as m/s²", "--units cm/s2")),
        Case("simulate .AT2 header g over cm/s²", (*SIM, "--record", f"{b}/sine_cm.AT2"),
             ("sine_cm.AT2", "cm/s²", "header")),
        Case("simulate --vertical-record cm/s² declared g", (*SIM[:5], "--friction", "0.5", *rec_g, "--units", "g",
                                                            "--vertical-record", f"{b}/sine_cm.csv"),
             ("--vertical-record", "sine_cm.csv", "cm/s² declared as g")),
        Case("records show cm/s² file declared g", ("records", "show", f"{b}/sine_cm.csv", "--units", "g"),
             ("sine_cm.csv", "cm/s² declared as g", "--units cm/s2")),
        Case("records plot cm/s² file declared g", ("records", "plot", f"{b}/sine_cm.csv", "--units", "g", "--out",
                                                    "r.png"), ("sine_cm.csv", "--units cm/s2")),
        Case("records show --units on a library record", ("records", "show", "fema-p695:far-field/NORTHR_MUL009",
                                                          "--units", "g"), ("--units", "library")),
        Case("records show dt line against --dt", ("records", "show", f"{b}/sine_ms2.txt", "--units", "m/s2", "--dt",
                                                   "0.01"), ("sine_ms2.txt", "dt", "0.01")),
        # scenes: blocks files and [records] files; the confirming key must be a bool
        Case("run a 400-m block", ("run", f"{b}/big_block.toml", "--out", "out"),
             ("blocks_mm.toml", "block[0].width", "millimetres", "accept_implausible = true")),
        Case("run cm/s² records declared g", ("run", f"{b}/cm_as_g.toml", "--out", "out"),
             ("cm_as_g.toml", "records.files", "sine_cm.csv", "records.units = cm/s2", "accept_implausible")),
        Case("run accept_implausible not a bool", ("run", f"{b}/confirm_not_bool.toml", "--out", "out"),
             ("accept_implausible", "yes")),
    ]


def test_implausible_units_are_refused(files, tmp_path):
    # every other case; the others behind slow (make test under 10 minutes)
    broken = sweep(units_cases(files)[0::2], tmp_path, workers=4, timeout=60)
    assert not broken, "\n".join(broken)


@pytest.mark.slow
def test_the_other_implausible_units_are_refused(files, tmp_path):
    broken = sweep(units_cases(files)[1::2], tmp_path, workers=4, timeout=60)
    assert not broken, "\n".join(broken)


def test_units_case_counts(files):
    counts = Counter(c.args[0] for c in units_cases(files))
    assert counts == {"simulate": 7, "threshold": 1, "records": 4, "run": 3}, counts


# --- the confirmation accepted ------------------------------------------------------------------------
def test_accept_implausible_runs_what_it_confirms(files, tmp_path):
    """The option confirms: the 400 x 600 m block runs (and is reported in metres), the cm/s² file declared g
    is shown at 100 g times its true PFA."""
    sim = run_opsrock(("simulate", "--width", "400", "--height", "600", *PULSE, "--solver", "housner_fast",
                       "--accept-implausible", "--json"), tmp_path)
    assert sim.returncode == 0 and not without_compile_notice(sim.stderr), sim.stderr
    assert json.loads(sim.stdout)["R"] == pytest.approx(math.hypot(200, 300), rel=1e-12)
    show = run_opsrock(("records", "show", f"{files}/sine_cm.csv", "--units", "g", "--accept-implausible", "--json"),
                       tmp_path)
    assert show.returncode == 0 and not show.stderr, show.stderr
    # the file's numbers are 100 G A (cm/s²); read as g they are 100 G A g = 100 G² A m/s²
    assert json.loads(show.stdout)["pfa"] == pytest.approx(100 * G * G * AMPLITUDE_G, rel=1e-6)


def test_scene_key_and_argument_confirm(files):
    """``accept_implausible = true`` in the scene, or ``load_scene(..., accept_implausible=True)`` (what ``run
    --accept-implausible`` passes), loads what the plain scene refuses."""
    for name in ("big_block", "cm_as_g"):
        with pytest.raises(ImplausibleInputError):
            load_scene(files / f"{name}.toml")
        assert load_scene(files / f"{name}.toml", accept_implausible=True).n_cases == \
            load_scene(files / f"{name}_confirmed.toml").n_cases
    assert load_scene(files / "big_block_confirmed.toml").blocks[0].width == 400.0


# --- records show | plot on the user's own file ---------------------------------------------------------
FORMATS = (("sine.AT2",), ("sine_cm.csv", "--units", "cm/s2"), ("sine_ms2.txt", "--units", "m/s2"))


def test_records_show_on_three_formats(files, tmp_path):
    """The same sine cycle in three formats gives the same measures, against the closed forms: PFA = A (to
    the written decimals); PFV = 2 A / omega, the peak of v = (A / omega)(1 - cos omega t), with no residual
    velocity to correct (trapezoidal integration at omega dt = 0.031 is exact to (omega dt)² / 12 = 8e-5:
    rtol 1e-3); the 5 %-damped PSA at 0.05 s, an oscillator 20 times stiffer than the motion (r = T / T_p =
    0.05), within r + r² = 5.3 % of PFA: the quasi-static response A / (1 - r²) plus the free vibration the
    jumps of the ground's jerk at the cycle's start and end excite, of amplitude at most r A (measured 1.1 %)."""
    a = AMPLITUDE_G * G
    for fmt in FORMATS:
        proc = run_opsrock(("records", "show", f"{files}/{fmt[0]}", *fmt[1:], "--json"), tmp_path)
        assert proc.returncode == 0 and not proc.stderr, proc.stderr
        out = json.loads(proc.stdout)
        assert out["pfa"] == pytest.approx(a, rel=1e-6) and out["pfa_g"] == pytest.approx(AMPLITUDE_G, rel=1e-6)
        assert out["pfv"] == pytest.approx(2 * a / (2 * math.pi * FREQ), rel=1e-3)
        assert out["dt"] == pytest.approx(DT, rel=1e-9) and out["duration"] == pytest.approx(2.0, rel=1e-9)
        spec = out["spectrum"]
        assert spec["damping"] == 0.05 and spec["period"][0] == 0.05
        assert spec["psa"][0] == pytest.approx(a, rel=0.053)
    text = run_opsrock(("records", "show", f"{files}/sine_cm.csv", "--units", "cm/s2"), tmp_path)
    assert text.returncode == 0 and "m/s²" in text.stdout and "PSA g" in text.stdout, text.stdout


@pytest.mark.parametrize("fmt", [FORMATS[1], *(pytest.param(f, marks=pytest.mark.slow) for f in FORMATS[::2])],
                         ids=lambda f: f[0])
def test_records_plot_on_three_formats(files, tmp_path, fmt):
    """A figure of the user's file in each format (the CSV in make test; the drawing is the same for all, the
    reading is checked by ``show`` above)."""
    out = tmp_path / "r.png"
    proc = run_opsrock(("records", "plot", f"{files}/{fmt[0]}", *fmt[1:], "--out", str(out)), tmp_path)
    assert proc.returncode == 0 and not proc.stderr, proc.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
