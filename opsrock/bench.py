"""Benchmarks that print ratios measured in one run: ``opsrock bench [--quick]``.

Each benchmark is a script in the repository's ``bench/`` folder exposing
``run(quick: bool) -> dict``; it times a baseline and the fast path *in the same run* (the
machines are shared: absolute seconds are not stable, ratios are) and reports the accuracy
reached. Results are printed and written to ``bench/results[_quick].json``.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import sys
import time
from pathlib import Path

#: Repository folder of the benchmark scripts.
BENCH_DIR = Path(__file__).resolve().parents[1] / "bench"

#: Benchmarks in run order: name -> script.
BENCHMARKS: dict[str, str] = {
    "opensees": "bench_opensees.py",
    "housner_fast": "bench_housner_fast.py",
    "records": "bench_records.py",
}


def load(name: str):
    """Import the benchmark script ``name`` (one of :data:`BENCHMARKS`)."""
    if name not in BENCHMARKS:
        raise ValueError(f"benchmark must be one of {', '.join(BENCHMARKS)}; got {name!r}")
    path = BENCH_DIR / BENCHMARKS[name]
    spec = importlib.util.spec_from_file_location(f"opsrock_bench_{name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)  # type: ignore[union-attr]
    return module


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of ``opsrock bench``."""
    parser.add_argument("--quick", action="store_true", help="small problem sizes (a minute in all)")
    parser.add_argument("--only", action="append", choices=list(BENCHMARKS), help="run only this benchmark")


def run_command(args: argparse.Namespace) -> int:
    """Run the benchmarks, print one JSON block each, save them all."""
    results = {}
    for name in args.only or list(BENCHMARKS):
        t0 = time.perf_counter()
        res = load(name).run(quick=args.quick)
        res["bench_wall_time_s"] = time.perf_counter() - t0
        results[name] = res
        print(f"== {name}")
        print(json.dumps(res, indent=2, default=str))
    out = BENCH_DIR / ("results_quick.json" if args.quick else "results.json")
    if args.only and out.exists():  # keep the other benchmarks' last results
        results = {**json.loads(out.read_text()), **results}
    tmp = out.with_suffix(".json.tmp")
    tmp.write_text(json.dumps(results, indent=2, default=str) + "\n")
    tmp.replace(out)
    print(f"saved {out}", file=sys.stderr)
    return 0
