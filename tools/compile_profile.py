"""Where a kernel's cold compile goes (issue 43): every numba compile a first solve triggers, from an empty cache.

Usage (any ``opsrock simulate`` arguments)::

    python tools/compile_profile.py simulate --json --width 0.4 --height 2.2 --pfa-ratio 4 --freq-ratio 6 \\
        --solver friction

It runs the command in this process with a new, empty ``NUMBA_CACHE_DIR`` and ``NUMBA_LLVM_PASS_TIMINGS=1`` (set
here, for this measurement only) and listens to numba's public event API (``numba.core.event``, the
``numba:compile`` event) for every compile: the entry point's and each ``jitable`` helper's. It prints,
on standard error, the process's CPU time, then one line per compiled function, slowest first: its exclusive
wall time (its own compile, less the compiles it triggered), inclusive time, how many times it was compiled and
with how many distinct signatures (a function compiled more often than it has signatures was compiled again
under other compile flags: numba keys a helper on the flags of the function being compiled when it meets it, and
an entry point's differ from a helper's), and the LLVM time of its library (function passes, module passes,
machine code). Wall times, not CPU times: compare them within one run only.
"""

from __future__ import annotations

import collections
import os
import sys
import tempfile
import time


def _listener(rows):
    """A ``numba:compile`` listener appending ``(name, args, inclusive s, exclusive s, dispatcher)`` to ``rows``."""
    from numba.core import event

    class Compiles(event.Listener):
        def __init__(self):
            self.stack = []

        def on_start(self, ev):
            data = ev.data or {}
            self.stack.append([data.get("dispatcher"), str(data.get("args")), time.perf_counter(), 0.0])

        def on_end(self, ev):
            disp, args, start, children = self.stack.pop()
            spent = time.perf_counter() - start
            if self.stack:
                self.stack[-1][3] += spent
            func = getattr(disp, "py_func", None)
            name = f"{func.__module__}.{func.__qualname__}" if func is not None else str(disp)
            rows.append((name, args, spent, spent - children, disp))

    return Compiles()


def _llvm_seconds(dispatchers):
    """LLVM time (s) of each compiled function's library, by function name (``llvm_pass_timings`` metadata)."""
    out = collections.Counter()
    for disp in dispatchers:
        for cres in list(getattr(disp, "overloads", {}).values()):
            timings = (getattr(cres, "metadata", None) or {}).get("llvm_pass_timings")
            func = getattr(disp, "py_func", None)
            if timings is not None and func is not None:
                out[f"{func.__module__}.{func.__qualname__}"] += sum(r.timings.get_total_time() for r in timings)
    return out


def main(argv):
    """Run ``opsrock`` with ``argv`` from an empty cache and print where its compile time went."""
    os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="compile_profile_")
    os.environ["NUMBA_LLVM_PASS_TIMINGS"] = "1"
    from numba.core import event

    rows = []
    event.register("numba:compile", _listener(rows))
    cpu = time.process_time()
    from opsrock.cli import main as opsrock_main

    try:
        opsrock_main(argv)
    except SystemExit:
        pass
    cpu = time.process_time() - cpu
    by_name = collections.defaultdict(lambda: [0, set(), 0.0, 0.0])
    for name, args, inclusive, exclusive, _ in rows:
        entry = by_name[name]
        entry[0] += 1
        entry[1].add(args)
        entry[2] += inclusive
        entry[3] += exclusive
    llvm = _llvm_seconds({id(r[4]): r[4] for r in rows}.values())
    print(f"process CPU {cpu:.2f} s, {len(rows)} compiles; per function: exclusive s, inclusive s, compiles, "
          f"signatures, LLVM s", file=sys.stderr)
    for name, (count, sigs, inclusive, exclusive) in sorted(by_name.items(), key=lambda kv: -kv[1][3]):
        again = "  compiled again" if count > len(sigs) else ""
        print(f"{exclusive:7.2f} {inclusive:7.2f} {count:3d} {len(sigs):3d} {llvm.get(name, 0.0):6.2f}  {name}{again}",
              file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1:])
