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


def test_import_without_blas_gives_the_message(tmp_path):
    # Simulate a machine without libblas.so.3: make ctypes refuse that one library, then import opsrock.
    code = (
        "import ctypes\n"
        "_real = ctypes.CDLL.__init__\n"
        "def _fake(self, name, *a, **k):\n"
        "    if name == 'libblas.so.3':\n"
        "        raise OSError('libblas.so.3: cannot open shared object file')\n"
        "    return _real(self, name, *a, **k)\n"
        "ctypes.CDLL.__init__ = _fake\n"
        "import opsrock\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode != 0
    assert MISSING_BLAS_MESSAGE in proc.stderr
    assert "Failed to import openseespy" not in proc.stderr
