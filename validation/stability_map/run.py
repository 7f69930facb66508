"""Re-run validation case 6 (time step x method stability map, explicit critical step) into this folder."""

import sys
from pathlib import Path

from opsrock.validation.stability_map import run

if __name__ == "__main__":
    metrics = run(Path(__file__).resolve().parent, quick="--quick" in sys.argv)
    print(metrics)
    sys.exit(0 if metrics["passed"] else 1)
