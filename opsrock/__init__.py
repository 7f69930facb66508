"""opsrock: rocking and overturning of freestanding rigid blocks under floor motions.

Reproduces the OpenSees workflow of Liu, Huang & Liu (2023), *Seismic Overturning Fragility
Analysis for Rigid Blocks Subjected to Floor Motions*, Sustainability 15, 4945, and checks it
against independent scipy solvers and closed forms.
"""

from opsrock._blas import require_blas as _require_blas

# OpenSeesPy's Linux wheel needs libblas.so.3; say so plainly instead of its bare RuntimeError.
_require_blas()

from opsrock.block import Block  # noqa: E402
from opsrock.constants import G  # noqa: E402
from opsrock.excitations import OneSinePulse, Record  # noqa: E402
from opsrock.model import SDOFModel  # noqa: E402
from opsrock.result import RockingResult  # noqa: E402
from opsrock.solvers import SOLVERS, simulate  # noqa: E402

__all__ = [
    "Block",
    "G",
    "OneSinePulse",
    "Record",
    "RockingResult",
    "SDOFModel",
    "SOLVERS",
    "simulate",
]
__version__ = "0.1.0"
