"""Input checks shared by the dataclasses: every error names the argument and its value."""

from __future__ import annotations

import math
from numbers import Real


def real_number(name: str, value: object) -> float:
    """Return ``value`` as a float, or raise ``TypeError`` naming ``name`` if it is not a real
    number (bool is refused), ``ValueError`` if it does not fit a float."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{name} must be a real number, got {value!r} ({type(value).__name__})")
    try:
        return float(value)
    except (OverflowError, ValueError):
        raise ValueError(f"{name} must be a finite number, got {value!r}") from None


def positive_finite(name: str, value: object) -> float:
    """Return ``value`` as a float, or raise ``ValueError`` naming ``name`` and the value.

    Parameters
    ----------
    name : str
        Argument name used in the message.
    value : object
        Value to check; must be a real, finite, strictly positive number (bool is refused).
    """
    v = real_number(name, value)
    if not math.isfinite(v) or v <= 0.0:
        raise ValueError(f"{name} must be positive and finite, got {value!r}")
    return v


def in_open_interval(name: str, value: object, low: float, high: float) -> float:
    """Return ``value`` as a float if ``low < value < high``, else raise naming ``name``."""
    v = real_number(name, value)
    if not (math.isfinite(v) and low < v < high):
        raise ValueError(f"{name} must lie in ({low:g}, {high:g}), got {value!r}")
    return v


def one_of(name: str, value: object, allowed: tuple[str, ...]) -> str:
    """Return ``value`` if it is one of ``allowed``, else raise naming ``name``."""
    if value not in allowed:
        raise ValueError(f"{name} must be one of {', '.join(map(repr, allowed))}; got {value!r}")
    return value  # type: ignore[return-value]


def int_at_least(name: str, value: object, minimum: int = 1) -> int:
    """Return ``value`` if it is an int >= ``minimum``, else raise naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return value


def bool_fields(obj: object) -> None:
    """Raise ``TypeError`` naming the first field of dataclass ``obj`` declared ``bool`` whose value
    is not a bool (``"no"``, ``0`` and ``None`` are refused, never read as true or false)."""
    from dataclasses import fields

    for f in fields(obj):  # type: ignore[arg-type]
        if f.type in ("bool", bool):
            value = getattr(obj, f.name)
            if not isinstance(value, bool):
                raise TypeError(f"{f.name} must be true or false (a bool), got {value!r}")
