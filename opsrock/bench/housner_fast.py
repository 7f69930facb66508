"""Benchmark of the fast rigid-body solver on a dense overturning spectrum (docs/guide/modelling.md section 5).

    opsrock bench --only housner_fast [--quick]

Runs 4 blocks x 100 x 100 one-sine pulses (``--quick``: 4 x 20 x 20), ``omega_p/p`` in
[0.5, 10] and ``PFA/(g tan alpha)`` in [1.0, 10.5], and prints, all measured in this run:

* wall time and cases per second of :func:`opsrock.solvers.housner_fast.solve_pulses`;
* accuracy against converged answers: (a) the same solver with steps eight times shorter,
  on every case; (b) the independent event-driven ``solve_ivp`` reference (rtol 1e-10) of
  :mod:`opsrock.bench.reference` on a random subset: max and 99th percentile of
  ``|d theta_max| / alpha`` and verdict disagreements;
* time per case relative to per-case ``solve_ivp`` loops measured on that subset (the
  reference, and ``opsrock.solvers.housner`` when present);
* the numba first-call time in this process (cache load, or compile if no cache), and with
  ``run(cold=True)`` the compile time of a fresh process with an empty cache.

The machine load (1-minute load average) is printed next to the timings: on a shared
machine absolute times move with it, ratios measured in the same run much less.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

import numpy as np

from opsrock.bench.reference import reference_solve
from opsrock.block import Block
from opsrock.excitations import OneSinePulse

#: The four blocks of the dense-spectrum target (docs/guide/modelling.md section 5), (width, height) in m.
BLOCKS = [Block(0.40, 2.20), Block(0.60, 2.00), Block(0.50, 1.15), Block(1.00, 2.40)]
#: Spectrum ranges (docs/guide/modelling.md section 3): omega_p/p and PFA/(g tan alpha).
FREQ_RANGE = (0.5, 10.0)
PFA_RANGE = (1.0, 10.5)


_COLD_SNIPPET = (
    "import time; t0 = time.perf_counter();"
    "from opsrock.solvers import housner_fast as hf; t1 = time.perf_counter();"
    "hf.solve_grid(0.2, 0.9, 3.0, 2.0); t2 = time.perf_counter();"
    "from opsrock.block import Block; from opsrock.excitations import OneSinePulse;"
    "b = Block(0.6, 2.0); hf.solve(b, OneSinePulse.from_ratios(b, 3.0, 2.0)); t3 = time.perf_counter();"
    "print(t1 - t0, t2 - t1, t3 - t2)"
)


def _cold_compile() -> dict:
    """Import and first-call times of a fresh process with an empty numba cache (s)."""
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        out = subprocess.run([sys.executable, "-c", _COLD_SNIPPET], env=env, capture_output=True,
                             text=True, check=True).stdout.split()
    t_import, t_grid, t_one = map(float, out)
    return {"cold_import_s": t_import, "cold_first_grid_s": t_grid, "cold_first_solve_s": t_one}


def run(quick: bool = False, cold: bool = False, seed: int = 2024) -> dict:
    """Run the benchmark; return every measured number in a flat dict.

    Parameters
    ----------
    quick : bool
        4 x 20 x 20 grid and a smaller reference subset instead of 4 x 100 x 100.
    cold : bool
        Also measure a cold numba compile in a subprocess with an empty cache.
    seed : int
        Seed of the random reference subset.
    """
    out: dict = {"quick": quick, "load_avg_start": os.getloadavg()[0]}
    t0 = time.perf_counter()
    from opsrock.solvers import housner_fast as hf

    out["import_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    hf.solve_grid(0.2, 0.9, 3.0, 2.0)
    out["first_call_s"] = time.perf_counter() - t0  # cache load, or compile without a cache
    if cold:
        out.update(_cold_compile())
    n = 20 if quick else 100
    pfa = np.linspace(*PFA_RANGE, n)
    freq = np.linspace(*FREQ_RANGE, n)
    grid = _grid(out, pfa, freq)
    _against_finer_steps(out, grid, pfa, freq)
    subset = _reference_subset(out, grid, pfa, freq, 15 if quick else 60, seed)
    _against_housner(out, grid, pfa, freq, subset[: 5 if quick else 15])
    out["load_avg_end"] = os.getloadavg()[0]
    return out


def _grid(out: dict, pfa: np.ndarray, freq: np.ndarray):
    """Time the whole grid with every thread and with one (the answers must be identical)."""
    from opsrock.solvers import housner_fast as hf
    from opsrock.solvers.housner_fast.grid import default_threads

    grid = hf.solve_pulses(BLOCKS, pfa, freq)
    out.update(n_cases=int(grid.theta_max.size), wall_s=grid.wall_time_s,
               cases_per_s=grid.theta_max.size / grid.wall_time_s, failed=int((~grid.ok).sum()),
               overturned_fraction=float(grid.overturned.mean()), mean_steps_per_case=float(grid.n_steps.mean()),
               threads=default_threads())
    grid1 = hf.solve_pulses(BLOCKS, pfa, freq, threads=1)
    out["wall_1thread_s"] = grid1.wall_time_s
    out["threads_identical"] = bool(np.array_equal(grid.theta_max, grid1.theta_max))
    return grid


def _against_finer_steps(out: dict, grid, pfa: np.ndarray, freq: np.ndarray) -> None:
    """Every case against the same solver with steps eight times shorter."""
    from opsrock.solvers import housner_fast as hf

    alpha = np.array([b.alpha for b in BLOCKS])[:, None, None] * np.ones_like(grid.theta_max)
    s = hf.HousnerFastSettings()
    fine_settings = hf.HousnerFastSettings(max_dtau=s.max_dtau / 8, steps_per_pulse=s.steps_per_pulse * 8)
    fine = hf.solve_pulses(BLOCKS, pfa, freq, settings=fine_settings)
    both_safe = ~grid.overturned & ~fine.overturned
    d = np.abs(grid.theta_max - fine.theta_max)[both_safe] / alpha[both_safe]
    out["fine_max_dtheta_over_alpha"] = float(d.max()) if d.size else 0.0
    out["fine_p99_dtheta_over_alpha"] = float(np.percentile(d, 99)) if d.size else 0.0
    out["fine_verdict_disagreements"] = int((grid.overturned != fine.overturned).sum())
    out["fine_wall_s"] = fine.wall_time_s


def _reference_subset(out: dict, grid, pfa: np.ndarray, freq: np.ndarray, n_sub: int, seed: int) -> list:
    """A random subset against the independent solve_ivp reference; returns the subset's indices."""
    rng = np.random.default_rng(seed)
    flat = rng.choice(grid.theta_max.size, n_sub, replace=False)
    subset = list(zip(*np.unravel_index(flat, grid.theta_max.shape)))
    t0 = time.perf_counter()
    refs = [reference_solve(BLOCKS[b].alpha, BLOCKS[b].e, pfa[i], freq[j]) for b, i, j in subset]
    t_ref = (time.perf_counter() - t0) / n_sub
    dref, disagree = [], 0
    for ref, (b, i, j) in zip(refs, subset):
        ov = bool(grid.overturned[b, i, j])
        disagree += ov != ref["overturned"]
        if not ov and not ref["overturned"]:
            dref.append(abs(grid.theta_max[b, i, j] - ref["theta_max"]) / BLOCKS[b].alpha)
    dref = np.array(dref) if dref else np.zeros(1)
    per_case_fast = grid.wall_time_s / grid.theta_max.size
    out.update(ref_subset=n_sub, ref_max_dtheta_over_alpha=float(dref.max()),
               ref_p99_dtheta_over_alpha=float(np.percentile(dref, 99)), ref_verdict_disagreements=int(disagree),
               fast_s_per_case=per_case_fast, solve_ivp_s_per_case=t_ref, speedup_vs_solve_ivp=t_ref / per_case_fast)
    return subset


def _against_housner(out: dict, grid, pfa: np.ndarray, freq: np.ndarray, subset: list) -> None:
    """Time per case of the event-driven scipy solver on the first cases of the subset."""
    from opsrock.solvers import housner

    t0 = time.perf_counter()
    for b, i, j in subset:
        housner.solve(BLOCKS[b], OneSinePulse.from_ratios(BLOCKS[b], pfa[i], freq[j]))
    t_h = (time.perf_counter() - t0) / len(subset)
    out["housner_s_per_case"] = t_h
    out["speedup_vs_housner"] = t_h / out["fast_s_per_case"]
