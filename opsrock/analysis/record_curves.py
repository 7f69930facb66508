"""The curves of a record figure (``opsrock records plot``): histories and response spectrum, computed
here so that :func:`opsrock.plots.records.plot_record` only draws."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from opsrock.excitations.records import Record, RecordInfo
from opsrock.intensity.records import response_spectrum, velocity_displacement


@dataclass(frozen=True)
class RecordCurves:
    """One motion's curves.

    Parameters
    ----------
    name : str
        The record's name.
    info : RecordInfo
        Where it comes from (event, year, station, floor).
    time : numpy.ndarray
        Sample times (s).
    acceleration : numpy.ndarray
        Acceleration (m/s²).
    velocity, displacement : numpy.ndarray
        Baseline-corrected velocity (m/s) and displacement (m) at the sample times.
    period : numpy.ndarray
        Oscillator periods of the response spectrum (s).
    psa : numpy.ndarray
        Pseudo-spectral acceleration, 5 % damping (m/s²).
    """

    name: str
    info: RecordInfo
    time: np.ndarray
    acceleration: np.ndarray
    velocity: np.ndarray
    displacement: np.ndarray
    period: np.ndarray
    psa: np.ndarray


def record_curves(record: Record) -> RecordCurves:
    """The histories and the 5 %-damped response spectrum of ``record`` (:mod:`opsrock.intensity.records`).

    Parameters
    ----------
    record : Record
        A ground or floor motion (m/s²).
    """
    v, d = velocity_displacement(record)
    spec = response_spectrum(record)
    return RecordCurves(name=record.name, info=record.info, time=record.time, acceleration=record.values,
                        velocity=v, displacement=d, period=spec["period"], psa=spec["psa"])


__all__ = ["RecordCurves", "record_curves"]
