"""Validation cases: each a module here with ``run(out_dir, quick=False) -> dict`` and a folder
``validation/<case>/`` holding its README (the relation and tolerance), ``run.py`` and small outputs.

``opsrock validate`` regenerates every case into ``validation/<case>/`` of the current folder (or
``--out DIR``): run from the checkout, that is the repository's case folders.
"""

from __future__ import annotations

import importlib
import json
import time
from pathlib import Path
from typing import Callable, Sequence

from opsrock.errors import InputError

#: The cases, in the order the evidence builds up (docs/guide/modelling.md section 5).
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
    "experiments",       # 10. measured free rocking of limestone blocks (Colombo et al., CC BY 4.0): restitution and decay
    "friction",          # 11. the block with friction and vertical motion: closed forms, Shenton's diagram, two implementations
)

def run_case(name: str, out_dir: str | Path = "validation", quick: bool = False) -> dict:
    """Run one case into ``out_dir`` (created) and return its metrics (with ``"passed"``).

    Parameters
    ----------
    name : str
        One of :data:`CASES`.
    out_dir : path
        The case's folder: its CSV and PNG outputs go there. Default ``validation`` under the
        current folder (the repository's own case folders when run from the checkout).
    quick : bool
        The fast subset (what ``make test`` runs).
    """
    if name not in CASES:
        raise InputError(f"case must be one of {', '.join(CASES)}; got {name!r}")
    module = importlib.import_module(f"opsrock.validation.{name}")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    return module.run(out, quick=quick)


def run_cases(names: Sequence[str], out_dir: str | Path = "validation", *, quick: bool = False,
              echo: Callable[[str], None] = print) -> list[str]:
    """Run the cases ``names`` into ``out_dir/<case>/``; return the names of those that failed.

    ``echo`` receives one summary line per case: its status, time (s) and scalar metrics.
    """
    failed = []
    for name in names:
        t0 = time.perf_counter()
        metrics = run_case(name, Path(out_dir) / name, quick=quick)
        status = "passed" if metrics.get("passed") else "FAILED"
        if not metrics.get("passed"):
            failed.append(name)
        brief = {k: v for k, v in metrics.items() if isinstance(v, (int, float, str, bool)) and k != "passed"}
        echo(f"{name}: {status} in {time.perf_counter() - t0:.1f} s  {json.dumps(brief, default=str)[:400]}")
    return failed
