"""The missing-BLAS message: one clear line instead of OpenSeesPy's bare RuntimeError."""

from __future__ import annotations

import subprocess
import sys

import pytest

from opsrock._blas import MISSING_BLAS_MESSAGE, MissingBlasError, blas_available, require_blas


def test_missing_library_raises_clear_error():
    with pytest.raises(MissingBlasError, match="libblas3"):
        require_blas("libopsrock-no-such-blas.so.9")
    assert "\n" not in MISSING_BLAS_MESSAGE


def test_present_blas_is_found():
    # The test environment is set up by `make test`, which installs libblas3.
    assert blas_available()


#: Simulates a machine without libblas.so.3: ctypes refuses that one library.
_NO_BLAS = (
    "import ctypes\n"
    "_real = ctypes.CDLL.__init__\n"
    "def _fake(self, name, *a, **k):\n"
    "    if name == 'libblas.so.3':\n"
    "        raise OSError('libblas.so.3: cannot open shared object file')\n"
    "    return _real(self, name, *a, **k)\n"
    "ctypes.CDLL.__init__ = _fake\n"
)


def _run(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", _NO_BLAS + code], capture_output=True, text=True)


def test_import_and_other_solvers_work_without_blas():
    # `import opsrock` and every solver but OpenSees need no system BLAS: OpenSeesPy is loaded when first used.
    proc = _run(
        "import sys\n"
        "import opsrock\n"
        "from opsrock.errors import MissingBlasError\n"
        "from opsrock._blas import blas_available\n"
        "assert not blas_available(), 'the BLAS was not made unavailable'\n"
        "b = opsrock.Block(0.40, 2.20)\n"
        "p = opsrock.OneSinePulse.from_ratios(b, freq_ratio=2.0, pfa_ratio=1.5)\n"
        "r = opsrock.simulate(b, p, solver='housner')\n"
        "print(r.verdict, r.theta_max > 0)\n"
        "assert not any('openseespy' in m for m in sys.modules), 'OpenSeesPy was imported'\n"
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split()[-1] == "True", proc.stdout


def test_opensees_without_blas_gives_the_message():
    # the OpenSees model, first used, says plainly what to install instead of OpenSeesPy's bare RuntimeError
    proc = _run(
        "import opsrock\n"
        "b = opsrock.Block(0.40, 2.20)\n"
        "p = opsrock.OneSinePulse.from_ratios(b, freq_ratio=2.0, pfa_ratio=1.5)\n"
        "opsrock.simulate(b, p, solver='opensees')\n"
    )
    assert proc.returncode != 0
    assert MISSING_BLAS_MESSAGE in proc.stderr, proc.stderr
    assert "Failed to import openseespy" not in proc.stderr
