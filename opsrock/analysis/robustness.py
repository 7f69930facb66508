"""Is the paper's IM ranking robust to the choice of blocks? The pulse study over many block sets.

The paper ranks the nine IMs on four blocks it does not list. Here the same study (the paper's
10 x 10 one-sine grid per block, ``omega_p/p`` 0.5-10, ``PFA/(g tan alpha)`` 1-10.5, the paper's
hybrid ratio and least-squares fit at ``W_SAS``) is repeated on ``n_sets`` sets of four blocks drawn,
seeded, from furniture ranges (:data:`ALPHA_RANGE`, :data:`R_RANGE`, uniform), with the rigid-body
solver ``housner_fast``. For each set the winner by HR, by CV and by ``beta`` is recorded; the share
of sets each IM wins is reported with its 95 % Wilson interval.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from opsrock.block import Block
from opsrock.intensity import IM_NAMES
from opsrock.limits import check_count, int_at_least

#: Slenderness of freestanding furniture and equipment (rad): a tall bookcase (about 0.15) to a
#: squat cabinet (about 0.45).
ALPHA_RANGE: tuple[float, float] = (0.15, 0.45)
#: Size R = sqrt(b² + h²) (m): a bedside cabinet (0.5) to a wardrobe or rack (1.5).
R_RANGE: tuple[float, float] = (0.5, 1.5)
#: The paper's pulse grid (reconstructed, as the shipped scene ``paper``).
FREQ_RATIOS: tuple[float, ...] = tuple(np.linspace(0.5, 10.0, 10))
PFA_RATIOS: tuple[float, ...] = tuple(np.linspace(1.0, 10.5, 10))
#: Ranking criteria: column of :func:`opsrock.fragility.analysis.rank_ims` (smaller is better).
CRITERIA: tuple[str, ...] = ("HR", "cv_percent", "beta")


def wilson_interval(k: int, n: int, z: float = 1.959963984540054) -> tuple[float, float]:
    """95 % (default ``z``) Wilson score interval of a proportion ``k / n``."""
    if n <= 0:
        return math.nan, math.nan
    p = k / n
    d = 1.0 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    # exact ends: at k = 0 (k = n) the lower (upper) bound is 0 (1), not a round-off residue of it
    return (0.0 if k == 0 else max(0.0, c - h)), (1.0 if k == n else min(1.0, c + h))


def draw_block_sets(n_sets: int, seed: int, per_set: int = 4) -> list[list[Block]]:
    """``n_sets`` sets of ``per_set`` blocks, alpha and R uniform in their ranges (seeded)."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(n_sets):
        alpha = rng.uniform(*ALPHA_RANGE, per_set)
        R = rng.uniform(*R_RANGE, per_set)
        out.append([Block(2 * r * math.sin(a), 2 * r * math.cos(a), name=f"s{i}b{j}")
                    for j, (a, r) in enumerate(zip(alpha, R))])
    return out


def pulse_cases(blocks: list[Block]) -> pd.DataFrame:
    """The paper's grid for ``blocks`` solved by ``housner_fast``, as a cases table with IM1-IM9."""
    from opsrock.constants import G
    from opsrock.intensity import add_intensity_measures
    from opsrock.solvers.housner_fast import solve_pulses

    res = solve_pulses(blocks, PFA_RATIOS, FREQ_RATIOS, threads=1)
    rows = []
    for b_i, b in enumerate(blocks):
        for a_i, ar in enumerate(PFA_RATIOS):
            for f_i, fr in enumerate(FREQ_RATIOS):
                rows.append({"block": b.name, "alpha": b.alpha, "R": b.R, "p": b.p, "e_R": b.e_R,
                             "pfa": ar * G * b.tan_alpha, "omega_p": fr * b.p,
                             "status": "ok" if res.ok[b_i, a_i, f_i] else "failed",
                             "rocked": bool(res.rocked[b_i, a_i, f_i]),
                             "overturned": bool(res.overturned[b_i, a_i, f_i])})
    return add_intensity_measures(pd.DataFrame(rows))


@dataclass(frozen=True)
class RobustnessResult:
    """Result of :func:`ranking_robustness`.

    Parameters
    ----------
    winners : pandas.DataFrame
        One row per block set: ``set``, ``winner_HR``, ``winner_cv_percent``, ``winner_beta``.
    shares : pandas.DataFrame
        One row per IM: wins and share per criterion, with Wilson intervals.
    n_sets, seed : int
    """

    winners: pd.DataFrame
    shares: pd.DataFrame
    n_sets: int
    seed: int


def _winners(cases: pd.DataFrame) -> dict[str, str]:
    from opsrock.fragility.analysis import FragilitySettings, analyse_fragility, rank_ims

    an = analyse_fragility(cases, FragilitySettings(strip_factors=(1.0,), n_boot=0))
    rank = rank_ims(an)
    return {c: (str(rank[c].idxmin()) if rank[c].notna().any() else "") for c in CRITERIA}


def _set_winners(blocks: list[Block]) -> dict[str, str]:
    return _winners(pulse_cases(blocks))


def ranking_robustness(n_sets: int = 200, seed: int = 0, progress: bool = False,
                       workers: int = 1) -> RobustnessResult:
    """Repeat the paper's pulse study on ``n_sets`` seeded block sets and count the winners.

    Parameters
    ----------
    n_sets : int, optional
        Block sets (four blocks each). Default 200.
    seed : int, optional
        Seed of the draws. Default 0.
    progress : bool, optional
        Show a progress bar (tqdm).
    workers : int, optional
        Processes (each set is independent; the draws are made here, so the result does not
        depend on ``workers``). Default 1.
    """
    n_sets = int_at_least("n_sets", check_count("robustness_sets", n_sets), 1)
    workers = check_count("workers", workers)
    sets = draw_block_sets(n_sets, seed)
    if workers == 1:
        it = map(_set_winners, sets)
        pool = None
    else:
        from concurrent.futures import ProcessPoolExecutor

        pool = ProcessPoolExecutor(max_workers=workers)
        it = pool.map(_set_winners, sets, chunksize=max(1, n_sets // (4 * workers)))
    if progress:
        from tqdm import tqdm

        it = tqdm(it, total=n_sets, desc="block sets", unit="set")
    try:
        rows = [{"set": i, **{f"winner_{c}": w for c, w in won.items()}} for i, won in enumerate(it)]
    finally:
        if pool is not None:
            pool.shutdown()
    winners = pd.DataFrame(rows)
    shares = []
    for im in IM_NAMES:
        row = {"im": im}
        for c in CRITERIA:
            k = int((winners[f"winner_{c}"] == im).sum())
            lo, hi = wilson_interval(k, n_sets)
            row.update({f"wins_{c}": k, f"share_{c}": k / n_sets, f"share_{c}_lo": lo, f"share_{c}_hi": hi})
        shares.append(row)
    return RobustnessResult(winners, pd.DataFrame(shares), n_sets, seed)
