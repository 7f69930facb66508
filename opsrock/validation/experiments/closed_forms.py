"""The closed forms of validation case ``experiments``: the SDOF model's running product of impact
ratios."""

from __future__ import annotations

import numpy as np

from opsrock.block import Block
from opsrock.model import SDOFModel
from opsrock.solvers.sdof import table_potential


def sdof_closed_form(block: Block, theta0: float, n_impacts: int) -> np.ndarray:
    """The SDOF model's running product of impact ratios in closed form (dimensionless, NaN at rest).

    The damper keeps ``e²`` of the energy ``E = 1/2 I_O theta'² + U(theta)`` per passage (``U`` the
    table spring's potential), flight conserves it, and an impact's velocities are logged at the band
    edges ``|theta| = delta alpha``; so after ``n`` passages ``E_n = e^(2n) U(theta0)`` and the product
    telescopes to ``sqrt((E_n - U(delta alpha)) / (E_0 - U(delta alpha)))``.

    Parameters
    ----------
    block : Block
        The block (its ``e``).
    theta0 : float
        Release angle (rad).
    n_impacts : int
        Impacts (no unit).
    """
    model = SDOFModel()
    u = table_potential(*model.spring_table(block))
    e0, ub = float(u(theta0)), float(u(model.band(block)))
    en = block.e ** (2.0 * np.arange(1, n_impacts + 1)) * e0
    with np.errstate(invalid="ignore"):
        return np.where(en > ub, np.sqrt(np.maximum(en - ub, 0.0) / (e0 - ub)), np.nan)
