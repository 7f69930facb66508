"""Digests of opsrock's computed outputs, to show that a restructuring changed no result.

    python tools/behaviour_digests.py compute OUT.json [--only NAME ...]
    python tools/behaviour_digests.py check tests/data/behaviour_digests.json [--only NAME ...]

What is digested (SHA-256 of a canonical CSV text, every float at full precision):

* ``cases.csv`` of three campaigns, every column but ``wall_time_s`` (the one measured column):
  the paper scene with ``housner`` and with ``opensees``, the FEMA P695 IDA scene with ``housner_fast``;
* the quick outputs of every validation case (``opsrock validate --quick --out DIR``): each CSV
  without its timing columns and rows (wall and CPU seconds, rates per second, and the
  speed-accuracy chart's Pareto flag, which ranks by time).

Everything runs through the ``opsrock`` console script of the current environment, whose command
line stayed the same across the restructuring; the scenes are found where the checkout keeps them
(``models/scenes/`` before, the package's own data after). ``check`` recomputes and lists every
digest that differs; exit status 1 if any does.
"""

from __future__ import annotations

import argparse
import hashlib
import io
import json
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pandas as pd

ROOT = Path(__file__).resolve().parents[1]

#: Campaigns digested: name -> (scene, solver).
CAMPAIGNS: dict[str, tuple[str, str]] = {
    "paper-housner": ("paper", "housner"),
    "paper-opensees": ("paper", "opensees"),
    "fema-far-field-ida-housner_fast": ("fema-far-field-ida", "housner_fast"),
}

#: Settings renamed by the restructuring (one meaning per name: ``dt`` is a record's sample interval,
#: the OpenSees step is ``step``; ``max_step`` is in seconds, the compiled solver's step in units of
#: ``1/p`` is ``max_dtau``): in a ``settings`` column the new name is mapped back to the old one
#: before hashing, so that a digest compares numbers, not the spelling of a key.
RENAMED_SETTINGS: dict[str, str] = {"'step':": "'dt':", "'min_step':": "'dt_min':", "'max_dtau':": "'max_step':"}

#: Columns and summary rows that hold measured times (or what is ranked by them).
TIMING = re.compile(r"(?:wall|cpu|_time$|^time_|_s_per_|per_wall_second|^pareto$)")


def _opsrock() -> str:
    exe = Path(sys.executable).with_name("opsrock")
    return str(exe) if exe.exists() else "opsrock"


def _scene(name: str) -> str:
    for candidate in (ROOT / "opsrock" / "data" / "scenes" / f"{name}.toml", ROOT / "models" / "scenes" / f"{name}.toml"):
        if candidate.exists():
            return str(candidate)
    raise FileNotFoundError(f"scene {name!r} not found under opsrock/data/scenes or models/scenes")


def _canonical(df: pd.DataFrame) -> str:
    buf = io.StringIO()
    df.to_csv(buf, index=False, float_format="%r", lineterminator="\n")
    return buf.getvalue()


def _digest_csv(path: Path) -> str:
    df = pd.read_csv(path, keep_default_na=False, dtype=str)  # text as written: no re-rounding
    df = df[[c for c in df.columns if not TIMING.search(str(c))]]
    if "settings" in df.columns:
        for new, old in RENAMED_SETTINGS.items():
            df["settings"] = df["settings"].str.replace(new, old, regex=False)
    if len(df.columns) >= 2 and df.columns[-1] == "value":  # a metric,value summary: drop timing rows
        key = df.columns[0]
        df = df[~df[key].str.contains(TIMING)]
    return hashlib.sha256(_canonical(df).encode()).hexdigest()


def _campaign(name: str, work: Path) -> str:
    scene, solver = CAMPAIGNS[name]
    out = work / name
    subprocess.run([_opsrock(), "run", _scene(scene), "--out", str(out), "--solver", solver, "--no-progress"],
                   check=True, stdout=subprocess.DEVNULL)
    return _digest_csv(out / "cases.csv")


def _validation(work: Path) -> dict[str, str]:
    out = work / "validate"
    subprocess.run([_opsrock(), "validate", "--quick", "--out", str(out)], check=True, stdout=subprocess.DEVNULL)
    return {f"validate/{p.relative_to(out)}": _digest_csv(p) for p in sorted(out.rglob("*.csv"))}


def compute(only: list[str] | None = None) -> dict[str, str]:
    """Every digest (or those whose name starts with one of ``only``)."""
    work = Path(tempfile.mkdtemp(prefix="opsrock-digests-"))
    try:
        digests = {}
        for name in CAMPAIGNS:
            if not only or any(name.startswith(o) for o in only):
                digests[f"campaign/{name}"] = _campaign(name, work)
        if not only or any(o.startswith("validate") for o in only):
            digests.update(_validation(work))
        return digests
    finally:
        shutil.rmtree(work, ignore_errors=True)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("action", choices=("compute", "check"))
    p.add_argument("file", help="JSON file of digests (written by compute, read by check)")
    p.add_argument("--only", action="append", help="campaign name or 'validate' (repeatable)")
    a = p.parse_args(argv)
    if a.action == "compute":
        digests = compute(a.only)
        Path(a.file).write_text(json.dumps(digests, indent=2, sort_keys=True) + "\n")
        print(f"{len(digests)} digests -> {a.file}")
        return 0
    reference = json.loads(Path(a.file).read_text())
    now = compute(a.only)
    wanted = {k: v for k, v in reference.items() if k in now or not a.only}
    differ = sorted(k for k in wanted if now.get(k) != wanted[k])
    extra = sorted(set(now) - set(reference))
    for k in differ:
        print(f"DIFFERS {k}: {'missing' if k not in now else now[k][:12]} vs reference {wanted[k][:12]}")
    for k in extra:
        print(f"NEW (no reference) {k}")
    print(f"{len(wanted) - len(differ)}/{len(wanted)} digests identical")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
