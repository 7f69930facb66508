"""The options of a box in three dimensions (issue 33: ``--depth``, ``--record2``, ``--azimuth``) through the
real console script: each bad value refused with exit 2 and one line naming the option (the promise of
``_hostile``), on ``simulate`` and on ``contents --solver rigid3d``: a depth given in millimetres (refused with its likely unit), zero or not a number; an azimuth
not an angle in [-360, 360] deg; a second record that is missing or meets a pulse; a planar solver given a
depth (refused: it would ignore it), a second component or a turned block; the solver in plan without a
depth or with another impact than Housner's."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest
from _hostile import Case, one_per_option, sweep

SIM = ("simulate", "--width", "0.4", "--height", "1.6")
PULSE = ("--pfa-ratio", "3", "--freq-ratio", "3")


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> Path:
    """A one-column record file in g at 0.01 s (1 s of 0.1 g), a manifest of it in direction 1 only and one in
    both directions, and a one-item inventory."""
    base = tmp_path_factory.mktemp("three_d_inputs")
    (base / "one.txt").write_text("0.1\n" * 100)
    (base / "half.txt").write_text("0.1\n" * 50)
    (base / "d1.csv").write_text("record,floor,direction,file,units,dt\nr,1,1,one.txt,g,0.01\n")
    (base / "d12.csv").write_text("record,floor,direction,file,units,dt\nr,1,1,one.txt,g,0.01\nr,1,2,one.txt,g,0.01\n")
    (base / "inv.csv").write_text("id,description,width,depth,height\ncab,a cabinet,0.4,0.6,1.2\n")
    return base


def three_d_cases(b: Path) -> list[Case]:
    """Bad plan options of ``simulate``."""
    rec = ("--record", f"{b}/one.txt", "--units", "g", "--dt", "0.01")
    cases = [Case(f"simulate --depth {v!r}", (*SIM, *PULSE, "--depth", v), ("--depth",) + extra)
             for v, extra in (("400", ("millimetres", "0.4")), ("0", ()), ("-0.5", ()), ("nan", ()), ("inf", ()),
                              ("deep", ()))]
    cases += [Case(f"simulate --azimuth {v!r}", (*SIM, *PULSE, "--depth", "0.6", "--azimuth", v), ("--azimuth",))
              for v in ("nan", "1e9", "-inf", "360.5", "north", "")]
    cases += [
        Case("simulate --record2 missing", (*SIM, *rec, "--depth", "0.6", "--record2", f"{b}/nope.txt"),
             ("--record2", "nope.txt")),
        Case("simulate --record2 shorter", (*SIM, *rec, "--depth", "0.6", "--record2", f"{b}/half.txt"),
             ("--record2", "50 samples", "100")),
        Case("simulate --record2 with-a-pulse", (*SIM, *PULSE, "--depth", "0.6", "--record2", f"{b}/one.txt"),
             ("--record2", "--record only")),
        Case("simulate planar --depth", (*SIM, *PULSE, "--depth", "0.6", "--solver", "housner_fast"),
             ("--depth", "housner_fast", "ignore")),
        Case("simulate planar --azimuth", (*SIM, *PULSE, "--azimuth", "30", "--solver", "friction"),
             ("--azimuth 30", "friction", "rigid3d")),
        Case("simulate planar --record2", (*SIM, *rec, "--record2", f"{b}/one.txt", "--solver",
                                                         "opensees"), ("--record2", "opensees", "rigid3d")),
        Case("simulate rigid3d no-depth", (*SIM, *PULSE, "--solver", "rigid3d"), ("--depth", "rigid3d")),
        Case("simulate rigid3d azimuth-without-depth", (*SIM, *PULSE, "--azimuth", "45"), ("--depth", "rigid3d")),
        Case("simulate rigid3d restitution-law", (*SIM, *PULSE, "--depth", "0.6", "--restitution-law",
                                                           "paper"), ("--restitution-law paper", "Housner")),
    ]
    inv = ("contents", "--inventory", f"{b}/inv.csv", "--out", "out")
    cases += [
        Case("contents rigid3d one-direction", (*inv, "--motions", f"{b}/d1.csv", "--solver", "rigid3d"),
             ("--motions", "direction 1 only")),
        Case("contents rigid3d azimuths-without-solver", (*inv, "--motions", f"{b}/d12.csv", "--azimuths", "0,45"),
             ("--azimuths", "rigid3d")),
        Case("contents rigid3d azimuths-nan", (*inv, "--motions", f"{b}/d12.csv", "--solver", "rigid3d", "--azimuths",
                                               "0,nan"), ("--azimuths",)),
        Case("contents rigid3d azimuths-400", (*inv, "--motions", f"{b}/d12.csv", "--solver", "rigid3d", "--azimuths",
                                               "400"), ("--azimuths", "400")),
        Case("contents rigid3d solver-unknown", (*inv, "--motions", f"{b}/d12.csv", "--solver", "rigid4d"),
             ("--solver", "rigid4d")),
    ]
    return cases


def test_three_d_case_counts(files):
    counts = Counter(c.name.rsplit(" ", 1)[0] for c in three_d_cases(files))
    assert counts == {"simulate --depth": 6, "simulate --azimuth": 6, "simulate --record2": 3, "simulate planar": 3,
                      "simulate rigid3d": 3, "contents rigid3d": 5}, counts


def test_bad_plan_options_are_refused_in_one_line(files, tmp_path):
    quick, _ = one_per_option(three_d_cases(files))
    assert len(quick) == 6  # one per group: about 1.5 s of start-up each, in make test
    assert sweep(quick, tmp_path) == []


@pytest.mark.slow
def test_every_bad_plan_option_is_refused_in_one_line(files, tmp_path):
    _, rest = one_per_option(three_d_cases(files))
    assert sweep(rest, tmp_path) == []
