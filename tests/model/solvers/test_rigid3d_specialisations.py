"""rigid3d's kernel in two specialisations, one for infinite friction (without the closed-form flat slide, which only
finite friction takes) and one for finite friction, each compiled the first time a case needs it (issue 43:
``workspace.make_flat_scratch``, ``sliding._slide_flat_typed``). The warm-up makes both ready, and which one a process
compiled first changes no result."""

from __future__ import annotations

import dataclasses
import json
import subprocess
import sys

from numba import types

#: A block sliding flat on its four corners (mu = b/h = 0.5 along the pulse, ``test_rigid3d``'s closed-form slide):
#: its steps take the flat slide, which only the finite-friction specialisation has; printed as JSON (floats by
#: ``repr``, arrays as lists).
SLIDE = """
import json, math, sys
from opsrock.block import Block
from opsrock.constants import G
from opsrock.excitations.plan import PlanMotion
from opsrock.excitations.pulses import OneSinePulse, RectangularPulse
from opsrock.solvers import rigid3d
if sys.argv[1] == "after-infinite":
    pulse = OneSinePulse.from_ratios(Block(0.3, 1.2, restitution_factor=1.0), 1.35, 3.0)
    assert rigid3d.solve(Block(0.3, 1.2, restitution_factor=1.0, depth=0.6), PlanMotion.along(pulse, 30.0)).ok
box = Block(0.6, 1.2, restitution_factor=1.0, friction=0.5, depth=0.9)
r = rigid3d.solve(box, PlanMotion.along(RectangularPulse(pfa=0.8 * G, omega_p=math.pi / 0.3), 0.0))
print(json.dumps({"theta": [repr(x) for x in r.theta], "slide": [repr(x) for x in r.slide],
                  "residual": [repr(x) for x in r.plan.slide_residual], "energy": {k: repr(v) for k, v in
                  r.plan.energy.items()}, "diagnostics": {k: repr(v) for k, v in r.diagnostics.items()}}))
"""


def _slide(order: str) -> dict:
    done = subprocess.run([sys.executable, "-c", SLIDE, order], capture_output=True, text=True, timeout=600,
                          stdin=subprocess.DEVNULL)
    assert done.returncode == 0, done.stderr[-2000:]
    return json.loads(done.stdout)


def test_a_finite_friction_solve_after_an_infinite_one_is_that_of_a_fresh_process():
    """The same sliding case solved in a fresh process and after an infinite-friction solve in its process (each
    specialisation loaded from the cache, or compiled, in either order): every field the same to the bit, and the
    flat slide taken (the specialisation for finite friction has it)."""
    fresh, after = _slide("fresh"), _slide("after-infinite")
    assert int(fresh["diagnostics"]["flat_slide_steps"]) > 0
    assert after == fresh


def test_warm_up_makes_both_specialisations_ready():
    """``warm_up("rigid3d")`` leaves the kernel compiled (or loaded) for both: its own solve on a slipping base for
    finite friction, ``warm_up_paths`` for infinite friction (the kernel's ``flat`` None)."""
    from opsrock.solvers import warm_up
    from opsrock.solvers.rigid3d import kernel as kn

    warm_up("rigid3d")
    flats = {type(sig[-1]) for sig in kn.run.signatures}
    assert types.NoneType in flats and len(flats) == 2


def test_a_case_that_slides_flat_without_the_coarse_slide_is_solved_again_with_it(monkeypatch):
    """The specialisation for infinite friction has no coarse slide (``run``'s ``flat`` None): a block that slides
    flat there is marked (``OUT_NEEDS_FLAT``) and the solver solves the case again from its start with ``flat`` True.
    With infinite friction a block slides flat only in the friction's limit (none of the directionality study's 370
    sampled infinite-friction cases did), so the hand-over is driven here by giving a sliding block on ``mu`` 0.5
    the specialisation for infinite friction first (``flat_slides`` patched): both runs are asked for, in that
    order, and every field of the result is that of the ordinary solve to the bit (the second run is that solve)."""
    import math

    from opsrock.block import Block
    from opsrock.constants import G
    from opsrock.excitations.plan import PlanMotion
    from opsrock.excitations.pulses import RectangularPulse
    from opsrock.solvers.rigid3d import solver as S

    box = Block(0.6, 1.2, restitution_factor=1.0, friction=0.5, depth=0.9)
    motion = PlanMotion.along(RectangularPulse(pfa=0.8 * G, omega_p=math.pi / 0.3), 0.0)
    ordinary = S.solve(box, motion)
    assert ordinary.diagnostics["coarse_slide_steps"] > 0
    flats = []
    call = S._call_kernel

    def spy(run, args):
        call(run, args)
        flats.append((args[-1], bool(args[4][S.kn.OUT_NEEDS_FLAT])))

    monkeypatch.setattr(S, "flat_slides", lambda friction: None)
    monkeypatch.setattr(S, "_call_kernel", spy)
    again = S.solve(box, motion)
    assert flats == [(None, True), (True, False)]
    for field in dataclasses.fields(ordinary):
        if field.name != "wall_time_s":
            assert _same(getattr(again, field.name), getattr(ordinary, field.name)), field.name


def _same(a, b) -> bool:
    """``a`` and ``b`` equal to the bit: arrays element by element (NaN where NaN), dataclasses, dicts and sequences
    item by item."""
    import numpy as np

    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(a, b, equal_nan=True)
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        return type(a) is type(b) and all(_same(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(a))
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return a == b or (a != a and b != b)
