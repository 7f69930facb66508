"""``opsrock validate``: the validation cases, a summary line each."""

from __future__ import annotations

import argparse
import sys

from opsrock._files import output_dir
from opsrock.cli import EXIT_FAILED
from opsrock.validation import CASES, run_cases


def validate(args: argparse.Namespace) -> int:
    """``opsrock validate``: :func:`opsrock.validation.run_cases`, a summary line each."""
    output_dir("--out", args.out)
    names = args.case or list(CASES)
    failed = run_cases(names, args.out, quick=args.quick, echo=print)
    if failed:
        print(f"opsrock validate: {len(failed)} case(s) failed: {', '.join(failed)}", file=sys.stderr)
        return EXIT_FAILED
    return 0


__all__ = ["validate"]
