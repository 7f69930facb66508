"""FEMA P-58 (second edition), component group E.20.22: the overturning of unanchored furniture in
peak floor velocity, and the rule that we find behind its nine medians.

What the database gives
-----------------------
Nine items "unanchored laterally" (bookcases of 2 to 6 shelves, vertical and lateral filing
cabinets; :data:`ITEMS`) fall over with a lognormal probability in the peak floor velocity ``PFV``,
dispersion ``beta = 0.5`` for all, medians of 0.251 to 1.229 m/s (``opsrock/data/fema-p58/``, the
rows as pelicun reads them, with their source and licence). Each record's description gives the
item's depth and height in inches, and each carries the same note: the velocity limit is worked out
from the item's aspect ratio and the building period ``T``, and at the ground floor the fragility
rests on the ground motion alone. The formula is not in the database (no column, comment or
calculation sheet holds it), the records are "Not Rated" and their author "Not Given". The FEMA
P-58 volumes and background reports, where the derivation would be, were not available to us:
only their first pages could be searched. The rule below is therefore our reading, tested against
the nine numbers; it is not quoted from a FEMA document.

The rule (our reading)
----------------------
A rigid block of depth ``b`` and height ``h`` (full dimensions, ``b/h = tan(alpha)``) starts to
rock when the floor acceleration reaches ``g b/h``. A floor that moves harmonically at the building
period ``T`` reaches the velocity ``PFA T / (2 pi)`` at that acceleration, so::

    PFV_50 = g (b/h) T / (2 pi)                                   (m/s; b/h dimensionless, T in s)

It is linear in ``b/h`` and in ``T``; size (``R``, ``p``), restitution and friction do not enter.
In floor acceleration it is ``PFA_50 = g b/h`` at any ``T``: the uplift threshold, a lower bound of
overturning (a block cannot overturn before it rocks), not an overturning capacity.

How well it reproduces the nine medians
---------------------------------------
The second-edition medians are the first-edition ones (PACT files of 2012, in inches per second to
one decimal) times 0.0254, rounded to 1 mm/s (:data:`ITEMS`, ``median_inps``): each is known to
+-0.05 in/s, 0.2 % (28.5 in/s) to 0.5 % (9.9 in/s). The period that makes the rule return each
median exactly (:func:`implied_period`) is 1.02-1.07 s for the five bookcases, 1.11 s for the
4-drawer vertical cabinet, 1.26 s for the 2-drawer one and 1.23-1.25 s for the two lateral ones.

* With one period, :data:`REFERENCE_PERIOD` = 1.039 s (the geometric mean of the five bookcases'),
  the rule gives the **five bookcases within -1.3 % / +2.5 %**. That is more than the rounding
  (at most 0.5 %): the implied periods differ among them (1.025 s for 103a and 104a, 1.065 s for
  102a) and not monotonically in ``b/h``, so no smooth function of ``b/h`` removes the rest;
  per-item inputs we cannot see (a centre of mass a little below mid-height, rounded heights) are
  the likely cause.
* The **four filing cabinets are not reproduced**: the database is 6.4 % (114a), 18 % (125a),
  20 % (124a) and 21 % (112a) above the rule at that period. Read as a centre of mass below
  mid-height (``h`` replaced by twice its height), the medians would need it at 0.40-0.45 of the
  height for the cabinets and 0.47-0.49 for the bookcases (at ``T`` = 1.0 s); the records state no
  centre of mass. Their descriptions are also inconsistent (124a is named "2 drawer" but described
  with 4 drawers, 125a "4 drawer" with 5), so the dimensions the medians were computed from may not
  be the ones described.
* Which period the database assumed is not stated anywhere we could read; the bookcases say about
  1.04 s. For a building of period ``T_1`` the rule asks for ``PFV_50`` at ``T = T_1`` on its floors
  (:func:`median_pfv`); what it asks for at the ground ("the ground motion only") is not said.

An empirical description of the nine numbers that needs no period, ``PFV_50 = 0.919 (b/h) sqrt(g b)``
(``b`` in m), fits eight of them within -3.1 % / +2.1 % and 112a at +10.7 %; we record it only as a
summary (it is the rule with ``T`` growing like ``sqrt(b)``), not as FEMA's method.

The PFV the database means is the peak *total* (absolute) floor velocity: at the ground floor the
note uses the ground motion's own velocity, which a velocity relative to the ground would make zero.
opsrock's ``pfv`` of a floor motion is the same quantity (:mod:`opsrock.intensity.records`).
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

from opsrock.constants import G
from opsrock.errors import InputError
from opsrock.published.reference import PublishedValue

#: Metres per inch.
INCH: float = 0.0254

#: Range of ``b/h`` of the rule (dimensionless): furniture from very slender to squat.
ASPECT_RANGE: tuple[float, float] = (0.01, 2.0)

#: Range of the building period ``T`` (s), as :data:`opsrock.limits.LIMITS` ``"period"``.
PERIOD_RANGE: tuple[float, float] = (0.01, 10.0)

#: The database's dispersion of all nine items (dimensionless).
BETA: float = 0.5


@dataclass(frozen=True)
class FemaItem:
    """One unanchored item of group E.20.22.

    Parameters
    ----------
    fema_id : str
        Component ID (``E.20.22.102a``), the block name in ``fema-p58-contents``.
    name : str
        The database's name of the item.
    depth_in, height_in : float
        Depth and height from the item's description (in).
    median_mps : float
        Median PFV of the second-edition database (m/s).
    median_inps : float
        Median PFV of the first-edition PACT file (in/s, one decimal).
    """

    fema_id: str
    name: str
    depth_in: float
    height_in: float
    median_mps: float
    median_inps: float

    @property
    def aspect_ratio(self) -> float:
        """``b/h`` = depth / height (dimensionless)."""
        return self.depth_in / self.height_in

    @property
    def depth(self) -> float:
        """Depth ``2b`` (m)."""
        return self.depth_in * INCH

    @property
    def height(self) -> float:
        """Height ``2h`` (m)."""
        return self.height_in * INCH

    @property
    def kind(self) -> str:
        """``"bookcase"`` or ``"filing cabinet"``."""
        return "bookcase" if self.name.startswith("Bookcase") else "filing cabinet"


#: The nine items: depth x height as described, the two editions' medians.
ITEMS: tuple[FemaItem, ...] = (
    FemaItem("E.20.22.102a", "Bookcase, 2 shelves", 12.625, 29.0, 0.724, 28.5),
    FemaItem("E.20.22.103a", "Bookcase, 3 shelves", 12.625, 41.0, 0.493, 19.4),
    FemaItem("E.20.22.104a", "Bookcase, 4 shelves", 12.625, 56.0, 0.361, 14.2),
    FemaItem("E.20.22.105a", "Bookcase, 5 shelves", 12.625, 71.0, 0.290, 11.4),
    FemaItem("E.20.22.106a", "Bookcase, 6 shelves", 12.625, 81.25, 0.251, 9.9),
    FemaItem("E.20.22.112a", "Vertical filing cabinet, 2 drawers", 15.0, 24.0, 1.229, 48.4),
    FemaItem("E.20.22.114a", "Vertical filing cabinet, 4 drawers", 15.0, 52.0, 0.498, 19.6),
    FemaItem("E.20.22.124a", "Lateral filing cabinet (4 drawers as described)", 18.6, 52.5, 0.688, 27.1),
    FemaItem("E.20.22.125a", "Lateral filing cabinet (5 drawers as described)", 18.6, 67.75, 0.526, 20.7),
)


def item(fema_id: str) -> FemaItem:
    """The item of ``fema_id``; ``InputError`` if it is not one of :data:`ITEMS`."""
    for it in ITEMS:
        if it.fema_id == fema_id:
            return it
    raise InputError(f"no FEMA P-58 unanchored item {fema_id!r} (known: {', '.join(i.fema_id for i in ITEMS)})")


def _check(name: str, value: float, bounds: tuple[float, float]) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not bounds[0] <= value <= bounds[1]:
        raise InputError(f"{name} must lie in [{bounds[0]:g}, {bounds[1]:g}], got {value!r}")
    return float(value)


def uplift_pfa(aspect_ratio: float) -> float:
    """Floor acceleration that starts a rigid block rocking, ``g b/h`` (m/s²): the rule in PFA.

    Parameters
    ----------
    aspect_ratio : float
        ``b/h``, depth over height (dimensionless), within :data:`ASPECT_RANGE`.
    """
    return G * _check("aspect_ratio", aspect_ratio, ASPECT_RANGE)


def median_pfv(aspect_ratio: float, period: float) -> float:
    """The rule's median overturning PFV, ``g (b/h) T / (2 pi)`` (m/s).

    Parameters
    ----------
    aspect_ratio : float
        ``b/h`` (dimensionless), within :data:`ASPECT_RANGE`.
    period : float
        Building period ``T`` (s), within :data:`PERIOD_RANGE`.
    """
    return uplift_pfa(aspect_ratio) * _check("period", period, PERIOD_RANGE) / (2.0 * math.pi)


def implied_period(median: float, aspect_ratio: float) -> float:
    """The period ``T`` (s) at which the rule gives ``median`` (m/s, > 0) for ``b/h`` = ``aspect_ratio``."""
    if isinstance(median, bool) or not isinstance(median, (int, float)) or not 0.0 < median < 100.0:
        raise InputError(f"median must be a velocity in (0, 100) m/s, got {median!r}")
    return 2.0 * math.pi * median / uplift_pfa(aspect_ratio)


def implied_period_bounds(it: FemaItem) -> tuple[float, float]:
    """The implied period (s) of ``it`` at the two ends of its first-edition rounding, +-0.05 in/s."""
    return (implied_period((it.median_inps - 0.05) * INCH, it.aspect_ratio),
            implied_period((it.median_inps + 0.05) * INCH, it.aspect_ratio))


def _reference_period() -> float:
    bookcases = [it for it in ITEMS if it.kind == "bookcase"]
    logs = [math.log(implied_period(it.median_mps, it.aspect_ratio)) for it in bookcases]
    return math.exp(sum(logs) / len(logs))


#: The period (s) that reproduces the five bookcases best (geometric mean of their implied periods).
REFERENCE_PERIOD: float = _reference_period()

#: Allowed relative error of the rule at :data:`REFERENCE_PERIOD` for a bookcase: 0.5 % is the
#: rounding of the printed medians, the rest the measured spread of the bookcases' implied periods.
BOOKCASE_TOLERANCE: float = 0.03


def reproduction(period: float = REFERENCE_PERIOD) -> list[dict]:
    """The rule against the nine database medians at one ``period`` (s).

    Returns
    -------
    list of dict
        Per item: ``fema_id``, ``kind``, ``aspect_ratio``, ``database`` and ``rule`` (m/s),
        ``ratio`` (database / rule), ``rounding`` (relative half-unit of the printed value),
        ``implied_period`` with ``implied_lo`` / ``implied_hi`` (s).
    """
    rows = []
    for it in ITEMS:
        rule = median_pfv(it.aspect_ratio, period)
        lo, hi = implied_period_bounds(it)
        rows.append({"fema_id": it.fema_id, "kind": it.kind, "aspect_ratio": it.aspect_ratio,
                     "database": it.median_mps, "rule": rule, "ratio": it.median_mps / rule,
                     "rounding": 0.05 / it.median_inps, "implied_period": implied_period(it.median_mps, it.aspect_ratio),
                     "implied_lo": lo, "implied_hi": hi})
    return rows


def database_file() -> Path:
    """The shipped database rows (``opsrock/data/fema-p58/fragility-E.20.22-unanchored.csv``)."""
    from importlib import resources

    return Path(str(resources.files("opsrock.data"))) / "fema-p58" / "fragility-E.20.22-unanchored.csv"


def database_rows() -> dict[str, tuple[float, float]]:
    """``{ID: (median PFV in m/s, beta)}`` read from :func:`database_file`."""
    with open(database_file(), newline="") as fh:
        return {r["ID"]: (float(r["LS1-Theta_0"]), float(r["LS1-Theta_1"])) for r in csv.DictReader(fh)}


def _published(it: FemaItem) -> PublishedValue:
    bookcase = it.kind == "bookcase"
    return PublishedValue(
        key=f"fema_p58_{it.fema_id}", source=f"FEMA P-58 2nd ed. fragility database v3.1.2, {it.fema_id} "
        f"({it.name}, {it.depth_in:g} x {it.height_in:g} in); 1st ed. {it.median_inps:.1f} in/s",
        pulse="harmonic", equations="exact", quantity="median PFV at overturning (m/s)", value=it.median_mps,
        tolerance=BOOKCASE_TOLERANCE if bookcase else 0.05 / it.median_inps,
        tolerance_reason=(
            "printed to 0.1 in/s (at most 0.5 %); the rest is the spread of the five bookcases' implied periods "
            "(1.02-1.07 s), which the rule at one period cannot follow" if bookcase else
            "printed to 0.1 in/s; the rule at the bookcases' period does not reproduce it (database 6-21 % "
            "above): only the item's own implied period does, within this rounding"),
        parameters={"aspect_ratio": it.aspect_ratio, "period": REFERENCE_PERIOD if bookcase else
                    implied_period(it.median_mps, it.aspect_ratio), "reproduced_at_reference_period": bookcase})


#: The nine published medians, with how closely the rule reproduces each (see the module docstring).
VALUES: tuple[PublishedValue, ...] = tuple(_published(it) for it in ITEMS)

__all__ = [
    "ASPECT_RANGE",
    "BETA",
    "BOOKCASE_TOLERANCE",
    "INCH",
    "ITEMS",
    "PERIOD_RANGE",
    "REFERENCE_PERIOD",
    "VALUES",
    "FemaItem",
    "database_file",
    "database_rows",
    "implied_period",
    "implied_period_bounds",
    "item",
    "median_pfv",
    "reproduction",
    "uplift_pfa",
]
