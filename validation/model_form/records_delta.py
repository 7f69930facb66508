"""The damper band delta on records: the SDOF model (scipy `sdof`, default damper law) against the rigid
body (`housner_fast`) on the broadband records of validation case 9, for several delta.

For each delta: verdict agreement with the rigid body, and percentiles of |theta_max(SDOF) -
theta_max(rigid)| / alpha on cases safe in both. Cases run in a process pool; output one CSV row per
(case, delta) and a summary printed per delta.

    python validation/model_form/records_delta.py OUT_CSV [--seeds N]
"""

import argparse
import csv
import sys
from concurrent.futures import ProcessPoolExecutor

import numpy as np

DELTAS = (0.002, 0.005, 0.01, 0.02, 0.05)


def one(case):
    from opsrock.solvers import simulate
    from opsrock.validation.sdof_records import case_motion

    seed, (w, h), level = case
    b, rec = case_motion(case)
    rigid = simulate(b, rec, "housner_fast")
    rows = []
    for d in DELTAS:
        r = simulate(b, rec, "sdof", delta=d)
        rows.append({"seed": seed, "width": w, "height": h, "level": level, "delta": d,
                     "rigid_theta": rigid.theta_max_over_alpha, "rigid_verdict": rigid.verdict,
                     "sdof_theta": r.theta_max_over_alpha, "sdof_verdict": r.verdict})
    return rows


def main(argv):
    from opsrock.validation.sdof_records import BLOCKS, LEVELS

    p = argparse.ArgumentParser()
    p.add_argument("out")
    p.add_argument("--seeds", type=int, default=6)
    args = p.parse_args(argv)
    cases = [(s, b, lv) for s in range(1, args.seeds + 1) for b in BLOCKS for lv in LEVELS]
    rows = []
    with ProcessPoolExecutor(2) as pool:
        for rs in pool.map(one, cases):
            rows += rs
    with open(args.out, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]), lineterminator="\n")
        w.writeheader()
        w.writerows({k: repr(float(v)) if isinstance(v, float) else v for k, v in r.items()} for r in rows)
    for d in DELTAS:
        sel = [r for r in rows if r["delta"] == d]
        agree = np.mean([r["sdof_verdict"] == r["rigid_verdict"] for r in sel])
        safe = [abs(r["sdof_theta"] - r["rigid_theta"]) for r in sel if r["sdof_verdict"] == r["rigid_verdict"] == "safe"]
        print(f"delta {d}: {len(sel)} cases, verdicts {agree:.3f}, safe-both {len(safe)}: median "
              f"{np.median(safe):.4f} p90 {np.percentile(safe, 90):.4f} p95 {np.percentile(safe, 95):.4f} alpha")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
