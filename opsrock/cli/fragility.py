"""``opsrock fragility``: the record fragility report of a record campaign."""

from __future__ import annotations

import argparse

from opsrock._files import output_dir, staged_folder
from opsrock.analysis.record_report import OUTPUTS, read_cases, write_record_report
from opsrock.errors import UsageError
from opsrock.fragility.cases import check_some_finished
from opsrock.fragility.ida import OUTCOMES


def fragility(args: argparse.Namespace) -> int:
    """``opsrock fragility``: :func:`opsrock.analysis.record_report.write_record_report` on a record campaign."""
    if args.outcome not in OUTCOMES:
        raise UsageError(f"--outcome must be one of {', '.join(OUTCOMES)}; got {args.outcome!r}")
    out = output_dir("--out", args.out)
    cases = read_cases(args.cases)
    check_some_finished(cases, str(args.cases))  # nothing to fit: one line, nothing written
    with staged_folder(out, OUTPUTS) as stage:  # all of the report and nothing of an earlier one, or nothing
        res = write_record_report(cases, stage, n_boot=args.n_boot, seed=args.seed, outcome=args.outcome,
                                  robustness_sets=args.robustness_sets, workers=args.workers, source=str(args.cases))
    print(f"opsrock fragility: {len(res.study.cases)} cases in {res.timings['total_s']:.1f} s: see {out}/report.md")
    return 0


__all__ = ["fragility"]
