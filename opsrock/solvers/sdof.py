"""The paper's equivalent SDOF model (Eq. 5-8) integrated by scipy, region by region.

    I_O theta'' + f_d(theta, theta') + M_s(theta) = -Lambda a(t)

solved with the same model as the OpenSees solver (:class:`opsrock.model.SDOFModel`: the
*tabulated* spring ``spring_table``, stiff branch and all; the damper ``c_D`` of
``damping_coefficient``; the lever ``lever_arm``) but none of its numerics:

* the rotation axis is cut at every kink of the spring table and at the damper band edges
  ``±delta alpha``; inside one region the equation is linear with constant coefficients and
  :func:`scipy.integrate.solve_ivp` integrates it with tight tolerances, stopping on a
  terminal event at the region's edges, at ``|theta| = pi/2`` (overturning, Eq. 11) and at
  every excitation breakpoint (pulse start and end, record samples);
* the damper is armed at the start of every passage through the band (on entering it, at a
  turning point inside it, and at the start from a state inside it) by the model's damper law
  (:meth:`opsrock.model.SDOFModel.arm_damper`: by default so that a free passage keeps ``e²`` of
  the energy; ``damper="entry_velocity"`` is Eq. 8 on entry only), and off when it is left. Before
  the first passage, and while the block is seated, ``c_D = 0``;
* the stiff branch ``|theta| <= theta_e`` (slope ``k_e = M_s(theta_e) / theta_e``, natural
  frequency ``omega_e = sqrt(k_e / I_O)``, about ``p sqrt(1 / theta_e_ratio)``: 1000 p by
  default) is integrated with an implicit method (``stiff_method``). A block that sits in it
  is handled as **seated**: the exact solution there is the quasi-static deflection
  ``theta_qs = -Lambda a(t) / k_e`` plus a free oscillation of amplitude ``A`` at
  ``omega_e``; once ``|theta_qs| + A < theta_e`` the solver drops the oscillation and follows
  ``theta_qs`` until ``Lambda |a(t)| > M_s(theta_e)``, where the block leaves the branch
  (for ``lever="housner"`` this is ``|a| > g tan(alpha - theta_e) / tan(alpha) · g tan(alpha)``,
  i.e. Eq. 4 to within ``theta_e``). The error of this treatment is below ``theta_e`` in
  rotation (1e-6 alpha by default) and ``k_e theta_e² / 2`` in energy; a block starting from
  rest is seated from the start.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

from opsrock._checks import bool_fields, int_at_least, one_of
from opsrock.block import Block
from opsrock.constants import OVERTURNING_ANGLE
from opsrock.excitations.records import Record
from opsrock.model import DEFAULT_DELTA, DEFAULT_TABLE_POINTS, DEFAULT_THETA_E_RATIO, SDOFModel, Seat, can_uplift
from opsrock.result import ImpactLog, RockingResult, failed_result, seated_result
from opsrock.solvers.housner import (
    METHODS,
    TAILS,
    _check_common,
    _out_with_turns,
    first_exceedance,
    make_settings,
)


@dataclass(frozen=True)
class SDOFSettings:
    """Model and numerical settings of the scipy SDOF solver.

    Parameters
    ----------
    delta : float
        Damper band half-width as a fraction of alpha (dimensionless). Default
        :data:`opsrock.model.DEFAULT_DELTA`.
    theta_e_ratio : float
        Stiff-branch half-width ``theta_e / alpha`` (dimensionless). Default
        :data:`opsrock.model.DEFAULT_THETA_E_RATIO`.
    table_points : int
        Spring-table points per side (see :meth:`SDOFModel.spring_table`).
    lever : str
        Excitation lever, ``"housner"`` (``m R cos alpha``) or ``"printed"`` (see
        :data:`opsrock.model.LEVERS`).
    damper : str
        How the damper coefficient is set, ``"energy"`` or ``"entry_velocity"`` (Eq. 8 as printed;
        see :data:`opsrock.model.DAMPER_LAWS`).
    method : str
        :func:`scipy.integrate.solve_ivp` method outside the stiff branch. Default ``"DOP853"``:
        there the equation is linear, non-stiff (rates ``p`` and ``c_D / I_O``) and smooth.
    stiff_method : str
        Method inside the stiff branch ``|theta| < theta_e``. Default ``"Radau"`` (implicit,
        L-stable: the branch's ``omega_e`` is ~1000 p).
    rtol : float
        Relative tolerance (dimensionless). Default 1e-10.
    atol : float
        Absolute tolerance on ``theta`` (rad); ``atol · p`` on ``theta'``. Default 1e-13 rad,
        ten times below the default ``theta_e`` of a slender block (~2e-7 rad) squared-off by
        the 1e-6 ratio, so the stiff branch is resolved.
    end_time : float or None
        Time to stop (s). None: the excitation's duration plus the free-rocking ``tail``.
    tail : str
        ``"rest"``: after the excitation, integrate until the block is trapped in the damper
        band (its energy ``1/2 I_O theta'² + U(theta)`` below ``U(delta alpha)``, where ``U``
        is the table spring's potential, so it can never rock out again) or seated;
        ``"peak"``: stop at the first turning point after the excitation with
        ``|theta| < alpha`` (energy only falls afterwards, so ``theta_max`` and the verdict
        are final).
    max_free_time : float
        Cap on the free-rocking tail (s). Default 60 s.
    max_step : float
        Largest step (s). Default ``inf``.
    theta0, theta_dot0 : float
        Initial rotation (rad) and angular velocity (rad/s). Default 0, 0 (seated).
    record : bool
        Keep the time histories (every accepted step). Default True.
    max_impacts : int
        Largest number of impacts (band crossings from one side to the other) before the run is
        reported as failed. Default 10 000.
    max_segments : int
        Largest number of region/breakpoint segments before the run is reported as failed.
        Default 200 000 (a record of 10 000 samples needs about that many).
    uplift_check : bool
        If True (default), a block starting from rest under an excitation that cannot uplift it
        (Eq. 4 for the model's lever, :func:`opsrock.model.can_uplift`) is returned seated
        without integration, as the OpenSees solver does.
    scan_step : float or None
        Grid spacing (s) of the seated-phase uplift scan (see
        :func:`opsrock.solvers.housner.first_exceedance`). None: ``duration / 2000``.
    dense_step : float or None
        If set (s), the history also holds the integrator's dense output every ``dense_step``
        (see :class:`opsrock.solvers.housner.HousnerSettings`). None (default): steps and events.
    stiff_closed_form : bool
        Under a record (acceleration linear between samples), solve the stiff branch in closed form
        (:class:`_ClosedFormSegment`) instead of with ``stiff_method``. Default True; False: the
        implicit integrator everywhere (the reference of the test that checks the closed form).
    """

    delta: float = DEFAULT_DELTA
    theta_e_ratio: float = DEFAULT_THETA_E_RATIO
    table_points: int = DEFAULT_TABLE_POINTS
    lever: str = "housner"
    damper: str = "energy"
    method: str = "DOP853"
    stiff_method: str = "Radau"
    rtol: float = 1e-10
    atol: float = 1e-13
    end_time: float | None = None
    tail: str = "rest"
    max_free_time: float = 60.0
    max_step: float = math.inf
    theta0: float = 0.0
    theta_dot0: float = 0.0
    record: bool = True
    max_impacts: int = 10_000
    max_segments: int = 200_000
    scan_step: float | None = None
    uplift_check: bool = True
    dense_step: float | None = None
    stiff_closed_form: bool = True

    def __post_init__(self) -> None:
        bool_fields(self)
        if not isinstance(self.uplift_check, bool):
            raise TypeError(f"uplift_check must be a bool, got {self.uplift_check!r}")
        self.model  # noqa: B018  (validates delta, theta_e_ratio, table_points, lever)
        one_of("method", self.method, METHODS)
        one_of("stiff_method", self.stiff_method, METHODS)
        one_of("tail", self.tail, TAILS)
        _check_common(self)
        int_at_least("max_segments", self.max_segments, 1)

    @property
    def model(self) -> SDOFModel:
        """The SDOF model these settings describe."""
        return SDOFModel(
            delta=self.delta, theta_e_ratio=self.theta_e_ratio, table_points=self.table_points, lever=self.lever,
            damper=self.damper,
        )


def table_potential(theta_tab: np.ndarray, moment_tab: np.ndarray):
    """Potential ``U(theta) = integral_0^theta M_s`` (J) of a piecewise-linear spring table.

    Returns a vectorised function; exact for the linear interpolation of the table.
    """
    th = np.asarray(theta_tab, dtype=float)
    m = np.asarray(moment_tab, dtype=float)
    i0 = int(np.searchsorted(th, 0.0))
    m0 = float(np.interp(0.0, th, m))
    nodes = np.concatenate([th[:i0], [0.0], th[i0:]])
    vals = np.concatenate([m[:i0], [m0], m[i0:]])
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (vals[1:] + vals[:-1]) * np.diff(nodes))])
    cum -= cum[i0]

    def U(theta: np.ndarray | float) -> np.ndarray:  # noqa: N802
        x = np.clip(np.asarray(theta, dtype=float), nodes[0], nodes[-1])
        j = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, nodes.size - 2)
        x0, m_0 = nodes[j], vals[j]
        slope = (vals[j + 1] - vals[j]) / (nodes[j + 1] - nodes[j])
        dx = x - x0
        return cum[j] + m_0 * dx + 0.5 * slope * dx**2

    return U


def solve(block: Block, excitation: Any, *, settings: SDOFSettings | None = None, **overrides: Any) -> RockingResult:
    """Rocking response of the paper's equivalent SDOF model, integrated by scipy.

    Parameters
    ----------
    block : Block
        The block.
    excitation : Excitation
        Floor acceleration (m/s²) as a function of time (s).
    settings : SDOFSettings, optional
        Model and numerical settings; keyword ``overrides`` replace single fields.

    Returns
    -------
    RockingResult
        ``solver="sdof"``, with ``spring_moment`` and ``damper_force`` histories when
        ``record``; ``n_impacts`` counts impacts (crossings of the damper band from one side to
        the other, logged in ``impacts`` with the velocities at the band's edges); ``rocked`` is True once
        ``|theta|`` leaves the stiff branch. Integrator failures and exceeded caps give
        ``status="failed"`` with the reason.
    """
    s = make_settings(SDOFSettings, settings, overrides)
    settings_dict: dict[str, Any] = dict(asdict(s))
    if math.isinf(s.max_step):
        settings_dict["max_step"] = "inf"
    t_wall = _time.perf_counter()
    model = s.model
    if s.uplift_check and s.theta0 == 0.0 and s.theta_dot0 == 0.0 and not can_uplift(block, model, excitation.pfa):
        return seated_result("sdof", settings_dict, block.alpha, excitation.duration, _time.perf_counter() - t_wall)
    alpha, p = block.alpha, block.p
    inertia = block.I_O
    lam = model.lever_arm(block)
    theta_e = model.theta_e(block)
    band = model.band(block)
    th_tab, m_tab = model.spring_table(block)
    U = table_potential(th_tab, m_tab)
    u_band = float(U(band))
    seat = Seat(model, block, excitation.acceleration)
    m_e, k_e = model.edge_moment(block), seat.k_e  # moment and stiffness of the stiff branch
    kinks = np.unique(np.concatenate([th_tab, [-band, band]]))
    slopes = np.diff(np.interp(kinks, th_tab, m_tab)) / np.diff(kinks)
    intercepts = np.interp(kinks[:-1], th_tab, m_tab) - slopes * kinks[:-1]
    in_band = (kinks[:-1] >= -band - 1e-15) & (kinks[1:] <= band + 1e-15)
    stiff = (kinks[:-1] >= -theta_e - 1e-15) & (kinks[1:] <= theta_e + 1e-15)

    duration = float(excitation.duration)
    t_final = s.end_time if s.end_time is not None else duration + s.max_free_time
    scan = s.scan_step if s.scan_step is not None else max(duration, 1e-9) / 2000.0
    atol = np.array([s.atol, s.atol * p])
    # the stiff branch in closed form where the floor acceleration is linear between breakpoints
    closed_form = s.stiff_closed_form and isinstance(excitation, Record)
    acc = excitation.acceleration
    bps = np.asarray(excitation.breakpoints(), dtype=float)
    bps = np.unique(np.append(bps[(bps > 0.0) & (bps < t_final)], duration if duration < t_final else t_final))

    ts: list[np.ndarray] = []
    ths: list[np.ndarray] = []
    tds: list[np.ndarray] = []
    cds: list[np.ndarray] = []
    n_steps = 0
    impacts = ImpactLog()
    entry: tuple[float, float, float] | None = None  # (time, velocity, side) of the last band entry
    n_segments = 0
    overturned = False
    c_d = 0.0

    def out(t, th, td, c) -> None:
        if s.record:
            t = np.atleast_1d(np.asarray(t, dtype=float))
            ts.append(t)
            ths.append(np.broadcast_to(np.asarray(th, dtype=float), t.shape).copy())
            tds.append(np.broadcast_to(np.asarray(td, dtype=float), t.shape).copy())
            cds.append(np.full(t.shape, c))

    def fail(reason: str) -> RockingResult:
        return failed_result(
            "sdof", settings_dict, alpha, reason,
            time=np.concatenate(ts) if ts else None, theta=np.concatenate(ths) if ths else None,
            theta_dot=np.concatenate(tds) if tds else None, n_steps=n_steps,
            wall_time_s=_time.perf_counter() - t_wall,
        )

    t = 0.0
    y = np.array([float(s.theta0), float(s.theta_dot0)])
    seated = s.theta0 == 0.0 and s.theta_dot0 == 0.0
    theta_max = abs(s.theta0)
    rocked = abs(s.theta0) > theta_e
    region = -1
    at_turn = False  # the current state is a turning point just handled (its event must not fire again)
    if not seated:
        region = _region_of(kinks, y[0], y[1])
        if model.tracks_passages() and theta_e < abs(y[0]) <= band and y[0] * y[1] <= 0.0:
            # starting inside the band, at rest or heading back towards zero: a passage begins
            c_d = model.arm_damper(block, y[0], y[1])
    out(t, y[0], y[1], 0.0)

    while t < t_final:
        n_segments += 1
        if n_segments > s.max_segments:
            return fail(f"more than max_segments = {s.max_segments} segments by t = {t:.6g} s")
        if seated:
            if s.end_time is None and t >= duration:
                break
            t_up = first_exceedance(excitation, m_e / lam, t, min(t_final, duration), scan)
            t_stop = t_up if t_up is not None else (t_final if s.end_time is not None else min(t_final, duration))
            if t_stop > t:
                grid = np.union1d(np.linspace(t, t_stop, 201), bps[(bps > t) & (bps < t_stop)])
                qs = np.clip(-lam * np.asarray(acc(grid), dtype=float) / k_e, -theta_e, theta_e)
                out(grid, qs, np.gradient(qs, grid), c_d)
                theta_max = max(theta_max, float(np.max(np.abs(qs))))
            t = t_stop
            if t_up is None:
                continue
            # leave the stiff branch at its edge, on the side the floor pushes towards
            sign = -math.copysign(1.0, float(acc(t_up)))
            # one-sided (forward) slope: a pulse may jump at t_up (a one-cosine or rectangular pulse
            # at t = 0), and a central difference across the jump is a spurious huge velocity
            h = 1e-7 * max(duration, 1e-9)
            qs_dot = -lam * (float(acc(t_up + h)) - float(acc(t_up))) / h / k_e
            y = np.array([sign * theta_e, qs_dot if qs_dot * sign > 0 else 0.0])
            region = _region_of(kinks, y[0], sign)
            seated = False
            continue

        if s.end_time is None and s.tail == "rest" and t >= duration and abs(y[0]) <= band:
            # trapped only *inside* the band: beyond alpha the table's potential falls below
            # U(delta alpha) too, and a block out there is falling over, not at rest
            energy = 0.5 * inertia * y[1] ** 2 + float(U(y[0]))
            if energy < u_band:
                break  # trapped in the damper band: it can never rock out again

        lo, hi = kinks[region], kinks[region + 1]
        at_turn, was_at_turn = False, at_turn
        k_i, m_i = slopes[region], intercepts[region]
        c_i = c_d if in_band[region] else 0.0
        is_stiff = bool(stiff[region])

        def rhs(tt, yy, k_i=k_i, m_i=m_i, c_i=c_i):
            return [yy[1], (-lam * float(acc(tt)) - c_i * yy[1] - (k_i * yy[0] + m_i)) / inertia]

        def lower(tt, yy, lo=lo):
            return yy[0] - lo

        lower.terminal, lower.direction = True, -1

        def upper(tt, yy, hi=hi):
            return yy[0] - hi

        upper.terminal, upper.direction = True, 1

        def overturn(tt, yy):
            return abs(yy[0]) - OVERTURNING_ANGLE

        overturn.terminal, overturn.direction = True, 1

        # peaks of |theta| only (theta' leaving the outward sign): a turning point beyond alpha,
        # from which the block falls outwards, does not fire again at the next segment's start
        mid = 0.5 * (lo + hi)
        direction = 0 if is_stiff else (-1 if mid > 0 else 1)

        def turning(tt, yy, t_start=t if was_at_turn else -math.inf, direction=direction):
            # a segment that starts at the turning point just handled reports there the sign that
            # follows a peak, so the same peak does not fire again
            return float(direction) if (tt <= t_start and direction) else yy[1]

        stop_at_peak = bool(s.end_time is None and s.tail == "peak" and t >= duration)
        # a turning point inside the band starts a new passage: the damper is re-armed there
        rearm = model.tracks_passages() and bool(in_band[region]) and not is_stiff
        turning.terminal = stop_at_peak or rearm
        turning.direction = direction
        events = [lower, upper, overturn, turning]
        if is_stiff:

            def capture(tt, yy):
                return seat.margin(tt, yy[0], yy[1])

            capture.terminal, capture.direction = True, 1
            events.append(capture)
        if s.end_time is None and s.tail == "rest" and t >= duration and in_band[region]:

            def trapped(tt, yy):
                return 0.5 * inertia * yy[1] ** 2 + float(U(yy[0])) - u_band

            trapped.terminal, trapped.direction = True, -1
            events.append(trapped)

        nxt = bps[bps > t + 1e-15 * max(1.0, t)]
        t_seg = float(nxt[0]) if nxt.size else t_final
        if is_stiff and closed_form and t_seg > t:
            # a record's acceleration is linear between samples: the stiff branch in closed form
            a0, a1 = float(acc(t)), (float(acc(t_seg)) - float(acc(t))) / (t_seg - t)
            if t_seg > duration:  # after the last sample the floor is still (a = 0)
                a0, a1 = (0.0, 0.0) if t >= duration else (a0, a1)
            seg = _ClosedFormSegment(inertia, c_i, k_i, m_i, lam, a0, a1, t, y)
            sol = _closed_form_solve(seg, t, t_seg, events)
        else:
            sol = solve_ivp(
                rhs, (t, t_seg), y, method=s.stiff_method if is_stiff else s.method,
                rtol=s.rtol, atol=atol, max_step=s.max_step, events=events, dense_output=s.dense_step is not None,
            )
        n_steps += max(len(sol.t) - 1, 0)
        if sol.status == -1:
            return fail(f"solve_ivp ({s.stiff_method if is_stiff else s.method}) failed at t = {t:.6g} s: {sol.message}")
        _out_with_turns(out, sol, 3, c_i, dense_step=s.dense_step)
        theta_max = max(theta_max, float(np.max(np.abs(sol.y[0]))))
        if sol.t_events[3].size:
            theta_max = max(theta_max, float(np.max(np.abs(sol.y_events[3][:, 0]))))
        if not is_stiff:
            rocked = True
        t = float(sol.t[-1])
        y = sol.y[:, -1].copy()
        if sol.status == 0:
            continue
        if sol.t_events[2].size:
            overturned = True
            theta_max = max(theta_max, OVERTURNING_ANGLE)
            break
        if sol.t_events[3].size and turning.terminal:
            if stop_at_peak and abs(sol.y_events[3][-1][0]) < alpha:
                break
            y = sol.y_events[3][-1].copy()
            if rearm:
                c_d = model.arm_damper(block, y[0], 0.0)
            at_turn = True
            continue
        fired = {ev.__name__ for ev, te in zip(events, sol.t_events) if te.size and ev.terminal}
        if "capture" in fired:
            seated = True
            if model.tracks_passages():
                c_d = 0.0  # no passage under way: the floor lifts the block again undamped
            continue
        if "trapped" in fired:
            break
        if sol.t_events[1].size:
            y = sol.y_events[1][-1].copy()
            y[0] = hi
            new = region + 1
        else:
            y = sol.y_events[0][-1].copy()
            y[0] = lo
            new = region - 1
        if new < 0 or new >= slopes.size:
            return fail(f"rotation {y[0]:.6g} rad left the spring table at t = {t:.6g} s")
        if in_band[new] and not in_band[region]:
            c_d = model.arm_damper(block, y[0], y[1])
            entry = (t, float(y[1]), math.copysign(1.0, y[0]))
        elif in_band[region] and not in_band[new] and entry is not None:
            if math.copysign(1.0, y[0]) != entry[2]:  # left on the other side: an impact
                impacts.add(entry[0], entry[1], y[1])
                if len(impacts) > s.max_impacts:
                    return fail(f"more than max_impacts = {s.max_impacts} impacts by t = {t:.6g} s")
            entry = None
        region = new

    time_arr = np.concatenate(ts) if ts else np.zeros(0)
    theta_arr = np.concatenate(ths) if ths else np.zeros(0)
    td_arr = np.concatenate(tds) if tds else np.zeros(0)
    spring = damper = None
    if s.record:
        spring = np.interp(theta_arr, th_tab, m_tab)
        damper = np.concatenate(cds) * td_arr * (np.abs(theta_arr) <= band)
    return RockingResult(
        solver="sdof",
        settings=settings_dict,
        alpha=alpha,
        time=time_arr,
        theta=theta_arr,
        theta_dot=td_arr,
        theta_max=theta_max,
        overturned=overturned,
        rocked=rocked,
        n_steps=n_steps,
        n_impacts=len(impacts),
        impacts=impacts.freeze(),
        wall_time_s=_time.perf_counter() - t_wall,
        spring_moment=spring,
        damper_force=damper,
    )


class _ClosedFormSegment:
    """The exact solution on one region of the table under a linear floor acceleration.

    ``I theta'' + c theta' + k theta + m = -lam (a0 + a1 (t - t0))`` has the solution
    ``P + Q tau + C1 exp(r1 tau) + C2 exp(r2 tau)`` (``tau = t - t0``; ``Q = f1 / k``,
    ``P = (f0 - c Q) / k`` with ``f0 = -lam a0 - m``, ``f1 = -lam a1``; ``r1,2`` the roots of
    ``I r² + c r + k``; ``C1, C2`` from the state at ``t0``). Used for the stiff branch under a record:
    there the natural frequency is about 1000 p and an implicit integrator needs thousands of steps
    per second of record, whereas the closed form needs none.
    """

    def __init__(self, inertia, c, k, m, lam, a0, a1, t0, y0):
        f0, f1 = -lam * a0 - m, -lam * a1
        self.Q = f1 / k
        self.P = (f0 - c * self.Q) / k
        sq = np.sqrt(complex(c * c - 4.0 * k * inertia))
        if sq == 0:  # critical damping: separate the roots by a relative 1e-12 (no effect on the answer)
            sq = complex(1e-12 * abs(c) + 1e-300)
        self.r1, self.r2 = (-c + sq) / (2.0 * inertia), (-c - sq) / (2.0 * inertia)
        d0, d1 = y0[0] - self.P, y0[1] - self.Q
        self.C1 = (d1 - self.r2 * d0) / (self.r1 - self.r2)
        self.C2 = d0 - self.C1
        self.t0 = t0
        self.omega = max(abs(self.r1.imag), abs(self.r1.real), abs(self.r2.real))

    def __call__(self, t):
        tau = np.asarray(t, dtype=float) - self.t0
        e1, e2 = np.exp(self.r1 * tau), np.exp(self.r2 * tau)
        th = self.P + self.Q * tau + (self.C1 * e1 + self.C2 * e2).real
        td = self.Q + (self.r1 * self.C1 * e1 + self.r2 * self.C2 * e2).real
        return np.array([th, td])


class _Solution:
    """What :func:`scipy.integrate.solve_ivp` returns, for a closed-form segment."""

    def __init__(self, t, y, status, t_events, y_events, sol):
        self.t, self.y, self.status, self.t_events, self.y_events, self.sol = t, y, status, t_events, y_events, sol
        self.message = ""


#: Samples per period of the fastest mode on which a closed-form segment's events are bracketed.
CLOSED_FORM_SAMPLES_PER_PERIOD: int = 16


#: Periods of the fastest mode per window of a closed-form segment: the events are searched window
#: by window and the search stops at the first terminal one (a block crosses the stiff branch in a
#: fraction of a period; a free tail can otherwise be a minute of record, a million grid points).
CLOSED_FORM_WINDOW_PERIODS: int = 64


def _closed_form_solve(seg: _ClosedFormSegment, t0: float, t1: float, events) -> _Solution:
    """Events of ``seg`` on ``[t0, t1]`` with solve_ivp's conventions (direction, terminal): sign
    changes bracketed on a grid of :data:`CLOSED_FORM_SAMPLES_PER_PERIOD` points per period, window
    by window (:data:`CLOSED_FORM_WINDOW_PERIODS`), then refined by Brent's method on the closed
    form to 1e-15 s."""
    period = 2 * math.pi / seg.omega if seg.omega > 0 else t1 - t0
    window = CLOSED_FORM_WINDOW_PERIODS * period
    hits: list[list[float]] = [[] for _ in events]
    grids, stop, ta = [], t1, t0
    while ta < t1:
        tb = min(t1, ta + window)
        n = int(max(8, math.ceil((tb - ta) / period * CLOSED_FORM_SAMPLES_PER_PERIOD)))
        grid = np.linspace(ta, tb, n + 1)
        grids.append(grid if not grids else grid[1:])
        stop = min(stop, _window_events(seg, grid, events, hits))
        if stop < t1 or any(h and ev.terminal for h, ev in zip(hits, events)):
            break
        ta = tb
    grid = np.concatenate(grids)
    t_events = [np.array([te for te in h if te <= stop]) for h in hits]
    y_events = [seg(te).T.reshape(-1, 2) if te.size else np.zeros((0, 2)) for te in t_events]
    t_out = np.append(grid[grid < stop], stop)
    status = 1 if stop < t1 or any(te.size and ev.terminal for te, ev in zip(t_events, events)) else 0
    return _Solution(t_out, seg(t_out), status, t_events, y_events, seg)


def _window_events(seg: _ClosedFormSegment, grid: np.ndarray, events, hits: list[list[float]]) -> float:
    """Append the events of ``seg`` on ``grid`` to ``hits``; return the first terminal one's time
    (or the grid's end)."""
    from scipy.optimize import brentq

    Y = seg(grid)
    stop = float(grid[-1])
    for j, ev in enumerate(events):
        g = np.array([ev(tt, Y[:, i]) for i, tt in enumerate(grid)])
        if ev.direction > 0:
            idx = np.flatnonzero((g[:-1] < 0) & (g[1:] >= 0))
        elif ev.direction < 0:
            idx = np.flatnonzero((g[:-1] > 0) & (g[1:] <= 0))
        else:
            idx = np.flatnonzero(((g[:-1] < 0) & (g[1:] >= 0)) | ((g[:-1] > 0) & (g[1:] <= 0)))
        for i in idx:
            a, b = grid[i], grid[i + 1]
            te = b if g[i + 1] == 0 else brentq(lambda tt: ev(tt, seg(tt)), a, b, xtol=1e-15, rtol=1e-15)
            hits[j].append(te)
            if ev.terminal:
                stop = min(stop, te)
                break
    return stop


def _region_of(kinks: np.ndarray, theta: float, direction: float) -> int:
    """Index ``i`` of the region ``[kinks[i], kinks[i+1]]`` holding ``theta``; on a kink, the
    region on the side ``direction`` points to."""
    i = int(np.searchsorted(kinks, theta, side="right") - 1)
    if theta == kinks[min(max(i, 0), kinks.size - 1)] and direction < 0:
        i -= 1
    return int(np.clip(i, 0, kinks.size - 2))


__all__ = ["SDOFSettings", "solve", "table_potential"]
