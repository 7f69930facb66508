"""rigid3d's kernel in two specialisations, one for infinite friction (without the closed-form flat slide, which only
finite friction takes) and one for finite friction, each compiled the first time a case needs it (issue 43:
``workspace.make_flat_scratch``, ``sliding._slide_flat_typed``). The warm-up makes both ready, and which one a process
compiled first changes no result."""

from __future__ import annotations

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
