"""``opsrock contents``: FEMA P-58's unanchored contents in one building, beside FEMA's fragilities."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from opsrock._files import output_dir
from opsrock.cli import EXIT_INTERRUPTED
from opsrock.cli.common import named_options
from opsrock.contents import SWEEP_BUILDINGS, ContentsDesign, run_contents_study
from opsrock.errors import UsageError

#: Fields of :class:`opsrock.contents.ContentsDesign` (``records``: its ``names``, as the design's check
#: calls them) -> the option that gives them.
CONTENTS_OPTIONS: dict[str, str] = {
    "period": "--period", "storeys": "--storeys", "damping": "--damping", "floors": "--floors",
    "record_set": "--record-set", "records": "--records", "items": "--items", "variants": "--variants",
    "friction": "--friction",
}


def _comma_list(option: str, text: str | None) -> tuple[str, ...]:
    """``"a, b"`` -> ``("a", "b")`` (spaces around a name are dropped); None -> (). An empty entry
    (``""``, ``"a,"``, ``",,"``) is refused naming ``option``; names given twice are refused by the
    library (:class:`opsrock.contents.ContentsDesign`), under the option's name."""
    if text is None:
        return ()
    parts = tuple(part.strip() for part in text.split(","))
    if not all(parts):
        raise UsageError(f"{option} needs comma-separated names without an empty one; got {text!r}")
    return parts


def _floors(text: str) -> tuple:
    """``--floors``: ASCII digits -> the floor number, anything else stays a name for the design to check
    (``"ground"``, ``"roof"``; ``"²"`` or ``"٣"`` are refused there, not read as numbers)."""
    return tuple(int(f) if f.isascii() and f.isdigit() else f for f in _comma_list("--floors", text))


def contents(args: argparse.Namespace) -> int:
    """``opsrock contents``: :func:`opsrock.contents.run_contents_study` for one building."""
    output_dir("--out", args.out)
    if args.store is not None:
        output_dir("--store", args.store)
    try:
        with named_options(CONTENTS_OPTIONS):
            design = ContentsDesign(period=args.period, storeys=args.storeys, damping=args.damping,
                                    floors=_floors(args.floors), record_set=args.record_set,
                                    names=_comma_list("--records", args.records),
                                    items=_comma_list("--items", args.items),
                                    variants=_comma_list("--variants", args.variants),
                                    friction=args.friction, sweep=() if args.no_sweep else SWEEP_BUILDINGS,
                                    n_boot=args.n_boot, seed=args.seed)
            res = run_contents_study(design, args.out, quick=args.quick, workers=args.workers,
                                     progress=not args.no_progress, force=args.force, store_dir=args.store)
    except KeyboardInterrupt:
        print(f"opsrock contents: interrupted; finished cases are stored in {args.store or Path(args.out) / 'campaigns'}: "
              "run the same command again to compute only the missing ones", file=sys.stderr)
        return EXIT_INTERRUPTED
    s = res.summary
    ratio = ("no headline ratio (no default variant)" if "default" not in res.design.variants
             else "no headline ratio (no finite default median)" if s.ratio_range is None
             else f"opsrock's no-slip median PFV over FEMA P-58's: {s.ratio_range[0]:.2f} to {s.ratio_range[1]:.2f}")
    print(f"opsrock contents: {s.n_cases} cases ({s.n_failed} failed) in {s.timings['total_s']:.1f} s; {ratio}; "
          f"see {res.report}")
    return 0


__all__ = ["contents"]
