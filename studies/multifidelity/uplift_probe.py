"""Near the uplift threshold: where do the rigid body and the OpenSees SDOF model give different verdicts?

    .venv/bin/python studies/multifidelity/uplift_probe.py [--records N]

The 44 roof motions of ``fema-far-field-ida-b3`` (the first ``N``, default all) x its four blocks, each
scaled to PFA / (g tan alpha) = 0.9, 0.98, 0.995, 1.005, 1.02, 1.05, 1.1, solved with ``housner_fast``
and ``opensees`` (defaults). Writes ``uplift_probe.csv`` here (one row per case) and prints the verdict
pairs and, for each pair that differs, the largest rigid ``theta_max / alpha``: the evidence behind
``uplift_q`` of :mod:`opsrock.campaign.multifidelity` (``UPLIFT_SAFETY`` x the SDOF model's rocking
threshold ``ROCKED_THETA_E_MULTIPLE theta_e = 1e-5 alpha``).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pandas as pd

HERE = Path(__file__).resolve().parent
RATIOS = (0.9, 0.98, 0.995, 1.005, 1.02, 1.05, 1.1)


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--records", type=int, default=None, help="first N roof motions only")
    a = p.parse_args(argv)
    from opsrock.campaign.motions import assemble_motions, compute_motions
    from opsrock.campaign.scene import load_scene
    from opsrock.solvers import simulate

    scene = load_scene("fema-far-field-ida-b3")
    items = scene.records.motion_items()[: a.records]
    motions = assemble_motions(items, compute_motions(items))
    rows = []
    for spec in scene.blocks:
        b = spec.block
        for (record, floor), m in motions.items():
            for ratio in RATIOS:
                rec = m.record.scaled(ratio * b.uplift_acceleration / m.measures.pfa)
                rigid, sdof = simulate(b, rec, solver="housner_fast"), simulate(b, rec, solver="opensees")
                rows.append({"block": spec.name, "record": record, "floor": floor, "pfa_ratio": ratio,
                             "rigid_verdict": rigid.verdict, "rigid_q": rigid.theta_max_over_alpha,
                             "opensees_verdict": sdof.verdict, "opensees_q": sdof.theta_max_over_alpha})
    df = pd.DataFrame(rows)
    df.to_csv(HERE / "uplift_probe.csv", index=False)
    print(pd.crosstab([df.pfa_ratio, df.rigid_verdict], df.opensees_verdict))
    differ = df[df.rigid_verdict != df.opensees_verdict]
    print(f"{len(differ)} of {len(df)} differ; largest rigid theta_max/alpha among them: {differ.rigid_q.max():.3g}; "
          f"smallest rigid theta_max/alpha of a safe/safe pair: {df[df.opensees_verdict == 'safe'].rigid_q.min():.3g}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
