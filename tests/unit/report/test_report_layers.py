"""Reports and plots compute nothing: they are given results and write or draw them.

Every import of every module of :mod:`opsrock.report` and :mod:`opsrock.plots` (at the top or inside a
function) is read from its source: none may bring in a solver, a validation case, the campaign engine or
an analysis beyond the result types they draw (the computations live in :mod:`opsrock.analysis`, and the
workflows :mod:`opsrock.analysis.reproduce` and :mod:`opsrock.analysis.record_report` call the writers
with what they computed).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import opsrock

PACKAGE = Path(opsrock.__file__).resolve().parent
#: The writing and drawing modules.
WRITERS: list[Path] = sorted([*PACKAGE.glob("report/*.py"), *PACKAGE.glob("plots/*.py"),
                              PACKAGE / "inventory" / "fema" / "report.py", PACKAGE / "inventory" / "fema" / "plots.py",
                              PACKAGE / "inventory" / "report.py", PACKAGE / "inventory" / "plots.py"])
#: Modules a writer must not import (a prefix each).
FORBIDDEN: tuple[str, ...] = ("opsrock.solvers", "opsrock.validation", "opsrock.campaign", "opsrock.analysis",
                              "opsrock.intensity.records", "opsrock.opensees_session", "openseespy")
#: Computations a writer must not import from anywhere: fits, bootstraps, simulations.
FORBIDDEN_NAMES: frozenset[str] = frozenset({"simulate", "solve", "record_fragility", "analyse_fragility",
                                             "fit_lognormal_mle", "sliding_table", "headline", "bootstrap",
                                             "response_spectrum", "velocity_displacement"})
#: What a writer may import from those: result types and the constants of a chart.
#: ``as_bool`` is the case table's parser of a boolean column (a table read from an older file holds text), no
#: computation.
ALLOWED: dict[str, set[str]] = {"opsrock.analysis.charts": {"ChartData", "Y_MAX"}, "opsrock.campaign.cases": {"as_bool"},
                                "opsrock.analysis.record_curves": {"RecordCurves"},
                                "opsrock.validation.experiments": {"Headline"}}


def _imports(path: Path) -> list[tuple[str, str, int]]:
    """``(module, name, line)`` of every import in ``path`` (name "" for ``import module``)."""
    out = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out += [(a.name, "", node.lineno) for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module:
            out += [(node.module, a.name, node.lineno) for a in node.names]
    return out


def test_the_writers_are_found():
    names = {p.name for p in WRITERS}
    assert {"paper.py", "records.py", "thresholds.py", "response.py", "fragility.py", "report.py"} <= names, names


@pytest.mark.parametrize("path", WRITERS, ids=[str(p.relative_to(PACKAGE)) for p in WRITERS])
def test_writer_imports_no_computation(path):
    bad = [f"line {line}: {module}{'.' + name if name else ''}" for module, name, line in _imports(path)
           if (module.startswith(FORBIDDEN) and name not in ALLOWED.get(module, set())) or name in FORBIDDEN_NAMES]
    assert not bad, f"{path.relative_to(PACKAGE)} imports computations: {'; '.join(bad)}"
