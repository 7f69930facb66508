"""Re-run validation case 'sdof_agreement' into this folder: ``python validation/sdof_agreement/run.py [--quick]``."""

import json
import sys
from pathlib import Path

from opsrock.validation.sdof_agreement import run

if __name__ == "__main__":
    metrics = run(Path(__file__).resolve().parent, quick="--quick" in sys.argv)
    print(json.dumps(metrics, indent=1, default=str))
    sys.exit(0 if metrics["passed"] else 1)
