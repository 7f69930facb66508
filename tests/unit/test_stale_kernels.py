"""The test suite's guard against numba's per-module cache stamp (``_support.drop_stale_kernels``, run before the
warm-up): a compiled entry point whose package (or a shared source its machine code reads) was edited after it was
cached is dropped and compiles again; one cached after every edit is kept."""

from __future__ import annotations

import os

from _support import SHARED_KERNEL_SOURCES, drop_stale_kernels

#: File times (s since the epoch) of the fake tree: sources written, a kernel cached, a source edited after it.
WRITTEN, CACHED, EDITED = 1_000_000.0, 2_000_000.0, 3_000_000.0


def _touch(path, when):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("")
    os.utime(path, (when, when))
    return path


def _tree(tmp_path):
    pkg = tmp_path / "opsrock"
    for name in SHARED_KERNEL_SOURCES:
        _touch(pkg / name, WRITTEN)
    for solver in ("rigid3d", "friction"):
        for module in ("kernel.py", "step.py"):
            _touch(pkg / "solvers" / solver / module, WRITTEN)
        cache = pkg / "solvers" / solver / "__pycache__"
        _touch(cache / "kernel.run-123.py311.nbi", CACHED)
        _touch(cache / "kernel.run-123.py311.1.nbc", CACHED)
        _touch(cache / "kernel.run-123.py311.2.nbc", CACHED)
        _touch(cache / "step.cpython-311.pyc", WRITTEN)
    return pkg


def _left(pkg, solver):
    return sorted(p.name for p in (pkg / "solvers" / solver / "__pycache__").iterdir())


def test_a_cache_newer_than_every_source_is_kept(tmp_path):
    pkg = _tree(tmp_path)
    assert drop_stale_kernels(pkg) == []
    assert len(_left(pkg, "rigid3d")) == 4 and len(_left(pkg, "friction")) == 4


def test_an_edit_of_a_callee_module_drops_that_package_s_kernel_only(tmp_path):
    pkg = _tree(tmp_path)
    _touch(pkg / "solvers" / "rigid3d" / "step.py", EDITED)  # numba's own stamp (kernel.py's) has not moved
    dropped = drop_stale_kernels(pkg)
    assert [p.name for p in dropped] == ["kernel.run-123.py311.nbi"]
    assert _left(pkg, "rigid3d") == ["step.cpython-311.pyc"]
    assert len(_left(pkg, "friction")) == 4


def test_an_edit_of_a_shared_source_drops_every_kernel(tmp_path):
    pkg = _tree(tmp_path)
    _touch(pkg / "solvers" / "__pycache__" / "forcing.forcing-69.py311.nbi", CACHED)  # a shared module's own
    _touch(pkg / "constants.py", EDITED)
    assert len(drop_stale_kernels(pkg)) == 3
    assert _left(pkg, "rigid3d") == _left(pkg, "friction") == ["step.cpython-311.pyc"]
    assert not list((pkg / "solvers" / "__pycache__").iterdir())
