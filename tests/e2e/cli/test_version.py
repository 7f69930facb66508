"""``opsrock --version``: the one version (pyproject.toml's), as the installed metadata, the package and the console
script give it."""

from __future__ import annotations

import importlib.metadata
import re
import tomllib

import opsrock
from _support import ROOT, run_opsrock


def _pyproject_version() -> str:
    """The ``version = "..."`` line of pyproject.toml's [project] table (its one source)."""
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]


def test_version_is_one_number_everywhere(tmp_path):
    proc = run_opsrock(["--version"], tmp_path, timeout=60)
    assert proc.returncode == 0 and proc.stderr == "", proc.stderr
    assert proc.stdout == f"opsrock {opsrock.__version__}\n"
    # opsrock.__version__ is read from the installed metadata, which repeats pyproject.toml's version
    assert importlib.metadata.version("opsrock") == opsrock.__version__ == _pyproject_version()
    assert re.fullmatch(r"\d+\.\d+\.\d+", opsrock.__version__)  # a release number, as a package index expects
    assert list(tmp_path.iterdir()) == []
