"""The nine dimensionless intensity measures of the paper's Table 1.

Every IM is declared once, in :data:`IMS`, with its formula, physical meaning, the paper's
reference and its orientation. The formulas (Liu, Huang & Liu 2023, Table 1; docs/guide/modelling.md
section 2), with ``PFA`` in m/s², ``omega_p`` and ``p`` in rad/s, ``R`` in m:

======  ==============================================  ======================================
IM1     ``omega_p / p``                                  dimensionless excitation frequency
IM2     ``PFA / (g tan alpha)``                          dimensionless PFA
IM3     ``p PFV / (g tan alpha)``                        dimensionless PFV
IM4     ``1.484 IM2^1.644 IM1^-2.013``                   PFA-frequency combination
IM5     ``0.063 IM2^2.954 IM1^-0.942``                   PFA-frequency combination
IM6     ``IM2^0.52 IM1^-0.48``                           PFA-frequency combination
IM7     ``IM2^0.6 IM1^-0.4``                             PFA-frequency combination
IM8     ``e_R^4 p PFV / (g tan alpha)``                  dimensionless PFV with restitution
IM9     ``PFA T_p^2 / (R tan alpha)``                    dimensionless floor displacement
======  ==============================================  ======================================

``PFV`` follows a named convention (:data:`opsrock.excitations.PFV_CONVENTIONS`):
``"amplitude"`` = ``PFA / omega_p`` (the paper's, which its Table 3 medians fit) or
``"peak"`` = ``2 PFA / omega_p`` (the true peak floor velocity of a one-sine pulse from rest).
Only IM3 and IM8 depend on it; under ``"peak"`` both double.

For a one-sine pulse the IMs are functions of ``(IM1, IM2)`` and the block's ``e_R`` alone:
``IM3 = c IM2 / IM1`` (``c = 1`` amplitude, ``2`` peak), ``IM8 = e_R^4 IM3`` and, since
``p² = 3 g / (4 R)`` and ``T_p = 2 pi / omega_p``, ``IM9 = (16 pi² / 3) IM2 / IM1²``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from opsrock.constants import G
from opsrock.errors import InputError
from opsrock.excitations import PFV_CONVENTIONS
from opsrock.limits import one_of

if TYPE_CHECKING:
    from opsrock.block import Block
    from opsrock.excitations import OneSinePulse


@dataclass(frozen=True)
class IntensityMeasure:
    """Metadata of one intensity measure of the paper's Table 1.

    Parameters
    ----------
    name : str
        ``"IM1"`` .. ``"IM9"``.
    formula : str
        The expression, in plain text (symbols as in the paper).
    meaning : str
        Physical meaning (Table 1, column 3).
    reference : str
        Who proposed it (Table 1, column 4, the paper's reference number and first author).
    decreasing : bool
        True if overturning becomes LESS likely as the IM grows (only IM1, the frequency
        ratio: a faster pulse of the same PFA overturns less). The fragility of such an IM is
        ``P(overturn | IM = x) = Phi(ln(mu / x) / beta)``.
    depends_on_pfv : bool
        True if the IM depends on the PFV convention (IM3, IM8).
    """

    name: str
    formula: str
    meaning: str
    reference: str
    decreasing: bool = False
    depends_on_pfv: bool = False

    @property
    def label(self) -> str:
        """Axis label, e.g. ``"IM1 = omega_p/p"``."""
        return f"{self.name} = {self.formula}"


#: The nine IMs of the paper's Table 1 (Liu, Huang & Liu 2023, Section 4.2), in order.
IMS: tuple[IntensityMeasure, ...] = (
    IntensityMeasure("IM1", "omega_p/p", "Dimensionless excitation frequency",
                     "[38] Zhang & Makris 2001", decreasing=True),
    IntensityMeasure("IM2", "PFA/(g tan alpha)", "Dimensionless PFA", "[38] Zhang & Makris 2001"),
    IntensityMeasure("IM3", "p PFV/(g tan alpha)", "Dimensionless PFV",
                     "[56] Dimitrakopoulos & Paraskeva 2015", depends_on_pfv=True),
    IntensityMeasure("IM4", "1.484 IM2^1.644 IM1^-2.013",
                     "Dimensionless combination of PFA and floor-motion frequency",
                     "[56] Dimitrakopoulos & Paraskeva 2015"),
    IntensityMeasure("IM5", "0.063 IM2^2.954 IM1^-0.942",
                     "Dimensionless combination of PFA and floor-motion frequency",
                     "[56] Dimitrakopoulos & Paraskeva 2015"),
    IntensityMeasure("IM6", "IM2^0.52 IM1^-0.48",
                     "Dimensionless combination of PFA and floor-motion frequency",
                     "[56] Dimitrakopoulos & Paraskeva 2015"),
    IntensityMeasure("IM7", "IM2^0.6 IM1^-0.4",
                     "Dimensionless combination of PFA and floor-motion frequency",
                     "[56] Dimitrakopoulos & Paraskeva 2015"),
    IntensityMeasure("IM8", "e_R^4 p PFV/(g tan alpha)",
                     "Dimensionless PFV considering the restitution coefficient",
                     "[58] Sieber et al. 2022", depends_on_pfv=True),
    IntensityMeasure("IM9", "PFA T_p^2/(R tan alpha)", "Dimensionless floor displacement",
                     "[59] Liu, Huang & Liu 2023"),
)

#: IM names in Table 1 order.
IM_NAMES: tuple[str, ...] = tuple(im.name for im in IMS)

_BY_NAME = {im.name: im for im in IMS}

# Coefficients and exponents of the bivariate IMs, paper Table 1 (from Dimitrakopoulos &
# Paraskeva 2015, ref. [56]): IM = a IM2^m IM1^n.
BIVARIATE: dict[str, tuple[float, float, float]] = {
    "IM4": (1.484, 1.644, -2.013),
    "IM5": (0.063, 2.954, -0.942),
    "IM6": (1.0, 0.52, -0.48),
    "IM7": (1.0, 0.6, -0.4),
}

#: Exponent of ``e_R`` in IM8 (Sieber et al. 2022, ref. [58] of the paper; Table 1).
IM8_RESTITUTION_EXPONENT: float = 4.0


def get_im(name: str) -> IntensityMeasure:
    """Return the metadata of the IM called ``name`` (``"IM1"`` .. ``"IM9"``)."""
    one_of("name", name, IM_NAMES)
    return _BY_NAME[name]


def _positive_array(name: str, value: object) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    bad = ~(np.isfinite(arr) & (arr > 0.0))
    if np.any(bad):
        first = arr.ravel()[int(np.flatnonzero(bad.ravel())[0])]
        raise InputError(f"{name} must be positive and finite everywhere, got {first!r}")
    return arr


def intensity_measures_array(
    alpha: np.ndarray | float,
    R: np.ndarray | float,  # noqa: N803  (the paper's symbol)
    p: np.ndarray | float,
    e_R: np.ndarray | float,  # noqa: N803
    pfa: np.ndarray | float,
    omega_p: np.ndarray | float,
    pfv_convention: str = "amplitude",
) -> dict[str, np.ndarray]:
    """The nine IMs of Table 1 for arrays of blocks and one-sine pulses (broadcast).

    Parameters
    ----------
    alpha : array_like
        Block slenderness ``alpha`` (rad), in (0, pi/2).
    R : array_like
        Block size ``R = sqrt(b² + h²)`` (m).
    p : array_like
        Frequency parameter ``p = sqrt(3 g / 4 R)`` (rad/s).
    e_R : array_like
        Rigid-body restitution coefficient ``1 - 1.5 sin²(alpha)`` (dimensionless, > 0).
    pfa : array_like
        Peak floor acceleration ``PFA`` (m/s²).
    omega_p : array_like
        Pulse circular frequency ``omega_p`` (rad/s).
    pfv_convention : {"amplitude", "peak"}, optional
        ``PFV = PFA / omega_p`` (the paper's) or ``2 PFA / omega_p``.

    Returns
    -------
    dict of str to ndarray
        Keys ``"IM1"`` .. ``"IM9"``, each dimensionless, with the broadcast shape of the inputs.
    """
    one_of("pfv_convention", pfv_convention, PFV_CONVENTIONS)
    alpha = _positive_array("alpha", alpha)
    if np.any(alpha >= 0.5 * math.pi):
        raise InputError(f"alpha must be below pi/2 rad, got {float(np.max(alpha))!r}")
    R = _positive_array("R", R)  # noqa: N806
    p = _positive_array("p", p)
    e_R = _positive_array("e_R", e_R)  # noqa: N806
    pfa = _positive_array("pfa", pfa)
    omega_p = _positive_array("omega_p", omega_p)

    tan_alpha = np.tan(alpha)
    pfv = pfa / omega_p * (1.0 if pfv_convention == "amplitude" else 2.0)
    t_p = 2.0 * math.pi / omega_p
    im1 = omega_p / p
    im2 = pfa / (G * tan_alpha)
    im3 = p * pfv / (G * tan_alpha)
    out = {"IM1": im1, "IM2": im2, "IM3": im3}
    for name, (a, m, n) in BIVARIATE.items():
        out[name] = a * im2**m * im1**n
    out["IM8"] = e_R**IM8_RESTITUTION_EXPONENT * im3
    out["IM9"] = pfa * t_p**2 / (R * tan_alpha)
    shape = np.broadcast(alpha, R, p, e_R, pfa, omega_p).shape
    return {k: np.broadcast_to(out[k], shape).copy() for k in IM_NAMES}


def intensity_measures(
    block: "Block", pulse: "OneSinePulse", pfv_convention: str = "amplitude"
) -> dict[str, float]:
    """The nine IMs of Table 1 for one block under one pulse.

    Parameters
    ----------
    block : Block
        The block (sets ``alpha``, ``R``, ``p``, ``e_R``).
    pulse : Pulse
        The pulse (sets ``PFA`` in m/s² and ``omega_p`` in rad/s). The IMs keep their definitions
        for every shape, with ``omega_p`` as the shape defines it (:mod:`opsrock.excitations.pulses`:
        its own frequency for the harmonic pulses, ``pi / t_1`` for the rectangular pulse, the
        Fourier peak for the Ricker wavelet). ``pfv_convention="peak"`` (``2 PFA / omega_p``) is
        the one-sine pulse's true peak velocity and is meant for it only.
    pfv_convention : {"amplitude", "peak"}, optional
        PFV used by IM3 and IM8 (see :data:`opsrock.excitations.PFV_CONVENTIONS`).

    Returns
    -------
    dict of str to float
        ``{"IM1": ..., ..., "IM9": ...}``, dimensionless.
    """
    arrays = intensity_measures_array(
        block.alpha, block.R, block.p, block.e_R, pulse.pfa, pulse.omega_p, pfv_convention
    )
    return {k: float(v) for k, v in arrays.items()}


def add_intensity_measures(cases, pfv_convention: str = "amplitude"):
    """Return a copy of a cases table with columns ``IM1`` .. ``IM9`` (re)computed.

    Parameters
    ----------
    cases : pandas.DataFrame
        Needs columns ``alpha`` (rad), ``R`` (m), ``p`` (rad/s), ``e_R`` (-), ``pfa`` (m/s²)
        and ``omega_p`` (rad/s), as in the campaign's ``cases.csv``.
    pfv_convention : {"amplitude", "peak"}, optional
        PFV used by IM3 and IM8.

    Returns
    -------
    pandas.DataFrame
        A copy with the nine IM columns overwritten.
    """
    needed = ("alpha", "R", "p", "e_R", "pfa", "omega_p")
    missing = [c for c in needed if c not in cases.columns]
    if missing:
        raise KeyError(f"cases lacks the column(s) {missing} needed to compute the IMs")
    ims = intensity_measures_array(*(cases[c].to_numpy(float) for c in needed), pfv_convention)
    out = cases.copy()
    for k, v in ims.items():
        out[k] = v
    return out
