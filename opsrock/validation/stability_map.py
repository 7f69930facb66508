"""Validation case 6: time step x integration method, classified accurate / wrong / failed / unstable.

For each block and each cell (time step ``dt``, method) the OpenSees solver runs a small fixed
set of one-sine pulses (one below uplift, one safe, one overturning, one near-threshold rocking) and the cell is
classified against the *same SDOF model* solved by scipy (:mod:`opsrock.solvers.sdof` at its
default tight tolerances, rtol 1e-10; it shares the spring table, damper and lever but none of
the numerics):

* ``"accurate"``: every run ok, the same verdict as the reference on every pulse, and
  ``max |theta_max - theta_max,ref| / alpha <= ACCURACY_TOLERANCE`` over the pulses that do not
  overturn (an overturned run stops one step past ``pi/2``, so its ``theta_max`` is the stopping
  point, not a peak: only its verdict is compared);
* ``"converged_but_wrong"``: every run ok, but an error above the tolerance or a wrong verdict;
  for a user this is the dangerous class: a plausible answer that is wrong;
* ``"failed"``: a run returned ``status="failed"`` for another reason (no convergence, end time);
* ``"unstable"``: a run returned ``status="failed"`` with a reason starting ``"unstable"``.

Methods: the fixed-step integrators of :data:`opsrock.solvers.opensees.INTEGRATORS` (the
explicit ``central_difference`` with ``explicit_step_check=False`` so that the map *measures*
its instability instead of refusing it up front) and ``"adaptive"`` (``adaptive=True`` with the
default integrator and ``dt`` as its largest step). Every other setting is the solver's default,
read from ``OpenSeesSettings()`` at run time.

The explicit critical step is measured by bisection (:func:`measured_critical_step`) and compared
with ``dt_cr = 2 sqrt(I_O theta_e / (m g R sin alpha))`` (:func:`~opsrock.solvers.opensees.
critical_time_step`).
"""

from __future__ import annotations

import csv
import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from opsrock.block import Block
from opsrock.data import blocks_file
from opsrock.errors import InputError
from opsrock.excitations import OneSinePulse
from opsrock.limits import positive_finite
from opsrock.result import RockingResult
from opsrock.solvers import opensees as osr
from opsrock.solvers import simulate

#: Cell classes, from best to worst for a user (a failed run is honest; a wrong one is not).
CLASSES: tuple[str, ...] = ("accurate", "converged_but_wrong", "failed", "unstable")

#: Accuracy tolerance on ``|theta_max - theta_max,ref| / alpha`` (docs/guide/modelling.md section 5: 5 % of
#: alpha separates "usable for a fragility verdict" from "wrong"; the paper's fragility only uses
#: the overturning verdict, which a 5 % error changes only for pulses within 5 % of the boundary).
ACCURACY_TOLERANCE: float = 0.05

#: Methods on the map: the fixed-step integrators, then the adaptive mode.
METHODS: tuple[str, ...] = (*osr.INTEGRATORS, "adaptive")

#: Time steps (s), log-spaced (1-2-5) from 1e-2 (13 times the explicit limit of these blocks,
#: 6-9e-4 s) down to 5e-5 (half the 1e-4 default). Not 1e-5: those cells alone would take ~10 min
#: on the shared 2-core machine (measured 2-17 s a run), and the accurate region is already
#: reached at 1e-3-1e-4 by every method.
DTS: tuple[float, ...] = (1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4, 5e-5)
QUICK_DTS: tuple[float, ...] = (1e-2, 1e-3, 1e-4)

#: Pulses as (label, PFA / (g tan alpha), omega_p / p). "no_uplift": half the uplift acceleration
#: (Eq. 4), the block stays on the stiff branch, where an explicit scheme above dt_cr blows up;
#: "safe": a moderate rocking response (sdof: theta_max 0.21-0.32 alpha on all four blocks);
#: "overturning": overturns all four.
COMMON_PULSES: tuple[tuple[str, float, float], ...] = (
    ("no_uplift", 0.5, 1.0), ("safe", 2.0, 6.0), ("overturning", 2.0, 2.0))

#: "near_threshold": per block, a safe pulse with a large peak (sdof: bookcase 0.72 alpha, others
#: 0.86 alpha; a slightly stronger pulse overturns), the most error-sensitive kind of response.
NEAR_THRESHOLD: dict[str, tuple[float, float]] = {
    "bookcase": (1.7, 4.0),
    "wardrobe": (2.0, 4.0),
    "medicine_cabinet": (4.0, 4.0),
    "equipment_rack": (4.0, 4.0),
}
DEFAULT_NEAR_THRESHOLD: tuple[float, float] = (4.0, 4.0)

#: Pulse of the critical-step measurement: half the uplift acceleration, omega_p = p, so the
#: block stays on the stiff branch (exact no_uplift answer, linear there: the textbook setting of
#: the central-difference limit ``omega_e dt = 2``).
CRITICAL_STEP_PULSE: tuple[float, float] = (0.5, 1.0)

#: Relative resolution of the critical-step bisection (-).
BISECTION_RTOL: float = 1e-4

#: A run that fails within this many steps blew up from its first steps (the onset of true
#: instability); a failure later on is the solver's sawtooth test tripping on a stable but
#: near-Nyquist oscillation (see :func:`measured_critical_step`).
ONSET_STEPS: int = 100


def map_blocks(names: tuple[str, ...] | None = None) -> tuple[Block, ...]:
    """The four project blocks of the shipped blocks file (:func:`opsrock.data.blocks_file`)."""
    from opsrock.campaign.scene import load_blocks

    blocks = tuple(spec.block for spec in load_blocks(blocks_file()))
    if names is not None:
        blocks = tuple(b for b in blocks if b.name in names)
    return blocks


def map_pulses(block: Block) -> tuple[tuple[str, OneSinePulse], ...]:
    """The fixed pulses of ``block``: (label, pulse) for no-uplift, safe, overturning, near-threshold."""
    specs = (*COMMON_PULSES, ("near_threshold", *NEAR_THRESHOLD.get(block.name, DEFAULT_NEAR_THRESHOLD)))
    return tuple((label, OneSinePulse.from_ratios(block, pr, fr)) for label, pr, fr in specs)


def method_settings(method: str, dt: float) -> dict[str, Any]:
    """OpenSees overrides of one map cell (everything else is ``OpenSeesSettings()``).

    Parameters
    ----------
    method : str
        One of :data:`METHODS`.
    dt : float
        Time step (s); the largest step for ``"adaptive"``.
    """
    positive_finite("dt", dt)
    # min_step: the default's, unless that exceeds dt (the settings refuse min_step > step)
    min_step = min(osr.OpenSeesSettings().min_step, dt)
    # uplift_check=False: the map probes the numerics, so pulses below Eq. 4's threshold are
    # integrated too (that is where explicit instability shows)
    if method == "adaptive":
        return {"adaptive": True, "step": dt, "min_step": min_step, "uplift_check": False}
    if method not in osr.INTEGRATORS:
        raise InputError(f"method must be one of {', '.join(METHODS)}; got {method!r}")
    s: dict[str, Any] = {"integrator": method, "step": dt, "adaptive": False, "min_step": min_step, "uplift_check": False}
    if method == "central_difference":
        s["explicit_step_check"] = False
        s["stiff_branch_check"] = False  # the map measures the raw scheme
    return s


def is_unstable(result: RockingResult) -> bool:
    """True if ``result`` failed with an instability reason."""
    return result.status == "failed" and result.reason.startswith("unstable")


def peak_error(result: RockingResult, reference: RockingResult) -> float:
    """``|theta_max - theta_max,ref| / alpha`` (-); 0 when both overturned (only the verdict counts)
    and NaN when either run failed or exactly one overturned (then the verdict is wrong anyway)."""
    if not (result.ok and reference.ok):
        return math.nan
    if result.overturned and reference.overturned:
        return 0.0
    if result.overturned != reference.overturned:
        return math.nan
    return abs(result.theta_max - reference.theta_max) / reference.alpha


@dataclass(frozen=True)
class Cell:
    """One map cell: a method and a time step on one block, over the block's pulses.

    Parameters
    ----------
    block : str
        Block name.
    method : str
        One of :data:`METHODS` (or ``"default"`` for ``OpenSeesSettings()``).
    dt : float
        Time step (s).
    cls : str
        One of :data:`CLASSES`.
    max_error : float
        Largest ``|theta_max - theta_max,ref| / alpha`` over the pulses where it is defined (-);
        NaN if none.
    n_wrong_verdicts : int
        Ok runs whose verdict differs from the reference.
    n_failed : int
        Failed runs (unstable ones included).
    reasons : str
        The failure reasons, ``" | "``-joined (shortened).
    wall_time_s : float
        Solver wall time summed over the pulses (s).
    """

    block: str
    method: str
    dt: float
    cls: str
    max_error: float
    n_wrong_verdicts: int
    n_failed: int
    reasons: str
    wall_time_s: float


def classify(
    block: Block,
    method: str,
    dt: float,
    results: list[RockingResult],
    references: list[RockingResult],
    tolerance: float = ACCURACY_TOLERANCE,
) -> Cell:
    """Classify one cell from its runs and the matching references (see the module docstring)."""
    if len(results) != len(references):
        raise InputError(f"results and references must match one to one, got {len(results)} and {len(references)}")
    errors = [peak_error(r, ref) for r, ref in zip(results, references)]
    finite = [e for e in errors if math.isfinite(e)]
    max_error = max(finite) if finite else math.nan
    failed = [r for r in results if not r.ok]
    n_wrong = sum(1 for r, ref in zip(results, references) if r.ok and r.verdict != ref.verdict)
    if any(is_unstable(r) for r in results):
        cls = "unstable"
    elif failed:
        cls = "failed"
    elif n_wrong or (finite and max_error > tolerance):
        cls = "converged_but_wrong"
    else:
        cls = "accurate"
    reasons = " | ".join(r.reason.splitlines()[0][:120] for r in failed)
    return Cell(block.name, method, float(dt), cls, float(max_error), int(n_wrong), len(failed), reasons,
                float(sum(r.wall_time_s for r in results)))


def references(block: Block) -> list[RockingResult]:
    """Converged references on the map's pulses: the scipy SDOF solver at its default tolerances."""
    refs = []
    for label, pulse in map_pulses(block):
        ref = simulate(block, pulse, solver="sdof", record=False)
        if not ref.ok:
            raise RuntimeError(f"sdof reference failed on {block.name} {label}: {ref.reason}")
        refs.append(ref)
    return refs


def run_cell(block: Block, method: str, dt: float, refs: list[RockingResult],
             overrides: dict[str, Any] | None = None) -> Cell:
    """Run one cell (all pulses of ``block``) and classify it. ``overrides`` replaces
    :func:`method_settings` (e.g. ``{}`` for the solver's defaults)."""
    s = method_settings(method, dt) if overrides is None else overrides
    results = [osr.solve(block, pulse, **s) for _, pulse in map_pulses(block)]
    return classify(block, method, dt, results, refs)


def measured_critical_step(block: Block, rtol: float = BISECTION_RTOL) -> dict[str, float]:
    """Measure the central-difference critical step of ``block`` by bisection.

    The run is :data:`CRITICAL_STEP_PULSE` (on the stiff branch throughout) with
    ``integrator="central_difference", explicit_step_check=False``; a step *passes* when the run
    is ok with the reference verdict ``no_uplift``. Two boundaries are bisected on
    ``[0.5, 2] dt_cr``:

    * ``dt_usable``: the largest passing step (what a user gets). Just below ``dt_cr`` the stable
      scheme oscillates near the Nyquist frequency, and the solver's sawtooth test may call it
      unstable, so this boundary is a lower bound of the true one;
    * ``dt_onset``: the smallest step whose run is unstable: it fails within :data:`ONSET_STEPS`
      steps, or ``theta`` leaves the stiff branch at all (ok or failed), which the exact answer
      (``theta_max = theta_e / 2``) never does: the true stability limit ``omega_e dt = 2``.

    Returns
    -------
    dict
        ``dt_formula``, ``dt_usable``, ``dt_onset`` (s) and their ratios to the formula (-).
    """
    dt_cr = osr.critical_time_step(block, osr.OpenSeesSettings().model)
    pulse = OneSinePulse.from_ratios(block, *CRITICAL_STEP_PULSE)

    def run(dt: float) -> RockingResult:
        return osr.solve(block, pulse, integrator="central_difference", step=dt, adaptive=False,
                         explicit_step_check=False, stiff_branch_check=False, uplift_check=False,
                         min_step=min(osr.OpenSeesSettings().min_step, dt))

    def passes(dt: float) -> bool:
        r = run(dt)
        return r.ok and r.verdict == "no_uplift"

    theta_e = osr.OpenSeesSettings().model.theta_e(block)

    def broken(dt: float) -> bool:
        # unstable: a blow-up within ONSET_STEPS steps, or theta off the stiff branch at all (the
        # exact answer stays below theta_e / 2 there; ok or failed alike); a *late* failure with
        # theta still on the branch is the sawtooth test on a stable near-Nyquist oscillation
        r = run(dt)
        early = (not r.ok) and r.n_steps <= ONSET_STEPS
        return early or (math.isfinite(r.theta_max) and r.theta_max > theta_e) or not math.isfinite(r.theta_max)

    def bisect(pred_low_true: bool, pred) -> float:
        # invariant: pred(lo) == pred_low_true, pred(hi) != pred_low_true
        lo, hi = 0.5 * dt_cr, 2.0 * dt_cr  # midpoints never land on dt_cr itself
        if pred(lo) != pred_low_true or pred(hi) == pred_low_true:
            return math.nan
        while hi - lo > rtol * dt_cr:
            mid = 0.5 * (lo + hi)
            if pred(mid) == pred_low_true:
                lo = mid
            else:
                hi = mid
        return lo if pred_low_true else hi

    dt_usable = bisect(True, passes)
    dt_onset = bisect(False, broken)
    return {"dt_formula": dt_cr, "dt_usable": dt_usable, "dt_onset": dt_onset,
            "usable_ratio": dt_usable / dt_cr, "onset_ratio": dt_onset / dt_cr}


def wrong_above_critical(cells: list[Cell], dt_cr: dict[str, float]) -> list[Cell]:
    """Central-difference cells (``explicit_step_check=False``) above the formula's ``dt_cr`` that
    came back ``converged_but_wrong``: a plausible but wrong answer from an unstable scheme."""
    return [c for c in cells if c.method == "central_difference" and c.dt > dt_cr[c.block]
            and c.cls == "converged_but_wrong"]


def checked_refusals(block: Block, dts: tuple[float, ...]) -> list[bool]:
    """With the default ``explicit_step_check``, is every central-difference run with
    ``dt >= dt_cr`` refused as failed/unstable? One bool per such ``dt`` and map pulse."""
    dt_cr = osr.critical_time_step(block, osr.OpenSeesSettings().model)
    out = []
    for dt in (d for d in dts if d >= dt_cr):
        for _, pulse in map_pulses(block):
            r = osr.solve(block, pulse, integrator="central_difference", step=dt, adaptive=False,
                          min_step=min(osr.OpenSeesSettings().min_step, dt))
            out.append(is_unstable(r) and r.verdict == "failed")
    return out


def plot(cells: list[Cell], dt_cr: dict[str, float], default: dict[str, Cell], path: Path) -> None:
    """One panel per block: methods x time steps, coloured by class, error in % of alpha."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch, Rectangle

    colours = {"accurate": "#4daf4a", "converged_but_wrong": "#ff7f00", "failed": "#999999",
               "unstable": "#e41a1c"}
    blocks = list(dict.fromkeys(c.block for c in cells))
    methods = list(dict.fromkeys(c.method for c in cells))
    dts = sorted({c.dt for c in cells}, reverse=True)
    fig, axes = plt.subplots(len(blocks), 1, figsize=(1.0 * len(dts) + 3.0, 1.9 * len(blocks) + 1.0),
                             squeeze=False)
    cmap = ListedColormap([colours[k] for k in CLASSES])
    for ax, name in zip(axes[:, 0], blocks):
        grid = np.full((len(methods), len(dts)), np.nan)
        for c in cells:
            if c.block != name:
                continue
            i, j = methods.index(c.method), dts.index(c.dt)
            grid[i, j] = CLASSES.index(c.cls)
            txt = "" if not math.isfinite(c.max_error) else f"{100 * c.max_error:.2g}"
            if c.n_wrong_verdicts:
                txt += f"\n{c.n_wrong_verdicts}v"
            ax.text(j, i, txt, ha="center", va="center", fontsize=6.5)
        ax.imshow(grid, cmap=cmap, vmin=-0.5, vmax=len(CLASSES) - 0.5, aspect="auto")
        ax.set_yticks(range(len(methods)), methods, fontsize=8)
        ax.set_xticks(range(len(dts)), [f"{d:g}" for d in dts], fontsize=8)
        # the formula's critical step, between the columns that bracket it
        x = np.interp(math.log(dt_cr[name]), np.log(dts[::-1]), np.arange(len(dts))[::-1])
        ax.axvline(x, color="k", ls="--", lw=1)
        ax.text(x, len(methods) - 0.5, " dt_cr", fontsize=7, va="top")
        d = default.get(name)
        if d is not None and d.dt in dts and "newmark" in methods:
            row = methods.index("adaptive" if d.method == "default/adaptive" else "newmark")
            ax.add_patch(Rectangle((dts.index(d.dt) - 0.5, row - 0.5), 1, 1, fill=False, lw=2.2, ec="k"))
        ax.set_title(f"{name}  (dt_cr = {dt_cr[name]:.3g} s)", fontsize=9)
    axes[-1, 0].set_xlabel("time step dt (s)  [numbers: max |d theta_max| / alpha in %; 'v': wrong verdicts]")
    fig.legend(handles=[Patch(color=colours[k], label=k) for k in CLASSES] +
               [Patch(fill=False, ec="k", lw=2, label="OpenSeesSettings() default")],
               loc="upper center", ncol=5, fontsize=8)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def run(out_dir: Path, quick: bool = False) -> dict:
    """Build the map, measure the explicit critical steps, write CSVs and the PNG.

    ``quick``: first block only (bookcase), :data:`QUICK_DTS`; about 30 s.
    """
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    blocks = map_blocks()
    if quick:
        blocks = blocks[:1]
    dts = QUICK_DTS if quick else DTS
    defaults = osr.OpenSeesSettings()
    cells: list[Cell] = []
    default_cells: dict[str, Cell] = {}
    dt_cr: dict[str, float] = {}
    crit_rows = []
    refusals: list[bool] = []
    for b in blocks:
        refs = references(b)
        for method in METHODS:
            for dt in dts:
                cells.append(run_cell(b, method, dt, refs))
        label = "default/adaptive" if defaults.adaptive else "default"
        default_cells[b.name] = run_cell(b, label, defaults.step, refs, overrides={})
        refusals.extend(checked_refusals(b, dts))
        crit = measured_critical_step(b)
        dt_cr[b.name] = crit["dt_formula"]
        crit_rows.append({"block": b.name, **crit})
    fields = ["block", "method", "dt", "class", "max_error", "n_wrong_verdicts", "n_failed", "reasons",
              "wall_time_s"]
    with open(out_dir / "stability_map.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(fields)
        for c in [*cells, *default_cells.values()]:
            w.writerow([c.block, c.method, repr(float(c.dt)), c.cls, repr(float(c.max_error)), c.n_wrong_verdicts,
                        c.n_failed, c.reasons, repr(float(c.wall_time_s))])
    with open(out_dir / "critical_step.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(crit_rows[0]))
        w.writeheader()
        for r in crit_rows:
            w.writerow({k: (repr(float(v)) if isinstance(v, float) else v) for k, v in r.items()})
    plot(cells, dt_cr, default_cells, out_dir / "stability_map.png")
    wrong_explicit = wrong_above_critical(cells, dt_cr)
    defaults_ok = all(c.cls == "accurate" for c in default_cells.values())
    usable = [r["usable_ratio"] for r in crit_rows]
    onset = [r["onset_ratio"] for r in crit_rows]
    crit_ok = all(math.isfinite(x) and abs(x - 1.0) <= 0.03 for x in usable + onset)
    counts = {k: sum(1 for c in cells if c.cls == k) for k in CLASSES}
    return {
        "n_cells": len(cells), **{f"n_{k}": v for k, v in counts.items()},
        "defaults": f"{defaults.integrator} step={defaults.step:g} adaptive={defaults.adaptive}",
        "defaults_accurate_all_blocks": defaults_ok,
        "defaults_max_error": max(c.max_error for c in default_cells.values()),
        "dt_cr_usable_ratio_min": min(usable), "dt_cr_usable_ratio_max": max(usable),
        "dt_cr_onset_ratio_min": min(onset), "dt_cr_onset_ratio_max": max(onset),
        "checked_explicit_refused_above_dt_cr": all(refusals),
        # a finding, not a gate: the unchecked explicit mode is a diagnostic (see README)
        "n_unchecked_explicit_wrong_above_dt_cr": len(wrong_explicit),
        "unchecked_explicit_wrong_above_dt_cr": "; ".join(f"{c.block} dt={c.dt:g}" for c in wrong_explicit),
        "wall_time_s": time.perf_counter() - t0,
        "passed": bool(defaults_ok and crit_ok and all(refusals)),
    }
