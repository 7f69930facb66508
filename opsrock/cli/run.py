"""``opsrock run``: :func:`opsrock.campaign.workflow.run_campaign` on a scene file or a shipped scene, by the
workflow the scene's ``[needs]`` chose (the library picks it).

Exit status: 0 when every case is stored (failed cases included: they are results), 2 for bad input (the
scene, the options, a damaged store), 1 for a fault of the environment (the store in use by another
process, a full disk: :class:`~opsrock.errors.StoreUnavailableError`, whose advice keeps the finished cases),
130 after Ctrl-C."""

from __future__ import annotations

import argparse
import sys

from opsrock._files import output_dir
from opsrock.campaign.executors import DaskExecutor
from opsrock.campaign.scene import load_scene
from opsrock.campaign.workflow import CampaignOptions, run_campaign
from opsrock.cli import EXIT_INTERRUPTED
from opsrock.errors import InputError, SceneError, UsageError


def run(args: argparse.Namespace) -> int:
    """``opsrock run``: :func:`opsrock.campaign.workflow.run_campaign` on a scene file or a shipped scene."""
    # checked before anything is written or started
    scene = load_scene(args.scene, accept_implausible=args.accept_implausible)
    if args.solver is not None:
        try:  # the scene's needs are checked against the solver now, before anything is written
            scene = scene.with_solver(args.solver)
        except InputError as exc:  # a SceneError, or the scene's [needs] the solver cannot answer
            told = exc.problem if isinstance(exc, SceneError) and exc.field == "solver.name" else str(exc)
            raise UsageError(f"--solver {args.solver}: {told}") from None
    output_dir("--out", args.out)
    dask = args.scheduler is not None or args.dask_local is not None
    if dask and args.workers is not None:
        raise UsageError("--workers sets local processes; with Dask use --dask-local N or the cluster's workers")
    try:
        executor = DaskExecutor(args.scheduler, local_workers=args.dask_local) if dask else None
    except OSError as exc:  # no scheduler at that address
        raise UsageError(" ".join(str(exc).split())) from None
    try:
        options = CampaignOptions(executor=executor, batch=args.batch, case_timeout=args.case_timeout)
        summary = run_campaign(scene, args.out, workers=args.workers, force=args.force,
                               progress=not args.no_progress, options=options)
    except KeyboardInterrupt:
        print(f"opsrock run: interrupted; finished cases are stored in {args.out}: "
              "run the same command again to compute only the missing ones", file=sys.stderr)
        return EXIT_INTERRUPTED
    finally:
        if executor is not None:
            executor.close()
    print("\n".join(summary.lines()))
    if summary.n_failed:
        print(f"opsrock run: {summary.n_failed} case(s) failed (status=failed, reason in {summary.cases_csv})",
              file=sys.stderr)
    for line in summary.warnings:
        print(f"opsrock run: warning: {line}", file=sys.stderr)
    return 0


__all__ = ["run"]
