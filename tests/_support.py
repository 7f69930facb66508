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
from typing import Mapping, Sequence

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


def opsrock_command(args: Sequence[str], user: int | None = None) -> list[str]:
    """The command line that runs ``opsrock ARGS`` through the installed console script; with ``user``, as
    that uid and gid (util-linux ``setpriv``, to drop root for one command)."""
    head = [str(OPSROCK)] if OPSROCK.exists() else [sys.executable, "-m", "opsrock.cli"]
    cmd = [*head, *map(str, args)]
    return cmd if user is None else ["setpriv", f"--reuid={user}", f"--regid={user}", "--clear-groups", *cmd]


def run_opsrock(args: Sequence[str], cwd: str | os.PathLike | None = None, *, timeout: float = 120,
                env: Mapping[str, str] | None = None, user: int | None = None) -> subprocess.CompletedProcess:
    """Run ``opsrock ARGS`` in ``cwd``, text output captured, no standard input; ``env`` is the whole
    environment (None: this one), ``user`` a uid to run as (:func:`opsrock_command`)."""
    return subprocess.run(opsrock_command(args, user), cwd=cwd, capture_output=True, text=True, timeout=timeout,
                          stdin=subprocess.DEVNULL, env=None if env is None else dict(env))
