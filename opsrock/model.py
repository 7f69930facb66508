"""The paper's equivalent SDOF model (Eq. 5-8): its parameters and its spring table.

This module holds the *model* both SDOF solvers share (the OpenSees one and the scipy one),
never their numerics: the damper band ``delta``, the stiff branch ``theta_e``, the spring
table and the excitation lever ``Lambda``.

    I_O theta'' + f_d(theta, theta') + M_s(theta) = -Lambda a(t)

* ``M_s(theta) = m g R sin(alpha sgn(theta) - theta)`` (Eq. 5), tabulated piecewise-linearly with a
  stiff branch of half-width ``theta_e`` through zero;
* ``f_d = c_D theta'`` while ``|theta| <= delta alpha``, zero outside. ``c_D`` is set afresh at the
  start of every *passage* through the band, i.e. on entering it and at every turning point inside
  it (:data:`DAMPER_LAWS`): by default (``damper="energy"``) so that a free passage keeps ``e²`` of
  the block's energy, as the rigid body's impact does; ``damper="entry_velocity"`` is the paper's
  Eq. 8 as printed, ``c_D = I_O (1 - e) |theta'_1| / (2 delta alpha)`` from the velocity on entering
  and set on entry only, which under-dissipates small rocking (docs/guide/modelling.md section 6);
* ``Lambda = m R cos(alpha)`` (``lever="housner"``, default) or the paper's printed
  ``I_O cos(alpha) / R`` (``lever="printed"``); docs/guide/modelling.md section 2 explains the choice.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from opsrock.block import Block
from opsrock.constants import G
from opsrock.errors import InputError
from opsrock.limits import in_open_interval, int_at_least, one_of

#: Excitation lever options: ``"housner"`` = ``m R cos(alpha)`` (agrees with Eq. 1 and the
#: uplift threshold Eq. 4), ``"printed"`` = ``I_O cos(alpha) / R`` as printed in Eq. 6.
LEVERS: tuple[str, ...] = ("housner", "printed")

#: How the damper coefficient is set (docs/guide/modelling.md section 6):
#:
#: * ``"energy"`` (default): at the start of every passage through the band (entering it, or turning
#:   inside it), ``c_D`` is chosen so that a free passage with the band's restoring moment keeps
#:   ``e²`` of the block's energy ``1/2 I_O theta'² + U(theta)``, the rigid body's loss per impact
#:   (:func:`passage_damping`). It tends to Eq. 8 when the entry kinetic energy dwarfs the band's
#:   potential ``U(delta alpha)``, i.e. in the paper's large rocking.
#: * ``"entry_velocity"``: Eq. 8 as printed, on entering the band only. A block rocking inside the
#:   band (never entering it from outside) then has ``c_D = 0`` and loses no energy at all; one whose
#:   entry velocity is small against the band's potential loses far less than ``1 - e²``.
DAMPER_LAWS: tuple[str, ...] = ("energy", "entry_velocity")

#: Default damper band ``delta`` (fraction of alpha). Chosen by the model-form convergence
#: study (validation/model_form): see docs/guide/solvers.md.
DEFAULT_DELTA: float = 0.005

#: Default stiff-branch half-width ``theta_e / alpha``. docs/guide/modelling.md section 4: 1e-6 alpha matched
#: the rigid-body first peak to 0.04 %, 1e-4 alpha gave 0.9 % high, 1e-2 alpha 10 % low.
DEFAULT_THETA_E_RATIO: float = 1e-6

#: Default number of table points per side beyond the stiff branch. docs/guide/modelling.md section 4:
#: about 30 points give 0.1-0.2 % of ``m g R sin(alpha)``.
DEFAULT_TABLE_POINTS: int = 30

#: The table extends this far beyond ``pi/2 + alpha`` (rad), so an overturning block never
#: runs off the table before the overturning check stops the analysis.
TABLE_MARGIN: float = 0.2


@dataclass(frozen=True)
class SDOFModel:
    """Parameters of the equivalent SDOF model (not of any solver's numerics).

    Parameters
    ----------
    delta : float
        Half-width of the damper band as a fraction of ``alpha`` (dimensionless, in (0, 1)).
    theta_e_ratio : float
        Half-width of the stiff spring branch, ``theta_e / alpha`` (dimensionless, in (0, delta)).
    table_points : int
        Number of tabulated points per side beyond the stiff branch (>= 4).
    lever : str
        Excitation lever, one of :data:`LEVERS`.
    damper : str
        How ``c_D`` is set, one of :data:`DAMPER_LAWS`.
    """

    delta: float = DEFAULT_DELTA
    theta_e_ratio: float = DEFAULT_THETA_E_RATIO
    table_points: int = DEFAULT_TABLE_POINTS
    lever: str = "housner"
    damper: str = "energy"

    def __post_init__(self) -> None:
        object.__setattr__(self, "delta", in_open_interval("delta", self.delta, 0.0, 1.0))
        object.__setattr__(self, "theta_e_ratio", in_open_interval("theta_e_ratio", self.theta_e_ratio, 0.0, 1.0))
        if self.theta_e_ratio >= self.delta:
            # name delta when theta_e_ratio is at its default: delta is what the caller changed
            changed = "delta" if self.theta_e_ratio == DEFAULT_THETA_E_RATIO else "theta_e_ratio"
            value = self.delta if changed == "delta" else self.theta_e_ratio
            raise InputError(
                f"{changed} = {value!r}: the stiff branch must lie inside the damper band, i.e. "
                f"theta_e_ratio < delta; got theta_e_ratio = {self.theta_e_ratio:g}, delta = {self.delta:g}"
            )
        int_at_least("table_points", self.table_points, 4)
        one_of("lever", self.lever, LEVERS)
        one_of("damper", self.damper, DAMPER_LAWS)

    # --- derived, per block ----------------------------------------------------------------
    def theta_e(self, block: Block) -> float:
        """Stiff-branch half-width ``theta_e`` (rad)."""
        return self.theta_e_ratio * block.alpha

    def band(self, block: Block) -> float:
        """Damper band half-width ``delta alpha`` (rad)."""
        return self.delta * block.alpha

    def lever_arm(self, block: Block) -> float:
        """Excitation lever ``Lambda`` (kg m): moment per unit floor acceleration."""
        return lever_coefficient(block, self.lever)

    def damping_coefficient(self, block: Block, entry_velocity: float) -> float:
        """``c_D = I_O (1 - e) |theta'_1| / (2 delta alpha)`` (N m s/rad), Eq. 8.

        Parameters
        ----------
        block : Block
        entry_velocity : float
            Angular velocity on entering the band, ``theta'_1`` (rad/s).
        """
        return block.I_O * (1.0 - block.e) * abs(entry_velocity) / (2.0 * self.band(block))

    def edge_moment(self, block: Block) -> float:
        """Restoring moment at the end of the stiff branch, ``M_s(theta_e)`` from the table (N m)."""
        th, m = self.spring_table(block)
        return float(np.interp(self.theta_e(block), th, m))

    def band_moment(self, block: Block) -> float:
        """Mean restoring moment of the table over ``theta_e <= |theta| <= delta alpha`` (N m)."""
        th, m = self.spring_table(block)
        edges = np.array([self.theta_e(block), self.band(block)])
        return float(np.mean(np.interp(edges, th, m)))  # the table is linear there

    def tracks_passages(self) -> bool:
        """True if ``c_D`` is set per passage: re-armed at turning points inside the band, and zero
        while the block is seated in the stiff branch (no passage under way), as for ``"energy"``."""
        return self.damper == "energy"

    def arm_damper(self, block: Block, theta: float, theta_dot: float) -> float:
        """``c_D`` (N m s/rad) for a passage starting at ``(theta, theta_dot)`` inside the band.

        Parameters
        ----------
        block : Block
        theta : float
            Rotation at the start of the passage (rad): the band edge on entry, the turning point.
        theta_dot : float
            Angular velocity there (rad/s), towards zero (or zero at a turning point).
        """
        if self.damper == "entry_velocity":
            return self.damping_coefficient(block, theta_dot)
        return passage_damping(
            block.I_O, self.band_moment(block), block.e, self.band(block), abs(theta), abs(theta_dot)
        )

    def spring_table(self, block: Block) -> tuple[np.ndarray, np.ndarray]:
        """Tabulated restoring moment, symmetric about zero.

        Returns
        -------
        theta : ndarray
            Rotations (rad), increasing: ``-theta_end .. -theta_e, theta_e .. theta_end``
            with ``theta_end = pi/2 + alpha + TABLE_MARGIN``.
        moment : ndarray
            ``M_s = m g R sin(alpha sgn(theta) - theta)`` at those rotations (N m). Between
            ``-theta_e`` and ``theta_e`` the table is a straight stiff branch through zero.
        """
        theta_e = self.theta_e(block)
        theta_end = 0.5 * math.pi + block.alpha + TABLE_MARGIN
        pos = np.linspace(theta_e, theta_end, self.table_points + 1)
        m_pos = block.mass * G * block.R * np.sin(block.alpha - pos)
        theta = np.concatenate([-pos[::-1], pos])
        moment = np.concatenate([-m_pos[::-1], m_pos])
        return theta, moment


class Seat:
    """The stiff branch ``|theta| <= theta_e`` holding a seated block: the treatment both SDOF solvers share.

    There the exact solution is the quasi-static deflection ``theta_qs = -Lambda a(t) / k_e`` plus a
    free oscillation of amplitude ``A`` at ``omega_e = sqrt(k_e / I_O)`` (about 1000 p), with
    ``k_e = M_s(theta_e) / theta_e``. Once ``|theta_qs| + A < theta_e`` the oscillation is dropped and
    the block follows ``theta_qs`` (seated) until the floor can lift it. An integrator with
    ``omega_e h >> 1`` (OpenSees' Newmark) would otherwise keep the oscillation undamped and could pump
    it out of the branch (docs/guide/modelling.md section 4).

    Parameters
    ----------
    model : SDOFModel
    block : Block
    acceleration : callable
        Floor acceleration (m/s²) as a function of time (s); zero after the excitation.
    """

    def __init__(self, model: "SDOFModel", block: Block, acceleration) -> None:
        self.acceleration = acceleration
        self.lam = model.lever_arm(block)
        self.theta_e = model.theta_e(block)
        self.k_e = model.edge_moment(block) / self.theta_e
        self.omega_e = math.sqrt(self.k_e / block.I_O)

    def theta_qs(self, t: float) -> float:
        """Quasi-static deflection (rad) at ``t`` (s)."""
        return -self.lam * float(self.acceleration(t)) / self.k_e

    def amplitude(self, t: float, theta: float, theta_dot: float) -> float:
        """Amplitude ``A`` (rad) of the free oscillation about ``theta_qs`` of the state ``(theta, theta_dot)``."""
        return math.hypot(theta - self.theta_qs(t), theta_dot / self.omega_e)

    def margin(self, t: float, theta: float, theta_dot: float) -> float:
        """``theta_e - |theta_qs| - A`` (rad): positive once the oscillation fits inside the branch."""
        return self.theta_e - abs(self.theta_qs(t)) - self.amplitude(t, theta, theta_dot)

    def captures(self, t: float, theta: float, theta_dot: float) -> bool:
        """True if the state's oscillation fits inside the branch (and is not already zero)."""
        amp = self.amplitude(t, theta, theta_dot)
        return 0.0 < amp and abs(self.theta_qs(t)) + amp < self.theta_e


def _g(x: float) -> float:
    """``-x - ln|1 - x|`` for ``x >= 0``, ``x != 1``, without cancellation at small ``x``."""
    if x < 1e-3:
        return x * x * (1 / 2 + x * (1 / 3 + x * (1 / 4 + x * (1 / 5 + x / 6))))
    return -x - math.log(abs(1.0 - x)) if x > 0.5 else -x - math.log1p(-x)


def _h(x: float) -> float:
    """``x - ln(1 + x)`` for ``x >= 0``, without cancellation at small ``x``."""
    if x < 1e-3:
        return x * x * (1 / 2 - x * (1 / 3 - x * (1 / 4 - x * (1 / 5 - x / 6))))
    return x - math.log1p(x)


def _inverse(fun, target: float, lo: float, hi: float) -> float:
    """``x`` in ``[lo, hi]`` with ``fun(x) = target`` for an increasing ``fun`` (Brent)."""
    from scipy.optimize import brentq

    if fun(lo) >= target:
        return lo
    return brentq(lambda x: fun(x) - target, lo, hi, xtol=1e-15, rtol=1e-13)


def _speed_at_zero(x_start: float, reduced_distance: float) -> float:
    """Reduced speed ``x = gamma theta' / accel`` after a reduced distance towards zero.

    ``g(x)`` grows by ``reduced_distance`` while ``x`` tends to the terminal speed 1: from below
    (the moment accelerates the block more than the damper brakes it) or from above.
    """
    from scipy.optimize import brentq

    if reduced_distance <= 0.0 or x_start == 1.0:
        return x_start
    target = _g(x_start) + reduced_distance
    lo, hi = (x_start, 1.0 - 1e-15) if x_start < 1.0 else (1.0 + 1e-15, x_start)
    if (_g(hi) if x_start < 1.0 else _g(lo)) <= target:
        return hi if x_start < 1.0 else lo  # within round-off of the terminal speed
    return brentq(lambda x: _g(x) - target, lo, hi, xtol=1e-15, rtol=1e-13)


def passage_energy_ratio(gamma: float, accel: float, band: float, distance: float, speed: float) -> float:
    """Energy kept by one free passage through the band: exact for a constant restoring moment.

    The block starts ``distance`` (rad) from zero moving towards it at ``speed`` (rad/s), under
    ``theta'' = -accel sgn(theta) - gamma theta'`` (``accel = M / I_O``, 1/s²; ``gamma = c_D / I_O``,
    1/s), and stops at its next turning point or on leaving the band on the other side (``|theta| =
    band``, rad). Returns its energy there over its energy at the start, energy being
    ``1/2 theta'² + accel |theta|`` per unit inertia. Distance as a function of speed is closed form
    on either side of zero (``accel / gamma²`` times ``_g`` accelerating, ``_h`` decelerating).
    """
    e_start = 0.5 * speed * speed + accel * distance
    if gamma == 0.0:
        return 1.0
    scale = accel / gamma**2  # rad
    x0 = _speed_at_zero(gamma * speed / accel, distance / scale)  # at zero: speed x0 accel / gamma
    if scale * _h(x0) <= band:  # turns inside the band
        return accel * scale * _h(x0) / e_start
    x_exit = _inverse(_h, _h(x0) - band / scale, 0.0, x0)
    v_exit = x_exit * accel / gamma
    return (0.5 * v_exit * v_exit + accel * band) / e_start


def passage_damping(inertia: float, moment: float, e: float, band: float, distance: float, speed: float) -> float:
    """``c_D`` (N m s/rad) with which a free passage keeps ``e²`` of the energy (``damper="energy"``).

    Parameters
    ----------
    inertia : float
        ``I_O`` (kg m²).
    moment : float
        Restoring moment in the band, taken constant (N m): :meth:`SDOFModel.band_moment`.
    e : float
        Coefficient of restitution (-).
    band : float
        Band half-width ``delta alpha`` (rad).
    distance : float
        ``|theta|`` at the start of the passage (rad), ``<= band``.
    speed : float
        ``|theta'|`` there (rad/s), towards zero.

    Notes
    -----
    For ``speed² >> 2 moment band / inertia`` this is Eq. 8, ``I_O (1 - e) speed / (2 band)``; for a
    block turning inside the band (``speed = 0``) Eq. 8 gives zero. Monotone in ``c_D``, solved by
    Brent's method on :func:`passage_energy_ratio`.
    """
    from scipy.optimize import brentq

    accel = moment / inertia
    e2 = e * e
    if distance <= 0.0 and speed <= 0.0:
        return 0.0
    e_start = 0.5 * speed * speed + accel * distance
    # a bracket: 2x Eq. 8 with the speed at zero of an undamped passage keeps less than e^2
    hi = max((1.0 - e) * math.sqrt(2.0 * e_start) / band, 1e-12)
    while passage_energy_ratio(hi, accel, band, distance, speed) > e2:
        hi *= 2.0
    gamma = brentq(lambda g: passage_energy_ratio(g, accel, band, distance, speed) - e2, 0.0, hi, rtol=1e-12)
    return inertia * gamma


def lever_coefficient(block: Block, lever: str = "housner") -> float:
    """Excitation lever ``Lambda`` (kg m) for the named option (see :data:`LEVERS`)."""
    one_of("lever", lever, LEVERS)
    if lever == "housner":
        return block.mass * block.R * math.cos(block.alpha)
    return block.I_O * math.cos(block.alpha) / block.R


#: Relative round-off allowance of the uplift test: ``PFA = 1.0 g tan(alpha)`` computed in floating
#: point may exceed the peak restoring moment by an ulp or two.
UPLIFT_RTOL: float = 1e-9


def can_uplift(block: Block, model: "SDOFModel", pfa: float) -> bool:
    """Eq. 4 for the SDOF model: can a floor motion of peak ``pfa`` (m/s²) uplift the block from rest?

    True when the peak excitation moment ``|Lambda| PFA`` exceeds the peak restoring moment
    ``m g R sin(alpha)`` (beyond a round-off allowance :data:`UPLIFT_RTOL`). With the housner
    lever this is ``PFA > g tan(alpha)``; with the printed lever ``PFA > 0.75 g tan(alpha)``.

    The SDOF model's stiff branch is finite, so at exactly the threshold it sits at neutral
    equilibrium and can tip numerically (measured in OpenSees: up to 0.03 alpha in 6 of the 40
    threshold cases of the paper grid); the solvers use this test instead (``uplift_check``).
    """
    return abs(model.lever_arm(block)) * pfa > block.overturning_rotation_moment * (1.0 + UPLIFT_RTOL)


def restoring_moment(block: Block, theta: np.ndarray | float) -> np.ndarray:
    """Exact restoring moment ``m g R sin(alpha sgn(theta) - theta)`` (N m), Eq. 5."""
    theta = np.asarray(theta, dtype=float)
    return block.mass * G * block.R * np.sin(block.alpha * np.sign(theta) - theta)


__all__ = [
    "DEFAULT_DELTA",
    "DEFAULT_TABLE_POINTS",
    "DEFAULT_THETA_E_RATIO",
    "DAMPER_LAWS",
    "LEVERS",
    "SDOFModel",
    "Seat",
    "UPLIFT_RTOL",
    "can_uplift",
    "lever_coefficient",
    "passage_damping",
    "passage_energy_ratio",
    "restoring_moment",
]
