"""Cost of each solver on real floor motions: record-seconds simulated per CPU-second.

Same run, same cases for every solver (the machines are shared: compare ratios, not seconds):
FEMA P695 far-field components at the roof of a 3-storey shear building (T_1 = 0.45 s, 5 %),
the 0.5 x 1.15 m block, scaled to PFA / (g tan alpha) = 2.5. CPU time is the process time of
the solve (time.process_time), so other load on the machine does not count. The agreement with
the reference rigid-body solver (`housner`) is printed beside the speed, and each solver's step
count per record (``n_steps``: machine-independent, so a change of cost per record-second that is not
the machine shows there). `sdof` gets a budget per case (it is slow on records; the SDOF-on-records
issue is about that).

    opsrock bench --only records [--quick]   # 4 records (quick: 1)
"""

from __future__ import annotations

import math
import time

SOLVERS = ("housner_fast", "housner", "opensees", "sdof")
BUDGET_S = 120.0


def run(quick: bool = False) -> dict:
    from opsrock.block import Block
    from opsrock.campaign.timeout import CaseTimeout, time_limit
    from opsrock.excitations import library
    from opsrock.excitations.building import ShearBuilding, floor_motion
    from opsrock.solvers import simulate

    block = Block(0.5, 1.15)
    building = ShearBuilding("b3", 0.45, 3)
    motions = [floor_motion(library.load(e.reference), building) for e in library.entries("far-field")[: 1 if quick else 4]]
    motions = [m.scaled(2.5 * block.uplift_acceleration / m.pfa) for m in motions]
    simulate(block, motions[0], "housner_fast")  # load the compiled kernel before timing
    out: dict = {"block": "0.5 x 1.15 m", "n_records": len(motions),
                 "record_seconds": sum(m.duration for m in motions)}
    ref = {}
    for solver in SOLVERS:
        cpu, answers, failed, steps = 0.0, [], 0, []
        for k, m in enumerate(motions):
            t0 = time.process_time()
            try:
                with time_limit(BUDGET_S):
                    r = simulate(block, m, solver)
                answers.append((r.verdict, r.theta_max_over_alpha))
                steps.append(r.n_steps)
            except CaseTimeout:
                failed += 1
                answers.append(("failed", math.nan))
                steps.append(None)
            cpu += time.process_time() - t0
        if solver == "housner":
            ref = dict(enumerate(answers))
        out[solver] = {"cpu_s": cpu, "record_seconds_per_cpu_second": out["record_seconds"] / cpu if cpu else math.inf,
                       "failed": failed, "answers": answers, "n_steps": steps}
    for solver in SOLVERS:
        ans = out[solver]["answers"]
        out[solver]["verdicts_as_housner"] = sum(a[0] == ref[i][0] for i, a in enumerate(ans))
        d = [abs(a[1] - ref[i][1]) for i, a in enumerate(ans) if a[0] == ref[i][0] == "safe"]
        out[solver]["max_dtheta_over_alpha_on_safe"] = max(d) if d else math.nan
    return out
