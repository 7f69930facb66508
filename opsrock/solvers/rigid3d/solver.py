"""One case: :func:`solve` (skeleton until the kernel lands)."""

from __future__ import annotations

from typing import Any

from opsrock.block import Block
from opsrock.result import RockingResult
from opsrock.solvers.rigid3d.settings import Rigid3DSettings

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "rigid3d"


def solve(block: Block, excitation: Any, settings: Rigid3DSettings | None = None,
          **overrides: Any) -> RockingResult:
    """Response of a box on a floor with Coulomb friction to a floor motion in plan (two horizontal components
    and a vertical one), by Moreau-Jean time stepping.

    Parameters
    ----------
    block : Block
        The block, with its ``depth`` (m).
    excitation : PlanMotion or Pulse or Record or None
        The floor motion in plan; a pulse or a record alone is taken along the block's width.
    settings : Rigid3DSettings, optional
        Numerical settings; keyword ``overrides`` replace individual fields.
    """
    raise NotImplementedError("rigid3d: the kernel lands with issue 33")


__all__ = ["SOLVER_NAME", "solve"]
