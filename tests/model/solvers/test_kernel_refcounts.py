"""Compiled kernel functions with numba's reference counting off (``_nrt=False``, issue 43): safe only if such a
function allocates nothing and returns no array, so that every array it touches is owned by its caller for the
whole call. Checked on the compiled signatures (a warm kernel) and by numba's allocation statistics over a run:
every allocation inside the kernel freed by the time it returns (a function without counting that received a
new array from an allocating callee would never free it)."""

from __future__ import annotations

import sys

import pytest
from numba.core import types
from numba.core.registry import CPUDispatcher
from numba.core.runtime import _nrt_python, rtsys

from opsrock.block import Block
from opsrock.excitations.plan import PlanMotion
from opsrock.excitations.pulses import OneSinePulse
from opsrock.solvers import simulate, warm_up

#: Kernels whose functions go without reference counting.
SOLVERS = ("rigid3d", "friction", "moreau_jean", "housner_fast")


def _holds_array(t) -> bool:
    if isinstance(t, types.Array):
        return True
    return isinstance(t, types.BaseTuple) and any(_holds_array(x) for x in t.types)


def _dispatchers(solver: str):
    prefix = f"opsrock.solvers.{solver}."
    for name, module in list(sys.modules.items()):
        if (name.startswith(prefix) or name == "opsrock.solvers.forcing") and module is not None:
            for value in vars(module).values():
                if isinstance(value, CPUDispatcher) and value.__module__ == name:
                    yield value


@pytest.mark.parametrize("solver", SOLVERS)
def test_functions_without_counting_return_no_array(solver):
    warm_up(solver)
    uncounted = [d for d in _dispatchers(solver) if d.targetoptions.get("_nrt") is False]
    assert uncounted, "no function without reference counting found: the check would pass vacuously"
    bad = [f"{d.__name__}: {s.return_type}" for d in uncounted for s in d.nopython_signatures
           if _holds_array(s.return_type)]
    assert bad == []
    assert all(d.targetoptions.get("_nrt") is not None for d in _dispatchers(solver)), \
        "every kernel function says whether it counts references (else it takes its first caller's setting)"


@pytest.mark.parametrize("mu, pfa_ratio", [(0.1, 0.8), (0.5, 3.0)], ids=["sliding flat", "rocking"])
def test_a_rigid3d_run_frees_every_allocation(mu, pfa_ratio):
    """Sliding flat (the allocating closed-form slide: friction 0.1 under 0.2 g, below the uplift's 0.25 g) and
    rocking on its corners."""
    warm_up("rigid3d")
    block = Block(0.3, 1.2, restitution_factor=1.0, depth=0.6, friction=mu)
    pulse = OneSinePulse.from_ratios(block, pfa_ratio, 4.0)
    _nrt_python.memsys_enable_stats()  # (what NUMBA_NRT_STATS=1 does at start-up)
    try:
        before = rtsys.get_allocation_stats()
        result = simulate(block, PlanMotion.along(pulse, 30.0), solver="rigid3d", record=False)
        after = rtsys.get_allocation_stats()
    finally:
        _nrt_python.memsys_disable_stats()
    assert result.status == "ok"
    allocated, freed = after.alloc - before.alloc, after.free - before.free
    assert allocated > 0 and allocated == freed
