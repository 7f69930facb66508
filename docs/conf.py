"""Sphinx configuration of the opsrock documentation site (``make docs``).

The site's pages:

- ``index.md``, ``getting-started.md`` and ``changelog.md`` (which includes ``CHANGELOG.md``);
- the user guide: every ``guide/*.md`` page, picked up by the glob of ``guide/index.md`` (a new page needs no
  edit here: put it into ``docs/guide/``);
- the gallery: every ``examples/*.py`` script, executed by sphinx-gallery when the site is built;
- pages generated into ``docs/api/``, ``docs/validation/`` and ``docs/studies/`` before Sphinx reads anything
  (never committed: .gitignore; rewritten on each build): the API reference (:func:`api_pages`), one page per validation case (``validation/*/README.md``) and
  one per study (``studies/*/``) (:func:`case_pages`), so a new public module or a new case folder needs no
  edit here either.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import shutil
from pathlib import Path

import opsrock

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
#: The folders of generated pages (each rewritten whole on every build).
GENERATED = ("api", "validation", "studies")

project = "opsrock"
author = "The opsrock developers"
copyright = "the opsrock developers"
release = opsrock.__version__
version = release

extensions = [
    "myst_parser",
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "auto_examples/*.ipynb", "auto_examples/*.py", "auto_examples/*.zip",
                    "auto_examples/*.md5", "auto_examples/*.json"]

html_theme = "pydata_sphinx_theme"
html_title = f"opsrock {release}"
html_theme_options = {"navigation_with_keys": False, "show_toc_level": 2}
html_static_path: list[str] = []

# MyST: the user guide's Markdown as it is on a repository browser (heading anchors for `page.md#section`)
myst_heading_anchors = 4
myst_enable_extensions = ["dollarmath", "colon_fence"]

# numpydoc renders the docstrings; autosummary writes one page per public name
autosummary_generate = True
autosummary_imported_members = True
autodoc_default_options = {"members": False}
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",  # every example is executed
    "ignore_pattern": r"/_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "matplotlib_animations": False,
    "min_reported_time": 0,
    "plot_gallery": "True",
    "abort_on_example_error": True,
}

#: Packages whose modules are not public API pages: the command line (its page is ``opsrock --help``).
API_EXCLUDED = ("opsrock.cli",)

#: The API reference's sections, by what a user does: heading -> the modules (and, with a trailing ``.``, the
#: packages) it holds, first match wins. A module in none of them is an internal (the report writers, the
#: plots, the limits and statistics helpers, the OpenSees session) and has no page.
API_GROUPS: dict[str, tuple[str, ...]] = {
    "One block": ("opsrock", "opsrock.block", "opsrock.constants", "opsrock.errors", "opsrock.excitations",
                  "opsrock.excitations.", "opsrock.model", "opsrock.restitution", "opsrock.result",
                  "opsrock.solvers", "opsrock.solvers."),
    "Campaigns": ("opsrock.campaign", "opsrock.campaign."),
    "Fragility": ("opsrock.fragility", "opsrock.fragility.", "opsrock.intensity", "opsrock.intensity."),
    "Contents studies": ("opsrock.inventory.run", "opsrock.inventory.study", "opsrock.inventory.three_d",
                         "opsrock.inventory.side_by_side",
                         "opsrock.inventory.fema", "opsrock.inventory.directionality.study",
                         "opsrock.inventory.items", "opsrock.inventory.friction", "opsrock.inventory.motions",
                         "opsrock.inventory.sources", "opsrock.inventory.stages", "opsrock.inventory.outputs"),
    "Validation": ("opsrock.validation", "opsrock.validation.", "opsrock.bench", "opsrock.bench.",
                   "opsrock.published", "opsrock.published.", "opsrock.analysis."),
}


def api_group(name: str) -> str | None:
    """The :data:`API_GROUPS` heading of module ``name``, or None for an internal."""
    for heading, members in API_GROUPS.items():
        if any(name == m or (m.endswith(".") or m.endswith("_")) and name.startswith(m) for m in members):
            return heading
    return None


def public_modules() -> list[str]:
    """The modules of the API reference: ``opsrock``, then every non-private subpackage and module of it except
    :data:`API_EXCLUDED`, where a package that declares ``__all__`` stands for its own modules (its
    ``__all__`` is its public API; a subpackage of it that declares one has its own page, as each solver of
    :mod:`opsrock.solvers`) and a package without one is shown through its modules."""
    names = ["opsrock"]
    covered: list[str] = []  # packages with an __all__: their inner modules are not shown

    for info in pkgutil.walk_packages(opsrock.__path__, "opsrock."):
        name = info.name
        if any(part.startswith("_") for part in name.split(".")) or name.startswith(API_EXCLUDED):
            continue
        module = importlib.import_module(name)
        if any(name.startswith(pkg + ".") for pkg in covered) and not (info.ispkg and hasattr(module, "__all__")):
            continue
        if info.ispkg and hasattr(module, "__all__"):
            covered.append(name)
        if info.ispkg and not hasattr(module, "__all__"):
            continue  # shown through its modules
        names.append(name)
    return names


def public_names(module) -> list[str]:
    """The names a module's page lists: its ``__all__``, else the public functions and classes it defines."""
    if hasattr(module, "__all__"):
        return list(module.__all__)
    return sorted(n for n, v in vars(module).items() if not n.startswith("_")
                  and (inspect.isfunction(v) or inspect.isclass(v)) and v.__module__ == module.__name__)


def _title(text: str, mark: str = "=") -> str:
    return f"{text}\n{mark * len(text)}\n"


def api_page(name: str, shown: dict[int, str]) -> str:
    """The reST page of one module: its docstring, then an autosummary table of its public names (one generated
    page each). A class or function already given a page under another module (``shown``: ``id`` -> the full
    name it was shown under; updated here) is listed as a link to that page instead (one page per object)."""
    module = importlib.import_module(name)
    new, again = [], []
    for n in public_names(module):
        value = getattr(module, n)
        if not (inspect.isclass(value) or inspect.isroutine(value)):
            new.append(n)  # constants: no identity to share
        elif id(value) in shown:
            again.append(shown[id(value)])
        else:
            shown[id(value)] = f"{name}.{n}"
            new.append(n)
    lines = [_title(f"``{name}``"), f".. automodule:: {name}", "   :no-members:", ""]
    if new:
        lines += [".. currentmodule:: " + name, "", ".. autosummary::", "   :toctree: generated/", ""]
        lines += [f"   {n}" for n in new] + [""]
    if again:
        lines += ["Also exported here: " + ", ".join(f":obj:`~{full}`" for full in again) + "."]
    return "\n".join(lines) + "\n"


def api_pages() -> None:
    """Writes ``api/index.rst`` and a page per public module."""
    out = DOCS / "api"
    out.mkdir(parents=True)
    groups: dict[str, list[str]] = {heading: [] for heading in API_GROUPS}
    for name in public_modules():
        heading = api_group(name)
        if heading is not None:
            groups[heading].append(name)
    shown: dict[int, str] = {}
    index = [_title("API reference"),
             "The public API of opsrock, generated from its docstrings (numpydoc), by what you do: one block under",
             "one floor motion (:func:`opsrock.simulate`), a campaign of many cases (:func:`opsrock.run_campaign`),",
             "fragility, a contents study (:func:`opsrock.run_study`), validation. For each package that declares",
             "``__all__``, the names it exports; for the others, each module's. Units are SI unless a parameter",
             "says otherwise. Internals (report writers, plots, helpers) are left out.", ""]
    for heading, names in groups.items():
        index += [_title(heading, "-"), ".. toctree::", "   :maxdepth: 1", ""]
        for name in names:
            (out / f"{name}.rst").write_text(api_page(name, shown))
            index.append(f"   {name}")
        index.append("")
    (out / "index.rst").write_text("\n".join(index) + "\n")


def _include(path: Path, page: Path) -> str:
    rel = Path("..", "..", path.relative_to(ROOT))
    return f"```{{include}} {rel.as_posix()}\n:relative-docs: ../\n:relative-images:\n```\n"


def _figures(folder: Path, page_text: str) -> str:
    """The folder's PNG figures that its Markdown does not show already, under a heading."""
    pngs = sorted(p for p in folder.glob("*.png") if p.name not in page_text)
    if not pngs:
        return ""
    blocks = [f"![{p.stem}](../../{p.relative_to(ROOT).as_posix()})\n" for p in pngs]
    return "\n## Figures\n\n" + "\n".join(blocks)


def case_pages(kind: str, intro: str) -> None:
    """Writes ``<kind>/index.md`` (``intro``, then a toctree of every case) and one page per folder
    of ``<kind>/`` (``validation`` or ``studies``): its README.md, then its report.md, then its figures."""
    out = DOCS / kind
    out.mkdir(parents=True)
    names = []
    for folder in sorted(p for p in (ROOT / kind).iterdir() if p.is_dir()):
        texts = [folder / f for f in ("README.md", "report.md") if (folder / f).is_file()]
        if not texts:
            continue
        page = out / f"{folder.name}.md"
        body = "\n".join(_include(t, page) for t in texts)
        body += _figures(folder, "".join(t.read_text() for t in texts))
        page.write_text(body)
        names.append(folder.name)
    toctree = "```{toctree}\n:maxdepth: 1\n\n" + "\n".join(names) + "\n```\n"
    (out / "index.md").write_text(intro + "\n" + toctree)


def generate() -> None:
    """Every generated page, written anew."""
    for folder in GENERATED:
        shutil.rmtree(DOCS / folder, ignore_errors=True)
    api_pages()
    case_pages("validation", "# Validation cases\n\nEach case states the relation it checks, its tolerance and its "
                             "result; `opsrock validate` runs them (`--quick` the quick forms).\n")
    readme = ROOT / "studies" / "README.md"
    case_pages("studies", f"```{{include}} ../../{readme.relative_to(ROOT).as_posix()}\n:relative-docs: ../\n```\n")


generate()
