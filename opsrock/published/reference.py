"""A value reported by a paper, kept with its source and the tolerance of a comparison."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping


@dataclass(frozen=True)
class PublishedValue:
    """One published number.

    Parameters
    ----------
    key : str
        Short unique id (used in the validation table).
    source : str
        Paper and place (equation, figure, example).
    pulse : str
        Pulse shape (a key of :data:`opsrock.excitations.PULSE_SHAPES`).
    equations : str
        ``"linearised"`` or ``"exact"``: the form the paper solved (or the one that reproduces it).
    quantity : str
        What the number is, with its unit.
    value : float
        The number as printed (its unit in ``quantity``).
    tolerance : float
        Allowed relative difference of a reproduction (dimensionless).
    tolerance_reason : str
        Why that tolerance.
    parameters : mapping
        The case: ``freq_ratio``, ``restitution``, block data, as the paper gives them.
    """

    key: str
    source: str
    pulse: str
    equations: str
    quantity: str
    value: float
    tolerance: float
    tolerance_reason: str
    parameters: Mapping[str, Any] = field(default_factory=dict)
