"""The command line answers a refusal without loading numpy: its parser reads the registry, the pulse names and
the analyses' defaults from modules that import nothing heavy, so that a command refused at parse time (and every
console-script test of the suite) costs about half the CPU it did with numpy loaded."""

from __future__ import annotations

import subprocess
import sys


def test_the_parser_loads_no_numpy():
    code = ("import sys; from opsrock.cli.parser import *; import opsrock.solvers.registry; "
            "print(sorted(m for m in ('numpy', 'pandas', 'scipy', 'numba') if m in sys.modules))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "[]"
