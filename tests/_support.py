"""What many test modules share, importable from any folder of the suite (``pythonpath = ["tests"]`` in
pyproject.toml): the checkout's paths and a runner for the real console script.

Fixtures built on these live in ``conftest.py``; this module holds plain names and functions, so that
module-level tables (parametrised cases) can use them too.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

#: The checkout (the folder that holds ``opsrock/`` and ``tests/``), wherever it was cloned.
ROOT = Path(__file__).resolve().parents[1]
#: The package's shipped data.
DATA = ROOT / "opsrock" / "data"
#: The shipped blocks library.
BLOCKS = DATA / "blocks.toml"
#: The shipped scenes.
SCENES = DATA / "scenes"
#: Test data of the suite itself.
TEST_DATA = ROOT / "tests" / "data"
#: The console script of the environment that runs the tests (``python -m opsrock.cli`` where absent).
OPSROCK = Path(sys.executable).parent / "opsrock"


def opsrock_command(*args: str) -> list[str]:
    """The command line that runs ``opsrock ARGS`` through the installed console script."""
    head = [str(OPSROCK)] if OPSROCK.exists() else [sys.executable, "-m", "opsrock.cli"]
    return [*head, *map(str, args)]


def run_opsrock(*args: str, cwd: Path | None = None, timeout: float = 120,
                env: dict[str, str] | None = None) -> subprocess.CompletedProcess:
    """Run ``opsrock ARGS`` (text output captured, no standard input); ``env`` entries are added to the
    current environment."""
    full_env = None if env is None else {**os.environ, **env}
    return subprocess.run(opsrock_command(*args), cwd=cwd, capture_output=True, text=True, timeout=timeout,
                          stdin=subprocess.DEVNULL, env=full_env)
