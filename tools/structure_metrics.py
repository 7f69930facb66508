"""The package's shape in numbers: ``python tools/structure_metrics.py [PACKAGE_DIR]``.

Prints, for the package folder (default ``opsrock/`` of this checkout): modules at its top level,
the longest function and every function over 80 lines (compiled kernels, decorated with a numba
``jit``/``njit``, counted with the rest and also listed apart), import cycles between its modules (every ``import``, at module
level or inside a function: a cycle is a cycle either way), imports of a private name of another
module outside the importer's own method package (see ``_shares_method_package``), and lines of Python. Used for the before/after table of the restructuring.

Also, for the contracts between the pieces: functions with more than 8 parameters (``self``/``cls`` not
counted; compiled kernels included, and also listed apart: :func:`compiled_functions`, which the test suite
holds to both limits), the lines and function-level imports of ``cli/``, function-level
imports in the whole package, and imports of a private scipy name (``scipy.x._y`` or ``_name`` from
scipy). With ``--tests DIR`` and ``--duplicates`` it adds the test files under DIR and the number of
pairs the ``duplicates`` command reports for the package.
"""

from __future__ import annotations

import ast
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

LONG = 80
MANY_PARAMETERS = 8

#: Solver names that are also words of the physics or of a study (Coulomb friction and the friction variant;
#: Housner's restitution and the housner variant): counted only where they stand for a solver
#: (:func:`solver_name_strings`).
AMBIGUOUS_NAMES = ("friction", "housner")

#: The packages that choose solvers by what the registry declares, never by name (issue 42).
ENGINE_PACKAGES = ("campaign", "inventory")


def _parameters(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    a = node.args
    names = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs]
    names += [x.arg for x in (a.vararg, a.kwarg) if x is not None]
    return len([n for n in names if n not in ("self", "cls")])


def _is_compiled(node: ast.FunctionDef | ast.AsyncFunctionDef) -> bool:
    """Decorated with a numba ``jit``/``njit`` (``@numba.njit(...)``, ``@njit``, ``@numba.jit``...)."""
    return any("jit" in ast.unparse(d) for d in node.decorator_list)


def compiled_functions(root: Path) -> list[dict]:
    """Every compiled (numba) function under the package folder ``root``: its qualified name
    (``opsrock.solvers.friction.kernel.solve_case``), ``file:line``, lines and parameters (the limits the
    package holds them to are :data:`LONG` and :data:`MANY_PARAMETERS`, as every other function)."""
    found = []
    for f in sorted(root.rglob("*.py")):
        module = _module_name(root, f)
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and _is_compiled(node):
                found.append({"name": f"{module}.{node.name}", "where": f"{f.relative_to(root.parent)}:{node.lineno}",
                              "lines": node.end_lineno - node.lineno + 1, "parameters": _parameters(node)})
    return found


def _function_level_imports(tree: ast.AST) -> int:
    """Imports inside a function body (at any depth), each counted once."""
    module_level = 0
    stack = list(ast.iter_child_nodes(tree))
    while stack:
        node = stack.pop()
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            module_level += 1
        elif not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            stack.extend(ast.iter_child_nodes(node))
    return sum(isinstance(x, (ast.Import, ast.ImportFrom)) for x in ast.walk(tree)) - module_level


def _private_scipy(tree: ast.AST) -> list[str]:
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("scipy"):
            mods = (node.module or "").split(".")
            out += [f"{node.module}.{a.name}" for a in node.names
                    if any(m.startswith("_") for m in mods) or (a.name.startswith("_") and not a.name.startswith("__"))]
        elif isinstance(node, ast.Import):
            out += [a.name for a in node.names if a.name.startswith("scipy") and
                    any(m.startswith("_") for m in a.name.split("."))]
    return out


def _module_name(root: Path, path: Path) -> str:
    parts = list(path.relative_to(root.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _imports(tree: ast.AST, here: str, is_package: bool) -> list[tuple[str, list[str]]]:
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(a.name, []) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = here.split(".")
                base = base[: len(base) - node.level + (1 if is_package else 0)]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            out.append((mod, [a.name for a in node.names]))
    return out


def _package(modules: dict[str, Path], name: str) -> str:
    return name if modules[name].name == "__init__.py" else name.rpartition(".")[0]


def _shares_method_package(modules: dict[str, Path], a: str, b: str) -> bool:
    """True when ``a`` and ``b`` sit in one package at least three levels deep (a method split into
    modules, such as ``opsrock.solvers.opensees``): its modules share private helpers. Sibling
    solvers (``opsrock.solvers.sdof``, ``opsrock.solvers.housner``) or packages do not."""
    pa, pb = _package(modules, a), _package(modules, b)
    return pa == pb and pa.count(".") >= 2


def _private_shared(modules: dict[str, Path], importer: str, source: str) -> bool:
    """A private module (``linearised``) serves the modules of its own package; a method package
    shares its privates inside (:func:`_shares_method_package`)."""
    if source.rpartition(".")[2].startswith("_") and _package(modules, importer) == _package(modules, source):
        return True
    return _shares_method_package(modules, importer, source)


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on, comps, counter = {}, {}, [], set(), [], [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                comps.append(sorted(comp))

    sys.setrecursionlimit(10_000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return comps


def metrics(root: Path) -> dict:
    files = sorted(root.rglob("*.py"))
    modules = {_module_name(root, f): f for f in files}
    top = sorted(f.name for f in root.glob("*.py"))
    long_functions, kernels, private, lines = [], [], [], 0
    many_parameters, scipy_private, cli_lines, cli_imports, local_imports = [], [], 0, 0, 0
    graph: dict[str, set[str]] = {m: set() for m in modules}
    longest = ("", 0)
    for name, f in modules.items():
        text = f.read_text()
        lines += len(text.splitlines())
        tree = ast.parse(text)
        local = _function_level_imports(tree)
        local_imports += local
        scipy_private += [f"{f.relative_to(root.parent)}: {x}" for x in _private_scipy(tree)]
        if name.split(".")[1:2] == ["cli"]:
            cli_lines += len(text.splitlines())
            cli_imports += local
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                n = node.end_lineno - node.lineno + 1
                where = f"{f.relative_to(root.parent)}:{node.lineno} {node.name} ({n})"
                if _is_compiled(node):
                    kernels.append(where)
                if _parameters(node) > MANY_PARAMETERS:
                    many_parameters.append(f"{f.relative_to(root.parent)}:{node.lineno} {node.name} "
                                           f"({_parameters(node)} parameters)")
                if n > longest[1]:
                    longest = (where, n)
                if n > LONG:
                    long_functions.append(where)
        for mod, names in _imports(tree, name, f.name == "__init__.py"):
            target = mod
            for n in names:  # "from pkg import module" imports the module
                if f"{mod}.{n}" in modules:
                    graph[name].add(f"{mod}.{n}")
            while target and target not in modules:
                target = target.rpartition(".")[0]
            if target and target != name and target.startswith(root.name):
                graph[name].add(target)
                for n in names:
                    if not n.startswith("_") or n.startswith("__"):
                        continue
                    source = f"{mod}.{n}" if f"{mod}.{n}" in modules else target  # a private module, or a name
                    if _private_shared(modules, name, source):
                        continue
                    private.append(f"{name} imports {target}.{n}")
    # a package's __init__ re-exporting its own modules is not a cycle of the design
    for m in graph:
        graph[m] = {t for t in graph[m] if not (modules[t].name == "__init__.py" and m.startswith(t + "."))}
    return {
        "top_level_modules": len(top),
        "top_level": top,
        "modules": len(modules),
        "longest_function": longest[0],
        "functions_over_80_lines": long_functions,
        "compiled_kernels_over_80_lines": [k for k in kernels if int(k.rsplit("(", 1)[1][:-1]) > LONG],
        "import_cycles": _cycles(graph),
        "private_imports_across_packages": sorted(set(private)),
        "lines": lines,
        "functions_over_8_parameters": many_parameters,
        "compiled_kernels_over_8_parameters": [f"{k['where']} {k['name'].rpartition('.')[2]} ({k['parameters']} "
                                               f"parameters)" for k in compiled_functions(root)
                                               if k["parameters"] > MANY_PARAMETERS],
        "cli_lines": cli_lines,
        "cli_function_level_imports": cli_imports,
        "function_level_imports": local_imports,
        "private_scipy_imports": scipy_private,
    }


def _docstrings(tree: ast.AST) -> set[int]:
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str):
                out.add(id(first.value))
    return out


def _solver_slots(tree: ast.AST) -> set[int]:
    """Constants compared with, or passed as, a solver or model (``x.model == "friction"``, ``solver="friction"``)."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Compare):
            parts = [node.left, *node.comparators]
            if any(isinstance(p, ast.Attribute) and p.attr in ("model", "solver")
                   or isinstance(p, ast.Name) and p.id in ("model", "solver") for p in parts):
                out |= {id(p) for p in parts if isinstance(p, ast.Constant)}
        elif isinstance(node, ast.keyword) and node.arg in ("model", "solver") and isinstance(node.value, ast.Constant):
            out.add(id(node.value))
    return out


def solver_name_strings(root: Path, names: tuple[str, ...], packages: tuple[str, ...] = ENGINE_PACKAGES) -> list[str]:
    """Every string constant (docstrings skipped) of ``root``'s ``packages`` that names a solver of ``names``:
    as a word anywhere in its text, or, for :data:`AMBIGUOUS_NAMES`, standing as a solver (the whole string compared
    with or passed as a ``model``/``solver``, or ``solver `name``` in a text). ``path:line: 'text'`` each."""
    plain = [n for n in names if n not in AMBIGUOUS_NAMES]
    word = re.compile(r"\b(" + "|".join(map(re.escape, plain)) + r")\b") if plain else None
    ambiguous = [n for n in names if n in AMBIGUOUS_NAMES]
    as_solver = re.compile(r"solvers? [`'\"]?(" + "|".join(ambiguous) + r")\b") if ambiguous else None
    out = []
    for package in packages:
        for f in sorted((root / package).rglob("*.py")):
            tree = ast.parse(f.read_text())
            skip, slots = _docstrings(tree), _solver_slots(tree)
            for node in ast.walk(tree):
                if not (isinstance(node, ast.Constant) and isinstance(node.value, str)) or id(node) in skip:
                    continue
                v = node.value
                if ((word and word.search(v)) or (as_solver and as_solver.search(v))
                        or (v in ambiguous and id(node) in slots)):
                    out.append(f"{f.relative_to(root.parent)}:{node.lineno}: {v[:100]!r}")
    return out


def duplicate_pairs(root: Path) -> int | None:
    """Pairs of places sharing six or more lines in ``root``, as the ``duplicates`` command counts them
    (None where the command is not installed)."""
    if shutil.which("duplicates") is None:
        return None
    out = subprocess.run(["duplicates", "--repo", str(root), "--seconds", "120"], capture_output=True,
                         text=True, check=False).stdout
    m = re.search(r"(\d+) pairs?", out)
    return int(m.group(1)) if m else (0 if "no duplicates" in out else None)


if __name__ == "__main__":
    args = sys.argv[1:]
    tests = args[args.index("--tests") + 1] if "--tests" in args else None
    with_duplicates = "--duplicates" in args
    rest = [a for i, a in enumerate(args) if a not in ("--tests", "--duplicates") and
            (i == 0 or args[i - 1] != "--tests")]
    root = Path(rest[0] if rest else Path(__file__).resolve().parents[1] / "opsrock").resolve()
    result = metrics(root)
    if tests is not None:
        result["test_files"] = len(list(Path(tests).rglob("test_*.py")))
    if with_duplicates:
        result["duplicate_pairs"] = duplicate_pairs(root)
    from opsrock.solvers.registry import SOLVERS

    result["solver_name_strings_in_engine"] = solver_name_strings(root, SOLVERS)
    print(json.dumps(result, indent=2))
