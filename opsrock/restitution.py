"""Restitution as a choice with its evidence: named laws, and a distribution sampled per case.

A block's restitution coefficient is ``e = f e_R``, Housner's ``e_R = 1 - 1.5 sin²(alpha)`` times a
factor ``f`` (:class:`opsrock.block.Block`). A blocks file may give ``f`` (``restitution_factor``), ``e``
itself (``restitution``), or a **named law** (``restitution = "<law>"``):

===================== ===========================================================================
``housner``           ``f = 1``: Housner's (1963) angular-momentum law, the rigid block's impact
``paper``             ``f = 0.95``: the reproduced paper's choice (opsrock's default)
``colombo-limestone`` ``f`` = the median of measured/``e_R`` over the first ten impacts of 134
                      free-rocking trials of limestone blocks (Colombo et al., shipped with opsrock;
                      validation case ``experiments``), computed from the data when first used
===================== ===========================================================================

An uncertain restitution is a table: ``restitution_factor = { distribution = "normal", mean = ..., std
= ..., low = ..., high = ..., seed = ... }`` (a normal distribution of ``f`` truncated to ``[low,
high]``), or ``{ distribution = "colombo-limestone", seed = ... }``: the data's median and robust
spread (1.4826 times the median absolute deviation of measured/``e_R`` over the first ten impacts).
Each case draws its own ``f`` from a generator seeded by the table's ``seed`` and the case's id, so a
draw does not depend on the order cases run in, on the workers, or on an interruption, and the same
scene gives the same draws. The factor is drawn once per case (the block's restitution is uncertain),
not per impact; ``e = f e_R`` is always kept at most 1.
"""

from __future__ import annotations

import functools
import hashlib
import math
from dataclasses import dataclass
from typing import Any

from opsrock.constants import DEFAULT_RESTITUTION_FACTOR
from opsrock.errors import InputError

#: The named laws: name -> what ``f`` is.
LAWS: tuple[str, ...] = ("housner", "paper", "colombo-limestone")

#: Distributions a blocks file may name.
DISTRIBUTIONS: tuple[str, ...] = ("normal", "colombo-limestone")

#: Impacts of each measured trial the data-derived law uses: the first ten, the impacts that matter for a
#: block on its way to overturning (later ones are small and noisy).
COLOMBO_IMPACTS: int = 10


@functools.lru_cache(maxsize=1)
def colombo_limestone() -> tuple[float, float]:
    """``(median, robust standard deviation)`` of ``f = measured / e_R`` over the first
    :data:`COLOMBO_IMPACTS` impacts of every distinct trial of the shipped limestone data (dimensionless)."""
    import numpy as np

    from opsrock.published.colombo_limestone import analysis_arrays, load_events

    a = analysis_arrays(load_events())
    q = a.q[a.event <= COLOMBO_IMPACTS]
    med = float(np.median(q))
    return med, float(1.4826 * np.median(np.abs(q - med)))


def law_factor(name: str) -> float:
    """The factor ``f`` of the named law ``name`` (one of :data:`LAWS`), dimensionless."""
    if name == "housner":
        return 1.0
    if name == "paper":
        return DEFAULT_RESTITUTION_FACTOR
    if name == "colombo-limestone":
        return colombo_limestone()[0]
    raise InputError(f"restitution law must be one of {', '.join(LAWS)}, got {name!r}", argument="restitution_law")


def _unit_draw(seed: int, case_id: str) -> float:
    """A uniform number in (0, 1) determined by ``seed`` and ``case_id`` alone."""
    import numpy as np

    key = int.from_bytes(hashlib.sha256(case_id.encode()).digest()[:8], "little")
    return float(np.random.default_rng([seed, key]).random()) or 0.5


@dataclass(frozen=True)
class RestitutionDistribution:
    """A normal distribution of the factor ``f`` truncated to ``[low, high]``, drawn once per case.

    Parameters
    ----------
    mean, std : float
        Mean and standard deviation of the untruncated normal (dimensionless).
    low, high : float
        Truncation (dimensionless), ``0 < low < high``; a draw is also kept at most ``1 / e_R``.
    seed : int
        Seed of the draws (with each case's id).
    source : str
        Where the numbers come from (``"normal"`` as given, or a data-derived law's name).
    """

    mean: float
    std: float
    low: float
    high: float
    seed: int
    source: str = "normal"

    def __post_init__(self) -> None:
        for name in ("mean", "std", "low", "high"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)):
                raise InputError(f"restitution_factor.{name} must be a finite number, got {v!r}")
        if not (self.std > 0.0 and 0.0 < self.low < self.high):
            raise InputError(f"restitution_factor needs std > 0 and 0 < low < high, got std = {self.std!r}, "
                             f"low = {self.low!r}, high = {self.high!r}")
        if not self.low <= self.mean <= self.high:
            raise InputError(f"restitution_factor.mean = {self.mean!r} must lie in [low, high] = "
                             f"[{self.low!r}, {self.high!r}]")

    def sample(self, case_id: str, e_R: float) -> float:  # noqa: N803  (Housner's symbol)
        """The factor of case ``case_id`` for a block of Housner's ``e_R`` (dimensionless); a block with ``e_R <= 0``
        lands flat whatever its factor (``e = 0``, :attr:`opsrock.block.Block.lands_flat`) and gets ``mean``."""
        from scipy.stats import truncnorm

        if e_R <= 0.0:
            return self.mean
        high = min(self.high, 1.0 / e_R)
        if high <= self.low:  # the block's e_R leaves no room above low: e = 1 at most
            return min(self.mean, 1.0 / e_R)
        a, b = (self.low - self.mean) / self.std, (high - self.mean) / self.std
        return float(truncnorm.ppf(_unit_draw(self.seed, case_id), a, b, loc=self.mean, scale=self.std))

    def fingerprint(self) -> list[Any]:
        """What determines the draws, as JSON data."""
        return [self.source, self.mean, self.std, self.low, self.high, self.seed]


def distribution_from_table(table: dict) -> RestitutionDistribution:
    """A :class:`RestitutionDistribution` from a blocks file's table (keys ``distribution``, ``seed`` and,
    for ``normal``, ``mean``, ``std``, ``low``, ``high``; for ``colombo-limestone`` the data's median and
    spread, truncated to 3 standard deviations)."""
    kind = table.get("distribution")
    if kind not in DISTRIBUTIONS:
        raise InputError(f"restitution_factor.distribution must be one of {', '.join(DISTRIBUTIONS)}, got {kind!r}")
    seed = table.get("seed")
    if isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed < 2**32:
        raise InputError(f"restitution_factor.seed must be an integer in [0, 2^32), got {seed!r}")
    allowed = {"distribution", "seed"} | ({"mean", "std", "low", "high"} if kind == "normal" else set())
    extra = sorted(set(table) - allowed)
    if extra:
        raise InputError(f"restitution_factor: unknown key {extra[0]!r} for distribution {kind!r} "
                         f"(allowed: {', '.join(sorted(allowed))})")
    if kind == "colombo-limestone":
        mean, std = colombo_limestone()
        return RestitutionDistribution(mean, std, mean - 3.0 * std, mean + 3.0 * std, seed, kind)
    missing = [k for k in ("mean", "std", "low", "high") if k not in table]
    if missing:
        raise InputError(f"restitution_factor: distribution 'normal' needs {', '.join(missing)}")
    return RestitutionDistribution(table["mean"], table["std"], table["low"], table["high"], seed, kind)


__all__ = ["COLOMBO_IMPACTS", "DISTRIBUTIONS", "LAWS", "RestitutionDistribution", "colombo_limestone",
           "distribution_from_table", "law_factor"]
