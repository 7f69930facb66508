"""Benchmarks that measure ratios in one run: ``opsrock bench [--quick] [--only NAME]``.

Each benchmark is a module of this package with ``run(quick: bool) -> dict``: it times a baseline
and the fast path *in the same run* (the machines are shared: absolute seconds are not stable,
ratios are) and reports the accuracy reached.

* :mod:`~opsrock.bench.opensees`: the adaptive OpenSees stepper against fixed steps of 1e-4 s;
* :mod:`~opsrock.bench.housner_fast`: the compiled rigid-body solver on a 40,000-case spectrum;
* :mod:`~opsrock.bench.records`: record-seconds simulated per CPU-second, every solver;
* :mod:`~opsrock.bench.friction`: the same for the block with friction and vertical motion;
* :mod:`~opsrock.bench.postprocessing`: ``opsrock fragility`` against the solving of its campaign, and
  ``opsrock reproduce``.
"""

from __future__ import annotations

import importlib
import json
import time
from pathlib import Path
from typing import Sequence

from opsrock._files import atomic_text
from opsrock.errors import InputError

#: Benchmarks in run order.
BENCHMARKS: tuple[str, ...] = ("opensees", "housner_fast", "records", "friction", "postprocessing")


def run_benchmarks(names: Sequence[str] | None = None, *, quick: bool = False, out: str | Path | None = None,
                   echo=print) -> dict:
    """Run the benchmarks ``names`` (default all, in :data:`BENCHMARKS` order) and save them.

    Parameters
    ----------
    names : sequence of str, optional
        Benchmarks to run.
    quick : bool
        Small problem sizes (a minute in all).
    out : path, optional
        JSON file of the results (default ``bench/results.json``, ``bench/results_quick.json`` with
        ``quick``, under the current folder). Results of benchmarks not run are kept from the file.
    echo : callable
        Receives one text block per finished benchmark (default :func:`print`).

    Returns
    -------
    dict
        Name -> the benchmark's measurements (with ``bench_wall_time_s``).
    """
    names = list(names or BENCHMARKS)
    for name in names:
        if name not in BENCHMARKS:
            raise InputError(f"benchmark must be one of {', '.join(BENCHMARKS)}; got {name!r}")
    path = Path(out) if out is not None else Path("bench") / ("results_quick.json" if quick else "results.json")
    results = {}
    for name in names:
        t0 = time.perf_counter()
        res = importlib.import_module(f"opsrock.bench.{name}").run(quick=quick)
        res["bench_wall_time_s"] = time.perf_counter() - t0
        results[name] = res
        echo(f"== {name}\n{json.dumps(res, indent=2, default=str)}")
    if len(names) < len(BENCHMARKS) and path.exists():  # keep the other benchmarks' last results
        results = {**json.loads(path.read_text()), **results}
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_text(path, json.dumps(results, indent=2, default=str) + "\n")
    return results


__all__ = ["BENCHMARKS", "run_benchmarks"]
