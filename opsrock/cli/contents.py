"""``opsrock contents``: FEMA P-58's unanchored contents in one building, beside FEMA's fragilities."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

from opsrock._files import output_dir
from opsrock.cli import EXIT_INTERRUPTED
from opsrock.cli.common import named_options
from opsrock.contents import SWEEP_BUILDINGS, ContentsDesign, run_contents_study

#: Fields of :class:`opsrock.contents.ContentsDesign` (``records``: its ``names``, as the design's check
#: calls them) -> the option that gives them.
CONTENTS_OPTIONS: dict[str, str] = {
    "period": "--period", "storeys": "--storeys", "damping": "--damping", "floors": "--floors",
    "record_set": "--record-set", "records": "--records", "items": "--items", "variants": "--variants",
    "friction": "--friction",
}


def _comma_list(text: str | None) -> tuple[str, ...]:
    """``"a,b"`` -> ``("a", "b")`` (an empty item stays, for the library to refuse by name); None -> ()."""
    return () if text is None else tuple(part.strip() for part in text.split(","))


def contents(args: argparse.Namespace) -> int:
    """``opsrock contents``: :func:`opsrock.contents.run_contents_study` for one building."""
    output_dir("--out", args.out)
    if args.store is not None:
        output_dir("--store", args.store)
    floors = tuple(int(f) if f.isdigit() else f for f in _comma_list(args.floors))
    try:
        with named_options(CONTENTS_OPTIONS):
            design = ContentsDesign(period=args.period, storeys=args.storeys, damping=args.damping, floors=floors,
                                    record_set=args.record_set, names=_comma_list(args.records),
                                    items=_comma_list(args.items), variants=_comma_list(args.variants),
                                    friction=args.friction, sweep=() if args.no_sweep else SWEEP_BUILDINGS,
                                    n_boot=args.n_boot, seed=args.seed)
            res = run_contents_study(design, args.out, quick=args.quick, workers=args.workers,
                                     progress=not args.no_progress, force=args.force, store_dir=args.store)
    except KeyboardInterrupt:
        print(f"opsrock contents: interrupted; finished cases are stored in {args.store or Path(args.out) / 'campaigns'}: "
              "run the same command again to compute only the missing ones", file=sys.stderr)
        return EXIT_INTERRUPTED
    t, (lo, hi) = res.summary.timings, res.summary.ratio_range or (math.nan, math.nan)
    print(f"opsrock contents: {res.summary.n_cases} cases ({res.summary.n_failed} failed) in {t['total_s']:.1f} s; "
          f"opsrock's no-slip median PFV over FEMA P-58's: {lo:.2f} to {hi:.2f}; see {res.report}")
    return 0


__all__ = ["contents"]
