"""The command line answers a refusal without loading numpy: its parser reads the registry, the pulse names and
the analyses' defaults from modules that import nothing heavy, so that a command refused at parse time (and every
console-script test of the suite) costs about half the CPU it did with numpy loaded."""

from __future__ import annotations

import subprocess
import sys


def test_the_parser_loads_no_numpy():
    code = ("import sys; from opsrock.cli.parser import *; import opsrock.solvers.registry; "
            "print(sorted(m for m in ('numpy', 'pandas', 'scipy', 'numba') if m in sys.modules))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "[]"


def test_the_study_and_campaign_handlers_load_no_scipy_submodule():
    """``opsrock contents``, ``run`` and ``records`` load scipy's submodules only where they compute with them
    (scipy.special imports numpy.f2py and numpy.testing, scipy.integrate scipy.optimize: 0.4 s of CPU of every
    refusal of these commands before, about 0.5 s of a contents refusal's 0.96 s)."""
    code = ("import sys; from opsrock.cli import handler\n"
            "for c in ('contents', 'run', 'records', 'fragility'): handler(c)\n"
            "print(sorted(m for m in ('scipy.special', 'scipy.integrate', 'scipy.optimize', 'scipy.stats')"
            " if m in sys.modules))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "[]"


SWALLOWING_IMPORT = r"""
import importlib, signal, sys
import opsrock.cli as cli

# Ctrl-C as a terminal's foreground process has it: a process started with SIGINT ignored (as a pytest-xdist
# worker may start its children) inherits the ignored disposition, and an ignored Ctrl-C is no Ctrl-C at all
signal.signal(signal.SIGINT, signal.default_int_handler)

real = importlib.import_module


class Importer:
    # a library whose import takes a Ctrl-C and loses it (C code that clears the error, a bare except):
    # the Ctrl-C arrives while the handler's module is being imported
    @staticmethod
    def import_module(name):
        try:
            # raise() delivers the signal to this thread before it returns; Python runs its handler at the next
            # instruction, inside this try (no waiting: nothing depends on how fast the machine is)
            signal.raise_signal(signal.SIGINT)
            for _ in range(100):
                pass
        except BaseException:
            pass
        return real(name)


cli.importlib = Importer
sys.exit(cli.main(["records", "list"]))
"""


def test_a_ctrl_c_during_the_handlers_imports_is_not_lost():
    """Ctrl-C while the command's handler and its libraries are imported, in a library that swallows the
    ``KeyboardInterrupt`` it would raise: recorded, then acted on once the imports are done (one line, exit 130),
    not lost (the command ran on past the Ctrl-C, issue 46)."""
    proc = subprocess.run([sys.executable, "-c", SWALLOWING_IMPORT], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 130, (proc.returncode, proc.stdout, proc.stderr)
    assert proc.stdout == "" and proc.stderr.strip().endswith("interrupted (nothing written)"), proc.stderr
    assert len(proc.stderr.splitlines()) == 1, proc.stderr
