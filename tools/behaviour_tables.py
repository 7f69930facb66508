"""Opsrock's computed outputs kept as reference tables, to show that a change altered no result beyond round-off.

    python tools/behaviour_tables.py compute DIR [--only NAME ...]
    python tools/behaviour_tables.py check tests/data/behaviour [--only NAME ...]

What is kept (one gzipped CSV per table in DIR, every float at full precision):

* ``cases.csv`` of three campaigns, every column but ``wall_time_s`` and ``cpu_time_s`` (the measured ones), values
  only (its ``Units`` row left out):
  the paper scene with ``housner`` and with ``opensees``, the FEMA P695 IDA scene with ``housner_fast``;
* the quick outputs of every validation case (``opsrock validate --quick --out DIR``): each CSV
  without its timing columns and rows (wall and CPU seconds, rates per second, and the
  speed-accuracy chart's Pareto flag, which ranks by time).

``check`` recomputes every table and compares it with the kept one, cell by cell: text (verdicts, reasons,
identifiers, settings) exactly, numbers to :data:`RTOL` relative (:data:`ATOL` absolute near zero). That is
round-off, not a model change: numpy picks its SIMD code for the processor it runs on (AVX-512, AVX2, baseline)
and numba compiles for the host, so the last bits of a ``sin`` or of a sum differ from one processor to another;
a solver that takes a discrete decision on such a number (an impact detected or not, stick or slip) can then give
a row that differs beyond round-off. Measured on a stand-in for another processor, every result agreed to round-off;
the cells that did not are not results (:data:`NOT_RESULTS`, with the reason). ``check`` lists every differing row
and says whether each table is bit for bit the kept one (as it is on the machine that computed them).

Exit status 1 if any row differs beyond round-off, or a table lacks rows, columns or is missing.
"""

from __future__ import annotations

import argparse
import math
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

ROOT = Path(__file__).resolve().parents[1]

#: Campaigns kept: name -> (scene, solver).
CAMPAIGNS: dict[str, tuple[str, str]] = {
    "paper-housner": ("paper", "housner"),
    "paper-opensees": ("paper", "opensees"),
    "fema-far-field-ida-housner_fast": ("fema-far-field-ida", "housner_fast"),
}

#: Columns and summary rows that hold measured times (or what is ranked by them).
TIMING = re.compile(r"(?:wall|cpu|_time$|^time_|_s_per_|per_wall_second|^pareto$)")

#: Relative tolerance of a number: round-off of a trajectory integrated over thousands of steps (1e-9, a
#: million times the double precision's 2.2e-16, still a thousand times below the 1e-6 at which any output
#: is reported).
RTOL: float = 1e-9
#: Absolute tolerance near zero (angles in rad, times in s, accelerations in m/s^2 or g).
ATOL: float = 1e-12

#: Cells that are not results where a row says so, by table: (column, value, the columns not compared on the rows
#: where ``column`` holds ``value``), with the reason. Measured by computing the tables on this machine (host
#: AVX-512) and checking them with numpy's SIMD dispatch limited to its x86-64-v2 baseline
#: (``NPY_DISABLE_CPU_FEATURES``), numba compiling for a generic x86-64 (``NUMBA_CPU_NAME=generic``, empty cache)
#: and OpenBLAS's Nehalem kernels: every other cell of all 34 tables agreed to round-off (11 bit for bit).
NOT_RESULTS: dict[str, tuple[str, str, tuple[str, ...], str]] = {
    "validate/friction/agreement": (
        "response_moreau_jean", "overturned", ("slide_max_moreau_jean", "slide_residual_moreau_jean"),
        "the slide of a block that overturned goes on while it falls, after the verdict, and the case compares "
        "none (its d_slide columns are nan there): Moreau-Jean's stick-or-slip decision on the falling block "
        "flips with the last bits of its impulses, and 4 of the 35 rows moved by up to 1.3 % on the generic "
        "processor"),
}


@dataclass(frozen=True)
class Comparison:
    """One table against its kept copy: rows differing beyond tolerance, whether bit for bit the same."""

    name: str
    rows: int
    differing: list[str]
    identical: bool
    problem: str | None = None  # missing table, rows or columns: always a failure

    def ok(self) -> bool:
        return self.problem is None and not self.differing


def _opsrock() -> str:
    exe = Path(sys.executable).with_name("opsrock")
    return str(exe) if exe.exists() else "opsrock"


def _scene(name: str) -> str:
    return str(ROOT / "opsrock" / "data" / "scenes" / f"{name}.toml")


def _table(path: Path) -> pd.DataFrame:
    """The CSV as written (text: no re-rounding), without its units row (a campaign's ``cases.csv``: the kept
    tables hold the values alone), its timing columns and rows."""
    from opsrock._files import read_units

    df = pd.read_csv(path, keep_default_na=False, dtype=str, skiprows=None if read_units(path)[1] is None else [1])
    df = df[[c for c in df.columns if not TIMING.search(str(c))]]
    if len(df.columns) >= 2 and df.columns[-1] == "value":  # a metric,value summary: drop timing rows
        df = df[~df[df.columns[0]].str.contains(TIMING)]
    return df.reset_index(drop=True)


def _campaign(name: str, work: Path) -> pd.DataFrame:
    scene, solver = CAMPAIGNS[name]
    out = work / name
    subprocess.run([_opsrock(), "run", _scene(scene), "--out", str(out), "--solver", solver, "--no-progress"],
                   check=True, stdout=subprocess.DEVNULL)
    return _table(out / "cases.csv")


def _validation(work: Path) -> dict[str, pd.DataFrame]:
    out = work / "validate"
    subprocess.run([_opsrock(), "validate", "--quick", "--out", str(out)], check=True, stdout=subprocess.DEVNULL)
    return {f"validate/{p.relative_to(out).with_suffix('')}": _table(p) for p in sorted(out.rglob("*.csv"))}


def compute(only: list[str] | None = None) -> dict[str, pd.DataFrame]:
    """Every table (or those whose name starts with one of ``only``), by name."""
    work = Path(tempfile.mkdtemp(prefix="opsrock-behaviour-"))
    try:
        tables = {}
        for name in CAMPAIGNS:
            if not only or any(name.startswith(o) for o in only):
                tables[f"campaign/{name}"] = _campaign(name, work)
        if not only or any(o.startswith("validate") for o in only):
            tables.update(_validation(work))
        return tables
    finally:
        shutil.rmtree(work, ignore_errors=True)


def _file(folder: Path, name: str) -> Path:
    return folder / f"{name.replace('/', '__')}.csv.gz"


def _same_cell(a: str, b: str) -> bool:
    if a == b:
        return True
    try:
        x, y = float(a), float(b)
    except ValueError:
        return False
    if math.isnan(x) or math.isnan(y) or math.isinf(x) or math.isinf(y):
        return False  # equal text was caught above: nan against a number, or inf of another sign
    return abs(x - y) <= ATOL + RTOL * max(abs(x), abs(y))


def compare(name: str, kept: pd.DataFrame, now: pd.DataFrame) -> Comparison:
    """``now`` against ``kept``, row by row (tables keep their row order: cases in the order of the scene)."""
    if list(kept.columns) != list(now.columns) or len(kept) != len(now):
        return Comparison(name, len(kept), [], False,
                          f"shape {len(now)} x {list(now.columns)} against kept {len(kept)} x {list(kept.columns)}")
    column, value, skipped, _ = NOT_RESULTS.get(name, (None, None, (), ""))
    differing = []
    for i, (a, b) in enumerate(zip(kept.itertuples(index=False), now.itertuples(index=False))):
        ignore = skipped if column is not None and a[kept.columns.get_loc(column)] == value else ()
        cols = [c for c, x, y in zip(kept.columns, a, b) if c not in ignore and not _same_cell(x, y)]
        if cols:
            differing.append(f"row {i}: " + ", ".join(f"{c} {x} -> {y}" for c, x, y in zip(kept.columns, a, b)
                                                       if c in cols))
    return Comparison(name, len(kept), differing, kept.equals(now))


def _write(folder: Path, tables: dict[str, pd.DataFrame]) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    for name, df in tables.items():
        df.to_csv(_file(folder, name), index=False, lineterminator="\n",
                  compression={"method": "gzip", "mtime": 0})  # mtime 0: the same table gives the same bytes


def check(folder: Path, only: list[str] | None) -> list[Comparison]:
    now = compute(only)
    kept_names = sorted(p.name[: -len(".csv.gz")].replace("__", "/") for p in folder.glob("*.csv.gz"))
    wanted = [n for n in kept_names if n in now or not only]
    results = []
    for name in wanted:
        kept = pd.read_csv(_file(folder, name), keep_default_na=False, dtype=str)
        results.append(compare(name, kept, now[name]) if name in now
                       else Comparison(name, len(kept), [], False, "not computed any more"))
    results += [Comparison(n, len(now[n]), [], False, "no kept table") for n in sorted(set(now) - set(kept_names))]
    return results


def _report(results: list[Comparison]) -> None:
    for r in results:
        verdict = "identical" if r.identical else ("round-off" if not r.differing else
                                                   f"{len(r.differing)}/{r.rows} rows beyond round-off")
        print(f"{'ok  ' if r.ok() else 'FAIL'} {r.name}: {r.problem or verdict}")
        for line in r.differing[:20]:
            print(f"       {line[:400]}")
    print(f"{sum(r.ok() for r in results)}/{len(results)} tables within tolerance; "
          f"{sum(r.identical for r in results)} bit for bit")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("action", choices=("compute", "check"))
    p.add_argument("folder", type=Path, help="folder of kept tables (written by compute, read by check)")
    p.add_argument("--only", action="append", help="campaign name or 'validate' (repeatable)")
    a = p.parse_args(argv)
    if a.action == "compute":
        tables = compute(a.only)
        _write(a.folder, tables)
        print(f"{len(tables)} tables -> {a.folder}")
        return 0
    results = check(a.folder, a.only)
    _report(results)
    return 0 if all(r.ok() for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
