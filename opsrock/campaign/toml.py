"""The one checker of opsrock's TOML files (scenes, record scenes, blocks files).

A :class:`TomlFile` reads a file and checks its values one field at a time; every problem raises
:class:`~opsrock.errors.SceneError` naming the file, the field as a dotted path (``grid.pfa_ratio.num``,
``block[2].width``, ``records.building[0].period``) and the value, so a bad file is refused whole
before anything runs.
"""

from __future__ import annotations

import math
import re
import tomllib
from numbers import Real
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from opsrock._files import not_a_file
from opsrock.errors import MISSING, SceneError

#: Largest number of values on one axis (a pulse grid's ratios, a record scene's intensity levels): a
#: guard against a typo (``num = 1000000``) that would otherwise allocate and queue an absurd campaign;
#: 10 000 x 10 000 pulses per block is already far beyond any overturning spectrum.
MAX_AXIS_POINTS: int = 10_000

#: Names that become part of case ids (``bookcase/f03/a07``) and file names: kept plain.
NAME_PATTERN = re.compile(r"^[A-Za-z0-9_.-]+$")


def dotted(prefix: str, key: str) -> str:
    """``prefix.key``, or ``key`` at the top level."""
    return f"{prefix}.{key}" if prefix else key


class TomlFile:
    """A TOML file and the checks of its fields.

    Parameters
    ----------
    path : str or Path
        The file; :meth:`read` loads it.
    """

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)

    def error(self, where: str, value: Any, problem: str) -> SceneError:
        """The error for field ``where`` holding ``value`` (:data:`~opsrock.errors.MISSING` if absent)."""
        return SceneError(self.path, where, value, problem)

    def read(self) -> dict:
        """The file's top-level table."""
        path = self.path
        kind = not_a_file(path)  # a device never ends, a FIFO blocks: neither is opened
        if kind is not None:
            raise self.error("(file)", str(path), f"is {kind}, not a TOML file")
        try:
            with open(path, "rb") as fh:
                return tomllib.load(fh)
        except FileNotFoundError:
            raise self.error("(file)", str(path), "no such file") from None
        except IsADirectoryError:
            raise self.error("(file)", str(path), "is a directory, not a TOML file") from None
        except tomllib.TOMLDecodeError as exc:
            raise self.error("(file)", str(path), f"not valid TOML: {exc}") from None
        except UnicodeDecodeError as exc:
            raise self.error("(file)", str(path), f"not UTF-8 text: {exc}") from None
        except RecursionError:  # a symlink loop reads as nested paths until Python gives up
            raise self.error("(file)", str(path), "cannot be read: too many levels of symbolic links") from None
        except OSError as exc:  # unreadable (permissions), a FIFO gone wrong, a symlink loop, an I/O error
            raise self.error("(file)", str(path), f"cannot be read: {exc.strerror or exc}") from None

    # --- structure -------------------------------------------------------------------------------
    def table(self, where: str, value: Any, what: str) -> dict:
        """``value`` if it is a table; ``what`` says which (``"a table [pulse] with shape"``)."""
        if not isinstance(value, dict):
            raise self.error(where, value, f"must be {what}")
        return value

    def keys(self, prefix: str, table: Mapping, *, allowed: set[str], required: set[str] = frozenset()) -> None:
        """Every key of ``table`` allowed, every required one present."""
        for key in table:
            if key not in allowed:
                raise self.error(dotted(prefix, key), table[key], f"unknown key (allowed: {', '.join(sorted(allowed))})")
        for key in sorted(required):
            if key not in table:
                raise self.error(dotted(prefix, key), MISSING, "required field is missing")

    # --- values ----------------------------------------------------------------------------------
    def string(self, where: str, value: Any, *, allow_empty: bool = False) -> str:
        if not isinstance(value, str):
            raise self.error(where, value, f"must be a string, not {type(value).__name__}")
        if not allow_empty and not value.strip():
            raise self.error(where, value, "must not be empty")
        return value

    def name(self, where: str, value: Any) -> str:
        """A plain name (letters, digits, ``_ . -``), as case ids need."""
        text = self.string(where, value)
        if not NAME_PATTERN.match(text):
            raise self.error(where, text, "must use only letters, digits, '_', '.', '-'")
        return text

    def number(self, where: str, value: Any) -> float:
        """A finite real number (bool is refused)."""
        if isinstance(value, bool) or not isinstance(value, Real):
            raise self.error(where, value, f"must be a number, not {type(value).__name__}")
        v = float(value)
        if not math.isfinite(v):
            raise self.error(where, value, "must be finite")
        return v

    def positive(self, where: str, value: Any) -> float:
        """A finite number > 0."""
        v = self.number(where, value)
        if v <= 0.0:
            raise self.error(where, value, "must be positive")
        return v

    def integer(self, where: str, value: Any, low: int, high: int) -> int:
        """An integer in ``[low, high]``."""
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.error(where, value, f"must be an integer, not {type(value).__name__}")
        if not low <= value <= high:
            raise self.error(where, value, f"must be an integer in {low}..{high}")
        return value

    def boolean(self, where: str, value: Any) -> bool:
        """``true`` or ``false`` (``"no"``, ``0`` and the like are refused, never read as either)."""
        if not isinstance(value, bool):
            raise self.error(where, value, "must be true or false")
        return value

    def strings(self, where: str, value: Any, what: str = "names") -> list[str]:
        """A non-empty list of strings."""
        if not isinstance(value, list) or not value or not all(isinstance(v, str) for v in value):
            raise self.error(where, value, f"must be a non-empty list of {what}")
        return value

    def axis(self, where: str, raw: Any) -> tuple[float, ...]:
        """One axis of values: ``{values = [...]}`` or a bare list (distinct positive numbers), or
        ``{start, stop, num}`` (``num >= 2`` equal steps from ``start`` to ``stop > start``); at most
        :data:`MAX_AXIS_POINTS` values."""
        bare = isinstance(raw, list)
        if bare:
            raw = {"values": raw}
        self.table(where, raw, "a list of values, or a table with start/stop/num or values")
        if "values" in raw:
            self.keys(where, raw, allowed={"values"}, required={"values"})
            return self._values(where if bare else f"{where}.values", raw["values"])
        self.keys(where, raw, allowed={"start", "stop", "num"}, required={"start", "stop", "num"})
        start = self.positive(f"{where}.start", raw["start"])
        stop = self.positive(f"{where}.stop", raw["stop"])
        num = raw["num"]
        if isinstance(num, bool) or not isinstance(num, int):
            raise self.error(f"{where}.num", num, f"must be an integer, not {type(num).__name__}")
        if num < 2:
            raise self.error(f"{where}.num", num, "must be >= 2 (use values = [x] for a single value)")
        if num > MAX_AXIS_POINTS:
            raise self.error(f"{where}.num", num, f"must be <= {MAX_AXIS_POINTS} (MAX_AXIS_POINTS)")
        if not stop > start:
            raise self.error(f"{where}.stop", raw["stop"], f"must exceed start = {raw['start']!r}")
        # float() of each numpy value: plain Python floats, identical on every run and platform.
        return tuple(float(v) for v in np.linspace(start, stop, num))

    def _values(self, where: str, values: Any) -> tuple[float, ...]:
        if not isinstance(values, list):
            raise self.error(where, values, "must be an array of numbers")
        if not values:
            raise self.error(where, values, "must not be empty")
        if len(values) > MAX_AXIS_POINTS:
            raise self.error(where, f"<{len(values)} values>", f"must hold <= {MAX_AXIS_POINTS}")
        out = tuple(self.positive(f"{where}[{k}]", v) for k, v in enumerate(values))
        if len(set(out)) != len(out):
            raise self.error(where, values, "must not repeat a value")
        return out

    def setting(self, where: str, value: Any) -> None:
        """A solver setting's value: a number, string, boolean or array of them (a table, one level deep)."""
        if isinstance(value, dict):
            for sub, v in value.items():
                self.setting(f"{where}.{sub}", v)
            return
        if isinstance(value, (bool, int, str)):
            return
        if isinstance(value, float):
            if not math.isfinite(value):
                raise self.error(where, value, "must be finite")
            return
        if isinstance(value, list):
            for k, v in enumerate(value):
                self.setting(f"{where}[{k}]", v)
            return
        raise self.error(where, value, f"must be a number, string, boolean or array, not {type(value).__name__}")


def canonical(value: Any) -> Any:
    """Settings as plain JSON data (dicts with sorted keys, lists, str, bool, int, float)."""
    if isinstance(value, Mapping):
        return {str(k): canonical(value[k]) for k in sorted(value)}
    if isinstance(value, (list, tuple)):
        return [canonical(v) for v in value]
    return value


__all__ = ["MAX_AXIS_POINTS", "NAME_PATTERN", "TomlFile", "canonical", "dotted"]
