"""No change alters a result beyond round-off: the outputs kept in ``tests/data/behaviour/`` are reproduced.

Runs ``tools/behaviour_tables.py check`` (three campaigns and the quick outputs of the validation cases, a few
minutes on 2 cores), so it is a slow test: ``make test-slow``. Text cells (verdicts, reasons, settings) must be
equal and numbers equal to a relative 1e-9 (round-off); cells that are not results are named by the tool
(``NOT_RESULTS``, each with its reason). When a change alters numbers on purpose, recompute the tables with
``compute`` and say why in the commit; tests/data/behaviour/README.md says how they were made and how far another
processor moves them.

The tables were computed with the reference (netlib) BLAS and LAPACK under OpenSees, and OpenBLAS moves three of
them beyond round-off (the README's table: 31 of 34 hold). The check therefore runs, where Debian's reference
libraries are installed beside another ``libblas.so.3`` (this machine: OpenBLAS), with them first on
``LD_LIBRARY_PATH``: the tables' own environment, so that the test sees a change of opsrock, not of the machine's
BLAS. Elsewhere the system's libraries are used, and a failure message says so.
"""

from __future__ import annotations

import os
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

from _support import ROOT


def reference_blas() -> list[str]:
    """Debian's reference BLAS and LAPACK folders (``/usr/lib/<multiarch>/blas`` and ``.../lapack``), where both
    hold their ``.so.3``; else none."""
    arch = sysconfig.get_config_var("MULTIARCH") or ""
    dirs = [Path("/usr/lib") / arch / "blas", Path("/usr/lib") / arch / "lapack"]
    found = arch and (dirs[0] / "libblas.so.3").exists() and (dirs[1] / "liblapack.so.3").exists()
    return [str(d) for d in dirs] if found else []


@pytest.mark.slow
def test_outputs_match_the_kept_tables_to_round_off():
    env, blas = dict(os.environ), reference_blas()
    if blas:
        env["LD_LIBRARY_PATH"] = os.pathsep.join(blas + [p for p in [os.environ.get("LD_LIBRARY_PATH")] if p])
    proc = subprocess.run([sys.executable, str(ROOT / "tools" / "behaviour_tables.py"), "check",
                           str(ROOT / "tests" / "data" / "behaviour")], capture_output=True, text=True, timeout=2400,
                          env=env)
    where = (f"with the reference BLAS and LAPACK first ({', '.join(blas)})" if blas else
             "with the system's BLAS and LAPACK (no reference libraries found: OpenBLAS moves three tables, "
             "tests/data/behaviour/README.md)")
    assert proc.returncode == 0, f"checked {where}:\n" + proc.stdout[-5000:] + proc.stderr[-2000:]
    assert "FAIL" not in proc.stdout
