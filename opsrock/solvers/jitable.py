"""The decorator of the compiled kernels' helper functions (numba).

:data:`jitable` is numba's ``register_jitable`` with its documented option ``no_cfunc_wrapper``: a helper compiles
into each kernel that calls it, and numba's default also builds it a C-callable wrapper, which only passing the
helper as a first-class function value needs (no kernel does). Each wrapper is lowered, optimised and turned into
machine code with its helper, in every kernel that links it: about 1.3 s of the 30 s rigid3d's kernel took to compile
(issue 43; both measured from an empty cache, alternated). Results do not change: the wrapper is never called.
"""

from __future__ import annotations

from numba.extending import register_jitable

#: The jit options of every helper (:data:`jitable`) and of the kernels' typed overloads
#: (``numba.extending.overload(..., jit_options=HELPER_OPTIONS)``).
HELPER_OPTIONS = {"no_cfunc_wrapper": True}

#: ``@jitable``: a plain Python function compiled into the kernels that call it (numba's ``register_jitable``,
#: :data:`HELPER_OPTIONS`).
jitable = register_jitable(**HELPER_OPTIONS)

__all__ = ["HELPER_OPTIONS", "jitable"]
