"""The fixed choices of validation case ``experiments``: references, resampling, windows, models and
tolerances (``validation/experiments/README.md`` justifies them)."""

from __future__ import annotations

from opsrock.constants import DEFAULT_RESTITUTION_FACTOR

#: The paper's restitution factor ``e / e_R``.
PAPER_FACTOR: float = DEFAULT_RESTITUTION_FACTOR
#: The references the measured ratio is compared with: name -> factor on ``e_R``.
REFERENCES: dict[str, float] = {"e_R": 1.0, "paper": PAPER_FACTOR}

#: Bootstrap resamples (full, quick), seed, and two-sided interval level.
N_BOOT, N_BOOT_QUICK, SEED, LEVEL = 2000, 200, 20250617, 0.95
#: Impact-number windows of the drift regression (impacts 1..n, every trial present to >= 81).
DRIFT_WINDOWS: tuple[int, ...] = (20, 40)
#: Rows of the per-impact table: single impact numbers 1..40, then bins.
IMPACT_ROWS: tuple[tuple[int, int], ...] = tuple((n, n) for n in range(1, 41)) + (
    (1, 10), (11, 20), (21, 40), (41, 80), (81, 10_000))
#: Impact subsets of the per-geometry table: label -> (first, last) impact number.
GROUP_SUBSETS: dict[str, tuple[int, int]] = {"1": (1, 1), "1-10": (1, 10), "all": (1, 10_000)}

#: Release angles of the predicted free rocking, ``theta0 / alpha`` (the first is the primary one).
RELEASE_RATIOS: tuple[float, ...] = (0.5, 0.25)
#: Impacts compared in the decay (plotted, and the RMSE windows of log running product).
DECAY_IMPACTS, DECAY_WINDOWS = 30, (10, 20)
#: A measured median running product needs at least this many trials still rocking.
MIN_TRIALS: int = 3
#: Geometries of the quick form: the stockiest and the most slender.
QUICK_GROUPS: tuple[int, ...] = (1, 12)
#: Predicted models: name -> (solver, factor on e_R or None for "the fitted factor").
MODELS: dict[str, tuple[str, float | None]] = {
    "rigid e_R": ("housner", 1.0), "rigid fitted": ("housner", None), "rigid 0.95 e_R": ("housner", PAPER_FACTOR),
    "sdof": ("sdof", PAPER_FACTOR), "opensees": ("opensees", PAPER_FACTOR), "sdof e_R": ("sdof", 1.0),
}

#: Tolerances of the checks (README, "Checks"): data identities (written to 16 digits); the rigid
#: body's impact is one multiplication (rounding only); the SDOF implementations against the model's
#: closed-form decay over the first 10 impacts: ``sdof`` 10 passages x 1e-4 (ten times case 1's
#: measured energy error per passage), ``opensees`` the 1 % agreement target of case 2.
TOL_DATA, TOL_RIGID = 1e-9, 1e-9
TOL_CLOSED_FORM: dict[str, float] = {"sdof": 1e-3, "opensees": 1e-2}
CLOSED_FORM_IMPACTS: int = 10
