"""An item's friction on its floor: a fixed coefficient or a distribution drawn once per case.

The inventory's ``friction`` cell holds a number (``0.4``) or a distribution, its name and parameters
(positional, or named as below):

================================= ==========================================================================
``uniform(low, high)``            uniform on ``[low, high]``, ``0 <= low < high <= 1.3``
``normal(mean, std)``             normal, truncated to ``(0, 1.3]``
``lognormal(median, beta)``       lognormal (``ln mu`` normal with median ``ln(median)``, standard deviation
                                  ``beta``), truncated to ``(0, 1.3]``
================================= ==========================================================================

Every draw lies in ``(0, MU_MAX]``, ``MU_MAX = 1.3`` (:data:`opsrock.limits.LIMITS` ``"friction_kinetic"``):
above it the slide-rock equations of a rectangle need a kinetic coefficient below the static one, and no
floor motion makes a block with ``mu`` above about 1 slide anyway. A normal or lognormal distribution that
puts more than :data:`MAX_TRUNCATED` of its probability outside ``(0, MU_MAX]`` is refused: truncating it
would make it another distribution than the one written.

Each case draws its own coefficient from a generator seeded by the study's seed and the case id (SHA-256 of
the id, as :class:`opsrock.restitution.RestitutionDistribution` draws a restitution factor, on a stream of
its own so that the two draws of one case are independent): a draw does not depend on the order cases run
in, on the workers, or on an interruption. The draw is the distribution's quantile at a uniform number
(inverse transform), so the same uniform gives the same quantile in every distribution.

A kinetic coefficient with a distribution (``friction_kinetic``) is the kinetic coefficient at the
distribution's median; each draw scales it with the static one (``mu_k = mu_s friction_kinetic / median``).
"""

from __future__ import annotations

import hashlib
import math
import re
from dataclasses import dataclass
from statistics import NormalDist
from typing import Any

import numpy as np

from opsrock.errors import InputError, OpsrockError
from opsrock.limits import LIMITS, check, check_count

#: Largest friction coefficient a distribution draws (dimensionless): the kinetic coefficient's bound.
MU_MAX: float = LIMITS["friction_kinetic"].high

#: Largest probability a normal or lognormal distribution may put outside ``(0, MU_MAX]`` (dimensionless).
MAX_TRUNCATED: float = 0.01

#: The distributions, with their parameter names in order.
FRICTION_DISTRIBUTIONS: dict[str, tuple[str, ...]] = {
    "uniform": ("low", "high"),
    "normal": ("mean", "std"),
    "lognormal": ("median", "beta"),
}

#: Stream of the friction draws, kept apart from the restitution draws of the same seed and case id.
FRICTION_STREAM: int = 0x6D75  # "mu"

_CALL = re.compile(r"^\s*([A-Za-z_]+)\s*\((.*)\)\s*$")
_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$", re.ASCII)  # ASCII digits only
_STD = NormalDist()

#: Parameters that must be positive (a spread, a lognormal's median).
_POSITIVE = frozenset({"std", "beta", "median"})

#: Smallest dispersion (``std`` of a normal law, ``beta`` of a lognormal one; dimensionless) a distribution may
#: have: below it every draw is the same coefficient to 0.1 %, so the distribution is a fixed coefficient
#: written in a misleading way, or a typing mistake (``1e-320``, a denormal, draws nothing but the median).
MIN_DISPERSION: float = 1e-3


def unit_draw(seed: int, case_id: str, stream: int = FRICTION_STREAM) -> float:
    """A uniform number in (0, 1) determined by ``seed``, ``case_id`` and ``stream`` alone (dimensionless)."""
    key = int.from_bytes(hashlib.sha256(case_id.encode()).digest()[:8], "little")
    return float(np.random.default_rng([seed, key, stream]).random()) or 0.5


@dataclass(frozen=True)
class FrictionLaw:
    """An item's friction: a fixed coefficient or a distribution drawn once per case.

    Parameters
    ----------
    distribution : str
        ``"fixed"``, or a key of :data:`FRICTION_DISTRIBUTIONS` (``"uniform"``, ``"normal"``, ``"lognormal"``).
    parameters : tuple of float
        ``(mu,)`` for ``"fixed"``; the distribution's parameters otherwise, in the order of
        :data:`FRICTION_DISTRIBUTIONS` (dimensionless).
    kinetic_ratio : float or None
        ``mu_k / mu_s`` when the inventory gives ``friction_kinetic`` with a distribution (in [0, 1]); None:
        ``mu_k = mu_s`` (a fixed coefficient keeps its kinetic coefficient in the item).
    """

    distribution: str
    parameters: tuple[float, ...]
    kinetic_ratio: float | None = None

    def __post_init__(self) -> None:
        kind = self.distribution
        if kind != "fixed" and kind not in FRICTION_DISTRIBUTIONS:
            raise InputError(f"friction: unknown distribution {kind!r} (known: "
                             f"{', '.join(_forms())}, or a number)", argument="friction")
        names = ("mu",) if kind == "fixed" else FRICTION_DISTRIBUTIONS[kind]
        params = tuple(self.parameters)
        if len(params) != len(names):
            raise InputError(f"friction: {kind} takes {len(names)} parameter(s) ({', '.join(names)}), got "
                             f"{len(params)}", argument="friction")
        values = tuple(_positive(f"friction {kind} {n}", v) if n in _POSITIVE
                       else _coefficient("friction" if kind == "fixed" else f"friction {kind} {n}", v)
                       for n, v in zip(names, params))
        object.__setattr__(self, "parameters", values)
        for n, v in zip(names, values):
            if n in ("std", "beta") and v < MIN_DISPERSION:
                raise InputError(f"friction: {kind} {n} = {v!r} is below {MIN_DISPERSION:g}: every draw would be the "
                                 "same coefficient; write the number itself", argument="friction")
        self._check_support()
        if self.kinetic_ratio is not None:
            r = self.kinetic_ratio
            if isinstance(r, bool) or not isinstance(r, (int, float)) or not (math.isfinite(r) and 0.0 <= r <= 1.0):
                raise InputError(f"friction_kinetic / median friction = {r!r} must lie in [0, 1]: the kinetic "
                                 "coefficient must not exceed the static one", argument="friction_kinetic")
            if kind == "fixed":
                raise InputError("friction: a fixed coefficient keeps friction_kinetic itself, not a ratio",
                                 argument="friction_kinetic")

    def _check_support(self) -> None:
        """Refuse a distribution whose draws would leave ``(0, MU_MAX]`` or that truncation would change."""
        kind, p = self.distribution, self.parameters
        if kind == "fixed":
            return
        if kind == "uniform":
            if not p[0] < p[1] <= MU_MAX:
                raise InputError(f"friction: uniform(low={p[0]:g}, high={p[1]:g}) needs 0 <= low < high <= "
                                 f"{MU_MAX:g}", argument="friction")
            return
        outside = 1.0 - self._mass_inside()
        if outside > MAX_TRUNCATED:
            raise InputError(f"friction: {self.text} puts {outside:.1%} of its draws outside (0, {MU_MAX:g}], more "
                             f"than {MAX_TRUNCATED:.0%}: narrow it or move it inside", argument="friction")

    def _z_bounds(self) -> tuple[float, float]:
        """The truncation ``(0, MU_MAX]`` in standard-normal units of a normal or lognormal law."""
        a, b = self.parameters
        if self.distribution == "normal":
            return -a / b, (MU_MAX - a) / b
        return -math.inf, math.log(MU_MAX / a) / b

    def _mass_inside(self) -> float:
        lo, hi = self._z_bounds()
        return _STD.cdf(hi) - (0.0 if lo == -math.inf else _STD.cdf(lo))

    # --- values ----------------------------------------------------------------------------------
    @property
    def fixed(self) -> bool:
        """True for a fixed coefficient (no draw)."""
        return self.distribution == "fixed"

    def quantile(self, u: float) -> float:
        """The static coefficient at probability ``u`` in (0, 1) (dimensionless): the truncated distribution's
        inverse CDF; the coefficient itself when fixed."""
        kind, p = self.distribution, self.parameters
        if kind == "fixed":
            return p[0]
        if kind == "uniform":
            return p[0] + u * (p[1] - p[0])
        lo, hi = self._z_bounds()
        c_lo = 0.0 if lo == -math.inf else _STD.cdf(lo)
        z = _STD.inv_cdf(min(max(c_lo + u * (_STD.cdf(hi) - c_lo), 1e-300), 1.0 - 1e-16))
        mu = p[0] + p[1] * z if kind == "normal" else p[0] * math.exp(p[1] * z)
        return min(max(mu, math.ulp(0.0)), MU_MAX)

    @property
    def median(self) -> float:
        """The median static coefficient (dimensionless), of the truncated distribution."""
        return self.quantile(0.5)

    def draw(self, case_id: str, seed: int) -> float:
        """The static coefficient of one case (dimensionless), the same for the same seed and case id."""
        if self.fixed:
            return self.parameters[0]
        return self.quantile(unit_draw(check_count("seed", seed), case_id))

    def kinetic(self, mu_s: float) -> float | None:
        """The kinetic coefficient that goes with the static coefficient ``mu_s`` of a draw (dimensionless);
        None: equal to it (or, when fixed, the item's own ``friction_kinetic``)."""
        return None if self.kinetic_ratio is None else self.kinetic_ratio * mu_s

    @property
    def text(self) -> str:
        """The law as an inventory writes it (``0.4``, ``lognormal(median=0.4, beta=0.2)``)."""
        if self.fixed:
            return repr(self.parameters[0])
        names = FRICTION_DISTRIBUTIONS[self.distribution]
        return f"{self.distribution}({', '.join(f'{n}={v!r}' for n, v in zip(names, self.parameters))})"

    def fingerprint(self) -> list[Any]:
        """What determines the draws (with the seed), as JSON data."""
        return [self.distribution, list(self.parameters), self.kinetic_ratio]


def _coefficient(label: str, value: object) -> float:
    """A friction coefficient within ``LIMITS["friction"]``; errors name ``friction`` as their argument."""
    try:
        return check("friction", value, shown_as=label)
    except OpsrockError as exc:
        raise InputError(str(exc), argument="friction") from None


def _positive(label: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (math.isfinite(value) and value > 0):
        raise InputError(f"{label} must be a positive finite number, got {value!r}", argument="friction")
    return float(value)


def _forms() -> list[str]:
    return [f"{k}({', '.join(v)})" for k, v in FRICTION_DISTRIBUTIONS.items()]


def parse_friction(text: str, kinetic_ratio: float | None = None) -> FrictionLaw:
    """The :class:`FrictionLaw` an inventory cell writes: a number (fixed), or ``name(p1, p2)`` with the
    parameters positional or named (``lognormal(median=0.4, beta=0.2)``); see the module docstring.

    Raises
    ------
    InputError
        Naming the text and what is wrong (``argument`` ``"friction"``).
    """
    raw = text.strip()
    if _NUMBER.match(raw):
        return FrictionLaw("fixed", (float(raw),), kinetic_ratio)
    call = _CALL.match(raw)
    if call is None:
        raise InputError(f"friction: {text!r} is neither a number nor a distribution ({', '.join(_forms())})",
                         argument="friction")
    kind = call.group(1).lower()
    if kind not in FRICTION_DISTRIBUTIONS:
        raise InputError(f"friction: unknown distribution {call.group(1)!r} (known: {', '.join(_forms())})",
                         argument="friction")
    names = FRICTION_DISTRIBUTIONS[kind]
    return FrictionLaw(kind, _parameters(kind, names, call.group(2)), kinetic_ratio)


def _parameters(kind: str, names: tuple[str, ...], body: str) -> tuple[float, ...]:
    """The parameters of ``kind(body)`` in the order of ``names``: all positional or all named."""
    parts = [s.strip() for s in body.split(",")] if body.strip() else []
    usage = f"{kind}({', '.join(names)})"
    if len(parts) != len(names):
        raise InputError(f"friction: {kind} takes {len(names)} parameters, {usage}; got {len(parts)}",
                         argument="friction")
    named = [p.partition("=") for p in parts]
    if all(sep for _, sep, _ in named):
        given = {k.strip().lower(): v.strip() for k, _, v in named}
        if sorted(given) != sorted(names):
            raise InputError(f"friction: {kind} takes the parameters {usage}, got {', '.join(given)}",
                             argument="friction")
        texts = [given[n] for n in names]
    elif any(sep for _, sep, _ in named):
        raise InputError(f"friction: give {usage} all by position or all by name", argument="friction")
    else:
        texts = parts
    for n, t in zip(names, texts):
        if not _NUMBER.match(t):
            raise InputError(f"friction: {kind} {n} = {t!r} is not a number", argument="friction")
    return tuple(float(t) for t in texts)


@dataclass(frozen=True)
class FrictionDistribution:
    """A :class:`FrictionLaw` with the seed of its draws: what a :class:`opsrock.campaign.scene.BlockSpec`
    carries to draw each case's friction (:meth:`opsrock.campaign.scene.BlockSpec.block_for`).

    Parameters
    ----------
    law : FrictionLaw
        The distribution (not fixed).
    seed : int
        Seed of the draws (with each case id), within :data:`opsrock.limits.LIMITS` ``"seed"``.
    """

    law: FrictionLaw
    seed: int = 0

    def __post_init__(self) -> None:
        check_count("seed", self.seed)
        if not isinstance(self.law, FrictionLaw):
            raise InputError(f"law must be a FrictionLaw, got {self.law!r}", argument="friction")

    def sample(self, case_id: str) -> tuple[float, float | None]:
        """``(mu_s, mu_k)`` of case ``case_id`` (dimensionless); ``mu_k`` None: equal to ``mu_s``."""
        mu = self.law.draw(case_id, self.seed)
        return mu, self.law.kinetic(mu)

    @property
    def median(self) -> float:
        """The law's median static coefficient (dimensionless)."""
        return self.law.median

    def fingerprint(self) -> list[Any]:
        """What determines the draws, as JSON data."""
        return [*self.law.fingerprint(), self.seed]


__all__ = ["FRICTION_DISTRIBUTIONS", "FRICTION_STREAM", "FrictionDistribution", "FrictionLaw", "MAX_TRUNCATED",
           "MU_MAX", "parse_friction", "unit_draw"]
