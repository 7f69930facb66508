"""``opsrock directionality``: contents under both horizontal floor components in three dimensions, beside the
planar analysis and pelicun's non-directional factor (:func:`opsrock.analysis.directionality.run_directionality_study`)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from opsrock._files import output_dir
from opsrock.analysis.directionality import DirectionalityDesign, run_directionality_study
from opsrock.cli import EXIT_INTERRUPTED


def directionality(args: argparse.Namespace) -> int:
    """``opsrock directionality``: the study, resumable; prints its headline."""
    output_dir("--out", args.out)
    if args.store is not None:
        output_dir("--store", args.store)
    try:
        res = run_directionality_study(DirectionalityDesign(), args.out, workers=args.workers,
                                       progress=not args.no_progress, quick_run=args.quick, force=args.force,
                                       store_dir=args.store)
    except KeyboardInterrupt:
        print(f"opsrock directionality: interrupted; finished cases are stored in "
              f"{args.store or Path(args.out) / 'campaigns'}: run the same command again to compute only the missing "
              "ones", file=sys.stderr)
        return EXIT_INTERRUPTED
    h = res.headline
    print(f"opsrock directionality: {h['n_cases']} cases ({h['n_failed']} failed) in {h['wall_time_s']:.1f} s; "
          f"factor on max(PFV_1, PFV_2) implied by 3-D: median {h['factor_implied_median']:.3g} (pelicun: 1.2); "
          f"3-D case cost {h['cost_ratio_3d']:.3g} x planar; see {res.report}")
    return 0


__all__ = ["directionality"]
