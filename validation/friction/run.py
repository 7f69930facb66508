"""Re-run validation case ``friction`` (the rigid block with friction and vertical motion) into this
folder: ``python validation/friction/run.py`` (``--quick`` for the fast form)."""

import sys
from pathlib import Path

from opsrock.validation.friction import run

if __name__ == "__main__":
    metrics = run(Path(__file__).resolve().parent, quick="--quick" in sys.argv)
    for key, value in metrics.items():
        print(f"{key}: {value}")
    sys.exit(0 if metrics["passed"] else 1)
