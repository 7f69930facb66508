"""Shenton (1996), *Criteria for initiation of slide, rock, and slide-rock rigid-body modes*, J. Eng.
Mech. 122(7): which motion a rectangular block on a floor with Coulomb friction starts from
rest under a floor acceleration.

What we could read of the paper is its abstract: a slide-rock mode can start from rest; it starts
when the friction coefficient exceeds the width-to-height ratio but stays below a critical value that
depends on the floor acceleration; the friction that pure rocking needs grows with the acceleration.
We could not read the paper's own inequalities. The criteria below are therefore derived here (from
the first instant of each mode, docs/guide/friction.md: leaving rest), and were checked
against those qualitative statements and against an independent Moreau-Jean time stepper with contact
and friction at impulse level (:mod:`opsrock.solvers.moreau_jean`, ``tests/model/solvers/test_moreau_jean.py``); they
are not a transcription of Shenton's equations.

Derivation in short. At rest (``theta = theta' = 0``) with floor accelerations ``a_h`` (horizontal) and
``a_v`` (vertical, up), write ``g_v = g + a_v``, ``lambda = |a_h| / g_v``, ``beta = b / h``. Rocking about
the corner ``s = -sgn(a_h)`` with the pivot stuck needs the pivot's friction-to-normal force ratio

    |F| / N = mu_crit(lambda, beta) = [lambda (1 + 4 beta²) + 3 beta] / [4 + beta² + 3 lambda beta],

which equals ``beta`` at ``lambda = beta``, grows with ``lambda``, tends to ``3 beta / (4 + beta²)`` as
``lambda -> 0`` and to ``(1 + 4 beta²) / (3 beta)`` as ``lambda -> infinity``. The modes (static
coefficient ``mu``, kinetic ``mu_k <= mu``):

==============  ====================================================================
rest            ``lambda <= mu`` and ``lambda <= beta``
slide           ``lambda > mu`` and ``mu < beta``
rock            ``lambda > beta`` and ``mu >= mu_crit(lambda, beta)``
slide-rock      ``lambda > beta``, ``beta <= mu < mu_crit(lambda, beta)`` and ``mu_k >= beta``
slide           ``lambda > beta``, ``beta <= mu < mu_crit(lambda, beta)`` and ``mu_k < beta``
==============  ====================================================================

The last row (an addition for ``mu_k < mu``, outside Shenton's single coefficient): the pivot cannot
stick, and once it slips a kinetic coefficient below ``b / h`` turns the block inwards, so both
corners stay down and the base slides. At ``mu_k = b / h`` exactly the initial rotation rate vanishes;
that boundary is given to slide-rock, as ``mu = b / h`` is in the single-coefficient table.

The block needs weight, ``g_v > 0``; without it there is no contact (free flight), which is outside
these criteria and refused.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from opsrock.constants import G
from opsrock.errors import InputError

#: Range of ``lambda = |a_h| / (g + a_v)`` (dimensionless): any ratio a floor can produce.
LAMBDA_RANGE: tuple[float, float] = (0.0, 1e6)
#: Range of ``beta = b / h`` (dimensionless): from a needle (1e-3) to a wide slab (10).
BETA_RANGE: tuple[float, float] = (1e-3, 10.0)
#: Range of the static friction coefficient ``mu`` (dimensionless), as :data:`opsrock.limits.LIMITS`.
MU_RANGE: tuple[float, float] = (0.0, 100.0)
#: Largest ``|a_h|`` and ``|a_v|`` (m/s²): 100 g, as the floor accelerations opsrock accepts.
ACCELERATION_MAX: float = 1e3

#: The modes a block can start from rest, in the order of the table above.
INITIAL_MODES: tuple[str, ...] = ("rest", "slide", "rock", "slide_rock")


class InitialMode(NamedTuple):
    """The motion a block starts from rest.

    Attributes
    ----------
    mode : str
        One of :data:`INITIAL_MODES`.
    corner : int
        For ``"rock"`` and ``"slide_rock"``: the pivot corner ``s = -sgn(a_h)`` (``+1`` the corner on the
        positive-x side, ``theta > 0``; ``-1`` the other), which is also the pivot's slip direction in
        slide-rock. For ``"slide"``: the slip direction of the base relative to the floor, ``-sgn(a_h)``.
        0 for ``"rest"``.
    """

    mode: str
    corner: int


def _in_range(name: str, value: float, bounds: tuple[float, float], unit: str) -> float:
    """``value`` as a float if finite and within ``bounds`` (closed); the message names ``name``."""
    v = float(value)
    if not (math.isfinite(v) and bounds[0] <= v <= bounds[1]):
        raise InputError(f"{name} must lie in [{bounds[0]:g}, {bounds[1]:g}]{unit}, got {value!r}")
    return v


def mu_crit(lam: float, beta: float) -> float:
    """Friction coefficient a block at rest needs to start pure rocking (dimensionless).

    Parameters
    ----------
    lam : float
        ``lambda = |a_h| / (g + a_v)`` (dimensionless), within :data:`LAMBDA_RANGE`.
    beta : float
        ``b / h = tan(alpha)`` (dimensionless), within :data:`BETA_RANGE`.

    Returns
    -------
    float
        ``[lambda (1 + 4 beta²) + 3 beta] / [4 + beta² + 3 lambda beta]`` (dimensionless). Meaningful as
        a rocking criterion for ``lambda > beta`` (below it the block does not uplift).
    """
    lam = _in_range("lam", lam, LAMBDA_RANGE, "")
    beta = _in_range("beta", beta, BETA_RANGE, "")
    return (lam * (1.0 + 4.0 * beta * beta) + 3.0 * beta) / (4.0 + beta * beta + 3.0 * lam * beta)


def initial_mode(a_h: float, a_v: float, b_over_h: float, mu: float, mu_k: float | None = None) -> InitialMode:
    """The mode a block at rest starts under the floor accelerations ``a_h``, ``a_v`` (module table).

    Parameters
    ----------
    a_h : float
        Horizontal floor acceleration (m/s², positive along +x), ``|a_h| <=`` :data:`ACCELERATION_MAX`.
        A positive ``a_h`` tips the block towards negative ``theta`` (corner ``-1``).
    a_v : float
        Vertical floor acceleration (m/s², positive up), with ``g + a_v > 0`` and ``a_v <=``
        :data:`ACCELERATION_MAX`.
    b_over_h : float
        Width over height of the block, ``beta = b / h`` (dimensionless), within :data:`BETA_RANGE`.
    mu : float
        Static Coulomb friction coefficient (dimensionless), within :data:`MU_RANGE`.
    mu_k : float or None, optional
        Kinetic coefficient (dimensionless), ``0 <= mu_k <= mu``. Default None: ``mu_k = mu``.

    Returns
    -------
    InitialMode
        The mode and the corner (or slip direction). Boundaries: ``lambda`` equal to ``mu`` or ``beta``
        stays at rest; ``mu`` equal to ``mu_crit`` rocks; ``mu`` equal to ``beta`` (with ``lambda > beta``)
        slide-rocks.

    Raises
    ------
    InputError
        An argument outside its range, or ``g + a_v <= 0`` (no weight: free flight).
    """
    a_h = _in_range("a_h", a_h, (-ACCELERATION_MAX, ACCELERATION_MAX), " m/s²")
    a_v = _in_range("a_v", a_v, (-ACCELERATION_MAX, ACCELERATION_MAX), " m/s²")
    beta = _in_range("b_over_h", b_over_h, BETA_RANGE, "")
    mu = _in_range("mu", mu, MU_RANGE, "")
    mu_k = mu if mu_k is None else _in_range("mu_k", mu_k, (0.0, mu), "")
    g_v = G + a_v
    if g_v <= 0.0:
        raise InputError(f"a_v = {a_v!r} m/s² leaves the block no weight (g + a_v = {g_v:g} <= 0): it flies, "
                         "which is outside the initiation criteria")
    lam = _in_range("|a_h| / (g + a_v)", abs(a_h) / g_v, LAMBDA_RANGE, "")
    s = -1 if a_h > 0.0 else 1
    if lam <= mu and lam <= beta:
        return InitialMode("rest", 0)
    if mu < beta:
        return InitialMode("slide", s)
    if mu >= mu_crit(lam, beta):
        return InitialMode("rock", s)
    return InitialMode("slide_rock" if mu_k >= beta else "slide", s)


__all__ = ["ACCELERATION_MAX", "BETA_RANGE", "INITIAL_MODES", "LAMBDA_RANGE", "MU_RANGE", "InitialMode",
           "initial_mode", "mu_crit"]
