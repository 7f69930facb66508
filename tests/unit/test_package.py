"""The package as it is shipped: a wheel built from the checkout holds its data, and the installed
package finds its scenes without the checkout; its changelog has the current version and its citation file
parses.

`make test-wheel` (called by CI) installs such a wheel into a fresh venv and runs `opsrock run tiny`,
`opsrock validate --quick` and `opsrock reproduce` from an empty folder; this test checks the wheel's
contents and the lookups in seconds, on every `make test`.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

import opsrock

from _support import ROOT
SCENES = {"paper", "spectrum", "tiny", "fema-far-field-ida", "fema-far-field-ida-b3"}


def _tracked(*paths: str) -> list[str]:
    """The files git tracks (and the new ones it does not ignore) under ``paths`` of the checkout."""
    return subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard", *paths], cwd=ROOT,
                          capture_output=True, text=True, check=True).stdout.split()


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> Path:
    # built from a copy of the checkout's files, as a fresh clone holds them: a build/ folder left by an
    # earlier build in the checkout would otherwise lend the wheel files its configuration does not ship
    src, out = tmp_path_factory.mktemp("src"), tmp_path_factory.mktemp("dist")
    for name in _tracked():
        if (ROOT / name).is_file():
            (src / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, src / name)
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps", "-w", str(out), str(src)],
                   check=True, capture_output=True, text=True, timeout=300)
    (whl,) = out.glob("opsrock-*.whl")
    return whl


def test_wheel_ships_the_data_and_nothing_of_the_repository(wheel):
    names = set(zipfile.ZipFile(wheel).namelist())
    assert "opsrock/data/blocks.toml" in names
    assert {f"opsrock/data/scenes/{s}.toml" for s in SCENES} <= names
    assert "opsrock/cli/__main__.py" in names
    # every data file the checkout tracks under opsrock/data is shipped (the solvers' evidence was not,
    # and the multi-fidelity policy reads it when the campaign workflow is imported)
    data = {n for n in _tracked("opsrock/data") if not n.endswith(".py")}
    assert data and data <= names, sorted(data - names)
    # the repository's folders are not packages: no tests, case folders or studies in the wheel
    assert not any(n.split("/")[0] in {"tests", "validation", "studies", "docs", "tools", "bench"} for n in names)


def test_installed_package_finds_its_scenes_outside_the_checkout(wheel, tmp_path):
    # The wheel unpacked, imported from an empty folder: python -S processes no .pth file, so the
    # checkout's editable install is not on the path; numpy & co. come from the venv's site-packages,
    # behind the unpacked wheel.
    import site

    unpacked = tmp_path / "unpacked"
    zipfile.ZipFile(wheel).extractall(unpacked)
    code = (f"import sys; sys.path[:0] = {[str(unpacked), *site.getsitepackages()]!r}; "
            "import opsrock, opsrock.data as d; from opsrock.campaign import load_scene; "
            "print(opsrock.__file__); print(sorted(d.scene_names())); s = load_scene('tiny'); "
            "print(s.n_cases); print(s.blocks_path)")
    empty = tmp_path / "empty"
    empty.mkdir()
    proc = subprocess.run([sys.executable, "-S", "-c", code], cwd=empty, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    module, scenes, n_cases, blocks_path = proc.stdout.splitlines()
    assert module.startswith(str(unpacked)) and blocks_path.startswith(str(unpacked))
    assert scenes == repr(sorted(SCENES)) and n_cases == "18"


def test_changelog_has_a_section_for_the_current_version():
    # keep-a-changelog form: "## [X.Y.Z] - YYYY-MM-DD", newest first, after an "Unreleased" section
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    versions = re.findall(r"^## \[(\d+\.\d+\.\d+)\] - \d{4}-\d{2}-\d{2}$", text, flags=re.M)
    assert versions and versions[0] == opsrock.__version__, versions
    assert versions == sorted(versions, key=lambda v: tuple(map(int, v.split("."))), reverse=True)
    assert text.index("## [Unreleased]") < text.index(f"## [{opsrock.__version__}]")


def _cff_top_level(text: str) -> dict[str, str]:
    """The top-level ``key: value`` pairs of a CITATION.cff (YAML is not a dependency: a key at column 0, its
    scalar value unquoted; nested blocks give ``""``). Fails on a line that is neither."""
    pairs = {}
    for line in text.splitlines():
        if not line.strip() or line.lstrip().startswith("#") or line[0] in " -":
            continue
        match = re.fullmatch(r"([a-z][a-z-]*):(?: (.*))?", line)
        assert match, f"not a key: value line: {line!r}"
        pairs[match.group(1)] = (match.group(2) or "").strip().strip('"')
    return pairs


def test_citation_cites_this_version_and_the_paper():
    text = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    cff = _cff_top_level(text)
    assert cff["cff-version"] == "1.2.0"
    assert {"message", "title", "authors", "type", "version", "preferred-citation"} <= set(cff)
    assert cff["version"] == opsrock.__version__
    # the paper opsrock reproduces, with the DOI the README and opsrock.published.liu_huang_liu_2023 give
    assert "Seismic Overturning Fragility Analysis for Rigid Blocks Subjected to Floor Motions" in text
    assert re.search(r"^  doi: 10\.3390/su15064945$", text, flags=re.M)
