"""Intensity measures of recorded floor motions, and the paper's nine IMs generalised to them.

Signal processing is eqsig's (``eqsig.AccSignal`` for integration and the Fourier amplitude
spectrum, ``eqsig.sdof`` for the Nigam-Jennings response spectra, exact for piecewise-linear
acceleration); this module only states the conventions.

Conventions
-----------
* ``PFA`` = ``max |a|`` (m/s²).
* ``PFV`` = ``max |v|`` (m/s), ``v`` the trapezoidal integral of ``a`` from rest with one
  baseline correction: the residual velocity ``v(T)`` is removed as a constant acceleration
  offset, i.e. ``v_c(t) = v(t) - v(T) t / T``; processed records end with ``v(T)`` near zero and
  barely change, an uncorrected filter output would otherwise drift. ``PFD`` = ``max |d|`` (m),
  ``d`` the trapezoidal integral of ``v_c``.
* ``T_m``: the mean period of Rathje, Abrahamson & Bray (1998), ``sum(C_i² / f_i) / sum(C_i²)``
  over the Fourier amplitudes ``C_i`` at ``0.25 <= f_i <= 20`` Hz (s).
* ``T_pred``: the predominant period, where the 5 %-damped pseudo-acceleration spectrum peaks, on
  :data:`SPECTRUM_PERIODS` (s).

The nine IMs of Table 1 need a pulse frequency ``omega_p``; for a record we put ``omega_p ->
2 pi / T_m`` and use the measured ``PFV``: ``IM1 = (2 pi / T_m) / p``, ``IM2 = PFA / (g tan
alpha)``, ``IM3 = p PFV / (g tan alpha)``, ``IM4..IM7`` the same powers of IM1 and IM2,
``IM8 = e_R^4 IM3``, ``IM9 = PFA T_m² / (R tan alpha)``. How they reduce for a one-sine pulse
(``tests/unit/intensity/test_intensity.py``): IM2 exactly; IM3 and IM8 to the ``"peak"`` PFV convention
(``2 PFA / omega_p``, the true peak velocity of the pulse), twice the paper's ``"amplitude"``
values; IM1, IM4-IM7 and IM9 reduce only approximately, because the mean period of a single sine
cycle is not quite its period: ``T_m / T_p`` = 1.023 for ``T_p`` from 0.25 to 2 s (measured
there), its broad Fourier spectrum weighting the long periods a little more. So IM1 is 2.2 %
low and IM9 4.6 % high against the pulse formulas.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from opsrock.constants import G
from opsrock.errors import InputError
from opsrock.excitations.records import Record
from opsrock.intensity.table1 import BIVARIATE, IM8_RESTITUTION_EXPONENT, IM_NAMES

#: Frequency band of the mean period (Hz), Rathje et al. (1998).
MEAN_PERIOD_BAND: tuple[float, float] = (0.25, 20.0)

#: Periods (s) of the spectra used for the predominant period: 200 points, log-spaced 0.02-5 s.
SPECTRUM_PERIODS: np.ndarray = np.geomspace(0.02, 5.0, 200)

#: Damping ratio of the spectra (dimensionless).
SPECTRUM_DAMPING: float = 0.05


@dataclass(frozen=True)
class MotionMeasures:
    """Scalar measures of one acceleration history.

    Parameters
    ----------
    pfa : float
        Peak absolute acceleration (m/s²).
    pfv : float
        Peak velocity, baseline-corrected (m/s).
    pfd : float
        Peak displacement (m).
    mean_period : float
        Rathje's mean period ``T_m`` (s).
    predominant_period : float
        Period of the peak of the 5 %-damped pseudo-acceleration spectrum (s).
    """

    pfa: float
    pfv: float
    pfd: float
    mean_period: float
    predominant_period: float

    def scaled(self, factor: float) -> "MotionMeasures":
        """Measures of the record times ``factor`` (peaks scale, periods do not)."""
        return MotionMeasures(self.pfa * factor, self.pfv * factor, self.pfd * factor,
                              self.mean_period, self.predominant_period)


def velocity_displacement(record: Record) -> tuple[np.ndarray, np.ndarray]:
    """Baseline-corrected velocity (m/s) and displacement (m) at the sample times (see module)."""
    import eqsig
    import scipy.integrate  # here, as eqsig: every command that reads records imports this module, few integrate

    v = np.asarray(eqsig.AccSignal(np.asarray(record.values), record.dt).velocity, dtype=float)
    t = record.time
    v = v - v[-1] * t / t[-1]
    d = scipy.integrate.cumulative_trapezoid(v, dx=record.dt, initial=0.0)
    return v, d


def mean_period(record: Record, band: tuple[float, float] = MEAN_PERIOD_BAND) -> float:
    """Rathje et al. (1998) mean period ``T_m`` (s) of ``record`` over ``band`` (Hz)."""
    import eqsig

    sig = eqsig.AccSignal(np.asarray(record.values), record.dt)
    f = np.asarray(sig.fa_frequencies)
    c2 = np.abs(np.asarray(sig.fa_spectrum)) ** 2
    inside = (f >= band[0]) & (f <= band[1])
    if not np.any(inside) or c2[inside].sum() == 0.0:
        raise InputError(f"record {record.name!r} has no Fourier amplitude in {band[0]:g}-{band[1]:g} Hz")
    return float(np.sum(c2[inside] / f[inside]) / np.sum(c2[inside]))


#: Bytes the response spectrum's work arrays may take at once. eqsig keeps three arrays of periods x samples (response
#: displacement, velocity and acceleration), 4.8 GB for 200 periods of a million samples: the periods are taken in
#: chunks that fit, each period's values the same whatever the chunk (eqsig's recurrence works period by period,
#: element-wise).
SPECTRUM_WORK_BYTES: float = 400e6

#: Seconds of eqsig's Nigam-Jennings per time step of one chunk of periods, and per time step and period (measured
#: on 100,000 samples at 2, 20 and 200 periods on the project's 2-core machine, issue 46: 8.2 us and 0.07 us).
SPECTRUM_S_PER_STEP: float = 8e-6
SPECTRUM_S_PER_STEP_PERIOD: float = 0.07e-6


def periods_per_chunk(n_samples: int) -> int:
    """Periods of a response spectrum computed at once for a record of ``n_samples`` samples, within
    :data:`SPECTRUM_WORK_BYTES` (at least one)."""
    return max(1, int(SPECTRUM_WORK_BYTES // (3 * 8 * max(1, n_samples))))


def spectrum_seconds(n_samples: int, n_periods: int) -> float:
    """Expected seconds of CPU of :func:`response_spectrum` on ``n_samples`` samples at ``n_periods`` periods."""
    chunks = math.ceil(n_periods / periods_per_chunk(n_samples))
    return n_samples * (chunks * SPECTRUM_S_PER_STEP + n_periods * SPECTRUM_S_PER_STEP_PERIOD)


def response_spectrum(record: Record, periods: np.ndarray = SPECTRUM_PERIODS,
                      damping: float = SPECTRUM_DAMPING, progress=None) -> dict[str, np.ndarray]:
    """Elastic response spectra of ``record`` (Nigam-Jennings, via eqsig), the periods taken in chunks of
    :func:`periods_per_chunk` so that the work arrays stay within :data:`SPECTRUM_WORK_BYTES`.

    Parameters
    ----------
    record : Record
        The (floor or ground) motion.
    periods : array_like
        Oscillator periods (s), > 0.
    damping : float
        Damping ratio (dimensionless).
    progress : callable, optional
        Called as ``progress(done, total)`` (periods) after each chunk.

    Returns
    -------
    dict
        ``"period"`` (s), ``"sd"`` (m), ``"psa"`` pseudo-acceleration ``w² S_d`` (m/s²) and
        ``"sa"`` absolute-acceleration spectrum (m/s²).
    """
    import eqsig.sdof

    periods = np.asarray(periods, dtype=float)
    if periods.ndim != 1 or periods.size == 0 or not np.all(np.isfinite(periods) & (periods > 0)):
        raise InputError("periods must be a non-empty 1-D array of positive periods (s)")
    values = np.asarray(record.values)
    step = periods_per_chunk(values.size)
    sd, sa = np.empty(periods.size), np.empty(periods.size)
    for start in range(0, periods.size, step):
        part = slice(start, start + step)
        sd[part], _, sa[part] = eqsig.sdof.true_response_spectra(values, record.dt, periods[part], damping)
        if progress is not None:
            progress(min(start + step, periods.size), periods.size)
    psa = (2.0 * math.pi / periods) ** 2 * sd
    return {"period": periods, "sd": sd, "psa": psa, "sa": sa}


def motion_measures(record: Record, progress=None) -> MotionMeasures:
    """PFA, PFV, PFD, ``T_m`` and ``T_pred`` of ``record`` (see the module's conventions); ``progress`` as
    :func:`response_spectrum` takes it."""
    v, d = velocity_displacement(record)
    spec = response_spectrum(record, progress=progress)
    return MotionMeasures(
        pfa=record.pfa,
        pfv=float(np.max(np.abs(v))),
        pfd=float(np.max(np.abs(d))),
        mean_period=mean_period(record),
        predominant_period=float(spec["period"][int(np.argmax(spec["psa"]))]),
    )


def record_intensity_measures(alpha, R, p, e_R, measures: MotionMeasures) -> dict[str, float]:  # noqa: N803
    """The nine IMs of Table 1 generalised to a record (``omega_p -> 2 pi / T_m``; module docstring).

    Parameters
    ----------
    alpha : float
        Block slenderness (rad).
    R : float
        Block size ``R`` (m).
    p : float
        Frequency parameter ``p`` (rad/s).
    e_R : float
        Rigid-body restitution coefficient (dimensionless).
    measures : MotionMeasures
        The floor motion's measures (already scaled).

    Returns
    -------
    dict of str to float
        ``"IM1"`` .. ``"IM9"``, dimensionless.
    """
    tan_alpha = math.tan(alpha)
    omega_m = 2.0 * math.pi / measures.mean_period
    im1 = omega_m / p
    im2 = measures.pfa / (G * tan_alpha)
    im3 = p * measures.pfv / (G * tan_alpha)
    out = {"IM1": im1, "IM2": im2, "IM3": im3}
    for name, (a, m, n) in BIVARIATE.items():
        out[name] = a * im2**m * im1**n
    out["IM8"] = e_R**IM8_RESTITUTION_EXPONENT * im3
    out["IM9"] = measures.pfa * measures.mean_period**2 / (R * tan_alpha)
    return {k: float(out[k]) for k in IM_NAMES}


__all__ = ["MEAN_PERIOD_BAND", "MotionMeasures", "SPECTRUM_DAMPING", "SPECTRUM_PERIODS", "SPECTRUM_S_PER_STEP",
           "SPECTRUM_S_PER_STEP_PERIOD", "SPECTRUM_WORK_BYTES", "mean_period", "periods_per_chunk", "spectrum_seconds",
           "motion_measures", "record_intensity_measures", "response_spectrum", "velocity_displacement"]
