"""The stiff branch under a record in closed form: a linear ODE with a linear forcing between samples.

There the natural frequency is about 1000 p and an implicit integrator needs thousands of steps per
second of record, whereas the closed form needs none. :func:`closed_form_solve` returns what
:func:`scipy.integrate.solve_ivp` would (events with its conventions), so the solver treats both alike.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq


class ClosedFormSegment:
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



def closed_form_solve(seg: ClosedFormSegment, t0: float, t1: float, events) -> _Solution:
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


def _window_events(seg: ClosedFormSegment, grid: np.ndarray, events, hits: list[list[float]]) -> float:
    """Append the events of ``seg`` on ``grid`` to ``hits``; return the first terminal one's time
    (or the grid's end)."""
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


__all__ = ["CLOSED_FORM_SAMPLES_PER_PERIOD", "CLOSED_FORM_WINDOW_PERIODS", "ClosedFormSegment", "closed_form_solve"]
