"""Re-run validation case 4 (lumped mass of Fig. 2b vs the rotational form) into this folder."""

import sys
from pathlib import Path

from opsrock.validation.lumped_mass import run

if __name__ == "__main__":
    metrics = run(Path(__file__).resolve().parent, quick="--quick" in sys.argv)
    print(metrics)
    sys.exit(0 if metrics["passed"] else 1)
