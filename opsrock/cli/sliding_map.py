"""``opsrock sliding-map``: where no-slip rocking holds, the model-form map."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from opsrock._files import output_dir
from opsrock.analysis.sliding_map import QUICK, SlidingMapDesign, write_map


def sliding_map(args: argparse.Namespace) -> int:
    """``opsrock sliding-map``: :func:`opsrock.analysis.sliding_map.write_map`, interrupted and resumed as a
    campaign."""
    output_dir("--out", args.out)
    summary = write_map(QUICK if args.quick else SlidingMapDesign(), args.out, workers=args.workers,
                        progress=not args.no_progress)
    print(json.dumps(summary))
    print(f"map: {Path(args.out) / 'sliding_map.csv'}, {Path(args.out) / 'sliding_map.png'}")
    return 0


__all__ = ["sliding_map"]
