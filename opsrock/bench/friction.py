"""Cost of the block with friction on real floor motions: record-seconds simulated per CPU-second.

Same run, same motions as :mod:`opsrock.bench.records` (FEMA P695 far-field components at the roof of a
3-storey shear building, T_1 = 0.45 s, 5 %; the 0.5 x 1.15 m block at PFA / (g tan alpha) = 2.5), for
the event-driven ``friction`` solver without friction (the no-slip block: the same answer as
``housner_fast``, which is timed beside it), with friction 0.4 (below b/h = 0.43: it slides) and 0.6 (it rocks), and with friction 0.4 under the
synthetic vertical motion, and for its reference ``moreau_jean`` (Housner's impact, e = e_R). CPU time
is the process time of the solves; ``friction`` also follows the block after the record until it is at
rest, which ``housner_fast`` does not need. Target of the friction solver: at least 1,000
record-seconds per CPU-second.

    opsrock bench --only friction [--quick]   # 4 records (quick: 1)
"""

from __future__ import annotations

import math
import time

#: The variants timed: name -> (solver, friction, vertical motion).
VARIANTS: dict[str, tuple[str, float | None, bool]] = {
    "housner_fast": ("housner_fast", None, False),
    "friction_no_slip": ("friction", None, False),
    "friction_mu0.4": ("friction", 0.4, False),
    "friction_mu0.6": ("friction", 0.6, False),
    "friction_mu0.4_vertical": ("friction", 0.4, True),
    "moreau_jean_mu0.4": ("moreau_jean", 0.4, False),
}


def _motions(quick: bool):
    from opsrock.block import Block
    from opsrock.excitations import library
    from opsrock.excitations.building import ShearBuilding, floor_motion
    from opsrock.excitations.vertical import synthetic_vertical

    block = Block(0.5, 1.15)
    building = ShearBuilding("b3", 0.45, 3)
    out = []
    for e in library.entries("far-field")[: 1 if quick else 4]:
        ground = synthetic_vertical(e.reference)
        roof = floor_motion(ground, building)  # moves vertically with the ground
        out.append(roof.scaled(2.5 * block.uplift_acceleration / roof.pfa))
    return out


def run(quick: bool = False) -> dict:
    from opsrock.block import Block
    from opsrock.solvers import simulate

    motions = _motions(quick)
    horizontal = [m.with_vertical(None) for m in motions]
    out: dict = {"block": "0.5 x 1.15 m", "n_records": len(motions), "record_seconds": sum(m.duration for m in motions)}
    for name, (solver, mu, vertical) in VARIANTS.items():
        block = Block(0.5, 1.15, friction=mu, restitution_factor=1.0 if solver == "moreau_jean" else 0.95)
        recs = motions if vertical else horizontal
        simulate(block, recs[0], solver)  # load the compiled kernel before timing
        cpu, answers = 0.0, []
        for m in recs:
            t0 = time.process_time()
            r = simulate(block, m, solver)
            cpu += time.process_time() - t0
            answers.append((r.response if r.contact is not None else r.verdict, r.theta_max_over_alpha))
        out[name] = {"cpu_s": cpu, "record_seconds_per_cpu_second": out["record_seconds"] / cpu if cpu else math.inf,
                     "answers": answers}
    ref = out["housner_fast"]["answers"]
    same = [a for a, b in zip(out["friction_no_slip"]["answers"], ref) if a[1] == a[1] and b[1] == b[1]]
    out["friction_no_slip"]["max_dtheta_over_alpha_vs_housner_fast"] = max(
        (abs(a[1] - b[1]) for a, b in zip(out["friction_no_slip"]["answers"], ref) if a[0] != "overturned"),
        default=math.nan) if same else math.nan
    return out
