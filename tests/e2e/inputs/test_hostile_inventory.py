"""Hostile inventories and motion manifests through the real console script (issue 32, area "inventory"):
``opsrock contents --inventory FILE --motions FILE --out DIR`` refuses each with exit 2 and one line naming
the file, its line, the column and the value, writing nothing (the promise of :mod:`_hostile`).

The readers are :mod:`opsrock.inventory.items` and :mod:`opsrock.inventory.motions`; their refusals are also
tested in-process (``tests/model/inventory/``).
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest
from _hostile import Case, sweep
from _support import run_opsrock


HEADER = "id,description,width,depth,height,friction,floor"
GOOD_ROW = "box,a box,0.4,0.5,1.0,0.5,1"
MANIFEST = "record,floor,direction,file,units,dt"
GOOD_MOTION = "r1,1,1,floor.txt,m/s2,0.01"


@pytest.fixture(scope="module")
def inputs(tmp_path_factory) -> Path:
    """A folder of inventories and manifests, each broken in one way (and one good of each), with a short
    floor motion in m/s² (``floor.txt``) and the same values declared too large (``floor_cm.txt``)."""
    base = tmp_path_factory.mktemp("inventory_inputs")
    motion = "\n".join(f"{0.5 * ((k % 20) - 10) / 10:.3f}" for k in range(1000))
    (base / "floor.txt").write_text(motion + "\n")
    rows = [f"{0.01 * k:.2f},{0.5 * ((k % 20) - 10) / 10:.3f},{0.3 * ((k % 16) - 8) / 8:.3f}" for k in range(1000)]
    (base / "txy.csv").write_text("time,ax,ay\n" + "\n".join(rows) + "\n")  # the structural engineer's file
    (base / "floor_cm.txt").write_text("\n".join(f"{float(v) * 10000:g}" for v in motion.split()) + "\n")
    files = {
        "good.csv": f"{HEADER}\n{GOOD_ROW}\n",
        "colour.csv": f"{HEADER},colour\n{GOOD_ROW},red\n",
        "word.csv": f"{HEADER}\n# a comment\nbox,a box,abc,0.5,1.0,0.5,1\n",
        "twice.csv": f"{HEADER}\n{GOOD_ROW}\n{GOOD_ROW}\n",
        "mm.csv": f"{HEADER}\nbox,a box,400,500,1000,0.5,1\n",
        "weibull.csv": f"{HEADER}\nbox,a box,0.4,0.5,1.0,\"weibull(1, 2)\",1\n",
        "wide.csv": f"{HEADER}\nbox,a box,0.4,0.5,1.0,\"normal(0.1, 0.2)\",1\n",
        "cm.csv": "id,description,width,depth,height,cm_height\nbox,a box,0.4,0.5,1.0,1.5\n",
        "floor4.csv": f"{HEADER}\nbox,a box,0.4,0.5,1.0,0.5,4\n",
        "empty.csv": "# nothing but a comment\n",
        "key.toml": "[[item]]\nid = 'box'\ndescription = 'a box'\nwidth = 0.4\ndepth = 0.5\nheight = 1.0\ncolour = 'red'\n",
        "good_motions.csv": f"{MANIFEST}\n{GOOD_MOTION}\n",
        "nofile.csv": f"{MANIFEST}\n{GOOD_MOTION}\nr2,1,1,nope.txt,m/s2,0.01\n",
        "cm_motions.csv": f"{MANIFEST}\nr1,1,1,floor_cm.txt,m/s2,0.01\n",
        "xy.csv": f"{MANIFEST}\nr1,1,X,floor.txt,m/s2,0.01\n",
        "nounits.csv": f"{MANIFEST}\nr1,1,1,floor.txt,,0.01\n",
        "dup_motions.csv": f"{MANIFEST}\n{GOOD_MOTION}\n{GOOD_MOTION}\n",
        "scale.csv": f"{MANIFEST},scale\n{GOOD_MOTION},2\n",
        # issue 44: a file of several columns, addressed by the manifest's column; floors' pelicun locations
        "nocolumn.csv": f"{MANIFEST}\nr1,1,1,txy.csv,m/s2,\n",
        "badcolumn.csv": f"{MANIFEST},column\nr1,1,1,txy.csv,m/s2,,az\n",
        "column9.csv": f"{MANIFEST},column\nr1,1,1,txy.csv,m/s2,,9\n",
        "timecolumn.csv": f"{MANIFEST},column\nr1,1,1,txy.csv,m/s2,,1\n",
        "location0.csv": f"{MANIFEST},column,location\nr1,1,1,txy.csv,m/s2,,ax,0\n",
        "location2.csv": f"{MANIFEST},column,location\nr1,1,1,txy.csv,m/s2,,ax,1\nr1,1,2,txy.csv,m/s2,,ay,2\n",
        "locationblank.csv": f"{MANIFEST},column,location\nr1,1,1,txy.csv,m/s2,,ax,1\nr1,1,2,txy.csv,m/s2,,ay,\n",
        "samelocation.csv": f"{MANIFEST},column,location\nr1,1,1,txy.csv,m/s2,,ax,1\nr1,2,1,txy.csv,m/s2,,ay,1\n",
        # issue 46: accepted silently before (float() reads any Unicode digit; a NUL is a character to csv)
        "arabic.csv": f"{HEADER}\nbox,a box,\u0660.\u0664,0.5,1.0,0.5,1\n",
        "fullwidth.csv": f"{HEADER}\nbox,a box,0.4,0.5,1.0,\uff10.\uff14,1\n",
        "nul.csv": f"{HEADER}\nbox,a b\x00ox,0.4,0.5,1.0,0.5,1\n",
        "fraction.toml": "[[item]]\nid = 'box'\ndescription = 'a box'\nwidth = 0.4\ndepth = 0.5\nheight = 1.0\n"
                         "quantity = 1.5\n",
        "huge.toml": "[[item]]\nid = 'box'\ndescription = 'a box'\nwidth = 0.4\ndepth = 0.5\nheight = 1.0\n"
                     "quantity = 99999999999999999999\n",
        "denormal.csv": f"{HEADER}\nbox,a box,0.4,0.5,1.0,\"lognormal(0.4, 1e-320)\",1\n",
    }
    for name, text in files.items():
        (base / name).write_text(text)
    return base


def inventory_cases(b: Path) -> list[Case]:
    """Each broken inventory (with good motions) and each broken manifest (with a good inventory)."""
    def inv(name: str, needles: tuple[str, ...]) -> Case:
        return Case(f"inventory {name}", ("contents", "--inventory", f"{b}/{name}", "--motions",
                                          f"{b}/good_motions.csv", "--out", "out"), needles)

    def mot(name: str, needles: tuple[str, ...]) -> Case:
        return Case(f"motions {name}", ("contents", "--inventory", f"{b}/good.csv", "--motions", f"{b}/{name}",
                                        "--out", "out"), needles)

    return [
        inv("colour.csv", ("colour.csv:1", "header = 'colour'", "unknown column")),
        inv("word.csv", ("word.csv:3", "width = 'abc'", "not a number")),
        inv("twice.csv", ("twice.csv:3", "id = 'box'", "used twice")),
        inv("mm.csv", ("mm.csv line 2: width", "400", "mm", "--accept-implausible")),
        inv("weibull.csv", ("weibull.csv:2", "friction", "weibull")),
        inv("wide.csv", ("wide.csv:2", "friction", "normal(0.1, 0.2)", "outside")),
        inv("cm.csv", ("cm.csv:2", "cm_height = '1.5'")),
        inv("floor4.csv", ("floor", "'4'")),
        inv("empty.csv", ("empty.csv", "empty file")),
        inv("missing.csv", ("missing.csv", "no such file")),
        inv("key.toml", ("key.toml:7", "colour", "unknown key")),
        inv("arabic.csv", ("arabic.csv:2", "width = '\u0660.\u0664'", "not a number")),
        inv("fullwidth.csv", ("fullwidth.csv:2", "friction", "neither a number")),
        inv("nul.csv", ("nul.csv:2", "description", "U+0000")),
        inv("fraction.toml", ("fraction.toml:7", "quantity = 1.5", "whole number")),
        inv("huge.toml", ("huge.toml:7", "quantity", "1000000")),
        inv("denormal.csv", ("denormal.csv:2", "friction", "1e-320", "below 0.001")),
        Case("inventory --levels-with-cloud", ("contents", "--inventory", f"{b}/good.csv", "--motions",
                                               f"{b}/good_motions.csv", "--method", "cloud", "--levels", "2,4",
                                               "--out", "out"), ("--levels 2,4", "--method cloud")),
        mot("nofile.csv", ("nofile.csv:3", "file = 'nope.txt'", "no such file")),
        mot("cm_motions.csv", ("cm_motions.csv line 2 (floor_cm.txt): PFA", "cm/s²", "--accept-implausible")),
        mot("xy.csv", ("xy.csv:2", "direction = 'X'")),
        mot("nounits.csv", ("nounits.csv:2", "units")),
        mot("dup_motions.csv", ("dup_motions.csv:3", "listed twice")),
        mot("scale.csv", ("scale.csv:1", "header = 'scale'", "unknown column")),
        mot("missing.csv", ("missing.csv", "no such file")),
        mot("nocolumn.csv", ("nocolumn.csv:2", "3 columns (time, ax, ay)", "manifest's column 'column'")),
        mot("badcolumn.csv", ("badcolumn.csv:2", "column = 'az'", "time, ax, ay")),
        mot("column9.csv", ("column9.csv:2", "column = '9'", "3 columns")),
        mot("timecolumn.csv", ("timecolumn.csv:2", "column = '1'", "the time")),
        mot("location0.csv", ("location0.csv:2", "location = '0'", "whole number >= 1")),
        mot("location2.csv", ("location2.csv:3", "location = '2'", "floor '1' is at location 1")),
        mot("locationblank.csv", ("locationblank.csv:3", "location", "blank while other rows give one")),
        mot("samelocation.csv", ("samelocation.csv:3", "location = '1'", "floor '1' is at location 1 already")),
    ]


#: Cases whose kind of refusal another case already shows in make test (an unknown column, a bad friction
#: distribution, a missing file, a repeated row, an empty file): behind ``slow``, to keep make test's budget
#: (each case is one start of the console script, about 0.7 s of CPU).
SECOND = {"inventory wide.csv", "inventory empty.csv", "motions scale.csv", "motions missing.csv",
          "motions dup_motions.csv", "inventory fullwidth.csv", "inventory huge.toml", "motions column9.csv",
          "motions timecolumn.csv", "motions location0.csv", "motions samelocation.csv"}


def test_hostile_inventories_and_manifests_are_refused(inputs, tmp_path):
    cases = [c for c in inventory_cases(inputs) if c.name not in SECOND]
    broken = sweep(cases, tmp_path, workers=4, timeout=120)
    assert not broken, "\n".join(broken)


@pytest.mark.slow
def test_more_hostile_inventories_and_manifests_are_refused(inputs, tmp_path):
    cases = [c for c in inventory_cases(inputs) if c.name in SECOND]
    assert len(cases) == len(SECOND)
    broken = sweep(cases, tmp_path, workers=4, timeout=120)
    assert not broken, "\n".join(broken)


def test_inventory_case_counts(inputs):
    counts = Counter(c.name.split()[0] for c in inventory_cases(inputs))
    assert counts == {"inventory": 18, "motions": 15}, counts
