"""The campaign workflow: :func:`run_campaign` runs a scene's cases by the workflow its ``[needs]`` chose.

One solver on every case is the engine itself (:class:`opsrock.campaign.run.Stage`); any other workflow
is a policy over that engine (:data:`POLICIES`: the multi-fidelity campaign of
:mod:`opsrock.campaign.multifidelity`), so ``run_campaign`` and ``opsrock run`` do the same thing. This
module sits above both: the engine knows no policy, and a policy knows the engine only.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from opsrock._pool import leave_if_reimported
from opsrock.campaign.executors import Executor
from opsrock.campaign.multifidelity import MultiFidelity, MultiFidelitySummary
from opsrock.campaign.run import CampaignSummary, Execution, Stage, case_budget
from opsrock.campaign.scene import Scene, load_scene
from opsrock.result import RockingResult

#: Workflows a scene's ``[needs]`` may choose (:attr:`opsrock.campaign.needs.Choice.strategy`), each the
#: policy that runs it from the choice; ``"single"`` (one solver on every case) is the engine itself.
POLICIES: dict[str, Callable[[Any], Any]] = {"multifidelity": MultiFidelity.from_choice}


def policy_for(scene: Scene):
    """The policy the scene's ``[needs]`` chose (:data:`POLICIES`), or None: one solver on every case."""
    strategy = "single" if scene.choice is None else scene.choice.strategy
    return None if strategy == "single" else POLICIES[strategy](scene.choice)


@dataclass(frozen=True)
class CampaignOptions:
    """How :func:`run_campaign` runs a scene beyond its everyday keywords: where, in what batches, within what case
    budget, with what solve function and workflow.

    Parameters
    ----------
    executor : Executor, optional
        Where to run (:class:`~opsrock.campaign.executors.LocalPool`,
        :class:`~opsrock.campaign.executors.DaskExecutor`); the caller closes it. Default: a local pool of
        ``workers`` processes.
    solve_fn : callable, optional
        Replace :func:`opsrock.solvers.simulate` (tests, custom solvers), picklable:
        ``solve_fn(block, excitation, solver=..., **settings) -> RockingResult``. Its name enters the
        manifest, so its results never mix with a real solver's. A multi-fidelity policy uses it for
        the expensive solver only.
    batch : int, optional
        Cases per batch. Default :func:`opsrock.campaign.executors.batch_size`.
    case_timeout : float, optional
        Wall-clock budget of one case (s). Default: the scene's ``[solver] case_timeout``, else
        :data:`opsrock.campaign.timeout.DEFAULT_CASE_TIMEOUT`. A case past it is stored failed with a
        reason starting ``"timeout"`` and the campaign goes on (the local executor also kills a worker
        stuck in native code).
    policy : MultiFidelity, optional
        The workflow. Default: the one the scene's ``[needs]`` chose (:func:`policy_for`), else one
        solver on every case (:class:`Stage`).
    """

    executor: Executor | None = None
    solve_fn: Callable[..., RockingResult] | None = None
    batch: int | None = None
    case_timeout: float | None = None
    policy: MultiFidelity | None = None


def run_campaign(
    scene: Scene | str | os.PathLike,
    out_dir: str | os.PathLike,
    *,
    solver: str | None = None,
    workers: int | None = None,
    force: bool = False,
    progress: bool = True,
    options: CampaignOptions | None = None,
) -> CampaignSummary | MultiFidelitySummary:
    """Run (or resume) every case of a scene into ``out_dir``, by the workflow its ``[needs]`` chose.

    Parameters
    ----------
    scene : Scene or path
        The scene, or its TOML file or shipped name (validated before anything is written).
    out_dir : str or Path
        Output folder: ``results.sqlite`` (the store), ``cases.csv``, ``manifest.json``.
    solver : str, optional
        Run with this solver instead of the scene's (:meth:`Scene.with_solver`: the scene's settings
        are dropped if they belong to another solver); a named solver runs every case.
    workers : int, optional
        Processes of the default :class:`~opsrock.campaign.executors.LocalPool` (default: all cores);
        ignored when ``options.executor`` is given.
    force : bool, optional
        Delete the folder's stored results first, even of other settings. Default False: resume, and
        refuse a folder of other settings.
    progress : bool, optional
        A progress bar on stderr (only when stderr is a terminal). Default True.
    options : CampaignOptions, optional
        Executor, solve function, batch size, case budget (s) and workflow (:class:`CampaignOptions`; default
        its defaults).

    Returns
    -------
    CampaignSummary or MultiFidelitySummary
        The latter when a multi-fidelity policy ran.

    Raises
    ------
    SceneError, InputError, CampaignConflictError, StoreError
        Invalid scene, settings or policy (nothing written); ``out_dir`` holds results of other settings
        and ``force`` is False; another run holds ``out_dir``.
    UnguardedScriptError
        The script that calls it has no ``if __name__ == "__main__":`` guard (the spawned workers import the
        script again, and would start its campaign again), or it runs inside a worker process with more
        than one worker: at once, no case stored. The message names the fix: the guard, or ``workers=1``
        (which runs the cases in this process).

    Examples
    --------
    The shipped scene ``tiny`` (2 blocks x 3 x 3 one-sine pulses), stored in a folder; run it again and
    nothing is computed twice (in a script, under ``if __name__ == "__main__":``):

    >>> import opsrock
    >>> summary = opsrock.run_campaign("tiny", "results/tiny", workers=1, progress=False)  # doctest: +SKIP
    >>> summary.n_cases, summary.n_failed  # doctest: +SKIP
    (18, 0)
    """
    leave_if_reimported()  # a worker process re-running an unguarded script ends here, quietly
    o = options if options is not None else CampaignOptions()
    scene = scene if isinstance(scene, Scene) else load_scene(scene)
    if solver is not None:
        scene = scene.with_solver(solver)
    policy = policy_for(scene) if o.policy is None else o.policy
    how = Execution(workers, o.executor, force, progress, o.batch, case_budget(scene, o.case_timeout))
    if policy is None:
        return Stage(how, o.solve_fn)(scene, out_dir)[0]
    return policy.run(scene, Path(out_dir), Stage(how, o.solve_fn))


__all__ = ["POLICIES", "CampaignOptions", "policy_for", "run_campaign"]
