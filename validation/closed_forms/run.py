"""Re-run the closed-form validation case into this folder: ``python validation/closed_forms/run.py``."""

from pathlib import Path

from opsrock.validation.closed_forms import run

if __name__ == "__main__":
    result = run(Path(__file__).resolve().parent)
    for row in result["rows"]:
        print(f"{row['solver']:12s} {row['check']:30s} error {row['error']:<12.3g} tol {row['tolerance']:<8.3g} "
              f"{'ok' if row['passed'] else 'FAIL'}")
    print("passed" if result["passed"] else "FAILED", f"({result['wall_time_s']:.1f} s)")
