"""Every column of the directionality study's tables (:data:`opsrock.inventory.directionality.study.TABLES`), once:
its unit and its meaning (:data:`COLUMNS`, the columns neither the inventory study's tables nor the FEMA P-58 nine's
have; a column of the same name and meaning there is :data:`opsrock.inventory.columns.COLUMNS`' and not repeated),
and the tables' one writer and reader (:func:`write_directionality_table`, :func:`read_directionality_table`).

Each table is written as the FEMA P-58 nine's are (:func:`opsrock._files.write_units_table`): the header, then a row
whose first cell is ``Units`` and whose other cells give each column's unit (pelicun's tabular form), then the rows
at full precision. The units are the contents study's: PFV in m/s, PFA in g (``pfa_1``, ``pfa_2``: the study keeps
m/s² inside and divides by :data:`opsrock.constants.G` on writing, :attr:`~opsrock.inventory.columns.Column.scale`),
azimuths in deg, wall times in s, ``-`` for a dimensionless number (ratios, dispersions, shares, counts), blank for
text, labels and flags. Every demand the study fits is a PFV (:data:`~opsrock.inventory.directionality.summary.
CONVENTIONS`), so ``fits.csv``'s ``median``, ``median_lo`` and ``median_hi`` (in the row's demand's unit, the
inventory study's definition) are in m/s, and its units row says so.

Reading a table back: :func:`read_directionality_table` (a table written before the units row still reads, to the
same frame: its ``pfa_1`` and ``pfa_2``, then in m/s², converted to g), ``pandas.read_csv(path, skiprows=[1])`` or a
spreadsheet as it is.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from opsrock._files import read_units, read_units_table, write_units_table
from opsrock.constants import G
from opsrock.inventory.columns import COLUMNS as STUDY_COLUMNS
from opsrock.inventory.columns import PER_ROW, Column
from opsrock.inventory.directionality.summary import CONVENTIONS
from opsrock.inventory.fema.columns import COLUMNS as FEMA_COLUMNS

_FIT = "the lognormal median of the item's {} fragility (orientations as the row's azimuth) in {}"
_BETA = "the dispersion of the same fit as {}"
#: The columns of the directionality study's tables that the inventory study's and the FEMA P-58 nine's tables do
#: not have (those are in :data:`opsrock.inventory.columns.COLUMNS`, with the same meaning here: ``item``,
#: ``floor``, ``record``, ``model``, ``demand``, ``median``, ``beta``, ``n_cases``, ``n_overturned``,
#: ``b_over_h``, ``share_corner``...).
COLUMNS: dict[str, Column] = {
    # where and how
    "azimuth": Column("deg", "the item's plan orientation, from motion direction 1 to its width axis; all: every "
                             "orientation pooled"),
    "solver": Column("", "the campaign's solver (opsrock.solvers.registry)"),
    "verdict": Column("", "where planar analysis suffices: suffices (ratio_weak within the tolerance of 1), differs, "
                          "never overturns (neither model) or no fit"),
    # the record pairs' floor demands (unscaled)
    "pfa_1": Column("g", "peak floor acceleration of direction 1 of the pair's floor motion", G),
    "pfa_2": Column("g", "peak floor acceleration of direction 2 of the pair's floor motion", G),
    "pfv_1": Column("m/s", "peak floor velocity of direction 1 of the pair's floor motion"),
    "pfv_2": Column("m/s", "peak floor velocity of direction 2 of the pair's floor motion"),
    "pfv_max": Column("m/s", "the larger of pfv_1 and pfv_2"),
    "pfv_nd": Column("m/s", "the non-directional PFV: the peak over time of the length of the horizontal velocity "
                            "vector, max_t sqrt(v_1^2 + v_2^2)"),
    "nd_over_max": Column("-", "pfv_nd / pfv_max (between 1 and sqrt 2): the motion's own part of pelicun's 1.2"),
    # the two models' fits side by side
    **{f"median_3d_{d}": Column("m/s", _FIT.format("3-D", d)) for d in CONVENTIONS["3d"]},
    **{f"median_planar_{d}": Column("m/s", _FIT.format("planar (weaker axis)", d)) for d in CONVENTIONS["planar"]},
    **{f"beta_3d_{d}": Column("-", _BETA.format(f"median_3d_{d}")) for d in CONVENTIONS["3d"]},
    **{f"beta_planar_{d}": Column("-", _BETA.format(f"median_planar_{d}")) for d in CONVENTIONS["planar"]},
    "n_overturned_3d": Column("-", "finished 3-D cases that overturned"),
    "n_overturned_planar": Column("-", "finished planar cases that overturned"),
    "ratio_weak": Column("-", "median_3d_pfv_weak / median_planar_pfv_weak"),
    "factor_implied": Column("-", "median_planar_pfv_weak / median_3d_pfv_max: the factor on max(PFV_1, PFV_2) the "
                                  "3-D fit asks of the planar fragility"),
    "pelicun_over_3d": Column("-", "factor_implied / 1.2 (pelicun's non-directional multiplier)"),
    "n_unstated": Column("-", "3-D overturnings whose case does not state over an edge or a corner"),
    # cost
    "mean_s": Column("s", "the mean wall time of the solver's cases in this run (a cold kernel's compile included)"),
    "median_s": Column("s", "the median wall time of the solver's cases in this run"),
    "total_s": Column("s", "the total wall time of the solver's cases in this run"),
    "ratio_to_planar": Column("-", "median_s / the fastest planar solver's median_s"),
    "cpu_mean_s": Column("s", "the mean CPU time of the solver's cases in this run (the solving thread's; empty for "
                              "cases read from a store written before opsrock measured it)"),
    "cpu_median_s": Column("s", "the median CPU time of the solver's cases in this run"),
    "cpu_total_s": Column("s", "the total CPU time of the solver's cases in this run"),
    "cpu_ratio_to_planar": Column("-", "cpu_median_s / the fastest planar solver's cpu_median_s: the cost ratio a "
                                       "machine's load does not stretch"),
}  # fmt: skip

_SHARED = sorted((set(COLUMNS) & set(STUDY_COLUMNS)) | (set(COLUMNS) & set(FEMA_COLUMNS)))
if _SHARED:  # one definition per name: a column of two lists would have two
    raise RuntimeError(f"opsrock.inventory.directionality.columns.COLUMNS repeats {_SHARED!r}")
if not all(d.startswith("pfv") for ds in CONVENTIONS.values() for d in ds):  # fits.csv's medians in m/s
    raise RuntimeError("a directionality fit in a demand other than a PFV: fits.csv's median needs its unit column")


def _column(name: str) -> Column:
    return COLUMNS.get(name) or STUDY_COLUMNS[name]


def units_of(columns: list[str] | tuple[str, ...]) -> list[str]:
    """The units row of a directionality table with these ``columns`` (:data:`COLUMNS`, then the inventory study's;
    a median in the row's unit is in m/s: every demand fitted is a PFV); ``KeyError`` naming a column that neither
    defines."""
    missing = [c for c in columns if c not in COLUMNS and c not in STUDY_COLUMNS]
    if missing:
        raise KeyError(f"columns without a definition in opsrock.inventory.directionality.columns.COLUMNS or "
                       f"opsrock.inventory.columns.COLUMNS: {missing!r}")
    return ["m/s" if _column(c).unit == PER_ROW else _column(c).unit for c in columns]


def write_directionality_table(df: pd.DataFrame, path: Path) -> Path:
    """``df`` (no index; its first column a label; PFA in m/s²) as ``path`` with its units row, atomically, every
    float at full precision (its shortest repr), each column in its written unit (PFA in g)."""
    units = units_of(list(df.columns))
    scaled = {c: df[c].to_numpy(float) / _column(c).scale for c in df.columns if _column(c).scale != 1.0}
    return write_units_table(df.assign(**scaled) if scaled else df, path, units)


def read_directionality_table(path: str | Path, **read_csv: object) -> pd.DataFrame:
    """A table :func:`write_directionality_table` wrote, every float as written, its units row skipped; a table of
    an opsrock before the row (none after the header, PFA in m/s²) reads to the same frame (PFA in g). Keyword
    arguments go to :func:`pandas.read_csv`."""
    table = read_units_table(path, **read_csv)
    if read_units(path)[1] is None:
        scaled = {c: table[c].to_numpy(float) / COLUMNS[c].scale for c in table.columns
                  if c in COLUMNS and COLUMNS[c].scale != 1.0}
        table = table.assign(**scaled)
    return table


__all__ = ["COLUMNS", "read_directionality_table", "units_of", "write_directionality_table"]
