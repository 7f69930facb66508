"""The exact rigid-body rocking equation with instantaneous impacts (paper Eq. 1-4, 9-11).

Between impacts the block pivots about one base corner (``s = sgn(theta)``)::

    theta'' = -p² [ sin(alpha s - theta) + a(t)/g cos(alpha s - theta) ]

with a positive floor acceleration ``a`` tipping the block towards negative ``theta``. The
solver is event-driven:

* **seated** while ``|a(t)| <= g tan(alpha)`` (Eq. 4); the first time ``|a|`` exceeds that
  level the block uplifts about the corner set by the sign of ``a`` (``s = -sgn(a)``);
* **impact** when ``theta`` returns to zero: ``theta' -> e theta'`` (Housner's instantaneous
  impact, ``e = block.e``) and the block goes on about the other corner;
* **rest** when the velocity after an impact falls below ``rest_velocity_ratio · p · alpha``:
  the remaining bounces ("chattering") form a geometric series ``e, e², ...`` of vanishing
  duration (at most ``2 |theta'| / ((1 - e) p² alpha)`` in free rocking), so the block is
  set down as seated; it lifts off again if ``|a|`` still exceeds ``g tan(alpha)``;
* **overturning** when ``|theta|`` reaches ``pi/2`` (Eq. 11), a terminal event.

With ``equations="linearised"`` the small-angle form of the classical rocking papers is solved
instead, ``theta'' = -p² [(alpha s - theta) + a/g]`` with uplift when ``|a| > g alpha``
(:data:`opsrock.constants.EQUATIONS`); overturning is still ``|theta| = pi/2``.

The lever here is the exact ``cos(alpha s - theta)`` of Eq. 1; the SDOF model of Eq. 6 keeps
it constant at ``cos(alpha)`` (see :mod:`opsrock.solvers.sdof`): one of the model-form
differences measured by ``validation/model_form``.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import asdict, dataclass, fields, replace
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar

from opsrock._checks import bool_fields, int_at_least, one_of, positive_finite
from opsrock.block import Block
from opsrock.constants import EQUATIONS, G, OVERTURNING_ANGLE
from opsrock.result import ImpactLog, RockingResult, failed_result

#: Explicit Runge-Kutta methods of :func:`scipy.integrate.solve_ivp` accepted here. The
#: rigid-body equation is not stiff (its only rate is ``p``), so explicit high-order methods
#: are the efficient choice; ``"LSODA"``/``"Radau"`` are accepted for cross-checks.
METHODS: tuple[str, ...] = ("DOP853", "RK45", "RK23", "Radau", "LSODA", "BDF")

#: What happens after the excitation ends when ``end_time`` is None:
#: ``"rest"`` integrates the free rocking until the block is seated again (or the cap
#: ``max_free_time`` is reached); ``"peak"`` stops at the first turning point after the
#: excitation ends with ``|theta| < alpha``: from there on the energy only falls (impacts
#: dissipate, nothing feeds it), so no later peak can exceed it and the verdict and
#: ``theta_max`` are already final.
TAILS: tuple[str, ...] = ("rest", "peak")


@dataclass(frozen=True)
class HousnerSettings:
    """Numerical settings of the rigid-body solver (the model has no free parameter).

    Parameters
    ----------
    method : str
        :func:`scipy.integrate.solve_ivp` method, one of :data:`METHODS`. Default
        ``"DOP853"`` (8th-order explicit: the equation is smooth and non-stiff between events).
    rtol : float
        Relative tolerance of the integrator (dimensionless). Default 1e-10: the closed-form
        tests compare to 1e-7 and the solver is the reference for the SDOF models.
    atol : float
        Absolute tolerance on ``theta`` (rad); ``atol · p`` is used on ``theta'`` (rad/s).
        Default 1e-12 rad, far below any rotation of interest (alpha is 0.1-0.5 rad).
    end_time : float or None
        Time at which to stop (s). None: the excitation's duration plus a free-rocking tail
        chosen by ``tail``, capped at ``max_free_time``.
    tail : str
        Free-rocking tail when ``end_time`` is None, one of :data:`TAILS`. Default ``"rest"``.
    max_free_time : float
        Cap on the free-rocking tail after the excitation ends (s). Default 60 s: a slender
        block of R = 1 m rocks down from alpha to rest in a few seconds; a block still rocking
        after the cap has its ``theta_max`` final anyway (energy only falls after the pulse).
    max_step : float
        Largest integrator step (s). Default ``inf`` (the error control decides; excitation
        breakpoints are always stepped on exactly).
    theta0 : float
        Initial rotation (rad), ``|theta0| < pi/2``. Default 0 (seated).
    theta_dot0 : float
        Initial angular velocity (rad/s). Default 0.
    record : bool
        Keep the time histories (every accepted step, both sides of every impact). Default True.
    max_impacts : int
        Largest number of impacts before the run is reported as failed. Default 10 000 (free
        rocking from ``alpha`` to rest takes about ``ln(rest_velocity_ratio) / ln(e)``, i.e.
        100-300 impacts).
    rest_velocity_ratio : float
        After an impact the block is set down as seated if ``|theta'| <
        rest_velocity_ratio · p · alpha`` (dimensionless). Default 1e-6: the bounces left
        would rise to ``~(1e-6)² alpha / 2`` at most.
    scan_step : float or None
        Grid spacing (s) on which the seated phase scans ``|a(t)|`` for uplift before refining
        with Brent's method (local maxima are refined too, so a peak just above the threshold
        between grid points is not missed). None: ``duration / 2000``.
    equations : str
        Form of the equation of motion, one of :data:`opsrock.constants.EQUATIONS`. Default
        ``"exact"`` (Eq. 1); ``"linearised"`` for the small-angle form of the classical papers.
    dense_step : float or None
        If set (s), the stored history also holds the integrator's dense output (its own
        interpolant, of the method's order) every ``dense_step`` inside each step, for figures
        that must not show the long straight chords of large steps. None (default): accepted
        steps and events only.
    """

    method: str = "DOP853"
    rtol: float = 1e-10
    atol: float = 1e-12
    end_time: float | None = None
    tail: str = "rest"
    max_free_time: float = 60.0
    max_step: float = math.inf
    theta0: float = 0.0
    theta_dot0: float = 0.0
    record: bool = True
    max_impacts: int = 10_000
    rest_velocity_ratio: float = 1e-6
    scan_step: float | None = None
    equations: str = "exact"
    dense_step: float | None = None

    def __post_init__(self) -> None:
        bool_fields(self)
        one_of("method", self.method, METHODS)
        one_of("equations", self.equations, EQUATIONS)
        one_of("tail", self.tail, TAILS)
        _check_common(self)
        positive_finite("rest_velocity_ratio", self.rest_velocity_ratio)


def _check_common(s: Any) -> None:
    """Checks shared by the settings of both scipy solvers (errors name the field)."""
    if not 0.0 < _real("rtol", s.rtol) < 1.0:
        raise ValueError(f"rtol must lie in (0, 1), got {s.rtol!r}")
    positive_finite("atol", s.atol)
    if s.end_time is not None:
        positive_finite("end_time", s.end_time)
    positive_finite("max_free_time", s.max_free_time)
    if not (_real("max_step", s.max_step) > 0.0):
        raise ValueError(f"max_step must be positive, got {s.max_step!r}")
    if not (math.isfinite(_real("theta0", s.theta0)) and abs(s.theta0) < OVERTURNING_ANGLE):
        raise ValueError(f"theta0 must be finite with |theta0| < pi/2, got {s.theta0!r}")
    if not math.isfinite(_real("theta_dot0", s.theta_dot0)):
        raise ValueError(f"theta_dot0 must be finite, got {s.theta_dot0!r}")
    if not isinstance(s.record, bool):
        raise TypeError(f"record must be a bool, got {s.record!r}")
    int_at_least("max_impacts", s.max_impacts, 1)
    if s.scan_step is not None:
        positive_finite("scan_step", s.scan_step)
    if s.dense_step is not None:
        positive_finite("dense_step", s.dense_step)


def _real(name: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise TypeError(f"{name} must be a real number, got {value!r}")
    return float(value)


def make_settings(cls: type, settings: Any, overrides: dict[str, Any]) -> Any:
    """Merge ``overrides`` into ``settings`` (an instance of ``cls`` or None), naming bad keys."""
    base = cls() if settings is None else settings
    if not isinstance(base, cls):
        raise TypeError(f"settings must be a {cls.__name__}, got {settings!r}")
    known = {f.name for f in fields(cls)}
    unknown = sorted(set(overrides) - known)
    if unknown:
        raise TypeError(f"unknown setting(s) {unknown} for {cls.__name__}; known: {sorted(known)}")
    return replace(base, **overrides) if overrides else base


def first_exceedance(excitation: Any, level: float, t_start: float, t_stop: float, step: float) -> float | None:
    """First time in ``[t_start, t_stop]`` at which ``|a(t)| > level``, or None.

    Scans ``|a|`` on a grid of spacing ``<= step`` that includes the excitation's
    breakpoints, refines every grid-local maximum lying within 0.1 % below ``level`` (so a
    peak that barely exceeds ``level`` between grid points is found), and locates the
    crossing with Brent's method to ~1e-14 s. The returned time is on the exceeding side.

    Parameters
    ----------
    excitation : Excitation
        Floor motion with ``acceleration(t)`` (m/s²) and ``breakpoints()`` (s).
    level : float
        Acceleration level (m/s²), > 0.
    t_start, t_stop : float
        Search interval (s).
    step : float
        Largest grid spacing (s).
    """
    if t_stop <= t_start:
        return None

    def f(t: float) -> float:
        return float(abs(excitation.acceleration(t))) - level

    if f(t_start) > 0.0:
        return t_start
    n = max(2, int(math.ceil((t_stop - t_start) / step)) + 1)
    bps = np.asarray(excitation.breakpoints(), dtype=float)
    grid = np.union1d(np.linspace(t_start, t_stop, n), bps[(bps > t_start) & (bps < t_stop)])
    vals = np.abs(np.asarray(excitation.acceleration(grid), dtype=float)) - level
    candidates: list[tuple[float, float]] = []  # (t_lo, t_hi) with f(t_lo) <= 0 < f(t_hi)
    above = np.flatnonzero(vals > 0.0)
    if above.size:
        j = int(above[0])
        candidates.append((grid[j - 1], grid[j]))
    # grid-local maxima just below the level, before the first grid exceedance
    last = int(above[0]) if above.size else grid.size - 1
    inner = np.arange(1, last)
    if inner.size:
        peak = (vals[inner] >= vals[inner - 1]) & (vals[inner] >= vals[inner + 1]) & (vals[inner] > -1e-3 * level)
        for i in inner[peak]:
            lo, hi = grid[i - 1], grid[i + 1]
            res = minimize_scalar(lambda t: -f(t), bounds=(lo, hi), method="bounded", options={"xatol": 1e-14 * max(1.0, hi)})
            if -res.fun > 0.0:
                candidates.append((lo, float(res.x)))
                break
    if not candidates:
        return None
    lo, hi = min(candidates)
    tol = 1e-14 * max(1.0, abs(hi))
    root = brentq(f, lo, hi, xtol=tol, rtol=4 * np.finfo(float).eps)
    # step onto the exceeding side so the uplift starts with the right sign of theta''
    for _ in range(60):
        if f(root) > 0.0:
            return root
        root = min(hi, root + tol)
        tol *= 2.0
    return hi


def _out_with_turns(out: Any, sol: Any, k: int, *extra: float, dense_step: float | None = None) -> None:
    """Record a segment's accepted steps merged with its turning points (event ``k``), so the
    stored history holds every peak exactly, not only the nearest step; with ``dense_step`` also
    the dense output (``sol.sol``) every ``dense_step`` seconds."""
    t, th, td = sol.t[1:], sol.y[0, 1:], sol.y[1, 1:]
    if dense_step is not None and sol.sol is not None and sol.t[-1] > sol.t[0]:
        td_grid = np.arange(sol.t[0] + dense_step, sol.t[-1], dense_step)
        if td_grid.size:
            yd = sol.sol(td_grid)
            t, th, td = np.concatenate([t, td_grid]), np.concatenate([th, yd[0]]), np.concatenate([td, yd[1]])
            order = np.argsort(t, kind="stable")
            t, th, td = t[order], th[order], td[order]
    if sol.t_events[k].size:
        inside = (sol.t_events[k] > sol.t[0]) & (sol.t_events[k] < sol.t[-1])
        t = np.concatenate([t, sol.t_events[k][inside]])
        th = np.concatenate([th, sol.y_events[k][inside, 0]])
        td = np.concatenate([td, sol.y_events[k][inside, 1]])
        order = np.argsort(t, kind="stable")
        t, th, td = t[order], th[order], td[order]
    out(t, th, td, *extra)


def rocking_energy(block: Block, theta: np.ndarray | float, theta_dot: np.ndarray | float) -> np.ndarray:
    """Mechanical energy of the rocking block (J), paper Section 2.1 / docs/modelling.md section 2.

    ``E = 1/2 I_O theta'² + m g R [cos(alpha - |theta|) - cos(alpha)]``, zero when seated;
    conserved between impacts when ``a = 0``.
    """
    theta = np.asarray(theta, dtype=float)
    theta_dot = np.asarray(theta_dot, dtype=float)
    potential = block.mass * G * block.R * (np.cos(block.alpha - np.abs(theta)) - math.cos(block.alpha))
    return 0.5 * block.I_O * theta_dot**2 + potential


def solve(block: Block, excitation: Any, *, settings: HousnerSettings | None = None, **overrides: Any) -> RockingResult:
    """Rocking response of the rigid block by the exact equation with instantaneous impacts.

    Parameters
    ----------
    block : Block
        The block (geometry, restitution ``e``).
    excitation : Excitation
        Floor acceleration (m/s²) as a function of time (s).
    settings : HousnerSettings, optional
        Numerical settings; keyword ``overrides`` replace single fields.

    Returns
    -------
    RockingResult
        ``solver="housner"``; ``n_impacts`` counts impacts; ``n_steps`` accepted steps.
        An integrator failure or more than ``max_impacts`` impacts give ``status="failed"``.
    """
    s = make_settings(HousnerSettings, settings, overrides)
    settings_dict = {k: (None if v is None else (float(v) if isinstance(v, float) else v)) for k, v in asdict(s).items()}
    if math.isinf(s.max_step):
        settings_dict["max_step"] = "inf"
    t_wall = _time.perf_counter()
    alpha, p, e = block.alpha, block.p, block.e
    p2 = p * p
    linearised = s.equations == "linearised"
    level = G * alpha if linearised else block.uplift_acceleration
    duration = float(excitation.duration)
    t_final = s.end_time if s.end_time is not None else duration + s.max_free_time
    scan = s.scan_step if s.scan_step is not None else max(duration, 1e-9) / 2000.0
    v_rest = s.rest_velocity_ratio * p * alpha
    atol = np.array([s.atol, s.atol * p])
    acc = excitation.acceleration
    bps = np.asarray(excitation.breakpoints(), dtype=float)
    bps = np.unique(np.append(bps[(bps > 0.0) & (bps < t_final)], duration if duration < t_final else t_final))

    ts: list[np.ndarray] = []
    ths: list[np.ndarray] = []
    tds: list[np.ndarray] = []
    theta_max = abs(s.theta0)
    rocked = s.theta0 != 0.0 or s.theta_dot0 != 0.0
    n_steps = 0
    impacts = ImpactLog()
    overturned = False

    def out(t: np.ndarray, th: np.ndarray, td: np.ndarray) -> None:
        if s.record:
            ts.append(np.atleast_1d(t))
            ths.append(np.atleast_1d(th))
            tds.append(np.atleast_1d(td))

    def fail(reason: str) -> RockingResult:
        return failed_result(
            "housner", settings_dict, alpha, reason,
            time=np.concatenate(ts) if ts else None, theta=np.concatenate(ths) if ths else None,
            theta_dot=np.concatenate(tds) if tds else None, n_steps=n_steps,
            wall_time_s=_time.perf_counter() - t_wall,
        )

    t = 0.0
    y = np.array([float(s.theta0), float(s.theta_dot0)])
    out(np.array(t), y[0], y[1])
    seated = not rocked
    side = 0.0 if seated else (math.copysign(1.0, y[0]) if y[0] != 0.0 else math.copysign(1.0, y[1]))

    while t < t_final:
        if seated:
            if s.end_time is None and t >= duration:
                break  # a = 0 from here on: the block stays seated
            t_up = first_exceedance(excitation, level, t, min(t_final, duration), scan)
            if t_up is None:
                t_stop = t_final if s.end_time is not None else min(t_final, duration)
                out(np.array(t_stop), 0.0, 0.0)
                t = t_stop
                continue
            if t_up > t:
                out(np.array(t_up), 0.0, 0.0)
            t = t_up
            side = -math.copysign(1.0, float(acc(t_up + 1e-12 * max(1.0, t_up))) or float(acc(t_up)))
            y = np.array([0.0, 0.0])
            seated = False
            rocked = True
            continue

        sd = side

        def rhs(tt: float, yy: np.ndarray, sd: float = sd) -> list[float]:
            ang = alpha * sd - yy[0]
            if linearised:
                return [yy[1], -p2 * (ang + float(acc(tt)) / G)]
            return [yy[1], -p2 * (math.sin(ang) + float(acc(tt)) / G * math.cos(ang))]

        def impact(tt: float, yy: np.ndarray, sd: float = sd) -> float:
            return sd * yy[0]

        impact.terminal = True
        impact.direction = -1

        def overturn(tt: float, yy: np.ndarray, sd: float = sd) -> float:
            return sd * yy[0] - OVERTURNING_ANGLE

        overturn.terminal = True
        overturn.direction = 1

        def turning(tt: float, yy: np.ndarray, sd: float = sd) -> float:
            return sd * yy[1]

        after_pulse = t >= duration
        turning.terminal = bool(after_pulse and s.end_time is None and s.tail == "peak")
        turning.direction = -1

        nxt = bps[bps > t + 1e-15 * max(1.0, t)]
        t_seg = float(nxt[0]) if nxt.size else t_final
        sol = solve_ivp(
            rhs, (t, t_seg), y, method=s.method, rtol=s.rtol, atol=atol, max_step=s.max_step,
            events=(impact, overturn, turning), dense_output=s.dense_step is not None,
        )
        n_steps += max(len(sol.t) - 1, 0)
        if sol.status == -1:
            return fail(f"solve_ivp ({s.method}) failed at t = {t:.6g} s: {sol.message}")
        _out_with_turns(out, sol, 2, dense_step=s.dense_step)
        theta_max = max(theta_max, float(np.max(np.abs(sol.y[0]))))
        if sol.t_events[2].size:
            theta_max = max(theta_max, float(np.max(np.abs(sol.y_events[2][:, 0]))))
        if sol.status == 0:
            t, y = float(sol.t[-1]), sol.y[:, -1].copy()
            continue
        t = float(sol.t[-1])
        if sol.t_events[1].size:
            overturned = True
            theta_max = max(theta_max, OVERTURNING_ANGLE)
            break
        if sol.t_events[2].size and turning.terminal:
            y_turn = sol.y_events[2][-1]
            if abs(y_turn[0]) < alpha:
                break  # energy only falls from here: theta_max and the verdict are final
            y = y_turn.copy()
            continue
        # impact: theta = 0, theta' -> e theta', pivot switches corner
        if len(impacts) + 1 > s.max_impacts:
            return fail(f"more than max_impacts = {s.max_impacts} impacts by t = {t:.6g} s")
        v_before = float(sol.y_events[0][-1][1])
        v = e * v_before
        impacts.add(t, v_before, v)
        out(np.array(t), 0.0, v)
        if abs(v) < v_rest:
            seated = True
            y = np.array([0.0, 0.0])
            out(np.array(t), 0.0, 0.0)
            continue
        side = math.copysign(1.0, v)
        y = np.array([0.0, v])

    time_arr = np.concatenate(ts) if ts else np.zeros(0)
    return RockingResult(
        solver="housner",
        settings=settings_dict,
        alpha=alpha,
        time=time_arr,
        theta=np.concatenate(ths) if ths else np.zeros(0),
        theta_dot=np.concatenate(tds) if tds else np.zeros(0),
        theta_max=theta_max,
        overturned=overturned,
        rocked=rocked,
        n_steps=n_steps,
        n_impacts=len(impacts),
        impacts=impacts.freeze(),
        wall_time_s=_time.perf_counter() - t_wall,
    )


__all__ = ["HousnerSettings", "METHODS", "TAILS", "first_exceedance", "rocking_energy", "solve"]
