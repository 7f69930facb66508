"""The unit of every column of ``opsrock fragility``'s tables, once (:data:`TABLE_UNITS`), and their one writer and
reader with a units row (:func:`write_record_table`, :func:`read_record_table`).

Each table is written as the contents study's tables and a campaign's ``cases.csv`` are, through the same writer
(:func:`opsrock._files.write_units_table`): the header, then a row whose first cell is ``Units`` and whose other cells
give each column's unit (pelicun's tabular form), then the rows at full precision. The units are the campaign's
(:data:`opsrock.campaign.cases.UNITS`): SI, ``m/s2`` for m/s², ``-`` for a dimensionless number (the paper's nine
IMs, the dispersions, counts, ranks and shares), ``%`` for ``cv_percent``, blank for text, labels and flags. Two
placeholders stand where the unit is not one per column: :data:`PER_ROW` (``see unit``: in the unit the row's
``unit`` column names, as ``blocks.csv``'s medians in PFA (m/s2) or PFV (m/s)) and :data:`MEASURE` (the scene's
intensity measure, :data:`opsrock.campaign.cases.MEASURE_UNITS`: ``g`` for ``pfa_g``, ``-`` for ``pfa_ratio``;
``see measure`` where it is not recognised from the cases).

``fragility_pelicun.csv`` is pelicun's damage-model file, whose units are its ``Demand-Unit`` column (pelicun's own
form, no units row). ``opsrock reproduce``'s tables (``table2.csv``, its ``robustness.csv``, ...) keep their form.

Reading a table back: :func:`read_record_table` (a table written before the units row still reads, to the same
frame), ``pandas.read_csv(path, skiprows=[1])`` or a spreadsheet as it is.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from opsrock._files import read_units_table, write_units_table
from opsrock.campaign.cases import MEASURE_UNITS
from opsrock.inventory.columns import PER_ROW

#: A units-row cell of a column in the scene's intensity measure, resolved on writing (:func:`measure_unit`).
MEASURE: str = "measure"

_FIT = {"beta": "-", "beta_lo": "-", "beta_hi": "-"}
#: Each table's columns and their units (``""`` text, labels and flags; ``-`` dimensionless; :data:`PER_ROW`,
#: :data:`MEASURE`). ``frequencies`` and ``robustness`` also have ``wins_<criterion>`` and ``share_<criterion>[_lo|
#: _hi]`` columns per ranking criterion (counts and shares: ``-``, :data:`SHARE_PREFIXES`).
TABLE_UNITS: dict[str, dict[str, str]] = {
    "ims": {"im": "", "n_cases": "-", "n_overturned": "-", "mu": "-", **_FIT, "mu_lo": "-", "mu_hi": "-",
            "cv_percent": "%", "HR": "-", "loglik_per_case": "-", "mle_success": "", "mle_message": "",
            "n_boot_used": "-", "logistic_mu": "-", "logistic_beta_equivalent": "-", "rank_beta": "-", "rank_HR": "-",
            "rank_cv_percent": "-", "rank_loglik_per_case": "-"},
    "measure_fits": {"outcome": "", "mu": MEASURE, **_FIT, "mu_lo": MEASURE, "mu_hi": MEASURE, "n_overturned": "-",
                     "n_cases": "-"},
    "resurrections": {"block": "", "record": "", "floor": "", "n_levels": "-", "n_overturned": "-",
                      "first_overturned_level": "-", "first_overturned_value": MEASURE, "n_resurrected": "-",
                      "resurrected": ""},
    "sufficiency": {"im": "", "covariate": "", "coefficient": "-", "std_error": "-", "z": "-", "p_value": "-",
                    "n_cases": "-", "message": ""},
    "frequencies": {"im": "", "n_resamples": "-"},
    "blocks": {"block": "", "floor": "", "demand": "", "unit": "", "mu": PER_ROW, **_FIT, "mu_lo": PER_ROW,
               "mu_hi": PER_ROW, "n_cases": "-", "n_overturned": "-", "n_records": "-", "success": "", "message": ""},
    "robustness": {"im": ""},
    "sliding": {"block": "", "floor": "", "distance": "m", "measure": "", "demand": "", "unit": "", "median": PER_ROW,
                "median_lo": PER_ROW, "median_hi": PER_ROW, **_FIT, "n_cases": "-", "n_beyond": "-", "success": "",
                "message": ""},
}  # fmt: skip
#: Column prefixes of the per-criterion counts and shares (dimensionless) of ``frequencies`` and ``robustness``.
SHARE_PREFIXES: tuple[str, ...] = ("wins_", "share_")


def measure_unit(measure: str) -> str:
    """The unit of the scene's measure (:func:`opsrock.analysis.record_report.scene_measure`): ``g``, ``-``, or
    ``see measure`` for one not recognised."""
    return MEASURE_UNITS.get(measure, "see measure")


def units_of(table: str, columns: list[str], measure: str = "") -> list[str]:
    """The units row of ``table`` (a key of :data:`TABLE_UNITS`) with these ``columns``, :data:`MEASURE` in
    ``measure``'s unit; ``KeyError`` naming a column without a unit."""
    known = TABLE_UNITS[table]
    shares = table in ("frequencies", "robustness")
    missing = [c for c in columns if c not in known and not (shares and c.startswith(SHARE_PREFIXES))]
    if missing:
        raise KeyError(f"{table}.csv: columns without a unit in opsrock.analysis.record_columns.TABLE_UNITS: "
                       f"{missing!r}")
    units = [known.get(c, "-") for c in columns]
    return [measure_unit(measure) if u == MEASURE else u for u in units]


def write_record_table(df: pd.DataFrame, path: Path, measure: str = "") -> Path:
    """``df`` (no index) as ``path`` (``<table>.csv``) with its units row, atomically, every float at full precision;
    ``measure``: the scene's (:func:`measure_unit`)."""
    path = Path(path)
    return write_units_table(df, path, units_of(path.stem, list(df.columns), measure))


def read_record_table(path: str | Path, **read_csv: object) -> pd.DataFrame:
    """A table :func:`write_record_table` wrote, every float as written, its units row skipped; a table of an opsrock
    before the row (none after the header) reads to the same frame. Keyword arguments go to
    :func:`pandas.read_csv`."""
    return read_units_table(path, **read_csv)


__all__ = ["MEASURE", "SHARE_PREFIXES", "TABLE_UNITS", "measure_unit", "read_record_table", "units_of",
           "write_record_table"]
