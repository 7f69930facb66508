"""Re-run validation case ``experiments`` (measured free rocking of limestone blocks) into this folder:
``python validation/experiments/run.py`` (``--quick`` for the fast form)."""

import sys
from pathlib import Path

from opsrock.validation.experiments import run

if __name__ == "__main__":
    metrics = run(Path(__file__).resolve().parent, quick="--quick" in sys.argv)
    for key, value in metrics.items():
        print(f"{key}: {value}")
    sys.exit(0 if metrics["passed"] else 1)
