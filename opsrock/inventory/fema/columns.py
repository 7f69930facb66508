"""Every column of the FEMA P-58 nine's tables (:data:`opsrock.inventory.fema.study.TABLES`), once: its unit and its
meaning (:data:`COLUMNS`, the columns the inventory study's tables do not have; a column of the same name and
meaning there is :data:`opsrock.inventory.columns.COLUMNS`' and not repeated), and the tables' one writer and reader
(:func:`write_fema_table`, :func:`read_fema_table`).

Each table is written as ``opsrock fragility``'s are (:func:`opsrock._files.write_units_table`), its units row as the
inventory study's tables' and a campaign's ``cases.csv``'s (:func:`opsrock._files.units_row_text`): the header, then
a row whose first cell is ``Units`` and whose other cells give each column's unit (pelicun's tabular form), then the
rows at full precision. The units are the study's: PFV
in m/s, PFA in g (the columns ending in ``_g``; ``fragility.csv``'s ``median`` in its row's ``unit``), periods in s,
sizes in m, ``-`` for a dimensionless number (ratios, dispersions, shares, counts, floor numbers), blank for text,
labels and flags.

Reading a table back: :func:`read_fema_table` (a table written before the units row still reads, to the same frame),
``pandas.read_csv(path, skiprows=[1])`` or a spreadsheet as it is.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from opsrock._files import read_units_table, write_units_table
from opsrock.inventory.columns import COLUMNS as STUDY_COLUMNS
from opsrock.inventory.columns import Column

_SHARE = "the share of the friction campaign's cases of the item on the floor that ended"
_MEDIAN = "opsrock's lognormal median in PFV of the variant's fit (overturning)"
#: The columns of the FEMA P-58 nine's tables that the inventory study's tables do not have (those are in
#: :data:`opsrock.inventory.columns.COLUMNS`, with the same meaning here: ``item``, ``floor`` (a floor label),
#: ``demand``, ``unit``, ``median``, ``beta``, ``n_cases``, ``ratio_fema``...).
COLUMNS: dict[str, Column] = {
    # who, where, which model
    "campaign": Column("", "the campaign a fit's cases come from: rocking (no slip), friction or sweep"),
    "variant": Column("", "the model: default (no slip, e = 0.95 e_R), housner (e = e_R) or friction"),
    "kind": Column("", "the FEMA P-58 item's kind: bookcase, vertical or lateral filing cabinet"),
    "floor_number": Column("-", "the floor's number in its building, 0 the ground"),
    "building_period": Column("s", "the fundamental period T1 of the building the floor is in (blank on the ground)"),
    "T1": Column("s", "the fundamental period of the sweep's building whose roof the row is on"),
    "period": Column("s", "the period T of the harmonic PFA T / 2 pi: T1 on a building floor, the rule's "
                          "reference period on the ground"),
    # the item
    "aspect_ratio": Column("-", "the FEMA P-58 item's aspect ratio b/h"),
    "R": Column("m", "the item's half-diagonal in its rocking plane"),
    # fits
    "n_boot_used": Column("-", "record resamples whose fit converged (the interval's sample)"),
    "median_pfv": Column("m/s", _MEDIAN),
    "median_pfv_lo": Column("m/s", "the lower end of median_pfv's 95 % record-bootstrap interval"),
    "median_pfv_hi": Column("m/s", "the upper end of median_pfv's 95 % record-bootstrap interval"),
    "beta_pfv": Column("-", "the dispersion of the variant's fit in PFV"),
    "beta_pfv_lo": Column("-", "the lower end of beta_pfv's 95 % record-bootstrap interval"),
    "beta_pfv_hi": Column("-", "the upper end of beta_pfv's 95 % record-bootstrap interval"),
    "median_pfa_g": Column("g", "opsrock's lognormal median in PFA of the variant's fit (overturning)"),
    "median_pfa_lo_g": Column("g", "the lower end of median_pfa_g's 95 % record-bootstrap interval"),
    "median_pfa_hi_g": Column("g", "the upper end of median_pfa_g's 95 % record-bootstrap interval"),
    "beta_pfa": Column("-", "the dispersion of the variant's fit in PFA"),
    "beta_ref": Column("-", "the dispersion in PFV of the reference variant's fit (default)"),
    # FEMA's database and rule
    "fema_median_pfv": Column("m/s", "FEMA P-58's database median PFV at overturning of the item"),
    "database": Column("m/s", "FEMA P-58's database median PFV at overturning of the item"),
    "rule": Column("m/s", "the rule's median PFV g (b/h) T / 2 pi at the rule's reference period"),
    "rule_pfv": Column("m/s", "the rule's median PFV g (b/h) T1 / 2 pi at the row's building period"),
    "rule_pfa_g": Column("g", "the rule in PFA: the uplift acceleration g b/h"),
    "ratio_fema_lo": Column("-", "the lower end of ratio_fema's 95 % record-bootstrap interval"),
    "ratio_fema_hi": Column("-", "the upper end of ratio_fema's 95 % record-bootstrap interval"),
    "ratio_rule": Column("-", "median_pfv / rule_pfv"),
    "ratio_pfa_rule": Column("-", "median_pfa_g / rule_pfa_g"),
    "ratio": Column("-", "a quotient of two medians in PFV: the variant's over the reference's "
                         "(paired_variants.csv), the database's over the rule's (rule_reproduction.csv)"),
    "rounding": Column("-", "half a unit of the database median's printed value (0.05 in/s), relative to it"),
    "implied_period": Column("s", "the period at which the rule gives the database median"),
    "implied_lo": Column("s", "implied_period of the printed median less 0.05 in/s (half its rounding unit)"),
    "implied_hi": Column("s", "implied_period of the printed median plus 0.05 in/s (half its rounding unit)"),
    # what drives the differences
    "overturn_over_uplift": Column("-", "median_pfa_g / (b/h): how far above the uplift acceleration the item "
                                        "overturns"),
    "velocity_factor": Column("-", "(median PFV / median PFA) / (T1 / 2 pi): ratio_rule / overturn_over_uplift"),
    "harmonic_median": Column("-", "the median over the records of PFV / (PFA T / 2 pi) of the unscaled floor "
                                   "motions (1 for a harmonic motion of period T)"),
    "harmonic_p16": Column("-", "the 16th percentile over the records of PFV / (PFA T / 2 pi)"),
    "harmonic_p84": Column("-", "the 84th percentile over the records of PFV / (PFA T / 2 pi)"),
    "rel_over_abs_min": Column("-", "the smallest over the items of the median in the PFV relative to the ground "
                                    "over the median in the absolute PFV"),
    "rel_over_abs_max": Column("-", "the largest over the items of the same quotient"),
    "a_slenderness": Column("-", "the exponent a of b/h in the least-squares ln median_pfv = c + a ln(b/h) + r ln R"),
    "r_size": Column("-", "the exponent r of R in the same least squares"),
    "r2": Column("-", "the coefficient of determination of the same least squares"),
    "max_residual": Column("-", "the largest residual of the same least squares, as a relative difference of "
                                "the median"),
    "n_items": Column("-", "the items in the least squares"),
    "slid": Column("-", f"{_SHARE} standing displaced on the floor"),
    "overturned": Column("-", f"{_SHARE} overturned"),
}  # fmt: skip

_SHARED = sorted(set(COLUMNS) & set(STUDY_COLUMNS))
if _SHARED:  # one definition per name: a column of both lists would have two
    raise RuntimeError(f"opsrock.inventory.fema.columns.COLUMNS repeats {_SHARED!r}")


def units_of(columns: list[str] | tuple[str, ...]) -> list[str]:
    """The units row of a FEMA P-58 table with these ``columns`` (:data:`COLUMNS`, then the inventory study's);
    ``KeyError`` naming a column that neither defines."""
    missing = [c for c in columns if c not in COLUMNS and c not in STUDY_COLUMNS]
    if missing:
        raise KeyError(f"columns without a definition in opsrock.inventory.fema.columns.COLUMNS or "
                       f"opsrock.inventory.columns.COLUMNS: {missing!r}")
    return [(COLUMNS.get(c) or STUDY_COLUMNS[c]).unit for c in columns]


def write_fema_table(df: pd.DataFrame, path: Path) -> Path:
    """``df`` (no index; its first column a label) as ``path`` with its units row, atomically, every float at full
    precision (its shortest repr)."""
    return write_units_table(df, path, units_of(list(df.columns)))


def read_fema_table(path: str | Path, **read_csv: object) -> pd.DataFrame:
    """A table :func:`write_fema_table` wrote, every float as written, its units row skipped; a table of an opsrock
    before the row (none after the header) reads to the same frame. Keyword arguments go to
    :func:`pandas.read_csv`."""
    return read_units_table(path, **read_csv)


__all__ = ["COLUMNS", "read_fema_table", "units_of", "write_fema_table"]
