"""The inventory: one row per item type, as loss assessors keep them (CSV, or TOML), read into
:class:`Inventory` (:func:`read_inventory`); the FEMA P-58 nine are a shipped inventory
(:func:`shipped_inventory`).

Columns (SI): ``id, description, width, depth, height`` (m; ``width`` along motion direction 1, ``depth``
along direction 2), optional ``mass`` (kg), ``cm_height`` (m), ``radius_of_gyration`` (m), ``friction``
(a number, or a distribution: its name and parameters, drawn per case from the seed and the case id),
``friction_kinetic``, ``restitution``, ``fema_id``, ``floor`` (the floors it stands on; empty: every floor
of the motions), ``quantity`` (per floor), ``support_period`` (s) and ``support_damping`` (-) for an item
standing on a desk, table or shelf, ``repair_cost``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class Support:
    """What an item stands on (a desk, a table, a shelf): a linear oscillator the floor motion goes through.

    Parameters
    ----------
    period : float
        Its natural period (s), within ``LIMITS["period"]``.
    damping : float
        Its viscous damping ratio (dimensionless), within ``LIMITS["damping"]``.
    """

    period: float
    damping: float = 0.05


@dataclass(frozen=True)
class FrictionLaw:
    """An item's friction: a fixed coefficient or a distribution drawn once per case.

    Parameters
    ----------
    distribution : str
        ``"fixed"``, or a distribution's name (e.g. ``"uniform"``, ``"lognormal"``, ``"normal"``).
    parameters : tuple of float
        ``(mu,)`` for ``"fixed"``; the distribution's parameters otherwise (dimensionless).
    kinetic_ratio : float or None
        ``mu_k / mu_s`` when the inventory gives ``friction_kinetic`` relative to a distribution; None:
        ``mu_k = mu_s``.
    """

    distribution: str
    parameters: tuple[float, ...]
    kinetic_ratio: float | None = None

    def draw(self, case_id: str, seed: int) -> float:
        """The static coefficient of one case (dimensionless), the same for the same seed and case id."""
        raise NotImplementedError


@dataclass(frozen=True)
class Item:
    """One item type of the inventory (a row).

    Parameters
    ----------
    id : str
        Unique label (letters, digits, ``_``, ``.``, ``-``); first part of its case ids.
    description : str
        What it is, for the report.
    width, depth, height : float
        Full dimensions (m): ``width`` along motion direction 1, ``depth`` along direction 2.
    mass : float or None
        Mass (kg); None: not given (rocking does not depend on it).
    cm_height, radius_of_gyration : float or None
        Mass distribution (m), as :class:`opsrock.block.Block`; None: homogeneous.
    friction : FrictionLaw or None
        None: no slip (rocking only).
    friction_kinetic : float or None
        Kinetic coefficient (dimensionless) when ``friction`` is fixed; None: equal to it.
    restitution : float or None
        ``e`` itself (dimensionless); None: the project's default ``0.95 e_R``.
    fema_id : str
        FEMA P-58 fragility ID it maps to (``E.20.22.102a``), or ``""``.
    floors : tuple of str
        Floors it stands on, as the motions name them; empty: every floor.
    quantity : float
        Units per floor (pelicun's ``Theta_0``).
    support : Support or None
        The desk, table or shelf it stands on; None: the floor itself.
    repair_cost : float or None
        Cost of one overturned unit (the inventory's currency); None: no loss assessment.
    """

    id: str
    description: str
    width: float
    depth: float
    height: float
    mass: float | None = None
    cm_height: float | None = None
    radius_of_gyration: float | None = None
    friction: FrictionLaw | None = None
    friction_kinetic: float | None = None
    restitution: float | None = None
    fema_id: str = ""
    floors: tuple[str, ...] = ()
    quantity: float = 1.0
    support: Support | None = None
    repair_cost: float | None = None


@dataclass(frozen=True)
class Inventory:
    """The items of one inventory file.

    Parameters
    ----------
    items : tuple of Item
        In file order, ids unique.
    source : str
        The file read, or ``"shipped:<name>"``.
    """

    items: tuple[Item, ...]
    source: str


def read_inventory(path: str | Path, *, confirm: bool = False) -> Inventory:
    """Read an inventory CSV or TOML file; a block larger than :data:`opsrock.limits.PLAUSIBLE` is refused
    unless ``confirm``. Raises :class:`opsrock.errors.InputError` naming the file, line, column and value."""
    raise NotImplementedError


def shipped_inventory(name: str = "fema-p58-nine") -> Inventory:
    """A shipped inventory (``fema-p58-nine``: FEMA P-58's nine unanchored contents; ``example``)."""
    raise NotImplementedError


__all__ = ["FrictionLaw", "Inventory", "Item", "Support", "read_inventory", "shipped_inventory"]
