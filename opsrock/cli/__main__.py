"""``python -m opsrock.cli ...``: the same as the ``opsrock`` console script."""

import sys

from opsrock.cli import main

sys.exit(main())
