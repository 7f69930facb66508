"""Re-run (or complete) validation case 9 (the SDOF model on 207 broadband records) into this folder."""

import sys
from pathlib import Path

from opsrock.validation.sdof_records import run

if __name__ == "__main__":
    metrics = run(Path(__file__).resolve().parent, quick="--quick" in sys.argv)
    print(metrics)
    sys.exit(0 if metrics["passed"] else 1)
