"""Is the paper's IM ranking robust to the choice of blocks? The pulse study over many block sets.

The paper ranks the nine IMs on four blocks it does not list. Here the same study (the paper's
10 x 10 one-sine grid per block, ``omega_p/p`` 0.5-10, ``PFA/(g tan alpha)`` 1-10.5, the paper's
hybrid ratio and least-squares fit at ``W_SAS``) is repeated on ``n_sets`` sets of four blocks drawn,
seeded, from furniture ranges (:data:`ALPHA_RANGE`, :data:`R_RANGE`, uniform), with the rigid-body
solver ``housner_fast``. For each set the winner by HR, by CV and by ``beta`` is recorded; the share
of sets each IM wins is reported with its 95 % Wilson interval.

Computed in tasks of :data:`SETS_PER_TASK` sets: one ``housner_fast`` solve and one evaluation of the IMs
for all the sets of a task (the cases are independent: the same numbers as set by set), then per set only
what the criteria read (the hybrid strip and the least-squares fit at ``W_SAS``; not the MLE); the
least-squares fits run on the fragility layer's own two-parameter solver (:mod:`opsrock.fragility.optimise`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from opsrock.block import Block
from opsrock.intensity import IM_NAMES
from opsrock.limits import check_count, int_at_least
from opsrock.stats import wilson_interval

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
    """The winner of each criterion on a cases table: the IM of the smallest value in
    :func:`opsrock.fragility.analysis.rank_ims` (the paper's analysis at ``W_SAS``), "" if none has one."""
    from opsrock.fragility.cases import split_cases

    rock = split_cases(cases).rocking
    return _winners_of(rock["overturned"].to_numpy(bool), {im: rock[im].to_numpy(float) for im in IM_NAMES})


def _winners_of(overturned: np.ndarray, values: dict[str, np.ndarray]) -> dict[str, str]:
    """:func:`_winners` from the rocking cases' outcomes and IM values: only what the criteria need, the
    hybrid strip (HR) and the least-squares fit at ``W_SAS`` (CV, beta), made exactly as
    :func:`~opsrock.fragility.analysis.analyse_fragility` makes them (not its MLE, which no criterion reads)."""
    from opsrock.fragility.hybrid_strip import hybrid_strip
    from opsrock.fragility.least_squares import fit_lognormal_least_squares
    from opsrock.fragility.strips import strip_fractions
    from opsrock.intensity import get_im

    table = {c: [] for c in CRITERIA}
    for im, x in values.items():
        dec = get_im(im).decreasing
        hs = hybrid_strip(x, overturned, im, dec)
        usable, cv, beta = False, math.nan, math.nan
        if hs.n_safe and hs.n_overturned:
            st = strip_fractions(x, overturned, hs, 1.0, "range")
            fit = fit_lognormal_least_squares(st.centre, st.fraction, dec)
            usable = fit.success and not st.fallback  # a fallback fit is flagged, as in analyse_fragility
            cv, beta = fit.cv_percent, fit.beta
        table["HR"].append(hs.HR)
        table["cv_percent"].append(cv if usable else math.nan)
        table["beta"].append(beta if usable else math.nan)
    ims = list(values)
    out = {}
    for c in CRITERIA:
        v = np.array(table[c], dtype=float)
        out[c] = ims[int(np.nanargmin(v))] if not np.isnan(v).all() else ""  # first smallest, as idxmin
    return out


def _set_winners(blocks: list[Block]) -> dict[str, str]:
    return _sets_winners([blocks])[0]


def _sets_winners(sets: list[list[Block]]) -> list[dict[str, str]]:
    """:func:`_winners` of :func:`pulse_cases` for each set, with one solve and one IM evaluation for all
    the sets (the cases are independent: the same numbers as set by set), on arrays, not tables."""
    from opsrock.constants import G
    from opsrock.intensity.table1 import intensity_measures_array
    from opsrock.solvers.housner_fast import solve_pulses

    blocks = [b for bs in sets for b in bs]
    res = solve_pulses(blocks, PFA_RATIOS, FREQ_RATIOS, threads=1)
    shape = res.ok.shape  # (block, pfa, freq): the rows of pulse_cases, in its order
    ar = np.broadcast_to(np.asarray(PFA_RATIOS)[None, :, None], shape)
    fr = np.broadcast_to(np.asarray(FREQ_RATIOS)[None, None, :], shape)
    prop = {k: np.broadcast_to(np.array([getattr(b, k) for b in blocks])[:, None, None], shape).ravel()
            for k in ("alpha", "R", "p", "e_R", "tan_alpha")}
    # the same products, in the same order, as pulse_cases' Python floats
    pfa = np.array([a * G * t for a, t in zip(ar.ravel().tolist(), prop["tan_alpha"].tolist())])
    omega_p = np.array([f * p for f, p in zip(fr.ravel().tolist(), prop["p"].tolist())])
    ims = intensity_measures_array(prop["alpha"], prop["R"], prop["p"], prop["e_R"], pfa, omega_p)
    rocking = (res.ok & res.rocked).ravel()
    over = res.overturned.ravel()
    odd = (res.ok & ~res.rocked & res.overturned).ravel()  # refused by split_cases
    out = []
    start = 0
    for bs in sets:
        n = len(bs) * shape[1] * shape[2]
        if odd[start:start + n].any():
            out.append(_winners(pulse_cases(bs)))  # raises split_cases' error on this set's table
        else:
            rows = np.flatnonzero(rocking[start:start + n]) + start
            out.append(_winners_of(over[rows], {im: ims[im][rows] for im in IM_NAMES}))
        start += n
    return out


#: Block sets per task of :func:`ranking_robustness` (one solve and one IM evaluation a task).
SETS_PER_TASK: int = 10


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
    chunks = [sets[i:i + SETS_PER_TASK] for i in range(0, n_sets, SETS_PER_TASK)]
    if workers == 1 or len(chunks) == 1:
        it = map(_sets_winners, chunks)
        pool = None
    else:
        from opsrock._pool import deferred_interrupts, process_pool

        pool = process_pool(min(workers, len(chunks)))
        with deferred_interrupts():  # the workers are forked at the first task
            it = pool.map(_sets_winners, chunks)
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=n_sets, desc="block sets", unit="set")
    try:
        rows = []
        for won in it:
            for w in won:
                rows.append({"set": len(rows), **{f"winner_{c}": x for c, x in w.items()}})
            if progress:
                bar.update(len(won))
    finally:
        if progress:
            bar.close()
        if pool is not None:
            pool.shutdown(cancel_futures=True)
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
