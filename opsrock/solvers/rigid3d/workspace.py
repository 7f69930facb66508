"""The scratch arrays of :mod:`opsrock.solvers.rigid3d`'s kernel as typed named tuples (numba), read by name
(``ws.Q``), built once a run by :func:`make_workspace`: the Moreau-Jean step's (:class:`StepWork`, with its contact
problem's :class:`Contact` and the closed-form slip on two corners' :class:`EdgeWork`), the smooth steps' about
stuck corners (:class:`PivotWork`), those on slipping corners (:class:`SlipWork`), and a probe step's
(:class:`Probe`).

Every array here is a view into one :class:`~opsrock.solvers.scratch.Arena` the kernel allocates once a run (of
:data:`ARENA_BYTES`), a view without a reference count (:mod:`opsrock.solvers.scratch`): numba counts a reference to
every array a compiled function binds, an atomic increment and decrement each, and a named tuple passed to a
function binds all its arrays. Before the arena those counts shaped this layout (the functions called several times
a step take the few arrays they read, :class:`Contact`; the 6-vectors of one role share a 2-D array, rows ``VEC_*``
and ``EVEC_*``; commit 671beba measured a third of a microsecond a step for each function the whole workspace passed
through); with it a count is a test of a NULL pointer, results bit for bit the same (what that saves depends on the
processor: :mod:`opsrock.solvers.scratch`). Called from Python (the closed-form tests), the builders below make new arrays instead.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import types
from numba.extending import overload

from opsrock.solvers.jitable import HELPER_OPTIONS, jitable
from opsrock.solvers.scratch import take

#: Rows of :attr:`StepWork.vec`: the velocities ``V`` and ``omega`` after the impulses, the free velocity
#: ``(V_f, omega_f)`` (6), a 6-vector of scratch for the closed forms (``y6``) and NSGS's local velocity ``q``, and
#: NSGS's new impulse.
VEC_V, VEC_OM, VEC_VF, VEC_Y6, VEC_PN = 0, 1, 2, 3, 4

#: Rows of :attr:`EdgeWork.vec` and :attr:`SlipWork.vec`: the two corners' free velocities (or accelerations) ``q``,
#: the linear system's right-hand side ``y``, the impulses (or forces) ``P6`` and the corners' velocities ``u``.
EVEC_Q, EVEC_Y, EVEC_P6, EVEC_U = 0, 1, 2, 3



class EdgeWork(NamedTuple):
    """Scratch of the closed-form slip on two corners (``sliding._edge_slip``): ``D``, ``A``, ``cols`` (6 x 6),
    ``vec`` (4 x 6, rows ``EVEC_*``), ``sdir`` (2 x 2), ``last`` (1, int: the status pair that held last), ``fw``
    (5 x 2: ``_edge_try``'s residuals, angles and Jacobian), ``stidx`` (4, int: the statuses, then the corners)."""

    D: np.ndarray
    A: np.ndarray
    cols: np.ndarray
    vec: np.ndarray
    sdir: np.ndarray
    last: np.ndarray
    fw: np.ndarray
    stidx: np.ndarray


class Contact(NamedTuple):
    """The contact problem of a Moreau-Jean step, what its closed forms and NSGS read and write: the floor-frame
    inverse inertia ``Iinv`` and inertia ``Iw`` (3 x 3), the corners' arms ``r`` (4 x 3), the Delassus blocks ``Wd``
    and their inverses ``Wi`` (4 x 3 x 3), ``vec`` (5 x 6, rows ``VEC_*``: the velocities), the closed forms' ``A6``
    (6 x 6) and a corner mask ``mask`` (4, bool). Kept apart from the rest of :class:`StepWork` so that the
    functions of the contact problem, called several times a step, take (and count references to) these arrays
    only."""

    Iinv: np.ndarray
    Iw: np.ndarray
    r: np.ndarray
    Wd: np.ndarray
    Wi: np.ndarray
    vec: np.ndarray
    A6: np.ndarray
    mask: np.ndarray


class FlatScratch(NamedTuple):
    """Scratch of the closed-form flat slide (``sliding._slide_flat``), which only finite friction takes: the slip
    directions ``sdir`` (4 x 2) and the system ``Am`` (6 x 7), both None in the kernel's specialisation for infinite
    friction (:func:`make_flat_scratch`)."""

    sdir: np.ndarray | None
    Am: np.ndarray | None


class StepWork(NamedTuple):
    """Scratch of a Moreau-Jean step (``step._step``), what it takes and nothing more (its arrays are counted at
    every call, several a step): its :class:`Contact`, the rotation ``Q`` (3 x 3), the flat slide's slip directions
    ``sdir`` (4 x 2) and ``Am`` (6 x 7), and :class:`EdgeWork`. The flat slide's two are None in the kernel's
    specialisation for infinite friction, which never slides flat: numba then compiles no flat slide
    (``sliding._slide_flat``; about a tenth of the kernel's compile, issue 43; :func:`make_flat_scratch`)."""

    contact: Contact
    Q: np.ndarray
    sdir: np.ndarray | None
    Am: np.ndarray | None
    edge: EdgeWork


class EndWork(NamedTuple):
    """Scratch around a step, kept out of :class:`StepWork` (``step._step`` reads none of it, and numba counts a
    reference to every array of its arguments at each call, several a step; issue 43): the end state's rotation
    ``Q1`` (3 x 3) and arms ``r1`` (4 x 3), the smooth step's pivots ``piv`` (2, int) and the step's floor
    accelerations ``a`` (3)."""

    Q1: np.ndarray
    r1: np.ndarray
    piv: np.ndarray
    a: np.ndarray


class PivotWork(NamedTuple):
    """Scratch of a smooth step about stuck corners (``pivot.integrate``): the state ``y`` (quaternion, omega), its
    derivative ``dy``, the Runge-Kutta sum ``acc`` and stage state ``ytmp`` (7 each), the body force ``F``, the pivot
    ``cb`` (body frame), the edge's direction ``e`` and the arm ``r`` (3 each), ``Q`` and ``I_O`` (3 x 3)."""

    y: np.ndarray
    dy: np.ndarray
    acc: np.ndarray
    ytmp: np.ndarray
    F: np.ndarray
    cb: np.ndarray
    e: np.ndarray
    r: np.ndarray
    Q: np.ndarray
    IO: np.ndarray


class SlipWork(NamedTuple):
    """Scratch of a smooth step on slipping corners (``smooth._slip_integrate``): ``Q``, ``Iinv``, ``Iw`` (3 x 3),
    the arms ``r`` (4 x 3), ``D``, ``A``, ``cols`` (6 x 6), ``vec`` (4 x 6, rows ``EVEC_*``), ``sdir`` (2 x 2), the
    Runge-Kutta ``dy``, ``acc``, ``ytmp`` (13 each), the body force ``F`` (3), and the contact corners ``idx`` and
    their statuses ``st`` (2 each, int)."""

    Q: np.ndarray
    Iinv: np.ndarray
    Iw: np.ndarray
    r: np.ndarray
    D: np.ndarray
    A: np.ndarray
    cols: np.ndarray
    vec: np.ndarray
    sdir: np.ndarray
    dy: np.ndarray
    acc: np.ndarray
    ytmp: np.ndarray
    F: np.ndarray
    idx: np.ndarray
    st: np.ndarray


class Probe(NamedTuple):
    """What a Moreau-Jean step (``step._step``) writes: its active corners ``act`` (4, bool), impulses ``P``
    (4 x 3), end state ``state`` (13) and bookkeeping ``out``: the run's own step's (its arrays, ``run``'s
    ``out``) or a probe step's (scratch of its own, built by :func:`make_workspace`)."""

    act: np.ndarray
    P: np.ndarray
    state: np.ndarray
    out: np.ndarray


class FlatWork(NamedTuple):
    """Scratch of the closed-form flat slide (``sliding._slide_flat``): the active corners ``idx`` (4, int), the
    solution ``xs`` (7: normal impulses, then ``V_x``, ``V_y``, ``omega_z``), the free direction ``zs`` (7), the slip
    directions ``sdir`` (4 x 2) and the system's ``Am`` (6 x 7)."""

    idx: np.ndarray
    xs: np.ndarray
    zs: np.ndarray
    sdir: np.ndarray
    Am: np.ndarray


class Corners(NamedTuple):
    """The corners' state carried from step to step: ``touch`` (4, bool: down) and ``slip`` (4, bool: down and
    slipping faster than ``Limits.velocity_tol``)."""

    touch: np.ndarray
    slip: np.ndarray


class Workspace(NamedTuple):
    """All the kernel's scratch: the Moreau-Jean step's (:class:`StepWork`) and that around it (:class:`EndWork`),
    the smooth steps' about stuck corners (:class:`PivotWork`), a probe step's (:class:`Probe`) and the smooth steps'
    on slipping corners (:class:`SlipWork`)."""

    step: StepWork
    end: EndWork
    pivot: PivotWork
    probe: Probe
    slip: SlipWork


@jitable
def make_edge_work(arena):
    """The scratch of the closed-form slip on two corners (:class:`EdgeWork`), zeroed, from ``arena``."""
    f8, i8 = np.float64, np.int64
    return EdgeWork(take(arena, (6, 6), f8), take(arena, (6, 6), f8), take(arena, (6, 6), f8), take(arena, (4, 6), f8),
                    take(arena, (2, 2), f8), take(arena, (1,), i8), take(arena, (5, 2), f8), take(arena, (4,), i8))


def flat_slides(friction):
    """The kernel's ``flat`` argument for ``friction`` (:class:`.model.Friction`): True if the block may slide flat
    (finite friction), None if it slides flat only in the friction's limit (infinite friction: the kernel then marks
    the case, ``OUT_NEEDS_FLAT``, and the solver runs it again with True)."""
    return None if friction.infinite else True


def make_flat_scratch(arena, flat):
    """The flat slide's scratch, zeroed (:class:`FlatScratch`), from ``arena`` for ``flat`` True; compiled by its type
    (:func:`_make_flat_scratch_typed`): both None for ``flat`` None."""
    return FlatScratch(take(arena, (4, 2), np.float64), take(arena, (6, 7), np.float64))


def _no_flat_scratch(arena, flat):
    """:func:`make_flat_scratch` for ``flat`` None (infinite friction): none."""
    return FlatScratch(None, None)


@overload(make_flat_scratch, jit_options=HELPER_OPTIONS)
def _make_flat_scratch_typed(arena, flat):
    """The implementation of :func:`make_flat_scratch` numba compiles for the type of ``flat``."""
    return _no_flat_scratch if isinstance(flat, types.NoneType) else make_flat_scratch


#: Bytes of a run's :class:`~opsrock.solvers.scratch.Arena`: the workspace (with the flat slide's scratch), the trial
#: step, the phase counts and the corners' flags take 6,448 (``tests/unit/test_scratch.py`` checks they fit; a kernel
#: that took more would stop with MemoryError).
ARENA_BYTES = 8192


@jitable
def make_workspace(arena, out_size, flat):
    """The kernel's scratch, zeroed, from ``arena`` (:mod:`opsrock.solvers.scratch`): a :class:`Workspace`
    (``out_size``: the length of the kernel's output vector, for the probe's; ``flat``: True to build the flat
    slide's scratch, None for none, :func:`flat_slides`)."""
    f8, i8, b1 = np.float64, np.int64, np.bool_
    edge = make_edge_work(arena)
    contact = Contact(take(arena, (3, 3), f8), take(arena, (3, 3), f8), take(arena, (4, 3), f8),
                      take(arena, (4, 3, 3), f8), take(arena, (4, 3, 3), f8), take(arena, (5, 6), f8),
                      take(arena, (6, 6), f8), take(arena, (4,), b1))
    fs = make_flat_scratch(arena, flat)
    ws = StepWork(contact, take(arena, (3, 3), f8), fs.sdir, fs.Am, edge)
    end = EndWork(take(arena, (3, 3), f8), take(arena, (4, 3), f8), take(arena, (2,), i8), take(arena, (3,), f8))
    wk = PivotWork(take(arena, (7,), f8), take(arena, (7,), f8), take(arena, (7,), f8), take(arena, (7,), f8),
                   take(arena, (3,), f8), take(arena, (3,), f8), take(arena, (3,), f8), take(arena, (3,), f8),
                   take(arena, (3, 3), f8), take(arena, (3, 3), f8))
    probe = Probe(take(arena, (4,), b1), take(arena, (4, 3), f8), take(arena, (13,), f8), take(arena, (out_size,), f8))
    sw = SlipWork(take(arena, (3, 3), f8), take(arena, (3, 3), f8), take(arena, (3, 3), f8), take(arena, (4, 3), f8),
                  take(arena, (6, 6), f8), take(arena, (6, 6), f8), take(arena, (6, 6), f8), take(arena, (4, 6), f8),
                  take(arena, (2, 2), f8), take(arena, (13,), f8), take(arena, (13,), f8), take(arena, (13,), f8),
                  take(arena, (3,), f8), take(arena, (2,), i8), take(arena, (2,), i8))
    return Workspace(ws, end, wk, probe, sw)


@jitable
def make_trial(arena, out):
    """The run's own step's :class:`Probe`: its active corners, impulses and end state, zeroed, from ``arena``, and
    the run's ``out``."""
    return Probe(take(arena, (4,), np.bool_), take(arena, (4, 3), np.float64), take(arena, (13,), np.float64), out)


@jitable
def make_phase(arena, size):
    """The run loop's phase counts (``size`` int64 slots, ``kernel``'s ``PH_*``), zeroed, from ``arena``."""
    return take(arena, (size,), np.int64)


@jitable
def make_corners(arena):
    """The corners' flags (:class:`Corners`), all False, from ``arena``."""
    return Corners(take(arena, (4,), np.bool_), take(arena, (4,), np.bool_))


__all__ = ["ARENA_BYTES", "EVEC_P6", "EVEC_Q", "EVEC_U", "EVEC_Y", "VEC_OM", "VEC_PN", "VEC_V", "VEC_VF", "VEC_Y6", "Contact", "Corners",
           "EdgeWork", "EndWork", "FlatScratch", "FlatWork", "PivotWork", "Probe", "SlipWork", "StepWork", "Workspace",
           "flat_slides", "make_corners", "make_edge_work", "make_flat_scratch", "make_phase", "make_trial",
           "make_workspace"]
