"""Re-run validation case 'speed_accuracy' into this folder: ``python validation/speed_accuracy/run.py [--quick]``."""

import json
import sys
from pathlib import Path

from opsrock.validation.speed_accuracy import run

if __name__ == "__main__":
    metrics = run(Path(__file__).resolve().parent, quick="--quick" in sys.argv)
    print(json.dumps(metrics, indent=1, default=str))
    sys.exit(0 if metrics["passed"] else 1)
