"""Hostile input to ``opsrock directionality`` and ``opsrock contents --model both`` (one route of the contents
study; the first is the second's alias), through the real console script: the promise of the README
(:mod:`_hostile`): one line naming the option, exit 2, nothing written, before any work."""

from __future__ import annotations

from collections import Counter

from _hostile import Case, sweep
from _support import BLOCKS, DATA

INVENTORY = DATA / "inventories" / "example.csv"
MOTIONS = DATA / "examples" / "floor-motions" / "motions.csv"

DIRECTIONALITY = ("directionality", "--out", "out", "--no-progress")
BOTH = ("contents", "--model", "both", "--out", "out", "--no-progress")

CASES: list[Case] = [
    Case("directionality --out a file", ("directionality", "--out", str(BLOCKS)), ("--out", "is a file")),
    Case("directionality --out ''", ("directionality", "--out", ""), ("--out",)),
    Case("directionality --store a file", (*DIRECTIONALITY, "--store", str(BLOCKS)), ("--store", "is a file")),
    Case("directionality --store ''", (*DIRECTIONALITY, "--store", ""), ("--store",)),
    Case("directionality --workers 0", (*DIRECTIONALITY, "--workers", "0"), ("--workers", "0")),
    Case("directionality --workers x", (*DIRECTIONALITY, "--workers", "x"), ("--workers", "x")),
    Case("directionality --workers 1.5", (*DIRECTIONALITY, "--workers", "1.5"), ("--workers", "1.5")),
    Case("directionality --bogus", (*DIRECTIONALITY, "--bogus"), ("--bogus",)),
    Case("contents --model both --solver rigid3d with files", (*BOTH, "--inventory", str(INVENTORY), "--motions",
                                                                  str(MOTIONS), "--solver", "rigid3d"), ("--solver",)),
    Case("contents --model both --items", (*BOTH, "--items", "E.20.22.102a"), ("--items", "--model both")),
    Case("contents --model both --period", (*BOTH, "--period", "2"), ("--period", "--model both")),
    Case("contents --model both --solver", (*BOTH, "--solver", "rigid3d"), ("--solver", "--model both")),
    Case("contents --model both --n-boot", (*BOTH, "--n-boot", "3"), ("--n-boot", "--model both")),
    Case("contents --model nope", ("contents", "--model", "nope", "--out", "out"), ("--model", "nope")),
]


def test_hostile_directionality_is_refused(tmp_path):
    broken = sweep(CASES, tmp_path)
    assert not broken, "\n".join(broken)


def test_directionality_case_counts():
    assert len({c.name for c in CASES}) == len(CASES)  # one name per case
    assert Counter(c.args[0] for c in CASES) == {"directionality": 8, "contents": 6}
