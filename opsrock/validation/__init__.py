"""Validation cases: each a module here with ``run(out_dir, quick=False) -> dict`` and a folder
``validation/<case>/`` holding its README (the relation and tolerance), ``run.py`` and small outputs.

``opsrock validate`` regenerates every case into its folder (or ``--out DIR``).
"""

from __future__ import annotations

import argparse
import importlib
import json
import sys
import time
from pathlib import Path

#: The cases, in the order the evidence builds up (docs/modelling.md section 5).
CASES: tuple[str, ...] = (
    "closed_forms",      # 1. closed forms, all solvers
    "sdof_agreement",    # 2. OpenSees against the scipy SDOF solver (same model)
    "model_form",        # 3. SDOF model against the rigid-body equation as delta, theta_e shrink
    "lumped_mass",       # 4. the lumped-mass form of Figure 2b against the rotational form
    "speed_accuracy",    # 5. wall time against error, Pareto front
    "stability_map",     # 6. time step x method: accurate / wrong / failed / unstable
    "published_thresholds",  # 7. the overturning thresholds of the rocking literature
    "records",           # 8. the four solvers on FEMA P695 records, ground and roof
    "sdof_records",      # 9. the SDOF model's two implementations and the rigid body on 207 broadband records
)

#: Repository folder that holds the case folders (README, run.py, outputs).
VALIDATION_DIR = Path(__file__).resolve().parents[2] / "validation"


def run_case(name: str, out_dir: Path | None = None, quick: bool = False) -> dict:
    """Run one case and return its metrics (with ``"passed"``); outputs go to ``out_dir``."""
    if name not in CASES:
        raise ValueError(f"case must be one of {', '.join(CASES)}; got {name!r}")
    module = importlib.import_module(f"opsrock.validation.{name}")
    out = Path(out_dir) if out_dir is not None else VALIDATION_DIR / name
    out.mkdir(parents=True, exist_ok=True)
    return module.run(out, quick=quick)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of ``opsrock validate``."""
    parser.add_argument("--case", action="append", choices=CASES, help="run only this case (repeatable)")
    parser.add_argument("--quick", action="store_true", help="the fast subset (what `make test` runs)")
    parser.add_argument("--out", help="write case folders under DIR instead of validation/")


def run_command(args: argparse.Namespace) -> int:
    """Run ``opsrock validate``: every case (or ``--case``), a summary line each; exit 1 if any fails."""
    names = args.case or list(CASES)
    failed = []
    for name in names:
        t0 = time.perf_counter()
        out = Path(args.out) / name if args.out else None
        metrics = run_case(name, out, quick=args.quick)
        status = "passed" if metrics.get("passed") else "FAILED"
        if not metrics.get("passed"):
            failed.append(name)
        brief = {k: v for k, v in metrics.items() if isinstance(v, (int, float, str, bool)) and k != "passed"}
        print(f"{name}: {status} in {time.perf_counter() - t0:.1f} s  {json.dumps(brief, default=str)[:400]}")
    if failed:
        print(f"opsrock validate: {len(failed)} case(s) failed: {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0
