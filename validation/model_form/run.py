"""Re-run the model-form study into this folder: ``python validation/model_form/run.py [--quick]``."""

import sys
from pathlib import Path

from opsrock.validation.model_form import run

if __name__ == "__main__":
    result = run(Path(__file__).resolve().parent, quick="--quick" in sys.argv)
    for row in result["rows"]:
        print(f"{row['study']:8s} lever={row['lever']:8s} delta={row['delta']:<6g} theta_e={row['theta_e_ratio']:<6g} "
              f"median={row['median_abs_err']:.4f} p95={row['p95_abs_err']:.4f} "
              f"band={row['band_error']:.4f} agree={row['verdict_agreement']:.3f} steps={row['mean_steps']:.0f}")
    print("recommended delta:", result["recommended_delta"], "passed" if result["passed"] else "FAILED",
          f"({result['wall_time_s']:.0f} s)")
