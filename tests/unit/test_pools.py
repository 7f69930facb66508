"""opsrock's post-processing pools choose their start method (:func:`opsrock._pool.pool_context`), so that a
script read from standard input keeps working when Python's default changes (``forkserver`` on Linux from Python
3.14, which starts each worker by importing the main script again). Python 3.14's default is set by hand here, on
whichever Python runs the suite."""

from __future__ import annotations

import subprocess
import sys

import pytest

SCRIPT = r"""
import multiprocessing, sys
multiprocessing.set_start_method(sys.argv[1], force=True)  # what Python 3.14 makes the default on Linux

from opsrock._pool import TaskPool


class Square:
    def run(self, k):
        return k * k


if __name__ == "__main__":
    with TaskPool(Square(), [(k,) for k in range(6)], workers=2) as pool:
        print(pool.results())
"""


@pytest.mark.parametrize("method", ["forkserver", "spawn"])
def test_a_task_pool_in_a_script_read_from_standard_input(method):
    """``python3 - <<EOF`` with the default start method set to ``forkserver`` or ``spawn``: the results, in
    task order, and nothing on stderr (a worker that had to import ``<stdin>`` again failed with a traceback)."""
    proc = subprocess.run([sys.executable, "-", method], input=SCRIPT, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "[0, 1, 4, 9, 16, 25]" and proc.stderr == "", proc.stderr


def test_the_pools_fork_on_linux():
    from opsrock._pool import pool_context

    expected = "fork" if sys.platform.startswith("linux") else None
    assert expected is None or pool_context().get_start_method() == expected
