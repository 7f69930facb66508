"""Sampled floor (or ground) acceleration histories: :class:`Record` and its metadata.

A record is piecewise linear between its samples and zero after the last one; every solver
reads it that way (the compiled rigid-body solver integrates each sample interval with the
linear acceleration of that interval, OpenSees uses a ``Path`` time series, the scipy solvers
interpolate). Records are read by :func:`opsrock.excitations.readers.read_record` (files and library
references alike), made by the building filter (:mod:`opsrock.excitations.building`), or built
directly from an array.

Units
-----
A record holds m/s², always, and says so where it is shown (``repr``: ``PFA 3.2 m/s² (0.33 g)``).
``Record(dt, values, units="g")`` (or ``"cm/s2"``) converts at construction and remembers the unit given
in ``info.units_in_file``; ``units="m/s2"`` states that the values are m/s². Without ``units`` the values
are read as m/s², and refused when they look like another unit: a peak strictly between 0 and
:data:`~opsrock.limits.G_LIKE_PEAK` (1 m/s²) looks like g (the argument is there), a peak beyond
``PLAUSIBLE["pfa"]`` (10 g) like cm/s². The fix is in the message: ``units="g"``, or ``units="m/s2"`` to
confirm. A record whose ``info.units_in_file`` is set was converted from stated units already (read from
a file or the library, filtered, scaled, renamed: every copy keeps its info) and is not guessed at again.

A record's values as read from a user's file are checked against the plausibility bound (10 g) by
:func:`check_plausible_record`, which names the unit they look like given the units declared.
"""

from __future__ import annotations

import functools
import re
from dataclasses import InitVar, dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from opsrock.constants import G
from opsrock.errors import ImplausibleInputError, InputError, InputTypeError
from opsrock.limits import G_LIKE_PEAK, LIMITS, PLAUSIBLE, check, implausible_message

#: Prefix of record-library references (``fema-p695:<set>/<name>``; :mod:`opsrock.excitations.library`).
LIBRARY_PREFIX: str = "fema-p695:"

#: Units a record's samples may be given in (``Record(..., units=)``, record files), with the factor to m/s².
UNITS: dict[str, float] = {"g": G, "m/s2": 1.0, "cm/s2": 0.01}

if TYPE_CHECKING:
    from opsrock.block import Block


@dataclass(frozen=True)
class RecordInfo:
    """Where a record comes from (all optional; for tables, plots and case ids).

    Parameters
    ----------
    source : str
        File path or library reference (``"fema-p695:far-field/NORTHR_MUL009"``).
    event : str
        Earthquake name.
    year : int or None
        Year of the earthquake.
    magnitude : float or None
        Moment magnitude.
    station : str
        Recording station.
    component : str
        Component label (``"MUL009"``, ``"a"``, ...).
    distance_km : float or None
        Joyner-Boore distance (km), where the source gives it.
    vs30 : float or None
        Time-averaged shear-wave velocity of the top 30 m at the station (m/s).
    units_in_file : str
        Units the samples were given in before conversion to m/s² (``"g"``, ``"m/s2"``,
        ``"cm/s2"``); set by :class:`Record` when it is built (``"m/s2"`` for values taken as m/s²).
    floor : str
        ``"ground"`` for a ground motion, else the building and floor it was filtered to
        (``"b3.f3"``).
    """

    source: str = ""
    event: str = ""
    year: int | None = None
    magnitude: float | None = None
    station: str = ""
    component: str = ""
    distance_km: float | None = None
    vs30: float | None = None
    units_in_file: str = ""
    floor: str = "ground"


@dataclass(frozen=True, eq=False)
class Record:
    """An acceleration history sampled at a constant time step, held in m/s² (module docstring: Units).

    Parameters
    ----------
    dt : float
        Sampling interval (s), within :data:`opsrock.limits.LIMITS`.
    values : array_like
        Acceleration samples, in ``units`` (m/s² once built), finite, at ``t = 0, dt, 2 dt, ...``. Linear
        interpolation between samples; zero after the last one.
    name : str, optional
        Label of the record (letters, digits, ``_ . -`` when it is used in case ids).
    info : RecordInfo, optional
        Where it comes from.
    vertical : array_like or None, optional
        Vertical floor acceleration samples ``a_v`` (m/s², positive up) at the same times as
        ``values``, finite; the block then feels ``g + a_v``. Only the solvers of the ``friction``
        model take it; the others refuse a record that carries one. Given in ``units`` too. Default None
        (no vertical motion).
    units : {"g", "m/s2", "cm/s2"} or None, optional
        Unit of ``values`` and ``vertical`` as given (init only): converted to m/s² and remembered in
        ``info.units_in_file``. None (default): m/s², refused when the values look like g or cm/s² and the
        info states no units.

    Raises
    ------
    ImplausibleInputError
        Without ``units``, for values that look like g (a peak between 0 and 1 m/s²) or cm/s² (beyond 10 g),
        naming the fix.
    """

    dt: float
    values: np.ndarray = field(repr=False)
    name: str = ""
    info: RecordInfo = field(default_factory=RecordInfo, repr=False)
    vertical: np.ndarray | None = field(default=None, repr=False)
    units: InitVar[str | None] = None

    def __post_init__(self, units: str | None) -> None:
        object.__setattr__(self, "dt", check("dt", self.dt))
        if units is not None and units not in UNITS:
            raise InputError(f"units must be one of {', '.join(UNITS)}; got {units!r}", argument="units")
        factor = 1.0 if units is None else UNITS[units]
        arr = np.array(self.values, dtype=float, copy=True).ravel() * factor
        if arr.size < 2:
            raise InputError(f"values must hold at least 2 samples, got {arr.size}")
        if not np.all(np.isfinite(arr)):
            bad = int(np.flatnonzero(~np.isfinite(arr))[0])
            raise InputError(f"values must be finite; sample {bad} is {arr[bad]!r}")
        check("duration", (arr.size - 1) * self.dt)
        peak, limit = float(np.max(np.abs(arr))), LIMITS["pfa"]
        if not isinstance(self.info, RecordInfo):
            raise InputTypeError(f"info must be a RecordInfo, got {self.info!r}")
        if units is None and not self.info.units_in_file:
            self._refuse_unstated(peak)
        if peak > limit.high:
            raise InputError(f"values: the peak |a| = {peak:.4g} m/s² ({peak / G:.4g} g) of record "
                             f"{self.name or '<unnamed>'} exceeds {limit.high:g} m/s² ({limit.why})")
        arr.setflags(write=False)
        object.__setattr__(self, "values", arr)
        if not self.info.units_in_file:
            object.__setattr__(self, "info", replace(self.info, units_in_file=units or "m/s2"))
        if self.vertical is not None:
            object.__setattr__(self, "vertical", self._checked_vertical(arr.size, factor))

    def _refuse_unstated(self, peak: float) -> None:
        """Values given without units that look like g (peak in (0, G_LIKE_PEAK)) or cm/s² (beyond 10 g)."""
        label, plausible = self.name or "<unnamed>", PLAUSIBLE["pfa"]
        if 0.0 < peak < G_LIKE_PEAK:
            raise ImplausibleInputError(
                f"values: record {label} is given without units and peaks at {peak:.4g}: that looks like g "
                f"({peak:.4g} g = {peak * G:.4g} m/s²); read as m/s² ({peak / G:.3g} g) it could neither uplift a "
                f"block with b/h nor slide one with friction above {peak / G:.3g}; pass units='g', or units='m/s2' "
                "to confirm", argument="values")
        if peak > plausible.high:
            raise ImplausibleInputError(implausible_message(
                "pfa", peak, what=f"values: record {label}, given without units (read as m/s²): PFA", declared="m/s2",
                option="units='m/s2'", fix="pass units='{unit}'", among=tuple(UNITS)), argument="values")

    def __repr__(self) -> str:
        given = self.info.units_in_file
        return (f"Record({self.name!r}, dt={self.dt:g} s, {self.values.size} samples, {self.duration:g} s, "
                f"PFA {self.pfa:.4g} m/s² ({self.pfa / G:.3g} g)"
                + ("" if given in ("", "m/s2") else f", values in m/s² converted from {given}")
                + (", with vertical" if self.vertical is not None else "") + ")")

    def _checked_vertical(self, n: int, factor: float) -> np.ndarray:
        """The vertical samples (times ``factor`` to m/s²) as a read-only array of ``n`` finite values within
        the PFA limit."""
        v = np.array(self.vertical, dtype=float, copy=True).ravel() * factor
        label = self.name or "<unnamed>"
        if v.size != n:
            raise InputError(f"vertical: record {label} has {n} horizontal samples but {v.size} vertical ones; "
                             "give both at the same times")
        if not np.all(np.isfinite(v)):
            bad = int(np.flatnonzero(~np.isfinite(v))[0])
            raise InputError(f"vertical must be finite; sample {bad} of record {label} is {v[bad]!r}")
        peak, limit = float(np.max(np.abs(v))), LIMITS["pfa"]
        if peak > limit.high:
            raise InputError(f"vertical: the peak |a_v| = {peak:.4g} m/s² of record {label} exceeds "
                             f"{limit.high:g} m/s² ({limit.why})")
        v.setflags(write=False)
        return v

    @functools.cached_property
    def time(self) -> np.ndarray:
        """Sample times (s), read-only (computed once)."""
        t = np.arange(self.values.size) * self.dt
        t.setflags(write=False)
        return t

    @property
    def duration(self) -> float:
        """Time of the last sample (s)."""
        return (self.values.size - 1) * self.dt

    @property
    def pfa(self) -> float:
        """Peak absolute acceleration (m/s²)."""
        return float(np.max(np.abs(self.values)))

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """Acceleration (m/s²) at times ``t`` (s), linearly interpolated; zero outside.

        A scalar ``t`` (what the event-driven solvers ask, once per right-hand-side call) is
        interpolated in O(1) on the uniform grid with ``numpy.interp``'s own formula, so both paths
        give the same number; arrays go through ``numpy.interp``.
        """
        if isinstance(t, (float, int, np.floating)) and not isinstance(t, bool):
            return np.float64(self._at(float(t)))
        t = np.asarray(t, dtype=float)
        return np.interp(t, self.time, self.values, left=0.0, right=0.0)

    def _at(self, t: float) -> float:
        """Scalar interpolation: the bracket ``time[j] <= t < time[j + 1]`` found arithmetically."""
        times, v = self.time, self.values
        n = v.size
        if not (0.0 <= t <= times[-1]):
            return 0.0
        if t == times[-1]:
            return float(v[-1])
        j = min(int(t / self.dt), n - 2)
        while j > 0 and times[j] > t:  # round-off in t / dt: step to the true bracket
            j -= 1
        while j < n - 2 and times[j + 1] <= t:
            j += 1
        x0, x1 = times[j], times[j + 1]
        return float((v[j + 1] - v[j]) / (x1 - x0) * (t - x0) + v[j])

    @property
    def pfa_vertical(self) -> float:
        """Peak absolute vertical acceleration (m/s²); 0 without vertical samples."""
        return 0.0 if self.vertical is None else float(np.max(np.abs(self.vertical)))

    def vertical_acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """Vertical acceleration (m/s², positive up) at times ``t`` (s), linearly interpolated; zero
        outside the record and without vertical samples."""
        t = np.asarray(t, dtype=float)
        if self.vertical is None:
            return np.zeros_like(t)
        return np.interp(t, self.time, self.vertical, left=0.0, right=0.0)

    def with_vertical(self, vertical: np.ndarray | None) -> "Record":
        """A copy with the vertical samples ``vertical`` (m/s², same times as the horizontal ones)."""
        return replace(self, vertical=vertical)

    def breakpoints(self) -> np.ndarray:
        """Every sample time (s): the interpolated acceleration has a kink at each."""
        return self.time

    def scaled(self, factor: float) -> "Record":
        """The record times ``factor`` (dimensionless, within ``LIMITS["scale"]``)."""
        factor = check("scale", factor)
        vertical = None if self.vertical is None else self.vertical * factor
        return replace(self, values=self.values * factor, vertical=vertical)

    def scale_to(self, pfa: float) -> float:
        """The factor that brings the record's peak to ``pfa`` (m/s²): ``pfa / self.pfa``.

        Raises
        ------
        InputError
            If the record is all zeros (no factor gives it a peak).
        """
        if self.pfa == 0.0:
            raise InputError(f"record {self.name or '<unnamed>'} is all zeros: it cannot be scaled to a PFA")
        return pfa / self.pfa

    def scaled_to_pfa(self, pfa: float) -> "Record":
        """The record scaled so that its peak is ``pfa`` (m/s²), the factor within ``LIMITS["scale"]``.

        Raises
        ------
        InputError
            If the record is all zeros, or the factor lies outside the limit (naming the factor).
        """
        factor, lim = self.scale_to(pfa), LIMITS["scale"]
        if not lim.low <= factor <= lim.high:
            raise InputError(f"record {self.name or '<unnamed>'} needs a scale factor of {factor:.4g} to reach "
                             f"PFA = {pfa:.4g} m/s², outside [{lim.low:g}, {lim.high:g}]")
        return self.scaled(factor)

    def with_name(self, name: str, **info_changes) -> "Record":
        """A copy under another name, with fields of :attr:`info` replaced."""
        return replace(self, name=name, info=replace(self.info, **info_changes))


_NAME_SAFE = re.compile(r"[^A-Za-z0-9_.-]+")


def safe_name(text: str) -> str:
    """``text`` with every run of characters outside ``[A-Za-z0-9_.-]`` replaced by ``_`` (a record's name
    is part of case ids)."""
    return _NAME_SAFE.sub("_", text).strip("_") or "record"


def check_plausible_record(record: Record, *, what: str, option: str, confirm: bool = False,
                           declared_units: str | None = None, units_option: str = "--units") -> None:
    """Refuse a record read from the user's file whose PFA exceeds ``PLAUSIBLE["pfa"]`` (10 g) unless
    ``confirm``, naming the unit its values look like given the units declared: the one check of every user
    boundary that reads a record (command line, scene, motions manifest). Records are checked as read,
    before any scaling; library records are real and never refused.

    Parameters
    ----------
    record : Record
        The record as read (m/s²).
    what : str
        Where it came from, for the message (``"--record rec.csv"``, ``"scene.toml: records.files rec.csv"``).
    option : str
        How the user confirms it (``"--accept-implausible"``, ``"accept_implausible = true"``).
    confirm : bool
        True: confirmed; nothing is checked.
    declared_units : str, optional
        The units the file was declared in (a key of :data:`UNITS`); default ``record.info.units_in_file``.
    units_option : str
        Where the user gives the units, for the fix (``"--units"``, ``"records.units ="``, ``"the units
        column"``); an ``.AT2`` file's units are its header's, and the fix says so.

    Raises
    ------
    ImplausibleInputError
        One line: the record, its PFA as written and in m/s², the bound and why, the unit the values look
        like and the fix ("the values look like cm/s² declared as g: give --units cm/s2"), and ``option``.
    """
    source = record.info.source
    if confirm or source.startswith(LIBRARY_PREFIX) or record.pfa <= PLAUSIBLE["pfa"].high:
        return
    declared = declared_units or record.info.units_in_file or "m/s2"
    fix = ("correct the units on line 3 of its header to {unit}" if source.lower().endswith(".at2")
           else f"give {units_option} {{unit}}")
    raise ImplausibleInputError(implausible_message("pfa", record.pfa, what=f"{what}: PFA", declared=declared,
                                                    option=option, fix=fix, among=tuple(UNITS)), argument=what)


def check_sampling(record: Record, block: "Block") -> None:
    """Refuse a record sampled too coarsely for ``block`` (``LIMITS["record_dt_p"]``).

    Raises
    ------
    ValueError
        Naming the record, its ``dt`` (s), the block's ``p`` (rad/s) and the limit.
    """
    ratio = record.dt * block.p
    limit = LIMITS["record_dt_p"]
    if ratio > limit.high:
        raise InputError(
            f"record {record.name or '<unnamed>'}: dt = {record.dt:g} s is too coarse for block "
            f"{block.name or '<unnamed>'} (p = {block.p:.4g} rad/s): dt p = {ratio:.3g} > {limit.high:g}; "
            f"resample the record to dt <= {limit.high / block.p:.3g} s")


__all__ = ["LIBRARY_PREFIX", "Record", "RecordInfo", "UNITS", "check_plausible_record", "check_sampling", "safe_name"]
