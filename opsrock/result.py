"""The one result type every solver returns."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np

from opsrock.constants import OVERTURNING_ANGLE
from opsrock.errors import InputError

#: Result status values. ``"failed"`` carries a reason and is never a safe or overturned verdict.
STATUSES: tuple[str, ...] = ("ok", "failed")

#: Verdicts a result can carry (see :attr:`RockingResult.verdict`).
VERDICTS: tuple[str, ...] = ("no_uplift", "safe", "overturned", "failed")

#: Contact modes of a block on a floor with friction (docs/guide/friction.md): both corners down and
#: stuck, both down and slipping, one corner up on a stuck pivot, one up on a slipping pivot, none down.
MODES: tuple[str, ...] = ("rest", "slide", "rock", "slide_rock", "flight")

#: What a block did, in order of precedence (see :attr:`RockingResult.response`): it overturned; else
#: it rocked (one corner lifted at some time, with or without slip); else its base slid; else it stayed
#: at rest. ``failed`` carries no verdict.
RESPONSES: tuple[str, ...] = ("overturned", "rocked", "slid", "at_rest", "failed")


@dataclass(frozen=True)
class ContactSummary:
    """What a block on a floor with friction did, beyond its rotation (solvers of the ``friction`` model).

    Parameters
    ----------
    first_mode : str
        The first mode (:data:`MODES`) the block left rest into: ``"slide"``, ``"rock"``,
        ``"slide_rock"`` or ``"flight"``; ``"rest"`` if it never moved.
    time_sliding : float
        Time during which the base slipped on the floor (s): modes ``slide`` and ``slide_rock``.
    time_rocking : float
        Time during which one base corner was lifted (s): modes ``rock`` and ``slide_rock``.
    slide_max : float
        Peak absolute horizontal displacement of the base relative to the floor (m).
    slide_residual : float
        Horizontal displacement of the base relative to the floor at the end of the run (m), signed
        (positive along the floor's positive acceleration).
    time_flight : float
        Time during which no corner touched the floor (s): mode ``flight``.
    slip_velocity_end : float
        The base's velocity relative to the floor (m/s, signed as ``slide_residual``) when the run ended;
        0 for a block at rest. Non-zero only for a block still sliding on the still floor after the
        excitation with a friction too small to stop it within ``max_free_time`` (none at all on a
        frictionless floor): the run ends there with this velocity (docs/guide/friction.md, the ending rule).
    energy : Mapping
        Energy balance of the run in J (per the block's mass): ``input_work`` (work of the floor's
        inertial forces), ``kinetic`` and ``potential`` at the end, ``friction_work`` (dissipated by
        slip), ``impact_loss`` (lost in impacts), and ``residual = input_work - kinetic - potential -
        friction_work - impact_loss``, which the equations make zero.
    """

    first_mode: str
    time_sliding: float
    time_rocking: float
    slide_max: float
    slide_residual: float
    time_flight: float = 0.0
    energy: Mapping[str, float] = field(default_factory=dict)
    slip_velocity_end: float = 0.0

    def __post_init__(self) -> None:
        if self.first_mode not in MODES:
            raise InputError(f"first_mode must be one of {MODES}, got {self.first_mode!r}")

    @property
    def still_sliding(self) -> bool:
        """Whether the block was still sliding when the run ended (``slip_velocity_end != 0``)."""
        return self.slip_velocity_end != 0.0

    def columns(self) -> dict[str, Any]:
        """The summary as flat table columns (SI units), without the energy balance."""
        return {"first_mode": self.first_mode, "time_sliding": float(self.time_sliding),
                "time_rocking": float(self.time_rocking), "time_flight": float(self.time_flight),
                "slide_max": float(self.slide_max), "slide_residual": float(self.slide_residual)}


@dataclass(frozen=True)
class Impacts:
    """The impacts of one run, as the solver located them (not read off stored samples).

    An impact is a passage of the block from one base corner to the other. For the rigid body
    it is instantaneous at ``theta = 0``; for the SDOF models it is a crossing of the damper
    band ``|theta| <= delta alpha`` from one side to the other (entering and leaving on the same
    side is not an impact).

    Parameters
    ----------
    time : ndarray
        When each impact began (s): the instant of impact (rigid body), the band entry (SDOF).
    theta_dot_before : ndarray
        Angular velocity just before (rad/s): at impact, or at the band entry.
    theta_dot_after : ndarray
        Angular velocity just after (rad/s): after the impact, or at the band exit.
    """

    time: np.ndarray
    theta_dot_before: np.ndarray
    theta_dot_after: np.ndarray

    def __post_init__(self) -> None:
        arrays = [np.asarray(getattr(self, n), dtype=float).ravel() for n in ("time", "theta_dot_before", "theta_dot_after")]
        if len({a.size for a in arrays}) != 1:
            raise InputError(f"impact arrays must have one length, got {[a.size for a in arrays]}")
        for name, a in zip(("time", "theta_dot_before", "theta_dot_after"), arrays):
            a.setflags(write=False)
            object.__setattr__(self, name, a)

    def __len__(self) -> int:
        return int(self.time.size)

    @property
    def velocity_ratio(self) -> np.ndarray:
        """``|theta_dot_after / theta_dot_before|`` per impact (dimensionless)."""
        return np.abs(self.theta_dot_after) / np.abs(self.theta_dot_before)



class ImpactLog:
    """What a solver fills while it runs; :meth:`freeze` gives the result's :class:`Impacts`."""

    def __init__(self) -> None:
        self._rows: list[tuple[float, float, float]] = []

    def add(self, time: float, theta_dot_before: float, theta_dot_after: float) -> None:
        """Log one impact: its time (s) and the angular velocities before and after (rad/s)."""
        self._rows.append((float(time), float(theta_dot_before), float(theta_dot_after)))

    def __len__(self) -> int:
        return len(self._rows)

    def freeze(self) -> Impacts:
        """The logged impacts as an immutable :class:`Impacts`."""
        cols = np.array(self._rows, dtype=float).reshape(-1, 3)
        return Impacts(cols[:, 0], cols[:, 1], cols[:, 2])


@dataclass(frozen=True)
class PlanSummary:
    """What a block did in three dimensions (solvers ``rigid3d``, a box, and ``cylinder3d``, a cylinder), beyond the
    tilt that :attr:`RockingResult.theta` holds.

    Parameters
    ----------
    tilt_max : float
        Peak tilt (rad): the angle between the block's vertical axis and the vertical. In planar motion it is
        ``|theta|``, so it equals :attr:`RockingResult.theta_max`.
    twist_max : float
        Peak rotation about the vertical (rad, absolute).
    slide_max : float
        Peak horizontal displacement of the base's centre relative to the floor (m, the magnitude of the
        vector).
    slide_residual : tuple of float
        Horizontal displacement ``(x, y)`` of the base's centre relative to the floor at the end of the run
        (m, block frame at rest).
    overturned_over : str
        The mechanism of overturning, ``""`` if it did not overturn. A box: ``"edge"`` or ``"corner"``, what it last
        stood on when it overturned (one base edge on the floor, or a single corner). A cylinder: ``"rim"`` (rocking
        over a rim point that stayed put in the body) or ``"rolling"`` (its contact point running round the rim:
        wobbling).
    overturn_direction : float
        Direction in plan (deg, block frame, from ``x`` towards ``y``) in which the centre of mass left the
        support polygon when the block overturned; ``nan`` if it did not.
    time_edge : float
        Time during which the block stood on one base edge (two corners) only (s): rocking about an edge.
    time_corner : float
        Time during which the block stood on a single corner (s): rocking on a corner, wobbling.
    time_sliding : float
        Time during which a loaded corner slipped (s).
    time_flight : float
        Time during which no corner touched the floor (s).
    energy : Mapping
        Energy balance in J (for the block's mass), as :attr:`ContactSummary.energy`.
    time_rim : float
        A cylinder: time during which it stood on one rim point (s); 0 for a box.
    time_rolling : float
        A cylinder: the part of ``time_rim`` during which its contact point ran round the rim (rolling, wobbling; s).
    """

    tilt_max: float
    twist_max: float
    slide_max: float
    slide_residual: tuple[float, float]
    overturned_over: str = ""
    overturn_direction: float = math.nan
    time_edge: float = 0.0
    time_corner: float = 0.0
    time_sliding: float = 0.0
    time_flight: float = 0.0
    energy: Mapping[str, float] = field(default_factory=dict)
    time_rim: float = 0.0
    time_rolling: float = 0.0


@dataclass(frozen=True)
class PlanHistory:
    """Time histories of a three-dimensional run (solver ``rigid3d``), on :attr:`RockingResult.time`.

    Parameters
    ----------
    rotation : ndarray
        ``(n, 3)`` rotation vector of the block (rad, floor frame at rest: ``x`` along the width, ``y`` along
        the depth, ``z`` up).
    position : ndarray
        ``(n, 3)`` position of the centre of mass relative to its place at rest (m, floor frame).
    twist : ndarray
        ``(n,)`` rotation about the vertical (rad).
    slide : ndarray
        ``(n, 2)`` horizontal displacement of the base's centre relative to the floor (m).
    corners_down : ndarray
        ``(n,)`` number of base corners on the floor (0 to 4).
    """

    rotation: np.ndarray = field(repr=False)
    position: np.ndarray = field(repr=False)
    twist: np.ndarray = field(repr=False)
    slide: np.ndarray = field(repr=False)
    corners_down: np.ndarray = field(repr=False)


@dataclass(frozen=True)
class RockingResult:
    """Response of one block to one excitation, whatever solver produced it.

    Parameters
    ----------
    solver : str
        Solver name (``"opensees"``, ``"sdof"``, ``"housner"``, ...).
    settings : Mapping
        Every setting the solver ran with (model and numerics), JSON-serialisable.
    alpha : float
        Block slenderness (rad), for the normalised peak.
    time : ndarray
        Output times (s).
    theta : ndarray
        Rotation (rad) at ``time``.
    theta_dot : ndarray
        Angular velocity (rad/s) at ``time``.
    theta_max : float
        Peak absolute rotation ``|theta|_max`` (rad); for an overturned block, the value at
        which the run stopped (>= pi/2).
    overturned : bool
        True if ``|theta|`` reached ``pi/2`` (Eq. 11).
    rocked : bool
        True if the block uplifted at all. A pulse below ``g tan(alpha)`` does not rock: the
        fragility layer leaves such cases out (Eq. 13 counts rocking simulations).
    status : str
        ``"ok"`` or ``"failed"`` (see :data:`STATUSES`).
    reason : str
        Why a run failed (empty when ``status == "ok"``).
    failure : str or None
        What kind of failure, machine-readable (one of
        :data:`opsrock.solvers.status.FAILURE_KINDS`: ``"nonfinite"``, ``"max_steps"``, ``"max_impacts"``,
        ``"timeout"``, ...); None when ``status == "ok"``. A failed result built without a kind is
        ``"error"``.
    n_steps : int
        Steps taken (time steps, or accepted integrator steps).
    wall_time_s : float
        Wall-clock time of the solve (s).
    spring_moment : ndarray or None
        Spring moment (N m) at ``time`` (SDOF models only).
    damper_force : ndarray or None
        Damper moment ``f_d`` (N m) at ``time`` (SDOF models only).
    n_impacts : int or None
        Number of impacts (passages from one base corner to the other, see :class:`Impacts`),
        the same meaning in every solver; None where a solver does not count them.
    impacts : Impacts or None
        Each impact's time and velocities, where the solver logs them.
    slide : ndarray or None
        Horizontal displacement of the base relative to the floor (m) at ``time`` (solvers of the
        ``friction`` model only).
    contact : ContactSummary or None
        Modes, sliding and energy balance (solvers of the ``friction`` model only).
    plan : PlanSummary or None
        What the block did in three dimensions (solver ``rigid3d`` only; its ``theta`` is then the tilt, rad,
        and ``alpha`` the slenderness of the weaker axis, ``atan(min(b, d) / h)``).
    plan_history : PlanHistory or None
        Its three-dimensional histories (solver ``rigid3d`` with ``record=True`` only).
    diagnostics : Mapping
        Solver bookkeeping that is not part of the answer, JSON-serialisable: for OpenSees the
        number of its own console messages (sent to its log file, never to the terminal), the
        failed steps retried and the log file's path.
    """

    solver: str
    settings: Mapping[str, Any]
    alpha: float
    time: np.ndarray = field(repr=False)
    theta: np.ndarray = field(repr=False)
    theta_dot: np.ndarray = field(repr=False)
    theta_max: float
    overturned: bool
    rocked: bool
    status: str = "ok"
    reason: str = ""
    n_steps: int = 0
    wall_time_s: float = 0.0
    spring_moment: np.ndarray | None = field(default=None, repr=False)
    damper_force: np.ndarray | None = field(default=None, repr=False)
    n_impacts: int | None = None
    impacts: Impacts | None = field(default=None, repr=False)
    diagnostics: Mapping[str, Any] = field(default_factory=dict)
    slide: np.ndarray | None = field(default=None, repr=False)
    contact: ContactSummary | None = None
    failure: str | None = None
    plan: PlanSummary | None = None
    plan_history: PlanHistory | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        if self.status == "failed" and self.failure is None:
            object.__setattr__(self, "failure", "error")
        if self.status == "ok" and self.failure is not None:
            raise InputError(f"an ok result carries no failure, got failure={self.failure!r}")
        if self.status not in STATUSES:
            raise InputError(f"status must be one of {STATUSES}, got {self.status!r}")
        if self.status == "failed" and not self.reason:
            raise InputError("a failed result must carry a reason")
        if self.status == "failed" and self.overturned:
            raise InputError("a failed result cannot carry an overturned verdict")
        if self.impacts is not None and self.n_impacts != len(self.impacts):
            raise InputError(f"n_impacts = {self.n_impacts} but {len(self.impacts)} impacts are logged")
        if self.status == "ok" and not math.isfinite(self.theta_max):
            raise InputError(f"an ok result must have a finite theta_max, got {self.theta_max!r}")
        if self.status == "ok" and self.overturned != (self.theta_max >= OVERTURNING_ANGLE):
            raise InputError(
                f"overturned={self.overturned} contradicts theta_max={self.theta_max!r} "
                f"against the limit state pi/2"
            )

    @property
    def theta_max_over_alpha(self) -> float:
        """Normalised peak rotation ``|theta|_max / alpha`` (dimensionless)."""
        return self.theta_max / self.alpha

    @property
    def ok(self) -> bool:
        """True if the solver finished without failure."""
        return self.status == "ok"

    @property
    def verdict(self) -> str:
        """One of :data:`VERDICTS`: failed runs never read as safe or overturned."""
        if self.status != "ok":
            return "failed"
        if self.overturned:
            return "overturned"
        return "safe" if self.rocked else "no_uplift"

    @property
    def response(self) -> str:
        """One of :data:`RESPONSES`: overturned, rocked, slid (the base slipped, no corner lifted) or at
        rest; a solver without friction never slides."""
        if self.status != "ok":
            return "failed"
        if self.overturned:
            return "overturned"
        if self.rocked:
            return "rocked"
        if self.contact is not None and self.contact.slide_max > 0.0:
            return "slid"
        return "at_rest"

    def summary(self) -> dict[str, Any]:
        """Scalar fields as a JSON-serialisable dict (no time histories)."""
        return {
            "solver": self.solver,
            "status": self.status,
            "reason": self.reason,
            "failure": self.failure,
            "verdict": self.verdict,
            "theta_max": float(self.theta_max),
            "theta_max_over_alpha": float(self.theta_max_over_alpha),
            "overturned": bool(self.overturned),
            "rocked": bool(self.rocked),
            "n_steps": int(self.n_steps),
            "n_impacts": None if self.n_impacts is None else int(self.n_impacts),
            "wall_time_s": float(self.wall_time_s),
            "settings": dict(self.settings),
            "diagnostics": dict(self.diagnostics),
            **({} if self.contact is None else {"response": self.response, **self.contact.columns(),
                                                "energy": dict(self.contact.energy)}),
        }


def failed_result(
    solver: str,
    settings: Mapping[str, Any],
    alpha: float,
    reason: str,
    *,
    time: np.ndarray | None = None,
    theta: np.ndarray | None = None,
    theta_dot: np.ndarray | None = None,
    n_steps: int = 0,
    wall_time_s: float = 0.0,
    failure: str = "error",
) -> RockingResult:
    """Build a ``status="failed"`` result that keeps whatever history was computed; ``failure`` is its
    kind (:data:`opsrock.solvers.status.FAILURE_KINDS`).

    ``theta_max`` is the largest finite ``|theta|`` reached before the failure (NaN if none);
    ``overturned`` and ``rocked`` are False: a failed case carries no verdict.
    """
    empty = np.zeros(0)
    th = empty if theta is None else np.asarray(theta, dtype=float)
    finite = np.abs(th[np.isfinite(th)])
    return RockingResult(
        solver=solver,
        settings=settings,
        alpha=alpha,
        time=empty if time is None else np.asarray(time, dtype=float),
        theta=th,
        theta_dot=empty if theta_dot is None else np.asarray(theta_dot, dtype=float),
        theta_max=float(finite.max()) if finite.size else math.nan,
        overturned=False,
        rocked=False,
        status="failed",
        reason=reason,
        n_steps=n_steps,
        wall_time_s=wall_time_s,
        failure=failure,
    )


def seated_result(solver: str, settings: Mapping[str, Any], alpha: float, duration: float,
                  wall_time_s: float = 0.0) -> RockingResult:
    """The result of an excitation too weak to uplift the block (Eq. 4): it stays seated.

    Parameters
    ----------
    solver : str
        Solver name.
    settings : Mapping
        The solver's settings.
    alpha : float
        Block slenderness (rad).
    duration : float
        Excitation duration (s): the history is ``theta = 0`` over ``[0, duration]``.
    wall_time_s : float
        Time spent (s).
    """
    t = np.array([0.0, float(duration)])
    z = np.zeros(2)
    return RockingResult(solver=solver, settings=settings, alpha=alpha, time=t, theta=z, theta_dot=z.copy(),
                         theta_max=0.0, overturned=False, rocked=False, n_steps=0, wall_time_s=wall_time_s,
                         spring_moment=z.copy(), damper_force=z.copy(), n_impacts=0)
