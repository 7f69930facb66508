"""Every column of the inventory study's tables, once: its unit and its meaning (:data:`COLUMNS`), and the one
writer and reader of those tables (:func:`write_table`, :func:`read_table`).

A table is written in the SimCenter tabular form that pelicun reads and writes (``pelicun.file_io.load_data``:
"a single header line ... the second line may start with 'Units' ... and provide the units for each column"):
the header, then a row whose first cell is ``Units`` and whose other cells give each column's unit, then the
rows. The units are written as the report writes them (``m/s``, ``g``, ``m``, ``s``, ``kg``, ``ea`` for units of an
item, ``USD`` for the inventory's currency as the pelicun folder labels it, ``-`` for a dimensionless number,
blank for text, labels and flags); pelicun's ``load_data`` converts ``g`` and takes the others as its SI base
units, which they are. A column whose unit changes from row to row (a fit's ``median`` in the row's ``unit``)
says ``see unit``.

One unit per quantity in the study's tables and report: PFV in m/s, PFA in g (1 g = :data:`opsrock.constants.G`
= 9.81 m/s²; FEMA P-58's and the report's unit; the study keeps m/s² inside and divides by ``G`` on writing,
:attr:`Column.scale`), displacements in m, periods in s, costs in the inventory's currency. The pelicun folder's
files state their units in pelicun's own form and give PFA in m/s² (``mps2``), so that no convention of g enters
pelicun (its g is 9.80665 m/s²): :mod:`opsrock.inventory.pelicun`.

Reading a table back: ``pandas.read_csv(path, skiprows=[1])`` (the values as written on pandas 3; pandas 2's default
parser can differ in a value's last digit, unless given ``float_precision="round_trip"``), a spreadsheet as it is,
or :func:`read_table` (the values and the units, a file without the ``Units`` row refused: written by an
opsrock before the row, its ``demands.csv`` had PFA in m/s²).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from opsrock._files import UNITS_ROW, read_units, units_row_text
from opsrock.constants import G

#: A units-row cell of a column whose unit is given per row in the column ``unit``.
PER_ROW: str = "see unit"


@dataclass(frozen=True)
class Column:
    """One column of the study's tables.

    Parameters
    ----------
    unit : str
        Its unit as the units row writes it (``""`` for text, labels and flags; ``-`` dimensionless;
        :data:`PER_ROW` where the row's ``unit`` column gives it).
    meaning : str
        What it holds (the docs' column tables repeat it).
    scale : float
        The written value is the study's value divided by it (``pfa``: the study's m/s² written in g).
    """

    unit: str
    meaning: str
    scale: float = 1.0


_FIT = "a lognormal fragility's"
#: A campaign's ``cases.csv`` (under ``campaigns/``) is not one of these tables: its columns, some of the same names
#: with another meaning (``status``, ``floor``, ``pfa`` in m/s²), are defined in :data:`opsrock.campaign.cases.UNITS`.
#: Every column of ``fits.csv``, ``fits3d.csv``, ``components.csv`` (and ``components3d.csv``), ``demands.csv``,
#: ``expected.csv``, ``boxes.csv``, ``side_by_side.csv`` and ``pelicun/mapping.csv``: one meaning and one unit per
#: name. The FEMA P-58 nine's and the directionality study's tables use these names in this meaning, and define
#: their other columns in :mod:`opsrock.inventory.fema.columns` and :mod:`opsrock.inventory.directionality.columns`.
COLUMNS: dict[str, Column] = {
    # who and where
    "item": Column("", "the inventory item's id"),
    "description": Column("", "the inventory item's description"),
    "floor": Column("", "the floor label, as the motions manifest names it"),
    "record": Column("", "the record, as the motions manifest names it"),
    "direction": Column("", "a horizontal direction of the motions, 1 or 2 (a fit's: the plane it was computed in)"),
    "shape": Column("", "the item's base: box or cylinder"),
    "model": Column("", "the model a row describes: the body (as given, the round item, or box of its size) or, in "
                        "the directionality study, the analysis (3d or planar)"),
    "pelicun_id": Column("", "the pelicun component of the item on the floor (opsrock.<item>.<floor>)"),
    "fema_id": Column("", "the item's FEMA P-58 fragility ID, where the inventory names one"),
    "location": Column("-", "pelicun's location number of the floor (1 the ground floor)"),
    "b_over_h": Column("-", "the item's base width over its height in the plane it rocks in most easily (tan alpha; "
                            "FEMA P-58's aspect ratio)"),
    # floor demands
    "pfa": Column("g", "peak floor acceleration: the largest absolute acceleration of the floor motion", G),
    "pfv": Column("m/s", "peak floor velocity: the largest absolute velocity of the floor motion"),
    "pfd": Column("m", "peak floor displacement: the largest absolute displacement of the floor motion"),
    "mean_period": Column("s", "the floor motion's mean period T_m (Rathje et al.)"),
    "predominant_period": Column("s", "the floor motion's predominant period: that of its largest 5 %-damped "
                                      "spectral acceleration"),
    # fits
    "outcome": Column("", "what a fit is for: overturning, sliding (beyond the slide distance), displaced "
                          "(either)"),
    "limit_state": Column("", "a component's limit state: displaced, then overturned"),
    "ls": Column("", "the limit state's pelicun label, LS1 or LS2"),
    "demand": Column("", "the demand a fragility is fitted in: pfv, pfa (one direction), pfv_1, pfv_2, pfv_max "
                         "(the larger direction), pfv_max_x1.2 (pelicun's default non-directional demand), pfv_nd "
                         "(the peak of the velocity vector) or pfv_weak (along the item's weaker axis)"),
    "unit": Column("", "the unit of the row's demand and of its median, median_lo and median_hi"),
    "method": Column("", "ida (each motion scaled to the levels) or cloud (the motions as recorded)"),
    "median": Column(PER_ROW, f"{_FIT} median, in the row's unit"),
    "median_lo": Column(PER_ROW, "the lower end of the median's 95 % record-bootstrap interval"),
    "median_hi": Column(PER_ROW, "the upper end of the median's 95 % record-bootstrap interval"),
    "beta": Column("-", f"{_FIT} dispersion (standard deviation of ln demand)"),
    "beta_lo": Column("-", "the lower end of beta's 95 % record-bootstrap interval"),
    "beta_hi": Column("-", "the upper end of beta's 95 % record-bootstrap interval"),
    "n_cases": Column("-", "cases that finished (failed cases are not in it)"),
    "n_exceeded": Column("-", "of the finished cases, those that reached the outcome"),
    "n_overturned": Column("-", "of the finished cases, those that overturned"),
    "n_failed": Column("-", "cases the solver did not finish (stored as failed with their reason)"),
    "n_records": Column("-", "records the row's cases come from"),
    "n_azimuths": Column("-", "azimuths in plan pooled in the fit"),
    "n_corner": Column("-", "overturnings of a box over a corner of its base"),
    "n_edge": Column("-", "overturnings of a box over an edge of its base"),
    "n_rim": Column("-", "overturnings of a cylinder over a point of its rim, rocking"),
    "n_rolling": Column("-", "overturnings of a cylinder while rolling on its rim (wobbling)"),
    "ok": Column("", "True when the fit converged to a finite median"),
    "status": Column("", "the row's state: a fit's fitted, extrapolated, never, always or no fit; a component's "
                         "fitted, never or no fit; an item-floor's ok, never damaged or no fit"),
    "message": Column("", "the fitter's message, or why there is no fit"),
    "source": Column("", "where a component's fragility comes from: the planar fits of directions 1 and 2 "
                         "combined, or the cases in three dimensions"),
    "max_error": Column("-", "the largest difference in probability between the combined planar curve and the "
                             "lognormal given to pelicun"),
    "fema_median": Column("m/s", "FEMA P-58's median non-directional PFV at overturning of the item's fema_id"),
    "ratio_fema": Column("-", "median / fema_median"),
    # expected numbers and costs
    "quantity": Column("ea", "the item's units on the floor"),
    "expected_damaged": Column("ea", "units expected damaged (displaced or overturned) over the records, with the "
                                     "fragilities pelicun is given"),
    "expected_displaced_only": Column("ea", "units expected displaced and not overturned"),
    "expected_overturned": Column("ea", "units expected overturned"),
    "expected_damaged_combined": Column("ea", "expected_damaged from the combined planar curves, before the "
                                              "lognormal"),
    "empirical_overturned": Column("ea", "quantity x the share of the records under which the item overturned "
                                         "(a cloud only)"),
    "slide_cost": Column("USD", "the cost of one unit displaced (the inventory's currency)"),
    "repair_cost": Column("USD", "the cost of one unit overturned (the inventory's currency)"),
    "expected_cost": Column("USD", "expected repair cost of the item on the floor"),
    # the pelicun folder's mapping
    "exported": Column("", "True when the component is in pelicun's inventory.csv"),
    "ds1": Column("", "damage state 1 of the component"),
    "ds2": Column("", "damage state 2 of the component"),
    "median_ds1": Column("m/s", "DS1's lognormal median in pfv_max"),
    "median_ds2": Column("m/s", "DS2's lognormal median in pfv_max"),
    "beta_ds1": Column("-", "DS1's lognormal dispersion"),
    "beta_ds2": Column("-", "DS2's lognormal dispersion"),
    # a round item against the box of its size
    "share_rim": Column("-", "n_rim / n_exceeded: the share of the overturnings on one rim point"),
    "share_rolling": Column("-", "n_rolling / n_exceeded: the share of the overturnings while rolling"),
    "share_edge": Column("-", "n_edge / n_exceeded: the share of the overturnings over an edge"),
    "share_corner": Column("-", "the share of the overturnings over a corner: n_corner / n_exceeded, n_corner / "
                                "(n_edge + n_corner) where n_unstated counts those that state neither"),
    "failed_reasons": Column("", "the failed cases by the kind of their reason (count x code (the first such reason); "
                                "...; opsrock.campaign.cases.reason_code)"),
    # the two models side by side (--model both: opsrock.inventory.side_by_side)
    "median_3d": Column("m/s", "the 3-D component's median in pfv_max"),
    "median_planar": Column("m/s", "the planar component's median in pfv_max (the two planes combined)"),
    "ratio_3d_planar": Column("-", "median_3d / median_planar"),
    "status_3d": Column("", "the 3-D component's status"),
    "status_planar": Column("", "the planar component's status"),
    "median_az_low": Column("m/s", "the lowest of the medians fitted at each azimuth alone"),
    "az_low": Column("deg", "the azimuth of median_az_low"),
    "median_az_high": Column("m/s", "the highest of the medians fitted at each azimuth alone"),
    "az_high": Column("deg", "the azimuth of median_az_high"),
    "corner_share": Column("-", "the share of the 3-D overturnings over a corner rather than an edge"),
    "slid_share_3d": Column("-", "the share of the finished 3-D cases whose base slid at least the slide distance"),
    "slid_share_planar": Column("-", "the share of the finished planar cases whose base slid at least the slide "
                                     "distance"),
    "n_cases_3d": Column("-", "finished 3-D cases"),
    "n_cases_planar": Column("-", "finished planar cases"),
    "box_off": Column("-", "the median of the box of a round item's size over the item's own, less 1"),
}  # fmt: skip


def units_of(columns: list[str] | tuple[str, ...]) -> list[str]:
    """The units row of a table with these ``columns``; ``KeyError`` naming a column that :data:`COLUMNS` lacks
    (every column of the study's tables is defined once, there)."""
    missing = [c for c in columns if c not in COLUMNS]
    if missing:
        raise KeyError(f"columns without a definition in opsrock.inventory.columns.COLUMNS: {missing!r}")
    return [COLUMNS[c].unit for c in columns]


def as_written(df: pd.DataFrame) -> pd.DataFrame:
    """``df`` with every column in the unit it is written in (:attr:`Column.scale`: ``pfa`` m/s² -> g)."""
    out = df.copy()
    for c in df.columns:
        scale = COLUMNS[c].scale if c in COLUMNS else 1.0
        if scale != 1.0:
            out[c] = df[c].to_numpy(float) / scale
    return out


def table_text(df: pd.DataFrame, index: bool = False) -> str:
    """The CSV text of ``df``: the header, the units row, the rows at full precision (the values of
    :func:`as_written`). The units row's first cell is ``Units``, where the first column (a label: an item, a
    record, a component; ``index`` True writes the index there, its name the header cell) has no unit."""
    names = ([df.index.name or ""] if index else []) + list(df.columns)
    units = ([""] if index else []) + units_of(list(df.columns))
    if units[0]:
        raise ValueError(f"the first column of a study table is a label without a unit, not {names[0]!r}")
    return units_row_text(names, units) + as_written(df).to_csv(index=index, header=False, lineterminator="\n")


def write_table(df: pd.DataFrame, path: Path, index: bool = False) -> Path:
    """``df`` as CSV at ``path`` with its units row (:func:`table_text`), atomically."""
    from opsrock._files import atomic_write

    text = table_text(df, index)
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_write(path, lambda fh: fh.write(text), durable=False)
    return path


class OldTableError(ValueError):
    """A study table without the ``Units`` row: written before opsrock gave its tables one."""


def read_table(path: str | Path, **read_csv: object) -> tuple[pd.DataFrame, dict[str, str]]:
    """A study table written by :func:`write_table`: ``(table, units)``, the values as written, ``units`` column ->
    unit. Keyword arguments go to :func:`pandas.read_csv` (``dtype``, ``index_col``...).

    Raises
    ------
    OldTableError
        The file has no ``Units`` row after its header (written by an opsrock before it had one, when
        ``demands.csv`` gave PFA in m/s²): the message says to run the study again (its campaigns resume from
        their stores, so nothing is computed twice).
    """
    path = Path(path)
    header, units = read_units(path)
    if units is None:
        raise OldTableError(f"{path}: no {UNITS_ROW!r} row after the header: written by an older opsrock (its "
                            "demands.csv gave PFA in m/s2); run the study again into the same folder (the campaigns "
                            "resume from their stores)")
    from opsrock._files import read_table as read_exactly

    table = read_exactly(path, skiprows=[1], **read_csv)  # every float as written, on pandas 2 as on pandas 3
    return table, {h: u for h, u in zip(header, units)}


__all__ = ["COLUMNS", "PER_ROW", "UNITS_ROW", "Column", "OldTableError", "as_written", "read_table", "table_text",
           "units_of", "write_table"]
