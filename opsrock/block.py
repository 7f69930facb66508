"""The freestanding rectangular rigid block (paper Section 2.1, Figure 1)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from opsrock.constants import DEFAULT_RESTITUTION_FACTOR, G
from opsrock.errors import InputError, InputTypeError
from opsrock.limits import LIMITS, check, positive_finite, real_number


@dataclass(frozen=True)
class Block:
    """A rectangular block of full width ``2b`` and full height ``2h``, homogeneous unless ``cm_height`` or
    ``radius_of_gyration`` say otherwise.

    Parameters
    ----------
    width : float
        Full base width ``2b`` (m), within :data:`opsrock.limits.LIMITS`.
    height : float
        Full height ``2h`` (m), within :data:`opsrock.limits.LIMITS`.
    mass : float, optional
        Mass ``m`` (kg). Rocking of a rigid block does not depend on it; it scales the
        moments and forces reported by the OpenSees model. Default 1 kg.
    restitution_factor : float, optional
        ``e / e_R``, the ratio of the restitution coefficient used to Housner's rigid-body
        value (dimensionless, > 0, with ``e = restitution_factor · e_R <= 1``; without effect on a block with
        ``e_R <= 0``, which lands flat, ``e = 0``). Default 0.95, the paper's
        choice; measured free rocking of limestone blocks gives about 1 (validation case
        ``experiments``), with scatter on both sides.
    name : str, optional
        Label used in tables and figures.
    restitution : float or None, optional
        The restitution coefficient ``e`` itself (dimensionless, in (0, 1]), as the rocking
        literature sets it (e.g. ``e = 0.9``), instead of ``restitution_factor · e_R``. Give one of
        the two: with ``restitution`` set, ``restitution_factor`` must keep its default. Default
        None (``e = restitution_factor · e_R``, or 0 for a block with ``e_R <= 0``, which lands flat).
    friction : float or None, optional
        Static Coulomb friction coefficient ``mu`` between the block's base and the floor
        (dimensionless, within :data:`opsrock.limits.LIMITS`). Default None: the base never slips
        (the no-slip rocking of every solver but ``friction`` and ``moreau_jean``, which then take
        ``mu`` as infinite).
    friction_kinetic : float or None, optional
        Kinetic coefficient ``mu_k <= mu`` (dimensionless, below 4/3) used while the base slips.
        Default None: ``mu_k = mu``, or infinite without ``friction``.
    cm_height : float or None, optional
        Height of the centre of mass above the base (m), in ``(0, height]``. Default None: mid-height,
        ``h = height / 2`` (a homogeneous block). A loaded bookcase or a rack with its batteries low has it
        lower.
    radius_of_gyration : float or None, optional
        Radius of gyration ``r`` about the centre of mass for rotation in the plane of the motion (m), so
        that ``I_cm = m r²``. Default None: a homogeneous block's, ``r² = (width² + height²) / 12``.
    depth : float or None, optional
        Full base depth ``2d`` (m), across the plane of ``width`` and ``height``, within
        :data:`opsrock.limits.LIMITS` (as ``width``). Default None: a planar block (every planar solver ignores
        the depth; the three-dimensional solver ``rigid3d`` needs it).

    Notes
    -----
    Derived quantities follow docs/guide/modelling.md section 2, with ``h`` the height of the centre of mass
    (:attr:`h_cm`): ``R = sqrt(b² + h²)``, ``alpha = atan(b / h)``, ``I_O = m (r² + R²)``,
    ``p = sqrt(m g R / I_O)``, ``e_R = 1 - 2 m b² / I_O`` (angular momentum about the new pivot kept
    through the impact). For a homogeneous block these are the paper's ``p = sqrt(3 g / 4 R)``,
    ``I_O = 4/3 m R²`` and ``e_R = 1 - 1.5 sin²(alpha)`` (Eq. 9); ``e = restitution_factor · e_R`` (or
    ``restitution``).

    A block with ``e_R <= 0`` (homogeneous: width/height >= sqrt(2), a desk, a crate) is a valid block: after
    an impact the angular momentum about the striking corner would turn it the wrong way (into the floor),
    so it lands flat and stops rocking, ``e = 0`` unless ``restitution`` says otherwise (docs/guide/modelling.md,
    "Wide blocks"). With friction
    ``mu < tan(alpha)`` it slides before it can uplift and never rocks under horizontal floor motion.
    """

    width: float
    height: float
    mass: float = 1.0
    restitution_factor: float = DEFAULT_RESTITUTION_FACTOR
    name: str = ""
    restitution: float | None = None
    friction: float | None = None
    friction_kinetic: float | None = None
    cm_height: float | None = None
    radius_of_gyration: float | None = None
    depth: float | None = None

    def __post_init__(self) -> None:
        self._check_friction()
        object.__setattr__(self, "width", check("width", self.width))
        if self.depth is not None:
            object.__setattr__(self, "depth", check("width", self.depth, shown_as="depth"))
        object.__setattr__(self, "height", check("height", self.height))
        object.__setattr__(self, "mass", check("mass", self.mass))
        self._check_mass_distribution()
        f = positive_finite("restitution_factor", self.restitution_factor)
        object.__setattr__(self, "restitution_factor", f)
        if not isinstance(self.name, str):
            raise InputTypeError(f"name must be a string, got {self.name!r}")
        if self.restitution is not None:
            e = real_number("restitution", self.restitution)
            if not (math.isfinite(e) and 0.0 < e <= 1.0):
                raise InputError(f"restitution must lie in (0, 1], got {self.restitution!r}", argument="restitution")
            object.__setattr__(self, "restitution", e)
            if f != DEFAULT_RESTITUTION_FACTOR:
                raise InputError(f"give restitution or restitution_factor, not both (restitution = {e!r}, "
                                 f"restitution_factor = {f!r})", argument="restitution")
            return
        if self.e_R > 0.0 and f * self.e_R > 1.0 + 1e-12:
            raise InputError(f"restitution_factor must lie in (0, 1/e_R] = (0, {1.0 / self.e_R:.6g}] for this block "
                             f"(e = restitution_factor · e_R <= 1), got {f!r}", argument="restitution_factor")

    def _check_friction(self) -> None:
        """Range-check ``friction`` and ``friction_kinetic``; ``mu_k`` defaults to ``mu``."""
        if self.friction is None:
            if self.friction_kinetic is not None:
                raise InputError(f"friction_kinetic = {self.friction_kinetic!r} needs friction (the static "
                                 "coefficient) too", argument="friction_kinetic")
            return
        mu = check("friction", self.friction)
        object.__setattr__(self, "friction", mu)
        if self.friction_kinetic is None:
            mu_k = mu if mu <= LIMITS["friction_kinetic"].high else None
            if mu_k is None:
                raise InputError(f"friction = {mu!r} needs friction_kinetic (at most "
                                 f"{LIMITS['friction_kinetic'].high:g}, the slide-rock equations' bound); give it "
                                 "explicitly", argument="friction")
        else:
            mu_k = check("friction_kinetic", self.friction_kinetic)
            if mu_k > mu:
                raise InputError(f"friction_kinetic = {mu_k!r} exceeds friction = {mu!r}: the kinetic "
                                 "coefficient must not exceed the static one", argument="friction_kinetic")
        object.__setattr__(self, "friction_kinetic", mu_k)

    def _check_mass_distribution(self) -> None:
        """Range-check ``cm_height`` (in ``(0, height]``) and ``radius_of_gyration`` (positive, at most the
        distance from the centre of mass to the farthest corner: all the mass there)."""
        if self.cm_height is not None:
            hc = real_number("cm_height", self.cm_height)
            if not (math.isfinite(hc) and 0.0 < hc <= self.height):
                raise InputError(f"cm_height must lie in (0, height] = (0, {self.height:g}] m, got {self.cm_height!r}",
                                 argument="cm_height")
            object.__setattr__(self, "cm_height", hc)
        if self.radius_of_gyration is not None:
            r = real_number("radius_of_gyration", self.radius_of_gyration)
            far = math.hypot(self.b, max(self.h_cm, self.height - self.h_cm))
            if not (math.isfinite(r) and 0.0 < r <= far):
                raise InputError(f"radius_of_gyration must lie in (0, {far:.6g}] m (all the mass at the corner "
                                 f"farthest from the centre of mass), got {self.radius_of_gyration!r}",
                                 argument="radius_of_gyration")
            object.__setattr__(self, "radius_of_gyration", r)

    @property
    def homogeneous(self) -> bool:
        """True if the block has a homogeneous block's mass distribution (neither ``cm_height`` nor
        ``radius_of_gyration`` given)."""
        return self.cm_height is None and self.radius_of_gyration is None

    @property
    def slips(self) -> bool:
        """True if the block has a finite friction coefficient (its base may slide)."""
        return self.friction is not None

    # --- geometry -----------------------------------------------------------------------
    @property
    def b(self) -> float:
        """Half-width ``b`` (m)."""
        return 0.5 * self.width

    @property
    def d(self) -> float:
        """Half-depth ``d`` (m); ``nan`` for a planar block (``depth`` None)."""
        return math.nan if self.depth is None else self.depth / 2.0

    @property
    def alpha_depth(self) -> float:
        """Slenderness across the depth, ``atan(d / h)`` (rad, ``h`` the height of the centre of mass); ``nan``
        for a planar block."""
        return math.atan2(self.d, self.h_cm) if self.depth is not None else math.nan

    @property
    def h(self) -> float:
        """Half-height ``h`` (m)."""
        return 0.5 * self.height

    @property
    def h_cm(self) -> float:
        """Height of the centre of mass above the base (m): ``cm_height``, or ``h`` for a homogeneous block."""
        return self.h if self.cm_height is None else self.cm_height

    @property
    def r_gyration(self) -> float:
        """Radius of gyration about the centre of mass (m): ``radius_of_gyration``, or a homogeneous block's
        ``sqrt((b² + h²) / 3)``."""
        if self.radius_of_gyration is not None:
            return self.radius_of_gyration
        return math.sqrt((self.b**2 + self.h**2) / 3.0)

    @property
    def R(self) -> float:  # noqa: N802  (the paper's symbol)
        """Size parameter ``R = sqrt(b² + h_cm²)`` (m): pivot to centre of mass."""
        return math.hypot(self.b, self.h_cm)

    @property
    def alpha(self) -> float:
        """Slenderness ``alpha = atan(b / h_cm)`` (rad)."""
        return math.atan2(self.b, self.h_cm)

    @property
    def tan_alpha(self) -> float:
        """``tan(alpha) = b / h_cm`` (dimensionless)."""
        return self.b / self.h_cm

    # --- dynamics -----------------------------------------------------------------------
    @property
    def p(self) -> float:
        """Frequency parameter ``p = sqrt(m g R / I_O)`` (rad/s); ``sqrt(3 g / 4 R)`` for a homogeneous block."""
        if self.homogeneous:
            return math.sqrt(3.0 * G / (4.0 * self.R))
        return math.sqrt(G * self.R / (self.r_gyration**2 + self.R**2))

    @property
    def I_O(self) -> float:  # noqa: N802
        """Moment of inertia about a pivot corner, ``m (r² + R²)`` (kg m²); ``4/3 m R²`` for a homogeneous block."""
        if self.homogeneous:
            return 4.0 / 3.0 * self.mass * self.R**2
        return self.mass * (self.r_gyration**2 + self.R**2)

    @property
    def e_R(self) -> float:  # noqa: N802
        """Housner's rigid-body restitution coefficient ``1 - 2 m b² / I_O``: ``1 - 1.5 sin²(alpha)`` (Eq. 9)
        for a homogeneous block."""
        if self.homogeneous:
            return 1.0 - 1.5 * math.sin(self.alpha) ** 2
        return 1.0 - 2.0 * self.b**2 / (self.r_gyration**2 + self.R**2)

    @property
    def lands_flat(self) -> bool:
        """True if Housner's ``e_R <= 0`` (a homogeneous block with width/height >= sqrt(2)): the angular momentum
        about the striking corner leaves no rotation about it, so an impact lands the block flat (``e = 0``)."""
        return self.e_R <= 0.0

    @property
    def e(self) -> float:
        """Restitution coefficient used, ``restitution`` if set, else ``restitution_factor · e_R``, or 0 for a block
        that lands flat (:attr:`lands_flat`) (dimensionless)."""
        if self.restitution is not None:
            return self.restitution
        return 0.0 if self.lands_flat else self.restitution_factor * self.e_R

    @property
    def uplift_acceleration(self) -> float:
        """Floor acceleration needed to uplift the block from rest, ``g tan(alpha)`` (m/s², Eq. 4)."""
        return G * self.tan_alpha

    @property
    def onset_acceleration(self) -> float:
        """Horizontal floor acceleration at which the block first moves from rest on a still vertical floor
        (m/s²): ``g min(tan(alpha), mu)`` with friction (it slides first where ``mu < tan(alpha)``), else the
        uplift acceleration ``g tan(alpha)``."""
        if self.friction is None:
            return self.uplift_acceleration
        return G * min(self.tan_alpha, self.friction)

    @property
    def overturning_rotation_moment(self) -> float:
        """Peak restoring moment ``m g R sin(alpha)`` (N m), at ``theta = 0±``."""
        return self.mass * G * self.R * math.sin(self.alpha)

    def describe(self) -> dict[str, float | str]:
        """Return the block's inputs and derived quantities as a flat dict (SI units)."""
        return {
            "name": self.name,
            "width": self.width,
            "height": self.height,
            "mass": self.mass,
            "alpha": self.alpha,
            "R": self.R,
            "p": self.p,
            "e_R": self.e_R,
            "e": self.e,
            "friction": self.friction,
            "friction_kinetic": self.friction_kinetic,
            "cm_height": self.h_cm,
            "radius_of_gyration": self.r_gyration,
            "depth": self.depth,
        }
