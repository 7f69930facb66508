"""No change alters a result beyond round-off: the outputs kept in ``tests/data/behaviour/`` are reproduced.

Runs ``tools/behaviour_tables.py check`` (three campaigns and the quick outputs of the validation cases, a few
minutes on 2 cores), so it is a slow test: ``make test-slow``. Text cells (verdicts, reasons, settings) must be
equal and numbers equal to a relative 1e-9 (round-off); the few tables whose solver takes discrete decisions on
numbers that differ in their last bits between processors may differ in the share of rows the tool states, each
with its reason (``ALLOWED``). When a change alters numbers on purpose, recompute the tables with ``compute``
and say why in the commit; tests/data/behaviour/README.md says how they were made and how far another processor
moves them.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from _support import ROOT


@pytest.mark.slow
def test_outputs_match_the_kept_tables_to_round_off():
    proc = subprocess.run([sys.executable, str(ROOT / "tools" / "behaviour_tables.py"), "check",
                           str(ROOT / "tests" / "data" / "behaviour")], capture_output=True, text=True, timeout=2400)
    assert proc.returncode == 0, proc.stdout[-5000:] + proc.stderr[-2000:]
    assert "FAIL" not in proc.stdout
