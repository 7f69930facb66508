"""What a contents study computes: the building and its floors, the records, the IDA levels, the
items and the model variants, and the campaign scenes that compute them.

Variants (:data:`VARIANTS`):

* ``default``: no-slip rocking (``housner_fast``), opsrock's default restitution ``e = 0.95 e_R``;
* ``housner``: no-slip rocking with Housner's own restitution ``e = e_R`` (``restitution_factor = 1``);
* ``friction``: the block on a floor with Coulomb friction (solver ``friction``), the friction default
  of the shipped library (:func:`library_friction`: ``mu_s = mu_k = 0.40``, an assumption) unless the
  study sets its own, default restitution.

The two no-slip variants share one campaign (same solver, same scale factors: a paired comparison);
the friction variant is a second campaign on the same floor motions.
"""

from __future__ import annotations

import dataclasses
import math
import re
from dataclasses import dataclass
from typing import Any

import numpy as np

from opsrock.errors import InputError
from opsrock.inventory.campaigns import DEFAULT_LEVELS  # noqa: F401  (the study's IDA levels, re-exported)
from opsrock.inventory.sources import QUICK_RECORDS  # noqa: F401  (the quick study's records, re-exported)

#: Name of the shipped blocks library of the nine items (its header states the friction default).
LIBRARY: str = "fema-p58-contents"

#: Name of the shipped inventory of the nine items (:func:`opsrock.inventory.items.shipped_inventory`).
INVENTORY: str = "fema-p58-nine"



def library_friction() -> tuple[float, float]:
    """The friction default that the shipped library states, ``(mu_s, mu_k)`` (dimensionless).

    The library's header line ``# friction default: mu_s = X, mu_k = Y`` holds it, with its source: an
    assumption, not a measurement (``opsrock/data/blocks/fema-p58-contents.md`` says why). The blocks
    themselves carry no ``friction`` so that every solver accepts them."""
    from opsrock.data import block_library

    text = block_library(LIBRARY).read_text(encoding="utf-8")
    found = re.search(r"^# friction default: mu_s = ([0-9.]+), mu_k = ([0-9.]+)\s*$", text, re.MULTILINE)
    if found is None:
        raise RuntimeError(f"the {LIBRARY} library states no friction default (line '# friction default: ...')")
    return float(found.group(1)), float(found.group(2))


#: The friction variant's default coefficients (static, kinetic; dimensionless), read from the library:
#: the stocky items (b/h above mu) slide instead of rocking.
DEFAULT_FRICTION, DEFAULT_FRICTION_KINETIC = library_friction()


#: Buildings of the optional period sweep (T_1 in s, storeys), the project's sliding-map set.
SWEEP_BUILDINGS: tuple[tuple[float, int], ...] = ((0.2, 2), (0.5, 4), (1.0, 8), (2.0, 16))



@dataclass(frozen=True)
class Variant:
    """One model of the items.

    Parameters
    ----------
    name : str
        Key of :data:`VARIANTS`, part of the campaign's block names.
    label : str
        One line for tables and figures.
    restitution_factor : float
        ``e / e_R`` (dimensionless).
    friction : float or None
        Static friction coefficient (dimensionless); None: no slip.
    friction_kinetic : float or None
        Kinetic friction coefficient (dimensionless, at most ``friction``); None: no slip.
    """

    name: str
    label: str
    restitution_factor: float
    friction: float | None = None
    friction_kinetic: float | None = None

    @property
    def campaign(self) -> str:
        """Folder of the campaign that computes it: ``rocking`` (no slip) or ``friction``."""
        return "rocking" if self.friction is None else "friction"

    @property
    def solver(self) -> str:
        """The solver of its campaign: the planar one the registry declares for a base that slips or not
        (:func:`opsrock.solvers.registry.planar_solver`)."""
        from opsrock.solvers.registry import planar_solver

        return planar_solver(self.friction is not None)


def _friction_label(mu_s: float, mu_k: float, library: bool) -> str:
    mu = f"mu = {mu_s:g}" if mu_s == mu_k else f"mu_s = {mu_s:g}, mu_k = {mu_k:g}"
    return f"friction {mu}{' (library default, assumed)' if library else ''}, e = 0.95 e_R"


#: The variants a study can ask for.
VARIANTS: dict[str, Variant] = {
    "default": Variant("default", "no slip, e = 0.95 e_R", 0.95),
    "housner": Variant("housner", "no slip, e = e_R (Housner)", 1.0),
    "friction": Variant("friction", _friction_label(DEFAULT_FRICTION, DEFAULT_FRICTION_KINETIC, True),
                        0.95, DEFAULT_FRICTION, DEFAULT_FRICTION_KINETIC),
}


@dataclass(frozen=True)
class ContentsDesign:
    """The study of one building.

    Parameters
    ----------
    period : float
        First period ``T_1`` of the linear shear building (s).
    storeys : int
        Its storeys.
    damping : float
        Modal damping ratio (dimensionless).
    floors : tuple
        Floors of interest: ``"ground"``, floor numbers 1..storeys (1 = first suspended floor) and/or ``"roof"``.
    record_set : str
        Library record set (``fema-p695:far-field``).
    names : tuple of str
        A subset of its records (empty: all).
    levels : tuple of float
        IDA levels of ``PFA / (g tan alpha)`` (dimensionless), per item.
    items : tuple of str
        FEMA IDs of the items (empty: all nine).
    variants : tuple of str
        Keys of :data:`VARIANTS`, each once (any non-empty subset: the tables and the report hold what the
        variants given allow; the comparisons with ``default`` need it).
    friction : float or None
        Friction coefficient of the ``friction`` variant, static = kinetic (dimensionless, in (0, 1.3]);
        None: the library's default (:func:`library_friction`).
    n_boot : int
        Record-bootstrap resamples of each fit.
    seed : int
        Seed of the bootstraps.
    sweep : tuple of (float, int)
        Buildings ``(T_1, storeys)`` whose roofs are added for the period chart (default variant only);
        empty: none.
    """

    period: float
    storeys: int
    damping: float = 0.05
    floors: tuple = ("ground", "roof")
    record_set: str = "fema-p695:far-field"
    names: tuple[str, ...] = ()
    levels: tuple[float, ...] = DEFAULT_LEVELS
    items: tuple[str, ...] = ()
    variants: tuple[str, ...] = tuple(VARIANTS)
    friction: float | None = None
    n_boot: int = 100
    seed: int = 0
    sweep: tuple[tuple[float, int], ...] = ()

    def __post_init__(self) -> None:
        # every error carries the field at fault (OpsrockError.argument: the command line names its option)
        from opsrock.excitations.building import ShearBuilding

        self.building  # noqa: B018  (checks period, storeys, damping)
        bad = [v for v in self.variants if v not in VARIANTS]
        if bad or not self.variants:
            raise InputError(f"variants must be a non-empty subset of {', '.join(VARIANTS)}; got {self.variants!r}", argument="variants")
        if len(set(self.variants)) != len(self.variants):
            raise InputError(f"variants name a variant twice: {list(self.variants)!r}", argument="variants")
        self.floor_numbers  # noqa: B018  (checks floors: opsrock.inventory.sources.floor_numbers)
        if not self.levels or any(isinstance(x, bool) or not (isinstance(x, (int, float)) and math.isfinite(x)
                                                              and x > 0) for x in self.levels):
            raise InputError(f"levels must be positive numbers (PFA / g tan alpha), got {self.levels!r}")
        if self.friction is not None and (isinstance(self.friction, bool) or not isinstance(self.friction, (int, float))
                                          or not 0.0 < self.friction <= 1.3):
            raise InputError(f"friction must lie in (0, 1.3] (static = kinetic), got {self.friction!r}", argument="friction")
        for t, n in self.sweep:
            ShearBuilding(sweep_name(t), t, n, self.damping)

    @property
    def building(self):
        """The :class:`~opsrock.excitations.building.ShearBuilding` of the study (named ``building``)."""
        from opsrock.excitations.building import ShearBuilding

        return ShearBuilding("building", self.period, self.storeys, self.damping)

    @property
    def floor_numbers(self) -> tuple[int, ...]:
        """The floors as numbers: 0 the ground, ``storeys`` the roof (:func:`opsrock.inventory.sources.floor_numbers`,
        the shipped building's motion source's check)."""
        from opsrock.inventory.sources import floor_numbers

        return floor_numbers(self.building, self.floors)

    @property
    def friction_pair(self) -> tuple[float, float]:
        """``(mu_s, mu_k)`` of the friction variant (dimensionless)."""
        return (DEFAULT_FRICTION, DEFAULT_FRICTION_KINETIC) if self.friction is None else (self.friction, self.friction)

    def variant(self, name: str) -> Variant:
        """The variant ``name``, with this study's friction."""
        v = VARIANTS[name]
        if v.friction is None or self.friction is None:
            return v
        return dataclasses.replace(v, friction=self.friction, friction_kinetic=self.friction,
                                   label=_friction_label(self.friction, self.friction, False))


def sweep_name(period: float) -> str:
    """Name of the sweep's building of period ``period`` (s): ``T0p5`` (a dot would split floor labels)."""
    return f"T{period:g}".replace(".", "p")


def floor_label(number: int, storeys: int) -> str:
    """The study's floor label: ``ground``, ``f<n>``; the roof is ``f<storeys>``."""
    return "ground" if number == 0 else f"f{number}"


def floor_name(number: int, storeys: int) -> str:
    """A floor in words: ``ground``, ``floor 3``, ``roof (floor 8)``."""
    if number == 0:
        return "ground"
    return f"roof (floor {number})" if number == storeys else f"floor {number}"


def quick(design: ContentsDesign) -> ContentsDesign:
    """A small copy of ``design`` for checks: six records (:data:`QUICK_RECORDS`, unless the design names
    its own), eight levels, 20 bootstrap resamples, no sweep; its floors as they are."""
    return dataclasses.replace(design, names=design.names or QUICK_RECORDS, n_boot=min(design.n_boot, 20), sweep=(),
                               levels=tuple(float(x) for x in np.geomspace(1.1, 9.0, 8)))


def item_specs(design: ContentsDesign) -> tuple[Any, ...]:
    """The items' :class:`~opsrock.campaign.scene.BlockSpec`, in the study's order: the shipped inventory
    :data:`INVENTORY` (FEMA P-58's nine) made block specs where every inventory item becomes one
    (:func:`opsrock.inventory.campaigns.item_block_spec`, direction 1: its ``width``, the database's depth; the
    same specs as the blocks library :data:`LIBRARY` gives, and so the same campaign digests)."""
    from opsrock.inventory.campaigns import item_block_spec
    from opsrock.inventory.items import shipped_inventory

    if len(set(design.items)) != len(design.items):
        raise InputError(f"items name an item twice: {list(design.items)!r}", argument="items")
    items = {it.id: it for it in shipped_inventory(INVENTORY).items}
    names = design.items or tuple(items)
    bad = [n for n in names if n not in items]
    if bad:
        raise InputError(f"items {bad!r} are not in the {INVENTORY} inventory (has: {', '.join(items)})",
                         argument="items")
    return tuple(item_block_spec(items[n], "1", n) for n in names)


def block_name(item: str, variant: str) -> str:
    """The campaign's block label of an item in a variant: ``E.20.22.102a-default``."""
    return f"{item}-{variant}"


def split_block_name(name: str) -> tuple[str, str]:
    """``(item, variant)`` of a campaign block label."""
    item, _, variant = name.rpartition("-")
    return item, variant


def _grounds(design: ContentsDesign):
    from opsrock.errors import OpsrockError
    from opsrock.excitations import library

    if len(set(design.names)) != len(design.names):  # before the set is read (seconds)
        raise InputError(f"records name a record twice: {list(design.names)!r}", argument="records")
    try:
        set_name, one = library.parse_reference(design.record_set)
        if one is not None:
            raise InputError("names one record; give a set (fema-p695:far-field) and --records for a subset")
    except OpsrockError as exc:
        raise InputError(f"record_set {design.record_set!r}: {exc}", argument="record_set") from None
    entries = [e for e in library.entries(set_name) if not design.names or e.name in design.names]
    found = {e.name for e in entries}
    missing = [n for n in design.names if n not in found]
    if missing:
        raise InputError(f"records {missing!r} are not in {design.record_set}", argument="records")
    return tuple(library.load(e.reference) for e in entries)


def sweep_buildings(design: ContentsDesign) -> tuple[tuple[float, int], ...]:
    """The sweep's buildings still to compute: the study's own building is left out when its roof is
    already a floor of the study with the default variant (its roof fits stand for it)."""
    own = (design.period, design.storeys)
    has_roof = design.storeys in design.floor_numbers and "default" in design.variants
    return tuple(b for b in design.sweep if not (has_roof and tuple(b) == own))


def campaign_scenes(design: ContentsDesign) -> dict[str, Any]:
    """The study's campaign scenes: ``rocking`` (the no-slip variants), ``friction``, and ``sweep`` (the
    roofs of :attr:`ContentsDesign.sweep`, default variant), each only if asked for."""
    from opsrock.campaign.records import Floor, Intensity, RecordSet
    from opsrock.campaign.scene import Scene
    from opsrock.excitations.building import ShearBuilding

    specs = item_specs(design)  # first: a wrong item is refused before any record is read
    grounds = _grounds(design)
    building = design.building
    floors = tuple(Floor(None, 0) if n == 0 else Floor(building, n) for n in design.floor_numbers)
    intensity = Intensity("ida", "pfa_ratio", tuple(float(x) for x in design.levels))
    records = RecordSet(grounds=grounds, floors=floors, source=design.record_set, intensity=intensity)
    scenes: dict[str, Any] = {}
    for campaign in ("rocking", "friction"):
        variants = [design.variant(v) for v in design.variants if VARIANTS[v].campaign == campaign]
        if variants:
            solver = variants[0].solver
            blocks = tuple(dataclasses.replace(s, name=block_name(s.name, v.name), restitution_factor=v.restitution_factor,
                                               friction=v.friction, friction_kinetic=v.friction_kinetic)
                           for v in variants for s in specs)
            scenes[campaign] = Scene(name=f"contents-{campaign}", path="", blocks=blocks, grid=None, solver=solver,
                                     records=records)
    sweep = sweep_buildings(design)
    if sweep:
        roofs = tuple(Floor(ShearBuilding(sweep_name(t), t, n, design.damping), n) for t, n in sweep)
        roof_set = RecordSet(grounds=grounds, floors=roofs, source=design.record_set, intensity=intensity)
        blocks = tuple(dataclasses.replace(s, name=block_name(s.name, "default")) for s in specs)
        scenes["sweep"] = Scene(name="contents-sweep", path="", blocks=blocks, grid=None, solver=VARIANTS["default"].solver,
                                records=roof_set)
    return scenes


__all__ = [
    "DEFAULT_FRICTION",
    "DEFAULT_FRICTION_KINETIC",
    "DEFAULT_LEVELS",
    "INVENTORY",
    "LIBRARY",
    "QUICK_RECORDS",
    "SWEEP_BUILDINGS",
    "VARIANTS",
    "ContentsDesign",
    "Variant",
    "block_name",
    "campaign_scenes",
    "floor_label",
    "floor_name",
    "item_specs",
    "library_friction",
    "quick",
    "split_block_name",
    "sweep_buildings",
    "sweep_name",
]
