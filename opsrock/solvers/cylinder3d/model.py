"""The inputs of :mod:`opsrock.solvers.cylinder3d`'s kernel as typed named tuples (numba compiles their fields as
scalars and arrays, read by name: ``model.design.r``), each built by one function here: the cylinder's geometry and
inertia (:class:`Design`), its friction, the time stepping, the contact solver's and the run's limits, the floor
motion (:class:`Floor`), the scratch arrays (:class:`Workspace`) and the run's state (:class:`State`).

Units as in :mod:`opsrock.solvers.cylinder3d.kernel` (SI, per unit mass).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from opsrock.block import Block
from opsrock.constants import G
from opsrock.errors import InputError
from opsrock.solvers.cylinder3d.constants import OUT_SIZE, ROLL_DTAU, T_LAST_N, T_PHI, T_SIZE, T_W_LAST
from opsrock.solvers.cylinder3d.settings import DEFAULT_TAIL_DTAU, Cylinder3DSettings


@dataclass(frozen=True)
class CylinderProperties:
    """A cylinder's mass properties and rocking parameters, as the solver reads them off a :class:`Block`.

    Parameters
    ----------
    r : float
        Radius of the base (m): ``Block.width / 2`` (the diameter is the block's width).
    h : float
        Height of the centre of mass above the base (m): ``Block.h_cm``.
    i_h : float
        Moment of inertia about a horizontal axis through the centre of mass, per unit mass (m²):
        ``Block.radius_of_gyration²``, or a homogeneous solid cylinder's ``r²/4 + H²/12`` without it.
    i_z : float
        Moment of inertia about the cylinder's axis per unit mass (m²): a homogeneous solid cylinder's ``r²/2``.
    alpha : float
        Slenderness ``atan(r / h)`` (rad).
    R : float
        Rim-to-centre-of-mass distance ``hypot(r, h)`` (m).
    p : float
        Frequency parameter of rocking in a vertical plane through the axis, ``sqrt(g R / (i_h + R²))`` (rad/s).
    e_housner : float
        Housner's coefficient of that planar rocking, ``1 - 2 r² / (i_h + R²)`` (dimensionless).
    """

    r: float
    h: float
    i_h: float
    i_z: float
    alpha: float
    R: float  # noqa: N815  (the paper's symbol)
    p: float
    e_housner: float


def cylinder_mass(diameter: float, height: float) -> dict[str, float]:
    """A homogeneous solid cylinder's mass distribution as :class:`Block` fields (m): ``cm_height = height / 2``,
    ``radius_of_gyration = sqrt(diameter² / 16 + height² / 12)`` (about a horizontal axis through the centre of
    mass), so that the block's planar properties are the cylinder's in a vertical plane through its axis."""
    return {"cm_height": 0.5 * height, "radius_of_gyration": math.sqrt(diameter**2 / 16.0 + height**2 / 12.0)}


def cylinder_properties(block: Block) -> CylinderProperties:
    """The cylinder ``block`` stands for: its width is the diameter; depth, if given, must equal it.

    Raises
    ------
    InputError
        A depth other than the width (a cylinder's base is round).
    """
    if block.depth is not None and not math.isclose(block.depth, block.width, rel_tol=1e-12):
        raise InputError(f"solver 'cylinder3d' takes a round base whose diameter is the block's width: depth must be "
                         f"None or the width ({block.width!r} m), got depth = {block.depth!r}", argument="depth")
    r, h = 0.5 * block.width, block.h_cm
    i_h = (r * r / 4.0 + block.height**2 / 12.0 if block.radius_of_gyration is None
           else block.radius_of_gyration**2)
    R = math.hypot(r, h)
    return CylinderProperties(r, h, i_h, 0.5 * r * r, math.atan2(r, h), R, math.sqrt(G * R / (i_h + R * R)),
                              1.0 - 2.0 * r * r / (i_h + R * R))


class Design(NamedTuple):
    """The cylinder's geometry and inertia per unit mass.

    Parameters
    ----------
    r, h : float
        Radius of the base and height of the centre of mass above it (m).
    g : float
        Gravity (m/s²).
    p, R : float
        Rocking's frequency parameter (rad/s) and rim-to-centre-of-mass distance (m): the time and length scales.
    alpha : float
        Slenderness ``atan(r / h)`` (rad): the tilt at which the centre of mass stands above the rim point.
    i_h, i_z : float
        Inertia about a horizontal axis through the centre of mass and about the axis, per unit mass (m²).
    n_rim : int
        Rim points carrying the flat base.
    """

    r: float
    h: float
    g: float
    p: float
    R: float  # noqa: N815
    alpha: float
    i_h: float
    i_z: float
    n_rim: int


class Friction(NamedTuple):
    """Coulomb friction at the rim: static ``mu_s`` and kinetic ``mu_k`` (dimensionless; 0 with ``infinite``, a
    base that never slips)."""

    mu_s: float
    mu_k: float
    infinite: bool


class Numerics(NamedTuple):
    """The time stepping: the Moreau-Jean step ``dt`` (s), the theta-method's ``theta_mj``, a history row every
    ``hist_every`` steps, ``smooth`` (Runge-Kutta sub-steps while rolling on a rim point, :mod:`.rolling`) of at
    most ``roll_steps`` Moreau-Jean steps."""

    dt: float
    theta_mj: float
    hist_every: int
    smooth: bool
    roll_steps: int


class ContactSolver(NamedTuple):
    """Nonsmooth Gauss-Seidel on the flat base: ``tol`` (relative to ``g dt``), ``max_sweeps`` a step,
    ``fail_steps`` unconverged steps in a row that fail the run."""

    tol: float
    max_sweeps: int
    fail_steps: int


class Limits(NamedTuple):
    """When the run ends and its thresholds: ``max_steps``, ``max_tail`` (steps after the excitation; < 0: none),
    ``rest_velocity`` (m/s), ``rest_steps``, ``velocity_tol`` (m/s), ``lift_gap`` (m), ``rocked_theta`` (rad)."""

    max_steps: int
    max_tail: int
    rest_velocity: float
    rest_steps: int
    velocity_tol: float
    lift_gap: float
    rocked_theta: float


class Model(NamedTuple):
    """Everything the kernel takes but the floor motion and the state."""

    design: Design
    friction: Friction
    numerics: Numerics
    nsgs: ContactSolver
    limits: Limits


class Floor(NamedTuple):
    """The floor motion in the cylinder's frame at rest: ``form`` (``FORCING_*``), accelerations ``ax``, ``ay``,
    ``av`` (m/s²), ``sub`` steps per sample interval, ``n_exc`` steps of excitation, ``tail_av`` after it (m/s²)."""

    form: int
    ax: np.ndarray
    ay: np.ndarray
    av: np.ndarray
    sub: int
    n_exc: int
    tail_av: float


class Workspace(NamedTuple):
    """Scratch of a step: rotation ``Q``, floor-frame inverse inertia ``Iinv`` and inertia ``Iw`` (3 x 3), the rim
    points' arms from the centre of mass ``arms`` (n x 3), Delassus blocks ``W`` (n x 3 x 3), impulses ``P``
    (n x 3), body angles ``phi`` (n), the velocity ``vel`` (6: ``V``, ``omega``), the free velocity ``free`` (6),
    the step's floor accelerations ``acc`` (3), the next state ``new`` (13), 3-vectors ``tmp`` and ``q``, and the
    lift's rim point off the rim points (:func:`.flat.lift_about`): its arm ``parm`` (3), Delassus block ``pW`` (3 x 3)
    and impulse ``pP`` (3)."""

    Q: np.ndarray
    Iinv: np.ndarray
    Iw: np.ndarray
    arms: np.ndarray
    W: np.ndarray
    P: np.ndarray
    phi: np.ndarray
    vel: np.ndarray
    free: np.ndarray
    acc: np.ndarray
    new: np.ndarray
    tmp: np.ndarray
    q: np.ndarray
    parm: np.ndarray
    pW: np.ndarray  # noqa: N815  (a matrix)
    pP: np.ndarray  # noqa: N815


class RollWork(NamedTuple):
    """Scratch of a Runge-Kutta sub-step rolling on a rim point (:mod:`.rolling`), in two arrays (few arguments for
    the compiler): ``m`` (4 x 3 x 3) the rotation ``Q``, floor-frame inertia ``Iw`` and its inverse ``Iinv`` and the
    contact's Delassus block ``W`` (rows ``RM_*``); ``v`` (10 x 13) the arm, the rim's tangent, the contact point's
    free acceleration, ``alpha_f``, the contact force and the body force (first 3 columns), the end state, a stage's
    derivative, the weighted sum and the stage state (rows ``RV_*``)."""

    m: np.ndarray
    v: np.ndarray


class State(NamedTuple):
    """The run's state: ``s`` (13 floats: centre of mass ``X``, unit quaternion ``(w, x, y, z)``, ``V``,
    ``omega``, floor frame), the tracker ``track`` (``T_*`` slots) and the output vector ``out`` (``OUT_*``)."""

    s: np.ndarray
    track: np.ndarray
    out: np.ndarray


def make_model(block: Block, cyl: CylinderProperties, settings: Cylinder3DSettings, dt: float, peak: float,
               tail: bool) -> Model:
    """The kernel's :class:`Model` of a case: ``dt`` the step (s), ``peak`` ``max |a_h| + max |a_v|`` (m/s², for
    the contact gap), ``tail`` True to follow the cylinder after the excitation."""
    p, R = cyl.p, cyl.R
    design = Design(float(cyl.r), float(cyl.h), float(G), float(p), float(R), float(cyl.alpha), float(cyl.i_h),
                    float(cyl.i_z),
                    int(settings.rim_points))
    inf = block.friction is None
    friction = Friction(0.0 if inf else float(block.friction), 0.0 if inf else float(block.friction_kinetic), inf)
    numerics = Numerics(float(dt), float(settings.theta_mj), int(max(1, round(settings.history_dtau / (p * dt)))),
                        bool(settings.smooth), int(max(1, ROLL_DTAU / (p * dt))))
    nsgs = ContactSolver(float(settings.nsgs_tol), int(settings.nsgs_max_sweeps), int(settings.nsgs_fail_steps))
    tail_dtau = DEFAULT_TAIL_DTAU if settings.max_free_time is None else settings.max_free_time * p
    limits = Limits(int(settings.step_limit), int(math.ceil(tail_dtau / (p * dt))) if tail else -1,
                    float(settings.rest_velocity * p * R), int(max(1, math.ceil(settings.rest_duration / (p * dt)))),
                    float(settings.velocity_tol * p * R), float(settings.contact_gap * (G + peak) * dt * dt),
                    float(settings.rocked_theta))
    return Model(design, friction, numerics, nsgs, limits)


def make_floor(form: int, ax: np.ndarray, ay: np.ndarray, av: np.ndarray, sub: int, n_exc: int,
               tail_av: float) -> Floor:
    """The kernel's :class:`Floor` (arrays contiguous float64, counts int); arguments as its fields."""
    return Floor(int(form), *(np.ascontiguousarray(a, dtype=np.float64) for a in (ax, ay, av)), int(sub), int(n_exc),
                 float(tail_av))


def make_workspace(n_rim: int) -> Workspace:
    """The scratch arrays for ``n_rim`` rim points."""
    return Workspace(np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((n_rim, 3)),
                     np.zeros((n_rim, 3, 3)), np.zeros((n_rim, 3)), np.zeros(n_rim), np.zeros(6), np.zeros(6),
                     np.zeros(3), np.zeros(13), np.zeros(3), np.zeros(3), np.zeros(3), np.zeros((3, 3)), np.zeros(3))


def make_roll_work() -> RollWork:
    """The scratch arrays of the smooth phase (:class:`RollWork`)."""
    return RollWork(np.zeros((4, 3, 3)), np.zeros((10, 13)))


def make_state(s0: np.ndarray) -> State:
    """The run's :class:`State` from the initial 13-float state ``s0`` (copied)."""
    track = np.zeros(T_SIZE)
    track[T_PHI] = math.nan
    track[T_LAST_N] = -1.0  # unknown: the first step's contact is no landing
    track[T_W_LAST] = math.nan
    return State(np.array(s0, dtype=np.float64), track, np.zeros(OUT_SIZE))


__all__ = ["ContactSolver", "CylinderProperties", "Design", "Floor", "Friction", "Limits", "Model", "Numerics",
           "RollWork", "State", "Workspace", "cylinder_mass", "cylinder_properties", "make_floor", "make_model", "make_roll_work", "make_state",
           "make_workspace"]
