"""Minimum overturning acceleration: the overturning boundary along the amplitude axis of a pulse.

For a block and a pulse shape at a fixed ``omega_p / p``, the verdict is a function of the pulse
amplitude alone, and it is not monotonic: above the first overturning amplitude the rocking
literature (Zhang and Makris 2001) finds safe windows, where the pulse is strong enough to make the
block impact and be pushed back upright. :func:`overturning_intervals` returns every overturning
interval along the amplitude axis, found in two stages:

1. **scan**: the verdict on a geometric grid of ``n_scan`` amplitudes from just above uplift to
   ``pfa_ratio_max`` (spacing ratio ``(max/min)^(1/(n_scan - 1))``, 0.65 % by default);
2. **bracket**: every pair of neighbouring grid points whose verdicts differ (overturned against
   safe or no uplift) brackets one boundary, refined by bisection until the bracket is narrower
   than ``rtol`` (relative).

Each boundary is exact to ``rtol`` (a verdict of the solver on each side). A window narrower than
the scan spacing can fall between two grid points and go unseen: the resolution is part of the
result (:attr:`OverturningIntervals.scan_ratio`). Cases a solver cannot decide are failed, listed
in :attr:`OverturningIntervals.failed`, never counted as either verdict; a boundary is not refined
across a failed point.

:func:`threshold_chart` does the same for many ``omega_p / p`` at once with ``housner_fast`` (one
batch per stage), which draws a whole minimum-overturning chart in seconds.

Amplitudes are ``pfa_ratio = PFA / (g tan alpha)`` throughout (the paper's IM2); the linearised
literature uses ``PFA / (g alpha)``, which is ``pfa_ratio tan(alpha) / alpha``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Sequence

import numpy as np

from opsrock.analysis.threshold_defaults import DEFAULT_N_SCAN, DEFAULT_PFA_RATIO_MAX, DEFAULT_RTOL
from opsrock.block import Block
from opsrock.constants import EQUATIONS, G
from opsrock.errors import InputError, InputTypeError
from opsrock.excitations import PULSE_SHAPES, pulse_class
from opsrock.limits import check, check_count, one_of, positive_finite, scaled_input

#: Solvers whose settings take ``equations`` (the SDOF models solve their own equation).
RIGID_SOLVERS: tuple[str, ...] = ("housner", "housner_fast")


@dataclass(frozen=True)
class OverturningIntervals:
    """The overturning intervals of one block and pulse along the amplitude axis.

    Parameters
    ----------
    freq_ratio : float
        ``omega_p / p`` (dimensionless).
    shape : str
        Pulse shape (a key of :data:`opsrock.excitations.PULSE_SHAPES`).
    solver : str
        Solver that gave the verdicts.
    equations : str
        ``"exact"`` or ``"linearised"`` (rigid-body solvers); ``"sdof"`` for the SDOF models, ``"friction"`` for
        the rigid block with friction.
    alpha : float
        Block slenderness (rad).
    intervals : tuple of (float, float)
        Overturning intervals ``[low, high]`` in ``PFA / (g tan alpha)``, ascending; ``high`` is
        ``inf`` when the block still overturns at the top of the scanned range.
    pfa_ratio_min, pfa_ratio_max : float
        The scanned range (dimensionless).
    scan_ratio : float
        Ratio of neighbouring scanned amplitudes: windows narrower than this may be missed.
    rtol : float
        Relative width of each refined boundary bracket.
    failed : tuple of (float, str)
        Amplitudes (``PFA / (g tan alpha)``) the solver failed on, with the reason.
    n_solves : int
        Solver runs used.
    """

    freq_ratio: float
    shape: str
    solver: str
    equations: str
    alpha: float
    intervals: tuple[tuple[float, float], ...]
    pfa_ratio_min: float
    pfa_ratio_max: float
    scan_ratio: float
    rtol: float
    failed: tuple[tuple[float, str], ...] = field(default=())
    n_solves: int = 0

    @property
    def minimum(self) -> float:
        """Smallest overturning amplitude ``PFA / (g tan alpha)``; nan if none in the range."""
        return self.intervals[0][0] if self.intervals else math.nan

    def to_g_alpha(self, value: float) -> float:
        """Convert ``PFA / (g tan alpha)`` to ``PFA / (g alpha)`` (the linearised papers' axis)."""
        return value * math.tan(self.alpha) / self.alpha

    def as_dict(self) -> dict[str, Any]:
        """Plain JSON data (``inf`` as the string ``"inf"``)."""
        def num(x: float) -> float | str:
            return "inf" if math.isinf(x) else x

        return {
            "freq_ratio": self.freq_ratio, "shape": self.shape, "solver": self.solver,
            "equations": self.equations, "alpha": self.alpha,
            "intervals_pfa_ratio": [[num(a), num(b)] for a, b in self.intervals],
            "intervals_pfa_over_g_alpha": [[num(self.to_g_alpha(a)), num(self.to_g_alpha(b))]
                                           for a, b in self.intervals],
            "minimum_pfa_ratio": num(self.minimum) if self.intervals else None,
            "pfa_ratio_min": self.pfa_ratio_min, "pfa_ratio_max": self.pfa_ratio_max,
            "scan_ratio": self.scan_ratio, "rtol": self.rtol,
            "failed": [[a, r] for a, r in self.failed], "n_solves": self.n_solves,
        }


def uplift_pfa_ratio(block: Block, equations: str = "exact") -> float:
    """``PFA / (g tan alpha)`` at which a pulse of peak ``PFA`` starts to uplift the block
    (dimensionless): 1 for the exact equation (Eq. 4), ``alpha / tan(alpha)`` for the linearised one."""
    return 1.0 if equations == "exact" else block.alpha / block.tan_alpha


def _scan_grid(lo: float, hi: float, n: int) -> np.ndarray:
    """Geometric grid from just above ``lo`` (a pulse at exactly the uplift level does not uplift)
    to ``hi``."""
    return np.geomspace(lo * (1.0 + 1e-9), hi, n)


def _check_common(block: Any, shape: str, equations: str, pfa_ratio_max: float, n_scan: int, rtol: float) -> None:
    if not isinstance(block, Block):
        raise InputTypeError(f"block must be a Block, got {block!r}")
    one_of("shape", shape, tuple(PULSE_SHAPES))
    one_of("equations", equations, EQUATIONS)
    scaled_input("pfa_ratio_max", positive_finite("pfa_ratio_max", pfa_ratio_max), "pfa", block.uplift_acceleration)
    check_count("n_scan", n_scan)
    if check("boundary_rtol", rtol, shown_as="rtol") >= 0.1:
        raise InputError(f"rtol must lie in [1e-12, 0.1), got {rtol!r}")


def _codes(res) -> np.ndarray:
    """Verdict codes of a ``housner_fast`` batch: 1 overturned, 0 not, -1 failed."""
    return np.where(res.ok, res.overturned.astype(int), -1)


class _Verdicts:
    """Verdict of one block at amplitudes ``pfa_ratio`` of one pulse, per solver; counts solves."""

    def __init__(self, block: Block, shape: str, freq_ratio: float, solver: str, equations: str,
                 settings: dict[str, Any]) -> None:
        self.block, self.shape, self.freq_ratio = block, shape, freq_ratio
        self.solver, self.equations, self.settings = solver, equations, dict(settings)
        if solver in RIGID_SOLVERS:
            self.settings["equations"] = equations
        self.n_solves = 0

    def __call__(self, ratios: np.ndarray) -> tuple[np.ndarray, list[str]]:
        """(overturned: 1, not: 0, failed: -1) per amplitude, and the failure reasons."""
        ratios = np.atleast_1d(np.asarray(ratios, dtype=float))
        self.n_solves += ratios.size
        if self.solver == "housner_fast":
            from opsrock.solvers.common import make_settings
            from opsrock.solvers.housner_fast import STATUS_REASONS, HousnerFastSettings, solve_grid

            res = solve_grid(self.block.alpha, self.block.e, ratios, self.freq_ratio,
                             settings=make_settings(HousnerFastSettings, None, self.settings), pulse=self.shape)
            code = _codes(res)
            return code, [STATUS_REASONS.get(int(s), "") for s in res.status]
        from opsrock.solvers import simulate

        code = np.empty(ratios.size, dtype=int)
        reasons = []
        for i, r in enumerate(ratios):
            pulse = pulse_class(self.shape).from_ratios(self.block, pfa_ratio=float(r), freq_ratio=self.freq_ratio)
            out = simulate(self.block, pulse, solver=self.solver, **self.settings)
            code[i] = -1 if not out.ok else int(out.overturned)
            reasons.append(out.reason if not out.ok else "")
        return code, reasons


def _refine(solve, lo: np.ndarray, hi: np.ndarray, v_lo: np.ndarray, rtol: float):
    """Bisect every bracket ``[lo, hi]`` (verdict ``v_lo`` at ``lo``, another one at ``hi``) until
    ``hi / lo - 1 <= rtol``. All brackets advance together: ``solve(amplitudes, bracket indices)``
    returns their verdict codes (1 overturned, 0 not, -1 failed) in one batch per halving. A failed
    midpoint stops its bracket where it is. Returns (lo, hi, solves per bracket)."""
    lo, hi = lo.astype(float), hi.astype(float)
    n = np.zeros(lo.size, dtype=int)
    active = hi / lo - 1.0 > rtol
    while np.any(active):
        idx = np.flatnonzero(active)
        mid = np.sqrt(lo[idx] * hi[idx])
        code = solve(mid, idx)
        n[idx] += 1
        same = code == v_lo[idx]
        other = (code != v_lo[idx]) & (code >= 0)
        lo[idx[same]] = mid[same]
        hi[idx[other]] = mid[other]
        active[idx[code < 0]] = False
        active &= hi / lo - 1.0 > rtol
    return lo, hi, n


def _edges(change: np.ndarray, v_lo: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> dict[int, float]:
    """Refined boundary per scanned change (keyed by the index of its left grid point), on the
    overturned side of its bracket."""
    return {int(i): float(hi[k] if v_lo[k] == 0 else lo[k]) for k, i in enumerate(change)}


def _intervals_from(grid: np.ndarray, code: np.ndarray, edges: dict[int, float]) -> tuple[tuple[float, float], ...]:
    """Overturning intervals from the scanned verdicts and the refined boundary of each change."""
    out: list[tuple[float, float]] = []
    start: float | None = None
    for i, c in enumerate(code):
        if c == 1 and start is None:
            start = edges.get(i - 1, grid[i]) if i > 0 else grid[i]
        elif c == 0 and start is not None:
            out.append((start, edges.get(i - 1, grid[i - 1])))
            start = None
    if start is not None:
        out.append((start, math.inf))
    return tuple(out)


def _model_of(solver: str) -> str:
    """The registry's model of ``solver`` (``"sdof"``, ``"friction"``)."""
    from opsrock.solvers import METHODS

    return METHODS[solver].model


def overturning_intervals(block: Block, freq_ratio: float, *, shape: str = "one-sine", solver: str = "housner_fast",
                          equations: str = "exact", pfa_ratio_max: float = DEFAULT_PFA_RATIO_MAX,
                          n_scan: int = DEFAULT_N_SCAN, rtol: float = DEFAULT_RTOL,
                          settings: dict[str, Any] | None = None) -> OverturningIntervals:
    """Every overturning interval of ``block`` along the amplitude axis of one pulse.

    Parameters
    ----------
    block : Block
        The block (its ``alpha``, ``p`` and ``e``).
    freq_ratio : float
        ``omega_p / p`` (dimensionless), > 0; for the rectangular pulse ``pi / (p t_1)``.
    shape : str, optional
        Pulse shape, a key of :data:`opsrock.excitations.PULSE_SHAPES`. Default ``"one-sine"``.
    solver : str, optional
        One of :data:`opsrock.solvers.SOLVERS`. Default ``"housner_fast"``.
    equations : str, optional
        ``"exact"`` or ``"linearised"``, for the rigid-body solvers (``housner``, ``housner_fast``).
    pfa_ratio_max : float, optional
        Top of the scanned range, ``PFA / (g tan alpha)`` (dimensionless). Default 50.
    n_scan : int, optional
        Scanned amplitudes, >= 3. Default 600.
    rtol : float, optional
        Relative width of each refined boundary bracket, in (0, 0.1). Default 1e-6.
    settings : dict, optional
        Further solver settings.

    Returns
    -------
    OverturningIntervals
    """
    from opsrock.solvers import SOLVERS

    one_of("solver", solver, SOLVERS)
    _check_common(block, shape, equations, pfa_ratio_max, n_scan, rtol)
    freq_ratio = positive_finite("freq_ratio", freq_ratio)
    if equations == "linearised" and solver not in RIGID_SOLVERS:
        raise InputError(f"equations = 'linearised' needs a rigid-body solver ({', '.join(RIGID_SOLVERS)}), "
                         f"not solver = {solver!r}")
    lo = uplift_pfa_ratio(block, equations)
    if pfa_ratio_max <= lo:
        raise InputError(f"pfa_ratio_max must exceed the uplift level {lo:.6g}, got {pfa_ratio_max!r}")
    verdicts = _Verdicts(block, shape, freq_ratio, solver, equations, settings or {})
    grid = _scan_grid(lo, pfa_ratio_max, n_scan)
    code, reasons = verdicts(grid)
    change = np.flatnonzero((code[:-1] >= 0) & (code[1:] >= 0) & (code[:-1] != code[1:]))
    a, b, _ = _refine(lambda mid, idx: verdicts(mid)[0], grid[change], grid[change + 1], code[change], rtol)
    edges = _edges(change, code[change], a, b)
    return OverturningIntervals(
        freq_ratio=freq_ratio, shape=shape, solver=solver,
        equations=equations if solver in RIGID_SOLVERS else _model_of(solver), alpha=block.alpha,
        intervals=_intervals_from(grid, code, edges), pfa_ratio_min=float(grid[0]), pfa_ratio_max=float(grid[-1]),
        scan_ratio=float(grid[1] / grid[0]), rtol=rtol,
        failed=tuple((float(grid[i]), reasons[i]) for i in np.flatnonzero(code < 0)), n_solves=verdicts.n_solves,
    )


def boundary(block: Block, freq_ratio: float, low: float, high: float, *, shape: str = "one-sine",
             solver: str = "housner_fast", equations: str = "exact", rtol: float = DEFAULT_RTOL,
             settings: dict[str, Any] | None = None) -> float:
    """The one overturning boundary inside ``[low, high]`` (``PFA / (g tan alpha)``) by bisection, for
    checking a boundary found by one solver with another without a full scan.

    Parameters
    ----------
    block, freq_ratio, shape, solver, equations, rtol, settings
        As in :func:`overturning_intervals`.
    low, high : float
        The bracket (dimensionless), ``0 < low < high``; the verdicts at its ends must differ.

    Returns
    -------
    float
        The boundary, on the overturned side of the final bracket; nan if a solve failed.

    Raises
    ------
    ValueError
        If the verdicts at ``low`` and ``high`` agree (no boundary, or an even number, inside).
    """
    from opsrock.solvers import SOLVERS

    one_of("solver", solver, SOLVERS)
    low, high = positive_finite("low", low), positive_finite("high", high)
    if not low < high:
        raise InputError(f"low must be below high, got low = {low!r}, high = {high!r}")
    verdicts = _Verdicts(block, shape, positive_finite("freq_ratio", freq_ratio), solver, equations, settings or {})
    code, _ = verdicts(np.array([low, high]))
    if code.min() < 0:
        return math.nan
    if code[0] == code[1]:
        raise InputError(f"{solver} gives the same verdict at pfa_ratio {low:.6g} and {high:.6g}: no single boundary between")
    a, b, _ = _refine(lambda mid, idx: verdicts(mid)[0], np.array([low]), np.array([high]), code[:1], rtol)
    return float(b[0] if code[0] == 0 else a[0])


def threshold_chart(block: Block, freq_ratios: Sequence[float], *, shape: str = "one-sine", equations: str = "exact",
                    pfa_ratio_max: float = DEFAULT_PFA_RATIO_MAX, n_scan: int = DEFAULT_N_SCAN,
                    rtol: float = DEFAULT_RTOL, settings: dict[str, Any] | None = None) -> list[OverturningIntervals]:
    """:func:`overturning_intervals` with ``housner_fast`` at many ``omega_p / p``, batched: one
    solver call scans every frequency, and every bracket of every frequency is bisected together.

    Parameters
    ----------
    block : Block
        The block.
    freq_ratios : sequence of float
        ``omega_p / p`` values (dimensionless), > 0.
    shape, equations, pfa_ratio_max, n_scan, rtol, settings
        As in :func:`overturning_intervals`.

    Returns
    -------
    list of OverturningIntervals
        One per ``freq_ratios`` value, in order.
    """
    from opsrock.solvers.common import make_settings
    from opsrock.solvers.housner_fast import HousnerFastSettings, solve_grid

    _check_common(block, shape, equations, pfa_ratio_max, n_scan, rtol)
    nu = np.asarray(freq_ratios, dtype=float).ravel()
    if nu.size == 0 or not np.all(np.isfinite(nu) & (nu > 0)):
        raise InputError(f"freq_ratios must be a non-empty list of positive numbers, got {freq_ratios!r}")
    hs = make_settings(HousnerFastSettings, None, {**(settings or {}), "equations": equations})
    lo = uplift_pfa_ratio(block, equations)
    grid = _scan_grid(lo, pfa_ratio_max, n_scan)

    def run(r: np.ndarray, f: np.ndarray) -> np.ndarray:
        res = solve_grid(block.alpha, block.e, r, f, settings=hs, pulse=shape)
        return _codes(res)

    code = run(np.broadcast_to(grid, (nu.size, grid.size)), nu[:, None])
    rows, cols = np.nonzero((code[:, :-1] >= 0) & (code[:, 1:] >= 0) & (code[:, :-1] != code[:, 1:]))
    v_lo = code[rows, cols]
    a, b, n_bis = _refine(lambda mid, idx: run(mid, nu[rows[idx]]), grid[cols], grid[cols + 1], v_lo, rtol)
    out = []
    for j, f in enumerate(nu):
        sel = np.flatnonzero(rows == j)
        out.append(OverturningIntervals(
            freq_ratio=float(f), shape=shape, solver="housner_fast", equations=equations, alpha=block.alpha,
            intervals=_intervals_from(grid, code[j], _edges(cols[sel], v_lo[sel], a[sel], b[sel])),
            pfa_ratio_min=float(grid[0]), pfa_ratio_max=float(grid[-1]), scan_ratio=float(grid[1] / grid[0]),
            rtol=rtol, failed=tuple((float(grid[i]), "housner_fast failed") for i in np.flatnonzero(code[j] < 0)),
            n_solves=int(grid.size + n_bis[sel].sum())))
    return out


def pfa_g(block: Block, pfa_ratio: float) -> float:
    """``PFA`` in g for an amplitude ``PFA / (g tan alpha)`` of ``block``."""
    return pfa_ratio * block.uplift_acceleration / G


__all__ = ["OverturningIntervals", "boundary", "overturning_intervals", "pfa_g", "threshold_chart", "uplift_pfa_ratio"]
