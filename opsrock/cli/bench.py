"""``opsrock bench``: benchmarks that measure ratios in one run."""

from __future__ import annotations

import argparse

from opsrock._files import output_file
from opsrock.bench import run_benchmarks


def bench(args: argparse.Namespace) -> int:
    """``opsrock bench``: :func:`opsrock.bench.run_benchmarks`."""
    if args.out is not None:
        output_file("--out", args.out, ".json")
    run_benchmarks(args.only, quick=args.quick, out=args.out, echo=print)
    return 0


__all__ = ["bench"]
