"""``opsrock --version``: the one version, as the package, its installed metadata and the console script give it."""

from __future__ import annotations

import importlib.metadata
import re

import opsrock
from _support import run_opsrock


def test_version_is_one_number_everywhere(tmp_path):
    proc = run_opsrock(["--version"], tmp_path, timeout=60)
    assert proc.returncode == 0 and proc.stderr == "", proc.stderr
    assert proc.stdout == f"opsrock {opsrock.__version__}\n"
    # pyproject.toml reads the version from opsrock.__version__: the installed metadata must repeat it
    assert importlib.metadata.version("opsrock") == opsrock.__version__
    assert re.fullmatch(r"\d+\.\d+\.\d+", opsrock.__version__)  # a release number, as a package index expects
    assert list(tmp_path.iterdir()) == []
