"""Telling the user that a compiled kernel is about to be compiled, and for how long.

numba compiles a kernel the first time it is called in a process and keeps the machine code in its cache
(``cache=True``: ``__pycache__`` next to the module, or ``NUMBA_CACHE_DIR``); every later process loads it in
a fraction of a second. A first call with an empty cache waits for the compiler instead, silently, for
seconds to minutes: :func:`announce_compile`, called by each compiled solver just before it calls its
kernel, has one line printed on standard error as the compile starts, with the expected duration
(:data:`COMPILE_CPU_S`), and nothing when the kernel is loaded from the cache. Standard output stays the
answer's alone (``opsrock simulate --json``).
"""

from __future__ import annotations

import gc
import sys
from contextlib import contextmanager
from typing import Any, Iterator

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
#: longer on a loaded machine. Later in issue 43, once friction's loop turn was no longer an inlined helper and the
#: garbage collector ran less during a compile (:func:`fewer_collections`): friction 9.9-10.5 s cold less 0.85 s warm,
#: moreau_jean 6.3-6.5 s cold less 0.85 s warm (load average 2-3); rigid3d, once its run loop had one exit and its
#: smooth steps took the workspace apart once (numba drops every array of a named tuple at each place a variable
#: holding it dies), 37.8-39.9 s cold less 1.0 s warm (load average 2). friction, once its free flight was a kernel
#: of its own compiled only when a block first leaves the floor: 7.9-9.3 s cold (against 9.6-10.5 s before, alternated,
#: load average 1.4-3) less 0.8 s warm. rigid3d, once its kernel was compiled per friction, this command (infinite
#: friction) compiling the specialisation without the flat slide: 36.5/36.6 s cold against 40.5/38.5 s before
#: (alternated, load average 2-3), and 35.2/34.7 s against 39.0/39.4 s (load average 1.6-2.4), less 1.0 s warm; a
#: finite-friction first solve is :data:`COMPILE_PART_CPU_S`'s. Once rigid3d's infinite-friction specialisation left
#: out the coarse slide and every kernel helper its C-callable wrapper (:mod:`opsrock.solvers.jitable`), alternated
#: with the code before, two rounds, load average 0.8-1.1: rigid3d 29.2/28.2 s against 33.1/33.6 s, friction
#: 7.5/7.5 s against 8.7/8.3 s, housner_fast 4.6/4.2 s against 4.9/4.5 s, moreau_jean 6.0/7.0 s against 6.5/6.9 s
#: cold, less about 0.8-1.0 s warm. cylinder3d, once only its ``run`` was a numba dispatcher and the rest ``@jitable``
#: helpers: 17.4/17.5 s against 24.3/25.1 s (the warm-up command above, alternated, load average 1.8-2.5), less 1 s
#: warm.
COMPILE_CPU_S: dict[str, float] = {
    "friction": 6.5,
    "housner_fast": 3.5,
    "moreau_jean": 5.5,
    "rigid3d": 28.0,
    "cylinder3d": 16.0,
}

#: CPU time (s) of the parts of a kernel compiled only when a case first needs them, by ``(solver, part)``: the
#: difference between a first solve from an empty cache that needs the part and one that does not (issue 43).
#: ``friction``'s free flight, a kernel of its own compiled when a block first leaves the floor: a block thrown by a
#: floor falling at 3 g took 12.1 and 11.6 s of CPU, one rocking under a one-sine pulse 9.7 and 9.3 s (alternated,
#: load average 2.5); the thrown block took as long before flight was split off (11.2/10.8 s against 11.2/10.9 s).
#: ``rigid3d``'s specialisation for finite friction, compiled when a case with friction first needs it: on its own it
#: replaces the infinite-friction one rather than adding to it (the part is the whole kernel with the flat slide), so
#: this is a first solve's with ``--friction 0.5``: 39.8/38.9 s cold against 38.3/39.7 s before the split
#: (alternated, load average 1.5-2.6), and 38.7/38.5 s against 38.3/38.2 s (load average 1.4-2.4), less 1.0 s warm.
#: After the infinite-friction one in the same process it takes 13-20 s: ``warm_up("rigid3d")``, which compiles
#: both, took 60.6 s against 40.0 s for the one kernel before (load average 3), and 52.0 s against 38.4 s (load
#: average 1). With the helpers' C-callable wrappers left out (:mod:`opsrock.solvers.jitable`): 35.9/35.3 s against
#: 38.3/36.8 s (alternated, load average 0.9-1.0), less 1.0 s warm.
COMPILE_PART_CPU_S: dict[tuple[str, str], float] = {
    ("friction", "flight"): 2.3,
    ("rigid3d", "finite-friction"): 35.0,
}


#: Python's cyclic garbage collector's thresholds while a kernel compiles (:func:`fewer_collections`). numba's
#: compiler makes and drops millions of small objects (its IR, copied whole to inline a function), and with the
#: default thresholds ``(700, 10, 10)`` the collector ran about 1,200 times during friction's first solve, a dozen of
#: them over every object of the process: 1.2 s of its 12.3 s of CPU (``gc.callbacks``, issue 43). With these it ran
#: 160 times, 0.4 s in all, none over the oldest objects; the process peaked at 322 MB resident instead of 298 MB.
COMPILE_GC_THRESHOLDS = (20_000, 1_000, 1_000)


@contextmanager
def fewer_collections() -> Iterator[None]:
    """Python's garbage collector run less often (:data:`COMPILE_GC_THRESHOLDS`) for the duration, its thresholds
    restored after, however the block ends; a collector the program has turned off by a zero threshold stays off.
    For a kernel's compile only: nothing is computed differently, cycles of garbage are still collected."""
    old = gc.get_threshold()
    if old[0] == 0:
        yield
        return
    gc.set_threshold(*(max(o, n) for o, n in zip(old, COMPILE_GC_THRESHOLDS)))
    try:
        yield
    finally:
        gc.set_threshold(*old)


#: The kernels whose compile start is to be announced: ``id(kernel) -> (kernel, solver, part)``
#: (:func:`announce_compile`).
_WATCHED: dict[int, tuple[Any, str, str | None]] = {}
#: The kernels, or ``(kernel, part)`` specialisations, found compiled or loaded in this process (never announced
#: again).
_READY: set[Any] = set()
#: The one listener of numba's ``"numba:compile"`` event, registered on the first announcement.
_LISTENER: list[Any] = []


def announce_compile(kernel: Any, solver: str, part: str | None = None, args: tuple | None = None) -> None:
    """One line on standard error when ``kernel`` (a numba dispatcher) starts compiling in this process, naming
    ``solver`` and its expected compile time (:data:`COMPILE_CPU_S`, s of CPU), or, for a ``part`` of the kernel
    compiled only when a case first needs it, that part (:data:`COMPILE_PART_CPU_S`); nothing when it is loaded from
    numba's cache or already compiled. Call it just before calling the kernel.

    numba broadcasts ``"numba:compile"`` (its documented event API, :mod:`numba.core.event`) when a dispatcher
    compiles, and only then: a kernel found in the cache is loaded without it. A kernel already in this process
    (it has ``signatures``) is not watched, and is remembered: a later solve costs one set look-up. A kernel that
    numba compiles once per kind of argument (rigid3d's, for finite and infinite friction) is given the call's
    ``args``: ready once a signature of theirs is compiled, each specialisation announced (``part``) on its own."""
    key = kernel if args is None else (kernel, part)
    if key in _READY:
        return
    if args is None:
        ready = bool(kernel.signatures)  # builds a list (about 5 us): asked once per kernel and process
    else:
        import numba

        ready = tuple(numba.typeof(a) for a in args) in kernel.signatures
    if ready:
        _READY.add(key)
        return
    _WATCHED[id(kernel)] = (kernel, solver, part)
    if not _LISTENER:
        from numba.core import event

        class CompileNotice(event.Listener):
            """Prints the notice when a watched dispatcher starts compiling."""

            def on_start(self, ev: Any) -> None:
                dispatcher = ev.data.get("dispatcher") if isinstance(ev.data, dict) else None
                watched = _WATCHED.pop(id(dispatcher), None)
                if watched is not None and watched[0] is dispatcher:
                    _say_compiling(*watched[1:])

            def on_end(self, ev: Any) -> None:
                pass

        _LISTENER.append(CompileNotice())
        event.register("numba:compile", _LISTENER[0])


def _say_compiling(solver: str, part: str | None) -> None:
    seconds = COMPILE_CPU_S.get(solver) if part is None else COMPILE_PART_CPU_S.get((solver, part))
    expected = f"about {seconds:.0f} s of CPU" if seconds is not None else "a while"
    what = f"the {solver} kernel" if part is None else f"the {solver} kernel's {part} path"
    print(f"opsrock: compiling {what} (numba, once: later runs load it from the cache); {expected}",
          file=sys.stderr, flush=True)


__all__ = ["COMPILE_CPU_S", "COMPILE_GC_THRESHOLDS", "COMPILE_PART_CPU_S", "announce_compile", "fewer_collections"]
