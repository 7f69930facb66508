"""The motions manifest (opsrock.inventory.motions): the shipped example reads in all its formats, one motion
written in four formats reads to the same record, the dt of a header line is used, and every bad row is
refused with one line naming the manifest, its line, the column and the value."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from _support import ROOT

from opsrock.constants import G
from opsrock.excitations.records import UNITS
from opsrock.data import example_motions_manifest
from opsrock.errors import ImplausibleInputError, InputError
from opsrock.inventory.motions import FloorMotion, MotionSet, header_dt, motion_name, read_motions
from opsrock.inventory.readers import TableFileError

#: One motion (m/s²), 0.01 s apart: 2 s of a 2-Hz sine of 3 m/s², the values of every file below.
DT = 0.01
ACC = [round(3.0 * float(np.sin(2 * np.pi * 2.0 * k * DT)), 6) for k in range(201)]


@pytest.fixture
def files(tmp_path: Path) -> Path:
    """The motion of :data:`ACC` in every format the manifest reads, in ``tmp_path/rec``."""
    rec = tmp_path / "rec"
    rec.mkdir()
    g = np.array(ACC) / G
    body = "\n".join(" ".join(f"{v:.9E}" for v in g[k:k + 4]) for k in range(0, g.size, 4))
    (rec / "a.AT2").write_text(f"title\nevent, station, comp\nACCELERATION TIME SERIES IN UNITS OF G\n"
                               f"NPTS= {g.size}, DT= {DT} SEC\n{body}\n")
    (rec / "b.txt").write_text(f"# a floor\n# dt = {DT} s\n" + "\n".join(f"{v!r}" for v in ACC) + "\n")
    (rec / "c.txt").write_text("\n".join(f"{v!r}" for v in ACC) + "\n")
    (rec / "d.csv").write_text("time,acc\n" + "\n".join(f"{k * DT:.2f},{v * 100!r}" for k, v in enumerate(ACC)) + "\n")
    (rec / "e.txt").write_text("\n".join(f"{v * 100!r}" for v in ACC) + "\n")  # cm/s²: PFA 300, looks like 30 g
    return tmp_path


def _manifest(folder: Path, rows: str, header: str = "record,floor,direction,file,units,dt") -> Path:
    path = folder / "motions.csv"
    path.write_text(f"{header}\n{rows}")
    return path


def test_the_example_motions_read_in_every_format():
    motions = read_motions(example_motions_manifest())
    assert len(motions.motions) == 30
    assert motions.floors == ("1", "2", "3") and motions.directions == ("1", "2")
    assert motions.records == ("northridge", "superstition", "kocaeli", "san_fernando", "landers")
    units = {m.motion.info.units_in_file for m in motions.motions}
    suffixes = {Path(m.motion.info.source).suffix for m in motions.motions}
    assert units == {"g", "m/s2", "cm/s2"} and suffixes == {".AT2", ".txt", ".csv"}
    for m in motions.motions:
        assert m.motion.name == motion_name(*m.key) and m.motion.info.floor == m.floor
        assert m.motion.dt == pytest.approx(0.02, rel=1e-9) and 0.15 * G < m.motion.pfa < 2.0 * G
    # the roof of every record shakes more than floor 1 in direction 1 (a shear building's first mode)
    for r in motions.records:
        assert motions.motion(r, "3", "1").motion.pfa > motions.motion(r, "1", "1").motion.pfa
    assert len(motions.select(floor="2")) == 10 and len(motions.select(direction="1", floor="3")) == 5


def test_one_motion_in_four_formats_reads_the_same(files):
    path = _manifest(files, "r,1,1,rec/a.AT2,,\nr,2,1,rec/b.txt,m/s2,\nr,3,1,rec/c.txt,m/s2,0.01\n"
                            "r,4,1,rec/d.csv,cm/s2,\nr,5,2,rec/a.AT2,g,\n")
    motions = read_motions(path)
    for m in motions.motions:
        assert m.motion.dt == pytest.approx(DT, rel=1e-9) and m.motion.values.size == len(ACC)
        # AT2 in g with 10 significant digits, times G: the samples to 1e-9 relative; the others are exact
        # decimal texts of the same values (cm/s² scaled back by 0.01)
        np.testing.assert_allclose(m.motion.values, ACC, rtol=1e-9, atol=1e-12)
    assert [m.motion.name for m in motions.motions] == ["r@1@1", "r@2@1", "r@3@1", "r@4@1", "r@5@2"]


def test_a_header_line_states_dt(files):
    assert header_dt(files / "rec" / "b.txt") == DT
    assert header_dt(files / "rec" / "c.txt") is None
    assert header_dt(files / "rec" / "d.csv") is None  # two columns: the time column rules
    assert header_dt(files / "rec" / "a.AT2") is None


def test_motion_sets_refuse_a_key_twice():
    rec = read_motions(example_motions_manifest()).motions[0]
    with pytest.raises(InputError, match="record 'northridge', floor '1', direction '1' appears twice"):
        MotionSet((rec, FloorMotion(rec.record, rec.floor, rec.direction, rec.motion)), "code")


BAD_ROWS = [
    ("r,1,X,rec/c.txt,m/s2,0.01\n", 2, "direction = 'X': must be 1 or 2"),
    ("r,1,3,rec/c.txt,m/s2,0.01\n", 2, "direction = '3': must be 1 or 2"),
    ("r,1,1,rec/c.txt,m/s²,0.01\n", 2, "units = 'm/s²': must be one of g, m/s2, cm/s2"),
    ("r,1,1,rec/c.txt,,0.01\n", 2, "units: blank, and c.txt is a text/CSV file"),
    ("r,1,1,rec/c.txt,m/s2,\n", 2, "file = 'rec/c.txt': " + "{rec}/c.txt: one-column record: give its time step dt"),
    ("r,1,1,rec/c.txt,m/s2,fast\n", 2, "dt = 'fast': is not a number"),
    ("r,1,1,rec/c.txt,m/s2,2\n", 2, "dt = '2': dt must lie in [1e-07, 1] s"),
    ("r,1,1,rec/b.txt,m/s2,0.02\n", 2, "dt = '0.02': but b.txt states dt = 0.01 s in its header"),
    ("r,1,1,rec/d.csv,cm/s2,0.01\n", 2, "file = 'rec/d.csv': {rec}/d.csv: dt = 0.01 given, but the file has a time"),
    ("r,1,1,rec/a.AT2,m/s2,\n", 2, "file = 'rec/a.AT2': {rec}/a.AT2:3: the header says units of g"),
    ("r,1,1,rec/nope.txt,m/s2,0.01\n", 2, "file = 'rec/nope.txt': {rec}/nope.txt: no such file"),
    ("r,1,1,rec,m/s2,0.01\n", 2, "file = 'rec': {rec}: is a folder"),
    ("r 1,1,1,rec/c.txt,m/s2,0.01\n", 2, "record = 'r 1': must use only letters"),
    ("r,1@2,1,rec/c.txt,m/s2,0.01\n", 2, "floor = '1@2': must use only letters"),
    (",1,1,rec/c.txt,m/s2,0.01\n", 2, "record: blank: every motion needs it"),
    ("r,1,1,rec/c.txt,m/s2,0.01\n# c\nr,1,1,rec/b.txt,m/s2,\n", 4,
     "record = 'r': floor '1', direction '1' listed twice (first on line 2)"),
    ("r,1,1,rec/c.txt,m/s2,0.01,9\n", 2, "7 cells where the header names 6 columns"),
]


@pytest.mark.parametrize("rows, line, needle", BAD_ROWS, ids=[n.split(":")[0] for _, _, n in BAD_ROWS])
def test_a_bad_row_is_refused_naming_the_manifest_line(files, rows, line, needle):
    path = _manifest(files, rows)
    with pytest.raises(TableFileError) as err:
        read_motions(path)
    message = str(err.value)
    assert message.startswith(f"{path}:{line}: ") and "\n" not in message
    assert needle.format(rec=files / "rec") in message, message


@pytest.mark.parametrize("header, needle", [
    ("record,floor,direction,file,units,dt,scale", "'scale': unknown column (known: record, floor,"),
    ("record,floor,file,units,dt", "lacks the column(s) direction"),
])
def test_a_bad_manifest_header_is_refused(files, header, needle):
    path = _manifest(files, "r,1,1,rec/c.txt,m/s2,0.01\n", header)
    with pytest.raises(TableFileError) as err:
        read_motions(path)
    assert str(err.value).startswith(f"{path}:1: header = ") and needle in str(err.value), str(err.value)


def test_an_empty_manifest_is_refused(tmp_path):
    path = tmp_path / "m.csv"
    path.write_text("# nothing\n")
    with pytest.raises(TableFileError, match="empty file: no header row"):
        read_motions(path)


def test_a_cm_file_declared_in_metres_is_refused_with_its_likely_unit(files):
    path = _manifest(files, "r,1,1,rec/e.txt,m/s2,0.01\n")
    peak = max(abs(v) for v in ACC)  # 2.994 m/s² (the samples miss the sine's crest)
    with pytest.raises(ImplausibleInputError, match=rf"^{path} line 2 \(rec/e.txt\): PFA = 299.4 m/s² exceeds 98.1 "
                                                    r"m/s².*look like cm/s² declared as m/s².*give the units column cm/s2.*--accept-implausible"):
        read_motions(path)
    assert read_motions(path, confirm=True).motions[0].motion.pfa == pytest.approx(100 * peak, rel=1e-12)
    assert read_motions(_manifest(files, "r,1,1,rec/e.txt,cm/s2,0.01\n")).motions[0].motion.pfa == pytest.approx(peak)


@pytest.mark.slow
def test_the_example_motions_are_what_the_tool_writes():
    # regenerates the 30 files (OpenSees, about 6 s) and compares bytes with the committed ones
    proc = subprocess.run([sys.executable, "tools/make_example_motions.py", "--check"], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_column_picks_one_acceleration_of_a_file_of_several(tmp_path):
    """Issue 44: ``time,ax,ay`` by header name or 1-based index, and OpenSees' Node recorder output with
    ``-time`` (no header, white space: the time, then one column per node and dof), each read exactly."""
    from opsrock.inventory.motions import read_motions

    t = np.arange(0.0, 1.0, 0.01)
    ax, ay = np.sin(7.0 * t), 0.5 * np.cos(3.0 * t)
    np.savetxt(tmp_path / "txy.csv", np.c_[t, ax, ay], delimiter=",", header="time,ax,ay", comments="")
    np.savetxt(tmp_path / "node.out", np.c_[t, ax, 0.0 * t, ay])  # nodes 2 and 3, dof 1
    (tmp_path / "m.csv").write_text("record,floor,direction,file,units,column,location\n"
                                    "r,L1,1,txy.csv,m/s2,AX,1\nr,L1,2,txy.csv,m/s2,3,1\n"
                                    "r,L2,1,node.out,g,2,2\nr,L2,2,node.out,g,4,2\n")
    m = read_motions(tmp_path / "m.csv")
    assert m.locations == (("L1", 1), ("L2", 2))
    got = {mm.key: mm.motion for mm in m.motions}
    np.testing.assert_allclose(got[("r", "L1", "1")].values, ax, rtol=1e-15)
    np.testing.assert_allclose(got[("r", "L1", "2")].values, ay, rtol=1e-15)
    np.testing.assert_allclose(got[("r", "L2", "2")].values, UNITS["g"] * ay, rtol=1e-12)  # g to m/s2
    assert got[("r", "L2", "1")].dt == pytest.approx(0.01, rel=1e-12)
