"""The compiled (numba) kernels keep the package's limits on every function: at most 8 parameters and at most
80 lines (issue 43; ``tools/structure_metrics.py`` counts them with the rest). Pure AST, no kernel compiled."""

from __future__ import annotations


from _support import ROOT, load_tool


def _metrics():
    return load_tool("structure_metrics")


def _offences():
    m = _metrics()
    kernels = m.compiled_functions(ROOT / "opsrock")
    over = {k["name"]: f"{k['where']}: {k['lines']} lines, {k['parameters']} parameters" for k in kernels
            if k["lines"] > m.LONG or k["parameters"] > m.MANY_PARAMETERS}
    return kernels, over


def test_the_metrics_find_the_compiled_kernels():
    """The AST walk sees the kernels at all (a decorator spelt differently would make the next test pass vacuously):
    the shared forcing helpers and every compiled solver's kernel module are among them."""
    names = {k["name"] for k in _offences()[0]}
    assert "opsrock.solvers.forcing.forcing" in names
    for solver in ("friction", "housner_fast", "moreau_jean", "rigid3d"):
        assert any(n.startswith(f"opsrock.solvers.{solver}.") for n in names), solver


def test_no_compiled_function_over_8_parameters_or_80_lines():
    """Every compiled function of every kernel keeps both limits (no allow-list: the last over them, friction's
    solve_case, was split into its phases)."""
    _, over = _offences()
    assert sorted(over.values()) == [], "compiled functions over 8 parameters or 80 lines"
