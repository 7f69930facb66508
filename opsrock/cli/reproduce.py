"""``opsrock reproduce``: every figure and table of the paper, from one command."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from opsrock._files import output_dir
from opsrock.analysis.reproduce import ReproduceSettings
from opsrock.analysis.reproduce import reproduce as run_pipeline
from opsrock.cli import EXIT_FAILED
from opsrock.errors import UsageError
from opsrock.report.paper import gate_text
from opsrock.solvers.registry import METHODS, solver_names


def reproduce(args: argparse.Namespace) -> int:
    """``opsrock reproduce``: :func:`opsrock.analysis.reproduce.reproduce`, the paper's workflow."""
    if METHODS.get(args.solver) is None:
        raise UsageError(f"--solver must be one of {', '.join(solver_names())}; got {args.solver!r}")
    output_dir("--out", args.out)
    settings = ReproduceSettings(solver=args.solver, ignore_gate=args.ignore_gate, force=args.force,
                                 robustness_sets=args.robustness_sets)
    result = run_pipeline(args.out, settings, workers=args.workers, progress=not args.no_progress)
    if result.stopped:
        print(gate_text(result.gate).splitlines()[0] + f" (see {Path(args.out) / 'validation_gate.md'})", file=sys.stderr)
        print(gate_text(result.gate), file=sys.stderr)
        return EXIT_FAILED
    t = result.timings
    print(f"reproduced into {args.out}/ in {t['total_s']:.1f} s (gate {t['validation_gate_s']:.1f} s, "
          f"campaign {t['campaign_s']:.1f} s, spectrum {t.get('spectrum_s', 0):.1f} s, "
          f"fragility {t['fragility_s']:.1f} s, robustness {t.get('robustness_s', 0):.1f} s, "
          f"figures {t['figures_s']:.1f} s): see {args.out}/report.md")
    return 0


__all__ = ["reproduce"]
