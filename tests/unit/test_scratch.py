"""The kernels' scratch without reference counts (``opsrock.solvers.scratch``): an arena hands out zeroed, aligned,
disjoint arrays and refuses to overrun, compiled and from Python alike; rigid3d's whole scratch fits its arena.
(That the kernels' results are unchanged by it is the behaviour digests' part: ``tests/data/behaviour``.)"""

from __future__ import annotations

import numba
import numpy as np
import pytest

from opsrock.solvers.rigid3d import kernel as kn
from opsrock.solvers.rigid3d.workspace import (ARENA_BYTES, make_corners, make_phase, make_trial, make_workspace)
from opsrock.solvers.scratch import ALIGN, make_arena, take, unmanaged


@numba.njit  # (not cached: a cache here would not see an edit of opsrock/solvers/scratch.py)
def _three(nbytes):
    """Three arrays from an arena of ``nbytes``, the first two written (element by element: numba's slice assignment
    compiles its error messages, seconds), and what they then hold: ``(a's sum, b's count, c's sum, bytes handed
    out)``."""
    arena = make_arena(nbytes)
    a = take(arena, (3, 3), np.float64)
    b = take(arena, (5,), np.bool_)
    c = take(arena, (2,), np.int64)
    for i in range(3):
        for j in range(3):
            a[i, j] = 1.5
    for i in range(5):
        b[i] = True
    view = unmanaged(a)
    return view.sum(), b.sum(), c.sum(), arena.used[0]


def test_compiled_views_are_disjoint_and_zeroed():
    # 72 bytes of float64, 5 of bool rounded up to 8, 16 of int64: 96 handed out, the int64 still zero
    assert _three(200) == (13.5, 5, 0, 72 + ALIGN + 16)


def test_compiled_arena_refuses_to_overrun():
    with pytest.raises(MemoryError, match="arena is too small"):
        _three(72 + ALIGN + 8)  # one int64 short


def test_python_path_counts_like_the_compiled_one():
    arena = make_arena(200)
    a, b = take(arena, (3, 3), np.float64), take(arena, (5,), np.bool_)
    assert a.shape == (3, 3) and not a.any() and b.dtype == np.bool_ and arena.used[0] == 72 + ALIGN
    with pytest.raises(MemoryError):
        take(arena, (20,), np.int64)


def test_rigid3d_scratch_fits_its_arena_with_the_flat_slide():
    arena = make_arena(ARENA_BYTES)
    make_workspace(arena, kn.OUT_SIZE, True)  # (from Python: the flat slide's scratch whatever ``flat`` is)
    make_trial(arena, np.zeros(kn.OUT_SIZE))
    make_phase(arena, kn.PH_SIZE)
    make_corners(arena)
    assert 0 < arena.used[0] <= ARENA_BYTES
