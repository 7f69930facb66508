"""Telling the user that a compiled kernel is about to be compiled, and for how long.

numba compiles a kernel the first time it is called in a process and keeps the machine code in its cache
(``cache=True``: ``__pycache__`` next to the module, or ``NUMBA_CACHE_DIR``); every later process loads it in
a fraction of a second. A first call with an empty cache waits for the compiler instead, silently, for
seconds to minutes: :func:`announce_compile`, called by each compiled solver just before it calls its
kernel, prints one line on standard error then, with the expected duration (:data:`COMPILE_CPU_S`), and
nothing when the cache is warm. Standard output stays the answer's alone (``opsrock simulate --json``).
"""

from __future__ import annotations

import os
import sys
from typing import Any

#: CPU time (s) a first solve spends compiling each solver's kernel from an empty numba cache: the user plus
#: system time of ``NUMBA_CACHE_DIR=$(mktemp -d) /usr/bin/time opsrock simulate --width 0.4 --height 2.2
#: --pfa-ratio 4 --freq-ratio 6 --solver NAME`` (``--restitution-law housner`` for ``moreau_jean``, ``--depth 0.6``
#: for ``rigid3d``; measured in issue 43 once only the kernels' entry points were numba dispatchers: housner_fast
#: 5.0 s, moreau_jean 8.1-8.6 s, friction 18.2 s (12.3 s once its helpers were compiled once each), rigid3d
#: 52.6 s; for ``cylinder3d`` the same of ``python -c 'from opsrock.solvers import warm_up; warm_up("cylinder3d")'``,
#: 15.4 s cold; 31.1 s with its rolling phase, against 24.1 s without it in the same run, issue 45) less that of the
#: same command with the
#: cache warm (about 1.3 s), measured on the project's shared 2-core development machine (numba 0.68, Python 3.11;
#: the CPU time varies by up to a fifth with the machine's load: these at load average 6-12). The wall time is
#: longer on a loaded machine.
COMPILE_CPU_S: dict[str, float] = {
    "friction": 11.0,
    "housner_fast": 4.0,
    "moreau_jean": 7.0,
    "rigid3d": 51.0,
    "cylinder3d": 30.0,
}


def cache_is_cold(kernel: Any) -> bool:
    """Whether calling ``kernel`` (a numba dispatcher) now would compile it: nothing compiled or loaded for it
    in this process yet, and no cache index of it on disk (numba writes one per function with its first
    compiled signature). Cheap: one attribute and one ``stat``. A kernel whose cache cannot be located counts as
    cold."""
    if kernel.signatures:
        return False
    cache_file = getattr(getattr(kernel, "_cache", None), "_cache_file", None)
    index = getattr(cache_file, "_index_path", None)
    return index is None or not os.path.exists(index)


def announce_compile(kernel: Any, solver: str) -> None:
    """One line on standard error if ``kernel`` is about to be compiled (:func:`cache_is_cold`), naming the
    solver and its expected compile time (:data:`COMPILE_CPU_S`, s of CPU); nothing otherwise."""
    if not cache_is_cold(kernel):
        return
    seconds = COMPILE_CPU_S.get(solver)
    expected = f"about {seconds:.0f} s of CPU" if seconds is not None else "a while"
    print(f"opsrock: compiling the {solver} kernel (numba, once: later runs load it from the cache); {expected}",
          file=sys.stderr, flush=True)


__all__ = ["COMPILE_CPU_S", "announce_compile", "cache_is_cold"]
