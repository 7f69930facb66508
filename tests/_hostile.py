"""The hostile-input harness every ``tests/e2e/inputs/test_hostile_*.py`` module shares: one case is a command
line and the promise it must keep, checked through the real console script in a folder of its own.

The promise (README): for bad input, exit status 2, one line on stderr (at most two), no traceback, nothing
on stdout, nothing written in the working folder, and the line names the argument. A case may expect
another status (an environment fault, an answered edge input) or files (valid input only).
"""

from __future__ import annotations

import os
import subprocess
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable, Mapping

from _support import run_opsrock


@dataclass(frozen=True)
class Case:
    """One hostile input: the arguments, the words the one line must hold, the expected status."""

    name: str
    args: tuple[str, ...]
    needles: tuple[str, ...]
    status: int = 2
    expect_files: tuple[str, ...] = field(default=())  # files the command may write (valid inputs only)


def listing(folder: Path) -> dict[str, tuple[int, float]]:
    """Every path under ``folder`` with its size and modification time (to show nothing was touched)."""
    return {str(p.relative_to(folder)): (p.lstat().st_size, p.lstat().st_mtime) for p in folder.rglob("*")}


def check_case(case: Case, work: Path, *, timeout: float = 90, env: Mapping[str, str] | None = None) -> str | None:
    """Run one case in its own empty folder under ``work``; return what broke the promise (None: kept)."""
    cwd = work / str(abs(hash(case.name)))
    cwd.mkdir()
    try:
        proc = run_opsrock(case.args, cwd, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return f"{case.name}: no answer within {timeout:g} s"
    problems = []
    lines = proc.stderr.splitlines()
    if proc.returncode != case.status:
        problems.append(f"exit {proc.returncode}")
    if "Traceback" in proc.stderr or len(lines) > 2 or not lines:
        problems.append(f"{len(lines)} stderr lines")
    if proc.stdout:
        problems.append("stdout not empty")
    written = sorted(p.name for p in cwd.iterdir() if p.name not in case.expect_files)
    if written:
        problems.append(f"wrote {written}")
    if "np.float64" in proc.stderr:
        problems.append("numpy repr in the message")
    missing = [n for n in case.needles if n not in (lines[0] if lines else "")]
    if missing:
        problems.append(f"message lacks {missing}")
    return f"{case.name}: {'; '.join(problems)} | {proc.stderr.strip()[:300]}" if problems else None


#: Environment variable: a file to which :func:`sweep` appends one line per case checked (command, kept or
#: broken, name), for the hostile-input counts by command that a closing note reports.
LOG_ENV = "OPSROCK_HOSTILE_LOG"


def sweep(cases: Iterable[Case], work: Path, *, workers: int = 4, timeout: float = 90) -> list[str]:
    """Check every case (in parallel threads, each its own subprocess); the broken promises, one line each."""
    cases = list(cases)
    with ThreadPoolExecutor(max_workers=workers) as pool:
        results = list(pool.map(lambda c: check_case(c, work, timeout=timeout), cases))
    if os.environ.get(LOG_ENV):
        with open(os.environ[LOG_ENV], "a", encoding="utf-8") as log:
            log.writelines(f"{c.args[0] if c.args else '-'}\t{'broken' if r else 'kept'}\t{c.name}\n"
                           for c, r in zip(cases, results))
    return [r for r in results if r]


def one_per_option(cases: list[Case]) -> tuple[list[Case], list[Case]]:
    """``(quick, rest)``: the cases split so that ``make test`` sweeps one bad value of every option and the slow
    test every other; together they are the whole table. A case's option is its name without the last word
    (``"simulate --width '-1'"`` -> ``"simulate --width"``); the k-th option takes its (k mod n)-th value, so the
    bad values are spread over the options. The values of one option meet the same check (one converter, one
    range check), so one value per option catches a broken check; a case whose name is its own group (a file
    defect, a regression named in words) is always in ``quick``."""
    groups: dict[str, list[Case]] = {}
    for case in cases:
        groups.setdefault(case.name.rsplit(" ", 1)[0], []).append(case)
    quick = [group[k % len(group)] for k, group in enumerate(groups.values())]
    chosen = {id(c) for c in quick}
    return quick, [c for c in cases if id(c) not in chosen]


def every_other(cases: list[Case]) -> tuple[list[Case], list[Case]]:
    """``(now, later)``: the even-numbered cases for ``make test``, the odd-numbered ones for the slow complement
    (``make test-slow``, run before a release). The sweeps' tables are written group by group (an option's bad
    values together, a file defect's variants together), so every other case still touches every group of
    more than one case; the two halves are the whole table. It keeps ``make test`` within its 6 minutes on 2
    cores: a console-script case costs a fresh interpreter (0.2-0.8 s of CPU)."""
    return cases[0::2], cases[1::2]
