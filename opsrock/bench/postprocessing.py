"""The post-processing beside the solving: ``opsrock fragility`` and ``opsrock reproduce``, timed in one run.

A record campaign of the shipped blocks (``opsrock/data/blocks.toml``) x the 44 FEMA P695 far-field
components x six floors (floors 2 and roof of a 3-storey building, T_1 = 0.45 s; floors 2, 4, 6 and roof of
an 8-storey one, T_1 = 1.0 s) x 12 IDA levels = 12,672 cases, solved by ``housner_fast``; then
:func:`opsrock.analysis.record_report.write_record_report` on it with the command's defaults (200 record resamples,
seed 0), and :func:`opsrock.analysis.reproduce.reproduce` (``make reproduce``'s work) into a fresh folder.

The ratio that does not depend on the machine's load is measured in this run: the report's wall time over
the campaign's (the solving). For scale, the numbers measured before the post-processing was reworked, on
the same kind of shared 2-core machine: the report 164 s on a campaign of 24.5 s (6.7 times the solving),
and ``make reproduce`` 66 s (:data:`BEFORE`).

    opsrock bench --only postprocessing [--quick]   # quick: the roofs only, 4 levels, no reproduce
"""

from __future__ import annotations

import tempfile
import time
from importlib import resources
from pathlib import Path

#: Wall times measured before the rework (s), for scale: the report on the 12,672-case campaign, the campaign
#: itself, and ``opsrock reproduce``.
BEFORE: dict[str, float] = {"fragility_s": 164.0, "campaign_s": 24.5, "reproduce_s": 66.0}

#: The campaign's IDA levels of ``PFA / (g tan alpha)`` (full and quick).
LEVELS = (1.25, 1.5, 1.75, 2.0, 2.5, 3.0, 3.5, 4.0, 5.0, 6.0, 7.0, 8.0)
LEVELS_QUICK = (1.5, 2.5, 4.0, 6.0)


def scene_text(quick: bool) -> str:
    """The benchmark's scene as TOML (the shipped blocks file by its installed path)."""
    blocks = Path(str(resources.files("opsrock.data"))) / "blocks.toml"
    floors3, floors8 = ('["roof"]', '["roof"]') if quick else ('[2, "roof"]', '[2, 4, 6, "roof"]')
    levels = ", ".join(f"{x:g}" for x in (LEVELS_QUICK if quick else LEVELS))
    return f'''name = "bench-postprocessing"
description = "blocks x FEMA P695 far-field x floors x IDA levels"
blocks = "{blocks.as_posix()}"

[solver]
name = "housner_fast"

[records]
set = "fema-p695:far-field"
ground = false

[[records.building]]
name = "b3"
period = 0.45
storeys = 3
floors = {floors3}
damping = 0.05

[[records.building]]
name = "b8"
period = 1.0
storeys = 8
floors = {floors8}
damping = 0.05

[records.intensity]
method = "ida"
measure = "pfa_ratio"
levels = [{levels}]
'''


def _timed(fn, *args, **kwargs) -> tuple[object, float]:
    t0 = time.perf_counter()
    out = fn(*args, **kwargs)
    return out, time.perf_counter() - t0


def run(quick: bool = False) -> dict:
    """Time the campaign, the record report and (unless ``quick``) the reproduction, in one run."""
    import os

    from opsrock.analysis.record_report import read_cases, write_record_report
    from opsrock.analysis.reproduce import reproduce
    from opsrock.campaign import run_campaign

    with tempfile.TemporaryDirectory(prefix="opsrock-bench-") as tmp:
        tmp = Path(tmp)
        (tmp / "scene.toml").write_text(scene_text(quick))
        summary, campaign_s = _timed(run_campaign, tmp / "scene.toml", tmp / "campaign", progress=False)
        cases = read_cases(tmp / "campaign")
        _, fragility_s = _timed(write_record_report, cases, tmp / "report", n_boot=200, seed=0,
                                workers=os.cpu_count() or 1, source=str(tmp / "campaign"))
        out: dict = {"n_cases": int(len(cases)), "n_failed": int((cases["status"] != "ok").sum()),
                     "campaign_s": campaign_s, "fragility_s": fragility_s,
                     "fragility_over_campaign": fragility_s / campaign_s,
                     "before": dict(BEFORE),
                     "before_fragility_over_campaign": BEFORE["fragility_s"] / BEFORE["campaign_s"]}
        if not quick:
            _, reproduce_s = _timed(reproduce, tmp / "reproduce", progress=False)
            out.update(reproduce_s=reproduce_s, reproduce_speedup_vs_before=BEFORE["reproduce_s"] / reproduce_s,
                       fragility_speedup_vs_before=BEFORE["fragility_s"] / fragility_s)
    return out
