"""Check for the system BLAS that OpenSeesPy's Linux wheel links against.

Without ``libblas.so.3`` OpenSeesPy fails with a bare ``RuntimeError('Failed to import
openseespy on Linux.')``. opsrock checks first and says what to install instead.
"""

from __future__ import annotations

import ctypes
import sys

from opsrock.errors import MissingBlasError

#: The one-line message shared with ``tools/ensure-blas.sh`` and the Makefile.
MISSING_BLAS_MESSAGE = (
    "opsrock: the system BLAS libblas.so.3 is missing; install it "
    "(Debian/Ubuntu: sudo apt-get install libblas3) and retry"
)


def blas_available(library: str = "libblas.so.3") -> bool:
    """Return True if ``library`` can be loaded (always True off Linux)."""
    if not sys.platform.startswith("linux"):
        return True
    try:
        ctypes.CDLL(library)
    except OSError:
        return False
    return True


def require_blas(library: str = "libblas.so.3") -> None:
    """Raise :class:`MissingBlasError` with :data:`MISSING_BLAS_MESSAGE` if the BLAS is absent."""
    if not blas_available(library):
        raise MissingBlasError(MISSING_BLAS_MESSAGE)
