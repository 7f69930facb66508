"""The restructuring changed no result: every output digested before it (4698d5c) is reproduced.

Runs ``tools/behaviour_digests.py check`` (three campaigns and the quick outputs of the nine validation
cases, about 1.5 min on 2 cores), so it is a slow test: ``make test-slow``. When a later change alters
numbers on purpose, recompute the digests with ``compute`` and say why in the commit.

The digests depend on the libraries as well as on the code (full-precision floats): they are those of 4698d5c
itself run in the environment of requirements.lock (recomputed in issue 33, when the locked libraries had moved
three of them: the FEMA P695 IDA campaign and validation case records; 4698d5c and main gave the same new values).
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from _support import ROOT


@pytest.mark.slow
def test_outputs_match_the_digests_taken_before_the_restructuring():
    proc = subprocess.run([sys.executable, str(ROOT / "tools" / "behaviour_digests.py"), "check",
                           str(ROOT / "tests" / "data" / "behaviour_digests.json")],
                          capture_output=True, text=True, timeout=1200)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "20/20 digests identical" in proc.stdout
