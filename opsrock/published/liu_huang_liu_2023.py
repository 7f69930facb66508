"""Reference values printed in Liu, Huang & Liu (2023), digitised for side-by-side reports.

Source: Liu, Huang & Liu (2023), *Seismic Overturning Fragility Analysis for Rigid Blocks
Subjected to Floor Motions*, Sustainability 15, 4945, doi:10.3390/su15064945. Table 2 (Section 4.3)
and Table 3 (Section 4.5) are copied digit for digit from the paper's tables (no rounding
added). Table 3's CV column is the paper's ``beta / mu`` in percent; it is kept as printed,
not recomputed (recomputing from the 2-decimal mu and beta differs in the last digit).

Comparison caveat (docs/guide/modelling.md section 3): the paper's four blocks are not listed, so these
numbers cannot be matched one for one; what carries over is the ranking of the IMs and the
dimensionless medians of the IMs whose threshold is nearly geometry-free. IM3 and IM8 use
the paper's PFV convention, ``PFV = PFA / omega_p`` ("amplitude").
"""

from __future__ import annotations

from dataclasses import dataclass

import pandas as pd


@dataclass(frozen=True)
class Table2Row:
    """One row of the paper's Table 2 (dimensionless, IM units)."""

    W_HS: float  # noqa: N815  (the paper's symbols)
    R_S: float  # noqa: N815
    R_O: float  # noqa: N815
    W_HS_over_R_S: float  # noqa: N815
    W_HS_over_R_O: float  # noqa: N815
    HR: float  # noqa: N815
    W_SAS: float  # noqa: N815


@dataclass(frozen=True)
class Table3Entry:
    """One ``(IM, strip width)`` cell of the paper's Table 3: least-squares lognormal fit."""

    mu: float
    beta: float
    cv_percent: float


#: Paper Table 2, "Analysis parameters of different IMs" (Section 4.3).
TABLE2: dict[str, Table2Row] = {
    "IM1": Table2Row(4.00, 8.00, 5.50, 0.50, 0.73, 0.88, 0.80),
    "IM2": Table2Row(9.50, 9.50, 9.50, 1.00, 1.00, 1.41, 1.90),
    "IM3": Table2Row(1.00, 1.40, 10.00, 0.71, 0.10, 0.72, 0.20),
    "IM4": Table2Row(1.09, 1.40, 70.52, 0.78, 0.02, 0.78, 0.20),
    "IM5": Table2Row(10.43, 10.46, 65.42, 1.00, 0.16, 1.01, 2.00),
    "IM6": Table2Row(0.62, 1.01, 2.68, 0.61, 0.23, 0.65, 0.12),
    "IM7": Table2Row(1.12, 1.49, 3.34, 0.75, 0.34, 0.83, 0.20),
    "IM8": Table2Row(0.98, 1.14, 8.08, 0.86, 0.12, 0.87, 0.19),
    "IM9": Table2Row(8.77, 17.07, 543.92, 0.51, 0.02, 0.51, 1.70),
}

#: Strip-width factors of Table 3: ``W_AS = factor · W_SAS`` (Section 4.5).
STRIP_FACTORS: tuple[float, ...] = (0.5, 1.0, 2.0)

#: Paper Table 3, "Analysis parameters for different widths of the analysis strips":
#: ``TABLE3[im][factor]`` for ``W_AS = factor · W_SAS``.
TABLE3: dict[str, dict[float, Table3Entry]] = {
    "IM1": {0.5: Table3Entry(4.60, 0.32, 6.96), 1.0: Table3Entry(4.77, 0.32, 6.71),
            2.0: Table3Entry(4.68, 0.28, 5.98)},
    "IM2": {0.5: Table3Entry(7.65, 1.48, 19.35), 1.0: Table3Entry(7.97, 1.72, 21.59),
            2.0: Table3Entry(8.19, 2.22, 27.12)},
    "IM3": {0.5: Table3Entry(1.39, 0.12, 8.63), 1.0: Table3Entry(1.36, 0.14, 10.32),
            2.0: Table3Entry(1.40, 0.13, 9.27)},
    "IM4": {0.5: Table3Entry(1.28, 0.11, 8.58), 1.0: Table3Entry(1.27, 0.14, 11.05),
            2.0: Table3Entry(1.32, 0.13, 9.82)},
    "IM5": {0.5: Table3Entry(8.01, 0.40, 5.00), 1.0: Table3Entry(7.43, 0.48, 6.46),
            2.0: Table3Entry(7.76, 0.51, 6.57)},
    "IM6": {0.5: Table3Entry(1.25, 0.07, 5.59), 1.0: Table3Entry(1.27, 0.07, 5.52),
            2.0: Table3Entry(1.27, 0.09, 7.10)},
    "IM7": {0.5: Table3Entry(1.74, 0.10, 5.73), 1.0: Table3Entry(1.73, 0.12, 6.92),
            2.0: Table3Entry(1.72, 0.12, 6.97)},
    "IM8": {0.5: Table3Entry(1.11, 0.11, 9.94), 1.0: Table3Entry(1.09, 0.14, 12.88),
            2.0: Table3Entry(1.06, 0.26, 24.57)},
    "IM9": {0.5: Table3Entry(12.80, 0.17, 1.33), 1.0: Table3Entry(13.15, 0.15, 1.14),
            2.0: Table3Entry(13.28, 0.15, 1.13)},
}

#: The paper's stated conclusions on the ranking (Sections 4.3-4.5): IM9 has the smallest
#: HR (Table 2) and the smallest CV at every strip width (Figure 11, Table 3); IM1 has the
#: smallest ``W_HS / R_S`` (0.50).
PAPER_BEST = {"HR": "IM9", "cv_percent": "IM9", "W_HS_over_R_S": "IM1"}

#: Pulses per block and blocks in the paper's campaign (Section 3: "100 one-sine pulse
#: excitations", "400 uniformly distributed cases", four blocks of Figure 5).
PULSES_PER_BLOCK: int = 100
N_BLOCKS: int = 4


def table2_frame() -> pd.DataFrame:
    """The paper's Table 2 as a DataFrame (columns as :func:`opsrock.fragility.table2`)."""
    rows = [{"im": im, **vars(row)} for im, row in TABLE2.items()]
    return pd.DataFrame(rows)


def table3_frame() -> pd.DataFrame:
    """The paper's Table 3 as a long DataFrame: ``im, strip_factor, mu, beta, cv_percent``."""
    rows = [
        {"im": im, "strip_factor": f, "mu": e.mu, "beta": e.beta, "cv_percent": e.cv_percent}
        for im, cells in TABLE3.items()
        for f, e in cells.items()
    ]
    return pd.DataFrame(rows)
