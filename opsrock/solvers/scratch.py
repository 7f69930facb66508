"""Arrays the compiled kernels do not count references to: views over memory that something else keeps alive.

numba counts a reference to every array a compiled function binds (its arguments, the arrays of a named tuple it
takes), an atomic increment as the function starts and an atomic decrement as it ends, through the array's
``meminfo``. An array built by ``numba.carray`` over a pointer has no ``meminfo`` (it is NULL), and numba's count
then tests the pointer and does nothing. A kernel's scratch is therefore taken from one :class:`Arena`, a zeroed
byte buffer the kernel allocates (and counts) once, as such views (:func:`take`), and its input arrays are used
through such views of themselves (:func:`unmanaged`): each count becomes a test of a NULL pointer. What that saves
depends on the processor's cost of an atomic operation: numba's own switch for the same counts (``_nrt=False``, not
public) cut a 3-D case's CPU by about 1.3 on one project machine, and the arena's saving on an AMD EPYC one was within
the runs' noise (-2 % to +7 %, issue 43). (``perf`` under a hypervisor puts up to 46 % of its samples just after the
atomic instructions, a sampling artefact, not their cost.)

The rule that keeps this safe: a view is valid only while the memory it points into is alive. The arena must stay
bound in the kernel until the kernel's last use of its views (:func:`keep_alive` at the end marks that use), and
an input's view only within the call that was passed the input (the caller holds it). No view is returned to
Python or stored.

Everything here is numba's public interface: ``numba.carray`` and ``numba.extending.intrinsic`` (the intrinsic is
numba's documented example that casts an integer to a pointer, with the element type a parameter).
"""

from __future__ import annotations

from typing import NamedTuple

import numba
import numpy as np
from numba import types
from numba.extending import intrinsic, overload

from opsrock.solvers.jitable import HELPER_OPTIONS, jitable

#: Alignment of every view an arena hands out (bytes): a float64's (and a cache line's eighth).
ALIGN = 8


@intrinsic
def _pointer(typingctx, address, offset, dtype):
    """A pointer to scalars of ``dtype`` (a numba ``DType`` or number class) at ``address + offset`` (bytes)."""
    if isinstance(dtype, types.NumberClass):
        elem = dtype.instance_type
    elif isinstance(dtype, types.DType):
        elem = dtype.dtype
    else:
        return None
    sig = types.CPointer(elem)(types.uintp, types.uintp, dtype)

    def codegen(context, builder, signature, args):
        return builder.inttoptr(builder.add(args[0], args[1]), context.get_value_type(signature.return_type))

    return sig, codegen


class Arena(NamedTuple):
    """A kernel's scratch memory: ``buf`` (bytes, zeroed) and ``used`` (1, int: the bytes handed out so far)."""

    buf: np.ndarray
    used: np.ndarray


@jitable
def make_arena(nbytes):
    """An :class:`Arena` of ``nbytes`` zeroed bytes."""
    return Arena(np.zeros(nbytes, dtype=np.uint8), np.zeros(1, dtype=np.int64))


def take(arena, shape, dtype):
    """A zeroed C-contiguous array of ``shape`` (a tuple) and ``dtype`` (``np.float64``, ``np.int64``, ``np.bool_``)
    from ``arena``, in a kernel without a reference count (module docstring; called from Python, as the closed-form
    tests do, a new array). An arena too small for it is a programming error (its size is the kernel's constant):
    MemoryError."""
    a = np.zeros(shape, dtype=dtype)
    arena.used[0] += (a.nbytes + ALIGN - 1) // ALIGN * ALIGN
    if arena.used[0] > arena.buf.size:
        raise MemoryError("a kernel's scratch arena is too small")
    return a


def _take_view(arena, shape, dtype):
    """:func:`take` as the kernels compile it: a view into the arena's buffer."""
    n = 1
    for s in shape:
        n *= s
    at = arena.used[0]
    arena.used[0] = at + (n * np.empty(0, dtype=dtype).itemsize + ALIGN - 1) // ALIGN * ALIGN
    if arena.used[0] > arena.buf.size:
        raise MemoryError("a kernel's scratch arena is too small")
    return numba.carray(_pointer(arena.buf.ctypes.data, at, dtype), shape)


@overload(take, jit_options=HELPER_OPTIONS)
def _take_typed(arena, shape, dtype):
    """The implementation of :func:`take` numba compiles."""
    return _take_view


def unmanaged(a):
    """A view of the contiguous array ``a`` without a reference count, valid while ``a`` is alive (module
    docstring); called from Python, ``a`` itself."""
    return a


def _unmanaged_view(a):
    """:func:`unmanaged` as the kernels compile it."""
    return numba.carray(_pointer(a.ctypes.data, 0, a.dtype), a.shape)


@overload(unmanaged, jit_options=HELPER_OPTIONS)
def _unmanaged_typed(a):
    """The implementation of :func:`unmanaged` numba compiles."""
    return _unmanaged_view


@jitable
def keep_alive(arena):
    """Marks the last use of ``arena``'s views: numba releases a variable after its last use, and the views do not
    hold the arena. Returns 0."""
    return arena.used.size - 1


__all__ = ["ALIGN", "Arena", "keep_alive", "make_arena", "take", "unmanaged"]
