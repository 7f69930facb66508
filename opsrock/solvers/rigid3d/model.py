"""The inputs of :mod:`opsrock.solvers.rigid3d`'s kernel as typed named tuples (numba compiles their fields as
scalars and arrays; a field is read by name, ``model.body.h``, never by position): the block's geometry and
inertia, its friction, the numerical settings, the contact solver's and the run's limits, and the floor motion,
each built by one function here.

Units as in :mod:`opsrock.solvers.rigid3d.kernel` (SI, per unit mass).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from opsrock.block import Block
from opsrock.constants import G
from opsrock.solvers.rigid3d.settings import DEFAULT_TAIL_DTAU, Rigid3DSettings


class Body(NamedTuple):
    """The box's geometry and inertia per unit mass.

    Parameters
    ----------
    b, d : float
        Half-width and half-depth of the base (m).
    h : float
        Height of the centre of mass above the base (m).
    g : float
        Gravity (m/s²).
    p : float
        The weaker axis's frequency parameter (rad/s): the time unit of the event time and of the smooth steps.
    R : float
        The weaker axis's pivot-to-centre-of-mass distance (m): the velocity scale ``R omega``.
    inertia : tuple of float
        ``(I_x, I_y, I_z) / m`` about the centre of mass, body axes (m²).
    weak_y : bool
        True if the depth is the weaker axis (the sign of ``theta``).
    """

    b: float
    d: float
    h: float
    g: float
    p: float
    R: float  # noqa: N815  (the paper's symbol)
    inertia: tuple[float, float, float]
    weak_y: bool


class Friction(NamedTuple):
    """Coulomb friction at the corners.

    Parameters
    ----------
    mu_s, mu_k : float
        Static and kinetic coefficients (dimensionless; 0 with ``infinite``).
    infinite : bool
        Infinite friction (``Block.friction = None``): corners stick only.
    """

    mu_s: float
    mu_k: float
    infinite: bool


class ContactSolver(NamedTuple):
    """Nonsmooth Gauss-Seidel's settings (:class:`~opsrock.solvers.rigid3d.settings.Rigid3DSettings`).

    Parameters
    ----------
    tol : float
        Tolerance relative to the step's velocity scale (dimensionless).
    max_sweeps : int
        Sweeps per step.
    fail_steps : int
        Consecutive unconverged steps after which the run fails.
    loose_tol : float
        The looser tolerance of a step that did not meet ``tol`` (dimensionless).
    extra_sweeps : int
        The further sweeps allowed to meet it.
    """

    tol: float
    max_sweeps: int
    fail_steps: int
    loose_tol: float
    extra_sweeps: int


class Numerics(NamedTuple):
    """The time stepping.

    Parameters
    ----------
    dt : float
        The Moreau-Jean step (s).
    theta_mj : float
        The theta-method's parameter (dimensionless).
    smooth : bool
        Smooth steps in the phases that have them (:mod:`opsrock.solvers.rigid3d.pivot`).
    hist_every : int
        A history row every this many steps (and the last state).
    """

    dt: float
    theta_mj: float
    smooth: bool
    hist_every: int


class Limits(NamedTuple):
    """When the run ends, and the thresholds of its bookkeeping.

    Parameters
    ----------
    max_steps : int
        Steps allowed (excitation and tail).
    max_tail : int
        Steps allowed after the excitation (< 0: no tail).
    rest_velocity : float
        Speeds (``|V|``, ``R |omega|``) below which the block is still (m/s).
    rest_steps : int
        Steps the block must stay at rest after the excitation for the run to end.
    velocity_tol : float
        Contact velocity above which a loaded corner slips and an unloaded one leaves (m/s).
    lift_gap : float
        Height above which a corner without load is up (m).
    peak_rule : bool
        The tail rule "peak" (:func:`opsrock.solvers.rigid3d.kernel._peak_reached`).
    rocked_theta : float
        Tilt above which the block rocked (rad).
    """

    max_steps: int
    max_tail: int
    rest_velocity: float
    rest_steps: int
    velocity_tol: float
    lift_gap: float
    peak_rule: bool
    rocked_theta: float


class Model(NamedTuple):
    """Everything the kernel takes but the floor motion and the state: :class:`Body`, :class:`Friction`,
    :class:`Numerics`, :class:`ContactSolver`, :class:`Limits`."""

    body: Body
    friction: Friction
    numerics: Numerics
    nsgs: ContactSolver
    limits: Limits


class Floor(NamedTuple):
    """The floor motion in the block frame.

    Parameters
    ----------
    form : int
        ``kernel.FORCING_STEPWISE`` (a value per step) or ``kernel.FORCING_LINEAR`` (samples, linear between).
    ax, ay, av : numpy.ndarray
        Horizontal and vertical accelerations (m/s²).
    sub : int
        Steps per sample interval.
    n_exc : int
        Steps of the excitation.
    tail_av : float
        Vertical acceleration after it (m/s²).
    """

    form: int
    ax: np.ndarray
    ay: np.ndarray
    av: np.ndarray
    sub: int
    n_exc: int
    tail_av: float


def make_model(block: Block, box, settings: Rigid3DSettings, dt: float, peak: float, tail: bool) -> Model:
    """The kernel's :class:`Model` of a case.

    Parameters
    ----------
    block : Block
        The block (its friction, half-sizes and centre of mass).
    box : BoxProperties
        Its three-dimensional mass properties (:func:`opsrock.solvers.rigid3d.solver.box_properties`).
    settings : Rigid3DSettings
        Numerical settings.
    dt : float
        The Moreau-Jean step (s).
    peak : float
        ``max |a_h| + max |a_v|`` of the floor motion (m/s²), for the contact gap.
    tail : bool
        Follow the block after the excitation (False: free motion for the excitation's span only).
    """
    p, R = box.p, box.R
    mu_inf = block.friction is None
    body = Body(float(block.b), float(block.d), float(block.h_cm), float(G), float(p), float(R),
                tuple(float(i) for i in box.inertia), bool(box.weak_y))
    friction = Friction(0.0 if mu_inf else float(block.friction), 0.0 if mu_inf else float(block.friction_kinetic),
                        mu_inf)
    every = max(1, round(settings.history_dtau / (p * dt)))
    numerics = Numerics(float(dt), float(settings.theta_mj), bool(settings.smooth), int(every))
    nsgs = ContactSolver(float(settings.nsgs_tol), int(settings.nsgs_max_sweeps), int(settings.nsgs_fail_steps),
                         float(settings.nsgs_loose_tol), int(settings.nsgs_extra_sweeps))
    tail_dtau = DEFAULT_TAIL_DTAU if settings.max_free_time is None else settings.max_free_time * p
    max_tail = math.ceil(tail_dtau / (p * dt)) if tail else -1
    limits = Limits(int(settings.step_limit), int(max_tail), float(settings.rest_velocity * p * R),
                    int(max(1, math.ceil(settings.rest_duration / (p * dt)))), float(settings.velocity_tol * p * R),
                    float(settings.contact_gap * (G + peak) * dt * dt), settings.tail == "peak",
                    float(settings.rocked_theta))
    return Model(body, friction, numerics, nsgs, limits)


def make_floor(form: int, ax: np.ndarray, ay: np.ndarray, av: np.ndarray, sub: int, n_exc: int,
               tail_av: float) -> Floor:
    """The kernel's :class:`Floor` (the arrays as contiguous float64, the counts as int); arguments as its fields."""
    return Floor(int(form), *(np.ascontiguousarray(a, dtype=np.float64) for a in (ax, ay, av)), int(sub), int(n_exc),
                 float(tail_av))


__all__ = ["Body", "ContactSolver", "Floor", "Friction", "Limits", "Model", "Numerics", "make_floor", "make_model"]
