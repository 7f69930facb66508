"""The defaults of the overturning-threshold scan (:mod:`opsrock.analysis.threshold`), in a module of their own
that imports nothing: the command line's parser shows them in its help, and every ``opsrock`` command, a refused
one included, would otherwise load numpy with the scan's module (about 0.2 s of CPU per command)."""

from __future__ import annotations

#: Default top of the scanned amplitude range, ``PFA / (g tan alpha)`` (dimensionless).
DEFAULT_PFA_RATIO_MAX: float = 50.0
#: Default number of scanned amplitudes.
DEFAULT_N_SCAN: int = 600
#: Default relative width of a refined boundary bracket (dimensionless).
DEFAULT_RTOL: float = 1e-6

__all__ = ["DEFAULT_N_SCAN", "DEFAULT_PFA_RATIO_MAX", "DEFAULT_RTOL"]
