"""The package's import graph keeps the design's rules (``tools/structure_metrics.py``, pure AST, nothing
imported): no import cycle between opsrock's modules, at module level or inside a function (a function-level
import that closes a cycle hides it from Python, not from a reader), and no private name imported across
packages (scipy ``_ivp``'s rule: solvers never import each other's privates)."""

from __future__ import annotations

from _support import ROOT, load_tool


def _metrics():
    return load_tool("structure_metrics").metrics(ROOT / "opsrock")


def test_no_import_cycle_and_no_private_import_across_packages():
    m = _metrics()
    assert m["modules"] > 100  # the walk saw the package (an empty walk would pass vacuously)
    assert m["import_cycles"] == [], "modules importing each other"
    assert m["private_imports_across_packages"] == [], "private names imported across packages"
