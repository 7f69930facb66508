"""Warnings a finished campaign gives about its own model: where no-slip rocking may not hold.

A block without ``friction`` is solved as if its base could never slip. On a real floor it slides first
if its friction coefficient is below ``b/h`` (it cannot start rocking: docs/guide/friction.md, mode
initiation), and friction caps the horizontal force that makes it rock whenever the floor's
acceleration exceeds ``mu g``. The campaign cannot know the floor's ``mu``; it compares each block
with :data:`ASSUMED_FRICTION` and says so when the no-slip answer is doubtful (the model-form map in
docs/guide/friction.md says where it matters for the fragility).
"""

from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

from opsrock.constants import G
from opsrock.solvers.registry import METHODS, solver_names

#: The floor friction coefficient the warnings assume for a block that has none (dimensionless): an
#: assumption of this project, at the high end of what is usually quoted for furniture on common floor
#: finishes, so that a warning is given only where sliding is likely on most floors.
ASSUMED_FRICTION: float = 0.5


def sliding_warnings(blocks: Sequence[Any], table: Sequence[Mapping[str, Any]],
                     mu: float = ASSUMED_FRICTION, solver: str | None = None) -> list[str]:
    """One line per block without friction whose no-slip result a floor of friction ``mu`` would change.

    Parameters
    ----------
    blocks : sequence of BlockSpec
        The scene's blocks.
    table : sequence of dict
        The rows of ``cases.csv`` (``block``, ``pfa`` in m/s², ``overturned``).
    mu : float
        Assumed floor friction coefficient (dimensionless).
    solver : str or None
        The scene's solver, as its registry entry declares it: with one that models friction the fix named is the
        block's friction alone; with one in plan ``b/h`` is that of the weaker axis (``min(width, depth) / height``).
    """
    out = []
    entry = METHODS.get(solver) if solver is not None else None
    in_plan, slips = bool(entry and entry.plan), bool(entry and entry.friction)
    fix = (f"give the block friction to model it ({solver} models it)" if slips
           else f"give the block friction (and solver {solver_names(friction=True, plan=False)[0]!r}) to model it")
    for spec in blocks:
        if spec.friction is not None:
            continue
        base = min(spec.width, spec.depth) if in_plan and getattr(spec, "depth", None) else spec.width
        ratio = base / spec.height
        if ratio > mu:
            out.append(f"block {spec.name}: b/h = {ratio:.3g} > {mu:g}: on a floor with friction below b/h it "
                       f"slides and cannot start rocking; it was solved as never slipping; {fix}")
            continue
        pfas = [float(r["pfa"]) for r in table if r["block"] == spec.name and r["overturned"] is True
                and math.isfinite(float(r["pfa"]))]
        if pfas and min(pfas) > mu * G:
            out.append(f"block {spec.name}: it overturned only under floor accelerations of {min(pfas) / G:.3g} g "
                       f"and above, beyond the {mu:g} g a floor of friction {mu:g} can transmit without slip; it was "
                       f"solved as never slipping; {fix}")
    return out


__all__ = ["ASSUMED_FRICTION", "sliding_warnings"]
