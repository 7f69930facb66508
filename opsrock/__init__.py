"""opsrock: rocking and overturning of freestanding rigid blocks under floor motions.

Reproduces the OpenSees workflow of Liu, Huang & Liu (2023), *Seismic Overturning Fragility
Analysis for Rigid Blocks Subjected to Floor Motions*, Sustainability 15, 4945, and checks it
against independent scipy solvers and closed forms.

OpenSeesPy (and the system BLAS its Linux wheel links against) is loaded when the OpenSees model is
first used (:mod:`opsrock.opensees_session`), so everything else works on a machine without it.
"""

from opsrock.block import Block
from opsrock.constants import G
from opsrock.excitations import OneSinePulse, Record
from opsrock.model import SDOFModel
from opsrock.result import RockingResult
from opsrock.solvers import SOLVERS, simulate

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
