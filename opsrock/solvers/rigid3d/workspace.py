"""The scratch arrays of :mod:`opsrock.solvers.rigid3d`'s kernel as typed named tuples (numba), read by name
(``ws.Q``), built once a run by :func:`make_workspace`: the Moreau-Jean step's (:class:`StepWork`, with its contact
problem's :class:`Contact` and the closed-form slip on two corners' :class:`EdgeWork`), the smooth steps' about
stuck corners (:class:`PivotWork`), those on slipping corners (:class:`SlipWork`), and a probe step's
(:class:`Probe`).

A named tuple is the same structure to numba as a plain tuple of the same arrays (its fields are read by a constant
offset), and a compiled function counts a reference to every array of its arguments as it starts and ends (an
atomic increment and decrement each): commit 671beba measured about a third of a microsecond a step for each
function the whole workspace passes through, and with every function of the contact problem taking the whole
:class:`StepWork` (23 arrays) those counts took 22 % of a quick Siconos run's CPU (``perf``, against 11.5 % with
the arrays passed one by one). So the functions called several times a step take the few arrays they read
(:class:`Contact`, 8), the small ones called once a step are inlined into theirs, and the 6-vectors of one role
share a 2-D array (rows named ``VEC_*``, ``EVEC_*``): fewer arrays to count.

Numba's own option to switch the counting off per function (``_nrt=False``) cut a 3-D case's CPU by a factor
of about 1.3 with results bit for bit the same (issue 43), but it is not part of numba's public interface, which is
all opsrock uses: the counting stays, and fewer arrays passed per call remain the public way to cut it.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import types
from numba.extending import overload

from opsrock.solvers.jitable import HELPER_OPTIONS, jitable

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
def make_edge_work():
    """The scratch of the closed-form slip on two corners (:class:`EdgeWork`), zeroed."""
    return EdgeWork(np.zeros((6, 6)), np.zeros((6, 6)), np.zeros((6, 6)), np.zeros((4, 6)), np.zeros((2, 2)),
                    np.zeros(1, dtype=np.int64), np.zeros((5, 2)), np.zeros(4, dtype=np.int64))


def flat_slides(friction):
    """The kernel's ``flat`` argument for ``friction`` (:class:`.model.Friction`): True if the block may slide flat
    (finite friction), None if it slides flat only in the friction's limit (infinite friction: the kernel then marks
    the case, ``OUT_NEEDS_FLAT``, and the solver runs it again with True)."""
    return None if friction.infinite else True


def make_flat_scratch(flat):
    """The flat slide's scratch, zeroed (:class:`FlatScratch`), for ``flat`` True; compiled by its type
    (:func:`_make_flat_scratch_typed`): both None for ``flat`` None."""
    return FlatScratch(np.zeros((4, 2)), np.zeros((6, 7)))


def _no_flat_scratch(flat):
    """:func:`make_flat_scratch` for ``flat`` None (infinite friction): none."""
    return FlatScratch(None, None)


@overload(make_flat_scratch, jit_options=HELPER_OPTIONS)
def _make_flat_scratch_typed(flat):
    """The implementation of :func:`make_flat_scratch` numba compiles for the type of ``flat``."""
    return _no_flat_scratch if isinstance(flat, types.NoneType) else make_flat_scratch


@jitable
def make_workspace(out_size, flat):
    """The kernel's scratch, zeroed: a :class:`Workspace` (``out_size``: the length of the kernel's output vector,
    for the probe's; ``flat``: True to build the flat slide's scratch, None for none, :func:`flat_slides`)."""
    edge = make_edge_work()
    contact = Contact(np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((4, 3)), np.zeros((4, 3, 3)), np.zeros((4, 3, 3)),
                      np.zeros((5, 6)), np.zeros((6, 6)), np.zeros(4, dtype=np.bool_))
    fs = make_flat_scratch(flat)
    ws = StepWork(contact, np.zeros((3, 3)), fs.sdir, fs.Am, edge)
    end = EndWork(np.zeros((3, 3)), np.zeros((4, 3)), np.zeros(2, dtype=np.int64), np.zeros(3))
    wk = PivotWork(np.zeros(7), np.zeros(7), np.zeros(7), np.zeros(7), np.zeros(3), np.zeros(3), np.zeros(3),
                   np.zeros(3), np.zeros((3, 3)), np.zeros((3, 3)))
    probe = Probe(np.zeros(4, dtype=np.bool_), np.zeros((4, 3)), np.zeros(13), np.zeros(out_size))
    sw = SlipWork(np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((4, 3)), np.zeros((6, 6)),
                  np.zeros((6, 6)), np.zeros((6, 6)), np.zeros((4, 6)), np.zeros((2, 2)), np.zeros(13), np.zeros(13),
                  np.zeros(13), np.zeros(3), np.zeros(2, dtype=np.int64), np.zeros(2, dtype=np.int64))
    return Workspace(ws, end, wk, probe, sw)


@jitable
def make_trial(out):
    """The run's own step's :class:`Probe`: its active corners, impulses and end state, zeroed, and the run's
    ``out``. Built here rather than in ``kernel.run``: numba compiles ``np.zeros`` once for each set of compile flags
    it is met under, and an entry point's differ from a helper's (issue 43)."""
    return Probe(np.zeros(4, dtype=np.bool_), np.zeros((4, 3)), np.zeros(13), out)


@jitable
def make_phase(size):
    """The run loop's phase counts (``size`` int64 slots, ``kernel``'s ``PH_*``), zeroed; built here for the reason
    :func:`make_trial` gives."""
    return np.zeros(size, dtype=np.int64)


@jitable
def make_corners():
    """The corners' flags (:class:`Corners`), all False."""
    return Corners(np.zeros(4, dtype=np.bool_), np.zeros(4, dtype=np.bool_))


__all__ = ["EVEC_P6", "EVEC_Q", "EVEC_U", "EVEC_Y", "VEC_OM", "VEC_PN", "VEC_V", "VEC_VF", "VEC_Y6", "Contact", "Corners",
           "EdgeWork", "EndWork", "FlatScratch", "FlatWork", "PivotWork", "Probe", "SlipWork", "StepWork", "Workspace",
           "flat_slides", "make_corners", "make_edge_work", "make_flat_scratch", "make_phase", "make_trial",
           "make_workspace"]
