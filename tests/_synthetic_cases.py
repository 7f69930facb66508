"""A synthetic campaign that several test modules share (importable from every folder of the suite: ``pythonpath =
["tests"]``): test modules import it, never each other, so each collects alone."""

from __future__ import annotations

import numpy as np
import pandas as pd

from opsrock import Block, OneSinePulse

# --- a synthetic campaign ----------------------------------------------------------------
# A 10 x 10 grid of one-sine pulses for one block, with verdicts that follow a known
# boundary, "overturned iff IM2 > 1.7 IM1" (the overturning spectrum's lower boundary is
# roughly this shape: faster pulses need larger PFA). The grid is built to reproduce the
# paper's Table 2 IM1 and IM2 rows:
#   IM1 values {0.5, 2, 3, ..., 10}: safe cases span IM1 in [2, 10] (R_S = 8.00), overturned
#   ones [0.5, 6] (R_O = 5.50), overlap [2, 6] (W_HS = 4.00), W_SAS = 0.80, HR = 0.88;
#   IM2 from 1.5 to 11 in 10 equal steps (range 9.5, every pulse above the uplift threshold
#   IM2 = 1): both states occur at IM2 = 1.5 (IM1 = 0.5) and at 11 (IM1 = 10), so
#   W_HS = R_S = R_O = 9.50, HR = sqrt(2) = 1.41, W_SAS = 1.90.
GRID_IM1 = np.array([0.5, 2, 3, 4, 5, 6, 7, 8, 9, 10.0])
GRID_IM2 = np.linspace(1.5, 11.0, 10)
BOUNDARY_SLOPE = 1.7


def case_row(block: Block, pulse: OneSinePulse, verdict: str) -> dict:
    return {
        "block": block.name, "alpha": block.alpha, "R": block.R, "p": block.p,
        "e_R": block.e_R, "pfa": pulse.pfa, "omega_p": pulse.omega_p,
        "status": "failed" if verdict == "failed" else "ok",
        "rocked": verdict in ("safe", "overturned"),
        "overturned": verdict == "overturned", "verdict": verdict,
    }


def grid_cases(block: Block | None = None) -> pd.DataFrame:
    block = block or Block(0.4, 1.6, name="B1")
    rows = []
    for im1 in GRID_IM1:
        for im2 in GRID_IM2:
            verdict = "overturned" if im2 > BOUNDARY_SLOPE * im1 else "safe"
            rows.append(case_row(block, OneSinePulse.from_ratios(block, im2, im1), verdict))
    return pd.DataFrame(rows)
