"""The campaign engine and the study choose a solver by what its registry entry declares (planar or in plan, the
restitution it models, its base, its model), never by its name (issue 42): no string constant of
``opsrock/campaign`` or ``opsrock/inventory`` names a registered solver (docstrings may). Pure AST."""

from __future__ import annotations

import ast

from _support import ROOT, load_tool

from opsrock.solvers.registry import SOLVERS


def _metrics():
    return load_tool("structure_metrics")


def test_the_walk_finds_a_solver_named_in_a_string(tmp_path):
    """The walk sees what it must (else the next test passes vacuously): a name as a word, an f-string's text, a
    model compared with an ambiguous name, a solver named in a message; and leaves alone docstrings and the words
    of the physics (Coulomb friction, Housner's restitution)."""
    package = tmp_path / "opsrock" / "campaign"
    package.mkdir(parents=True)
    (package / "m.py").write_text(
        '"""Runs rigid3d (a docstring)."""\n'
        'A = "rigid3d"\n'
        'B = f"use {x} or sdof"\n'
        'C = entry.model == "friction"\n'
        'D = "slides (solver `friction`)"\n'
        'E = "friction"  # a column of the scene\n'
        'F = "Housner\'s restitution"\n'
        'def f():\n    """opensees in a docstring."""\n')
    found = _metrics().solver_name_strings(tmp_path / "opsrock", SOLVERS)
    assert sorted(int(line.split(":")[1]) for line in found) == [2, 3, 4, 5], found


def test_no_solver_name_in_a_string_of_the_engine_or_the_study():
    found = _metrics().solver_name_strings(ROOT / "opsrock", SOLVERS)
    assert found == [], "solver names in strings of opsrock/campaign or opsrock/inventory"


def test_the_engine_is_parsed_at_all():
    """Both packages exist and parse (a moved package would make the walk find nothing)."""
    for package in ("campaign", "inventory"):
        files = list((ROOT / "opsrock" / package).rglob("*.py"))
        assert len(files) > 5, package
        for f in files:
            ast.parse(f.read_text())
