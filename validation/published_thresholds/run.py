"""Re-run validation case 7 (the published overturning thresholds) into this folder."""

import sys
from pathlib import Path

from opsrock.validation.published_thresholds import run

if __name__ == "__main__":
    metrics = run(Path(__file__).resolve().parent, quick="--quick" in sys.argv)
    print(metrics)
    sys.exit(0 if metrics["passed"] else 1)
