"""The inventory: one row per item type, as loss assessors keep them (CSV, or TOML), read into
:class:`Inventory` (:func:`read_inventory`); the FEMA P-58 nine and an example are shipped inventories
(:func:`shipped_inventory`). ``docs/guide/inventory.md`` describes the file formats.

Columns (SI): ``id, description, width, depth, height`` (m; ``width`` along motion direction 1, ``depth``
along direction 2), optional ``shape`` (``box``, the default, or ``cylinder``: a round base whose ``diameter``
(m) stands in place of ``width`` and ``depth``, solved in three dimensions by ``cylinder3d``), ``mass`` (kg), ``cm_height`` (m), ``radius_of_gyration`` (m), ``friction``
(a number, or a distribution: its name and parameters, drawn per case from the seed and the case id;
:mod:`opsrock.inventory.friction`), ``friction_kinetic``, ``restitution``, ``fema_id``, ``floor`` (the floors
it stands on, separated by ``;``; empty: every floor of the motions), ``quantity`` (per floor),
``support_period`` (s) and ``support_damping`` (-) for an item standing on a desk, table or shelf,
``repair_cost`` (per overturned unit), ``slide_distance`` (m: the item counts as displaced once it slides
that far; default the study's) and ``slide_cost`` (per unit displaced but not overturned).

A CSV file has a header row naming its columns (any order, any case, spaces trimmed), then one row per item;
lines starting with ``#`` are comments, blank lines and blank cells are allowed (a blank optional cell takes
its default), UTF-8 with or without a byte-order mark. A TOML file has one ``[[item]]`` table per item with
the same keys (``floor`` a string or an array). Every value is checked as the block it makes
(:class:`opsrock.block.Block`, in each direction) and a dimension beyond
:data:`opsrock.limits.PLAUSIBLE` ``"block_size"`` is refused as a likely unit mistake unless confirmed;
every error is one line naming the file, the line, the column and the value (:class:`TableFileError`).
"""

from __future__ import annotations

import csv
import dataclasses
import io
import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from opsrock import data
from opsrock._files import atomic_text
from opsrock.block import Block
from opsrock.campaign.toml import NAME_PATTERN
from opsrock.constants import DEFAULT_RESTITUTION_FACTOR
from opsrock.errors import MISSING, InputError, OpsrockError
from opsrock.inventory.friction import FrictionLaw, parse_friction
from opsrock.inventory.readers import (LIST_SEPARATOR, Row, TableFileError, number_cell, read_csv_rows,
                                      read_toml_rows, text_cell)
from opsrock.limits import LIMITS, check, check_count, check_plausible, positive_finite
from opsrock.published import fema_p58

#: The horizontal directions of the floor motions: ``Item.width`` lies along ``"1"``, ``Item.depth`` along
#: ``"2"``.
DIRECTIONS: tuple[str, ...] = ("1", "2")

#: The inventory's columns, in the order :func:`write_inventory` writes them.
COLUMNS: tuple[str, ...] = ("id", "description", "width", "depth", "height", "mass", "cm_height",
                            "radius_of_gyration", "friction", "friction_kinetic", "restitution", "fema_id", "floor",
                            "quantity", "support_period", "support_damping", "repair_cost", "slide_distance",
                            "slide_cost", "shape", "diameter")

#: The columns every inventory has (a box's row needs ``width`` and ``depth`` too, a cylinder's ``diameter``).
REQUIRED: tuple[str, ...] = ("id", "description", "height")

#: The shapes of an item's base (``shape``): a box (``width`` x ``depth``) or a cylinder (``diameter``).
SHAPES: tuple[str, ...] = ("box", "cylinder")

#: Separator of several floors in one cell (``1;2;roof``).
FLOOR_SEPARATOR: str = LIST_SEPARATOR

def _argued(name: str, fn: Callable[..., Any], *args: Any, **kwargs: Any) -> Any:
    """``fn(*args, **kwargs)``, an error of it re-raised with ``argument`` ``name`` (the checks of
    :mod:`opsrock.limits` name the value, not always the argument)."""
    try:
        return fn(*args, **kwargs)
    except OpsrockError as exc:
        raise InputError(str(exc), argument=name) from None


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

    def __post_init__(self) -> None:
        object.__setattr__(self, "period", _argued("support_period", check, "period", self.period,
                                                   shown_as="support_period"))
        object.__setattr__(self, "damping", _argued("support_damping", check, "damping", self.damping,
                                                    shown_as="support_damping"))


@dataclass(frozen=True)
class Item:
    """One item type of the inventory (a row); checked when made, as the block it makes in each direction.

    Parameters
    ----------
    id : str
        Unique label (letters, digits, ``_``, ``.``, ``-``); first part of its case ids.
    description : str
        What it is, for the report (not empty).
    width, depth, height : float
        Full dimensions (m): ``width`` along motion direction 1, ``depth`` along direction 2.
    mass : float or None
        Mass (kg); None: not given (rocking does not depend on it).
    cm_height, radius_of_gyration : float or None
        Mass distribution (m), as :class:`opsrock.block.Block`, the same in both directions; None: homogeneous.
    friction : FrictionLaw or None
        None: no slip (rocking only).
    friction_kinetic : float or None
        Kinetic coefficient (dimensionless): of the fixed coefficient, or at the distribution's median (each draw
        then scales it, ``FrictionLaw.kinetic_ratio``, set here); None: equal to the static one.
    restitution : float or None
        ``e`` itself (dimensionless); None: the project's default ``0.95 e_R`` (or the study's factor).
    fema_id : str
        FEMA P-58 fragility ID it maps to, one of :data:`opsrock.published.fema_p58.ITEMS` (``E.20.22.102a``),
        or ``""``.
    floors : tuple of str
        Floors it stands on, as the motions name them; empty: every floor.
    quantity : float
        Units per floor (pelicun's ``Theta_0``), positive.
    support : Support or None
        The desk, table or shelf it stands on; None: the floor itself.
    repair_cost : float or None
        Cost of one overturned unit (the inventory's currency), >= 0; None: no loss assessment.
    slide_distance : float or None
        Sliding (or rolling, on casters) beyond it (m) displaces the item: the damage state below overturning
        where friction is modelled; None: the study's ``slide_distance``.
    slide_cost : float or None
        Cost of one unit displaced but not overturned (the inventory's currency), >= 0, with ``repair_cost``;
        None: not priced (0).
    shape : str
        ``"box"`` (the default) or ``"cylinder"``: a round base of diameter ``width`` (``depth`` equal to it), whose
        planar block has a homogeneous solid cylinder's ``cm_height`` and ``radius_of_gyration`` unless given, and
        which the study in three dimensions solves with ``cylinder3d``.
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
    slide_distance: float | None = None
    slide_cost: float | None = None
    shape: str = "box"

    def __post_init__(self) -> None:
        if self.shape not in SHAPES:
            raise InputError(f"shape of item {self.id!r} must be one of {', '.join(SHAPES)}, got {self.shape!r}",
                             argument="shape")
        if self.shape == "cylinder" and self.depth != self.width:
            raise InputError(f"item {self.id!r} is a cylinder: its diameter stands for width and depth, got width = "
                             f"{self.width!r}, depth = {self.depth!r}", argument="diameter")
        if not isinstance(self.id, str) or not NAME_PATTERN.match(self.id):
            raise InputError(f"id = {self.id!r} must use only letters, digits, '_', '.', '-'", argument="id")
        if not isinstance(self.description, str) or not self.description.strip():
            raise InputError(f"description of item {self.id!r} must be a non-empty string", argument="description")
        for name in ("width", "depth", "height"):
            limit = "height" if name == "height" else "width"
            object.__setattr__(self, name, _argued(name, check, limit, getattr(self, name), shown_as=name))
        if self.mass is not None:
            object.__setattr__(self, "mass", _argued("mass", check, "mass", self.mass))
        self._check_friction()
        object.__setattr__(self, "fema_id", _fema_id(self.fema_id))
        object.__setattr__(self, "floors", _floors(self.floors))
        object.__setattr__(self, "quantity", _argued("quantity", positive_finite, "quantity", self.quantity))
        if self.support is not None and not isinstance(self.support, Support):
            raise InputError(f"support must be a Support or None, got {self.support!r}", argument="support_period")
        if self.repair_cost is not None:
            cost = _argued("repair_cost", check_nonnegative, "repair_cost", self.repair_cost)
            object.__setattr__(self, "repair_cost", cost)
        if self.slide_cost is not None:
            object.__setattr__(self, "slide_cost", _argued("slide_cost", check_nonnegative, "slide_cost", self.slide_cost))
            if self.repair_cost is None:
                raise InputError(f"item {self.id!r} prices a displaced unit (slide_cost) but not an overturned one: give "
                                 "its repair_cost too (without it, the loss would count an overturned unit as costing "
                                 "nothing)", argument="slide_cost")
        if self.slide_distance is not None:
            value = self.slide_distance
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
                raise InputError(f"slide_distance of item {self.id!r} must be a positive distance (m), got {value!r}",
                                 argument="slide_distance")
            object.__setattr__(self, "slide_distance", float(value))
        for direction in DIRECTIONS:
            self.planar_block(direction)  # the Block's own checks, in both directions

    def _check_friction(self) -> None:
        law = self.friction
        if law is not None and not isinstance(law, FrictionLaw):
            raise InputError(f"friction must be a FrictionLaw or None, got {law!r}", argument="friction")
        if self.friction_kinetic is None or law is None or law.fixed:
            return  # a fixed pair is the Block's to check; a kinetic coefficient without friction too
        mu_k = _argued("friction_kinetic", check, "friction_kinetic", self.friction_kinetic)
        if mu_k > law.median:
            raise InputError(f"friction_kinetic = {mu_k!r} exceeds the median static friction {law.median:.6g} of "
                             f"{law.text}: the kinetic coefficient must not exceed the static one",
                             argument="friction_kinetic")
        ratio = mu_k / law.median
        if law.kinetic_ratio is None:
            object.__setattr__(self, "friction", dataclasses.replace(law, kinetic_ratio=ratio))
        elif not math.isclose(law.kinetic_ratio, ratio, rel_tol=1e-9):
            raise InputError(f"friction_kinetic = {mu_k!r} at the median friction {law.median:.6g} gives the ratio "
                             f"{ratio:.6g}, but the friction law says {law.kinetic_ratio!r}", argument="friction_kinetic")

    # --- the planar blocks --------------------------------------------------------------------------
    def dimension(self, direction: str) -> float:
        """The base dimension along the motion of ``direction`` (m): ``width`` along ``"1"``, ``depth`` along
        ``"2"``."""
        if direction not in DIRECTIONS:
            raise InputError(f"direction = {direction!r} must be one of {', '.join(DIRECTIONS)}", argument="direction")
        return self.width if direction == "1" else self.depth

    def planar_block(self, direction: str, restitution_factor: float = DEFAULT_RESTITUTION_FACTOR) -> Block:
        """The rigid block that rocks and slides in the plane of ``direction`` (``"1"`` or ``"2"``), with the
        median friction of a distribution (:func:`opsrock.inventory.campaigns.item_block_spec` draws it per case).

        Parameters
        ----------
        direction : str
            ``"1"``: ``width`` along the motion; ``"2"``: ``depth`` along it.
        restitution_factor : float
            ``e / e_R`` (dimensionless) when the item gives no ``restitution`` of its own.

        Raises
        ------
        InputError
            The Block's refusal, with the direction when the base dimension matters, ``argument`` the column.
        """
        base = self.dimension(direction)
        law = self.friction
        mu = None if law is None else (law.parameters[0] if law.fixed else law.median)
        mu_k = self.friction_kinetic if law is None or law.fixed else law.kinetic(mu)
        try:
            return Block(width=base, height=self.height, mass=1.0 if self.mass is None else self.mass,
                         restitution_factor=DEFAULT_RESTITUTION_FACTOR if self.restitution is not None
                         else restitution_factor, name=self.id, restitution=self.restitution, friction=mu,
                         friction_kinetic=mu_k, **self.mass_distribution())
        except OpsrockError as exc:
            if exc.argument not in _PLANAR:  # the same in both directions: the column is the argument
                raise InputError(str(exc), argument=exc.argument) from None
            column = "depth" if direction == "2" and exc.argument in (None, "width") else (exc.argument or "width")
            along = "width" if direction == "1" else "depth"
            raise InputError(f"{exc} (direction {direction}: {along} {base:g} m along the motion)",
                             argument=column) from None

    def mass_distribution(self) -> dict[str, float | None]:
        """``cm_height`` and ``radius_of_gyration`` (m) of the item's blocks: as given; a cylinder's blank ones a
        homogeneous solid cylinder's (:func:`opsrock.solvers.cylinder3d.model.cylinder_mass`), so that its planar
        block rocks as the cylinder in a vertical plane through its axis; a box's blank ones None (homogeneous)."""
        given = {"cm_height": self.cm_height, "radius_of_gyration": self.radius_of_gyration}
        if self.shape != "cylinder":
            return given
        from opsrock.solvers.cylinder3d.model import cylinder_mass

        return {**cylinder_mass(self.width, self.height), **{k: v for k, v in given.items() if v is not None}}

    def floors_in(self, available: tuple[str, ...] | list[str]) -> tuple[str, ...]:
        """The floors of ``available`` (the motions' floors, in their order) this item stands on: all of them
        when :attr:`floors` is empty. Raises ``InputError`` naming the item and a floor not available."""
        if not self.floors:
            return tuple(available)
        missing = [f for f in self.floors if f not in available]
        if missing:
            raise InputError(f"item {self.id!r}: floor {missing[0]!r} is not among the motions' floors "
                             f"({', '.join(available)})", argument="floor")
        return tuple(f for f in available if f in self.floors)


#: Arguments of a Block's refusal that depend on the base along the motion (the direction is then named).
_PLANAR = frozenset({None, "width", "radius_of_gyration", "restitution_factor"})


def check_nonnegative(name: str, value: object) -> float:
    """``value`` as a float if it is a finite number >= 0; ``InputError`` naming ``name`` otherwise."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (math.isfinite(value) and value >= 0):
        raise InputError(f"{name} must be a finite number >= 0, got {value!r}", argument=name)
    return float(value)


def _fema_id(value: object) -> str:
    if not isinstance(value, str):
        raise InputError(f"fema_id must be a string, got {value!r}", argument="fema_id")
    if value:
        _argued("fema_id", fema_p58.item, value)
    return value


def _floors(value: object) -> tuple[str, ...]:
    if isinstance(value, str) or not isinstance(value, (tuple, list)):
        raise InputError(f"floors must be a tuple of floor labels, got {value!r}", argument="floor")
    floors = tuple(value)
    for f in floors:
        if not isinstance(f, str) or not NAME_PATTERN.match(f):
            raise InputError(f"floor {f!r} must use only letters, digits, '_', '.', '-'", argument="floor")
    if len(set(floors)) != len(floors):
        raise InputError(f"floor lists {next(f for f in floors if floors.count(f) > 1)!r} twice", argument="floor")
    return floors


@dataclass(frozen=True)
class Inventory:
    """The items of one inventory file.

    Parameters
    ----------
    items : tuple of Item
        In file order, ids unique, at least one.
    source : str
        The file read, or ``"shipped:<name>"``.
    """

    items: tuple[Item, ...]
    source: str

    def __post_init__(self) -> None:
        items = tuple(self.items)
        if not items:
            raise InputError(f"inventory {self.source}: no items", argument="inventory")
        ids = [it.id for it in items]
        seen: set[str] = set()
        dup = next((i for i in ids if i in seen or seen.add(i)), None)  # one pass (list.count: 100,000 rows took
        # minutes)
        if dup is not None:
            raise InputError(f"inventory {self.source}: id {dup!r} is used twice", argument="id")
        object.__setattr__(self, "items", items)

    @property
    def ids(self) -> tuple[str, ...]:
        """The item ids, in file order."""
        return tuple(it.id for it in self.items)

    def item(self, item_id: str) -> Item:
        """The item ``item_id``; ``KeyError`` if none."""
        for it in self.items:
            if it.id == item_id:
                return it
        raise KeyError(f"no item {item_id!r} in {self.source} (items: {', '.join(self.ids)})")


# --- cells to values ------------------------------------------------------------------------------
def floors_cell(value: Any) -> tuple[str, ...]:
    """A ``floor`` cell's floors: labels separated by ``;`` (spaces trimmed), or one TOML integer."""
    if isinstance(value, int) and not isinstance(value, bool):
        return (str(value),)
    return tuple(f.strip() for f in text_cell(value).split(FLOOR_SEPARATOR))


def _friction(row: Row) -> FrictionLaw | None:
    if "friction" not in row.cells:
        return None
    value = row.cells["friction"][0]
    if isinstance(value, str):
        return parse_friction(value)
    return FrictionLaw("fixed", (number_cell(value),))


def quantity_cell(value: Any) -> float:
    """A ``quantity`` cell: a whole number of units (the inventory counts items; pelicun's ``Theta_0`` of an
    ``EA`` component), from 1 to ``LIMITS["quantity"].high``."""
    v = number_cell(value)
    if v != math.floor(v):
        raise InputError("is not a whole number of units (the inventory counts items)")
    return check_count("quantity", int(v)) * 1.0


#: How each column's cell becomes an :class:`Item` argument: (argument, parser).
_PARSERS: dict[str, tuple[str, Callable[[Any], Any]]] = {
    "id": ("id", text_cell), "description": ("description", text_cell), "width": ("width", number_cell),
    "depth": ("depth", number_cell), "height": ("height", number_cell), "mass": ("mass", number_cell),
    "cm_height": ("cm_height", number_cell), "radius_of_gyration": ("radius_of_gyration", number_cell),
    "friction_kinetic": ("friction_kinetic", number_cell), "restitution": ("restitution", number_cell),
    "fema_id": ("fema_id", text_cell), "quantity": ("quantity", quantity_cell),
    "floor": ("floors", floors_cell),
    "repair_cost": ("repair_cost", number_cell), "slide_distance": ("slide_distance", number_cell),
    "slide_cost": ("slide_cost", number_cell), "shape": ("shape", text_cell),
}


def _item(path: Path, row: Row, confirm: bool) -> Item:
    """The :class:`Item` of one row; every error names the file, the line, the column and the value."""
    for column in REQUIRED:
        if column not in row.cells:
            raise TableFileError(path, row.line, column, MISSING, "blank: every item needs it")
    cylinder = row.cells.get("shape", ("box", 0))[0] == "cylinder"
    for column in (("diameter",) if cylinder else ("width", "depth")):
        if column not in row.cells:
            raise TableFileError(path, row.line, column, MISSING,
                                 "blank: a cylinder needs its diameter" if cylinder else
                                 "blank: a box needs its width and depth (a round base: shape cylinder, diameter)")
    for column in (("width", "depth") if cylinder else ("diameter",)):
        if column in row.cells:
            value, line = row.cells[column]
            raise TableFileError(path, line, column, value, "a cylinder has a diameter in place of width and depth"
                                 if cylinder else "diameter is a cylinder's (shape cylinder); a box has width and depth")
    kwargs: dict[str, Any] = {}
    for column, (value, line) in row.cells.items():
        if column in _PARSERS:
            arg, parse = _PARSERS[column]
            try:
                if row.typed and parse is number_cell and isinstance(value, str):
                    raise InputError("must be a number, not str")
                kwargs[arg] = parse(value)
            except OpsrockError as exc:
                raise TableFileError(path, line, column, value, str(exc)) from None
    if cylinder:
        kwargs["width"] = kwargs["depth"] = _argued("diameter", number_cell, row.cells["diameter"][0])
    for column in ("diameter", "height") if cylinder else ("width", "depth", "height"):
        value, line = row.cells[column]
        check_plausible("block_size", kwargs["width" if column == "diameter" else column],
                        what=f"{path} line {line}: {column}", option="--accept-implausible", confirm=confirm)
    try:
        kwargs["friction"] = _friction(row)
        kwargs["support"] = _support(row)
        return Item(**kwargs)
    except OpsrockError as exc:
        column = _column_of(exc.argument, row)
        value, line = row.cells.get(column, (MISSING, row.line))
        raise TableFileError(path, line, column, value, str(exc)) from None


def _support(row: Row) -> Support | None:
    cells = row.cells
    if "support_period" not in cells:
        if "support_damping" in cells:
            raise InputError("support_damping needs support_period (the desk's or table's period)",
                             argument="support_damping")
        return None
    period = _argued("support_period", number_cell, cells["support_period"][0])
    if "support_damping" not in cells:
        return Support(period)
    return Support(period, _argued("support_damping", number_cell, cells["support_damping"][0]))


def _column_of(argument: str | None, row: Row) -> str:
    """The inventory column an error's ``argument`` names (the row's first given one when it names none)."""
    column = {"floors": "floor", "support": "support_period"}.get(argument or "", argument or "")
    if column in COLUMNS:
        return column
    return next(iter(row.cells))


# --- the public readers and writer ------------------------------------------------------------------
def read_inventory(path: str | Path, *, confirm: bool = False) -> Inventory:
    """Read an inventory CSV or TOML file (``.toml``: TOML; anything else: CSV).

    Parameters
    ----------
    path : str or Path
        The file (formats: the module docstring, ``docs/guide/inventory.md``).
    confirm : bool
        True: dimensions beyond :data:`opsrock.limits.PLAUSIBLE` ``"block_size"`` are accepted (the user
        confirmed them, ``--accept-implausible``).

    Raises
    ------
    TableFileError
        Naming the file, the line, the column and the value (an :class:`opsrock.errors.InputError`).
    ImplausibleInputError
        A dimension beyond 10 m, with its likely unit.
    """
    path = Path(path)
    if path.suffix.lower() == ".toml":
        rows = read_toml_rows(path, "item", COLUMNS, REQUIRED)
    else:
        rows = read_csv_rows(path, COLUMNS, REQUIRED)
    if len(rows) > LIMITS["inventory_items"].high:
        raise TableFileError(path, None, None, MISSING, f"{len(rows):,} items, more than the "
                             f"{LIMITS['inventory_items'].high:,.0f} an inventory may hold: "
                             f"{LIMITS['inventory_items'].why}")
    items: list[Item] = []
    seen: dict[str, int] = {}
    for row in rows:
        item = _item(path, row, confirm)
        if item.id in seen:
            raise TableFileError(path, row.cells["id"][1], "id", item.id, f"used twice (first on line {seen[item.id]})")
        seen[item.id] = row.cells["id"][1]
        items.append(item)
    return Inventory(tuple(items), str(path))


def item_cells(item: Item) -> dict[str, Any]:
    """The non-blank cells of ``item``'s row (column -> value: str, float), as :func:`write_inventory` writes
    them; reading them back gives the same item."""
    law = item.friction
    cells: dict[str, Any] = {
        "id": item.id, "description": item.description, "width": item.width, "depth": item.depth,
        "height": item.height, "mass": item.mass, "cm_height": item.cm_height,
        "radius_of_gyration": item.radius_of_gyration,
        "friction": None if law is None else (law.parameters[0] if law.fixed else law.text),
        "friction_kinetic": item.friction_kinetic, "restitution": item.restitution, "fema_id": item.fema_id or None,
        "floor": FLOOR_SEPARATOR.join(item.floors) or None, "quantity": item.quantity,
        "support_period": None if item.support is None else item.support.period,
        "support_damping": None if item.support is None else item.support.damping,
        "repair_cost": item.repair_cost, "slide_distance": item.slide_distance, "slide_cost": item.slide_cost,
    }
    if item.shape == "cylinder":
        cells.update(width=None, depth=None, shape="cylinder", diameter=item.width)
    return {k: v for k, v in cells.items() if v is not None}


def write_inventory(inventory: Inventory, path: str | Path) -> Path:
    """Write ``inventory`` to ``path`` (``.toml``: TOML, else CSV) so that :func:`read_inventory` reads it back
    equal: every float at full precision (``repr``). Written atomically (whole or not at all)."""
    path = Path(path)
    rows = [item_cells(it) for it in inventory.items]
    if path.suffix.lower() == ".toml":
        text = "".join("[[item]]\n" + "".join(f"{k} = {_toml_value(v)}\n" for k, v in row.items()) + "\n"
                       for row in rows)
    else:
        columns = [c for c in COLUMNS if any(c in row for row in rows)]
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow(columns)
        writer.writerows([_csv_value(row.get(c)) for c in columns] for row in rows)
        text = buf.getvalue()
    atomic_text(path, text)
    return path


def _toml_value(value: Any) -> str:
    return json.dumps(value, ensure_ascii=False) if isinstance(value, str) else repr(float(value))


def _csv_value(value: Any) -> str:
    return "" if value is None else (value if isinstance(value, str) else repr(float(value)))


#: The shipped inventories: name -> what it holds.
SHIPPED: dict[str, str] = {
    "fema-p58-nine": "FEMA P-58's nine unanchored contents that overturn (the fema-p58-contents blocks library)",
    "example": "an example office: a low cabinet that slides, a loaded bookcase, server racks, a printer on a desk",
}


def shipped_inventory(name: str = "fema-p58-nine") -> Inventory:
    """A shipped inventory (:data:`SHIPPED`: ``fema-p58-nine``, FEMA P-58's nine unanchored contents;
    ``example``), read from ``opsrock/data/inventories/<name>.csv`` (its ``.md`` gives every number's source).

    Raises
    ------
    InputError
        ``name`` is not shipped (``argument`` ``"inventory"``).
    """
    try:
        path = data.inventory_file(name)
    except KeyError as exc:
        raise InputError(str(exc.args[0]), argument="inventory") from None
    inventory = read_inventory(path)
    return dataclasses.replace(inventory, source=f"shipped:{name}")


__all__ = ["COLUMNS", "DIRECTIONS", "FLOOR_SEPARATOR", "FrictionLaw", "Inventory", "Item", "REQUIRED", "SHIPPED",
           "Support", "check_nonnegative", "floors_cell", "item_cells", "read_inventory", "shipped_inventory",
           "write_inventory"]
