"""``opsrock records list|show|plot``: the record library (:mod:`opsrock.excitations.library`), and
``show|plot`` of the user's own record file (``--units``, ``--dt``), checked for plausibility like every
record file (:func:`~opsrock.excitations.records.check_plausible_record`)."""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import sys
import time

import numpy as np

from opsrock._files import output_file
from opsrock.cli.common import given_by
from opsrock.constants import G
from opsrock.errors import UnknownRecordError, UsageError
from opsrock.excitations import library
from opsrock.excitations.building import ShearBuilding, floor_motion
from opsrock.excitations.readers import read_record
from opsrock.excitations.records import Record, check_plausible_record
from opsrock.limits import ACCEPT_OPTION

#: Periods (s) of the 5 %-damped spectrum ``records show`` prints for a record file.
SHOW_PERIODS: tuple[float, ...] = (0.05, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0)

#: ``records show`` of a record whose spectra are estimated to take longer than this (s) says so on stderr first.
LONG_SHOW_S: float = 10.0

#: Size (bytes) of a record file above which ``records show|plot`` say on stderr that they are reading it
#: (a text record is read at about 13 µs a sample: 5 MB, about 400,000 samples, take some 5 s).
LONG_READ_BYTES: int = 5_000_000


def records(args: argparse.Namespace) -> int:
    """``opsrock records list|show|plot``: the record library (:mod:`opsrock.excitations.library`)."""
    with given_by(f"records {args.records_command}"):
        return {"list": _records_list, "show": _records_show, "plot": _records_plot}[args.records_command](args)


def _entry_json(e) -> dict:
    i = e.info
    return {"name": e.name, "reference": e.reference, "event": i.event, "year": i.year, "magnitude": i.magnitude,
            "station": i.station, "component": i.component, "distance_km": i.distance_km, "vs30": i.vs30,
            "dt": e.dt, "npts": e.npts, "duration": e.duration, "pga_g": e.pga_g}


def _records_list(args: argparse.Namespace) -> int:
    if args.set not in library.SETS:
        raise UnknownRecordError(f"unknown record set {args.set!r}; the sets are {', '.join(library.SETS)}")
    entries = library.entries(args.set)
    if args.json:
        for e in entries:
            print(json.dumps(_entry_json(e)))
        return 0
    print(f"{'name':<22} {'event':<24} {'year':>4} {'M':>4} {'station':<28} {'dt s':>6} {'dur s':>6} {'PGA g':>6}")
    for e in entries:
        i = e.info
        print(f"{e.name:<22} {i.event[:24]:<24} {i.year:>4} {i.magnitude:>4.1f} {i.station[:28]:<28} "
              f"{e.dt:>6g} {e.duration:>6.1f} {e.pga_g:>6.3f}")
    print(f"{len(entries)} records in {library.LIBRARY}:{args.set} (name them as {library.LIBRARY}:{args.set}/NAME)")
    return 0


def _record(args: argparse.Namespace) -> Record:
    """The record ``NAME`` names (a library reference, or a file read with --units and --dt), a file's checked
    for plausibility unless --accept-implausible."""
    if not library.is_reference(args.name):
        with contextlib.suppress(OSError):
            size = os.stat(args.name).st_size
            if size > LONG_READ_BYTES:
                print(f"opsrock records: reading {args.name} ({size / 1e6:.1f} MB)", file=sys.stderr, flush=True)
    rec = read_record(args.name, units=args.units, dt=args.dt)
    check_plausible_record(rec, what=args.name, option=ACCEPT_OPTION, confirm=args.accept_implausible)
    return rec


def _records_show(args: argparse.Namespace) -> int:
    from opsrock.intensity.records import motion_measures  # lazy: scipy.integrate (0.45 s), for show only

    if not library.is_reference(args.name):
        return _file_show(args)
    if args.units is not None or args.dt is not None:
        raise UsageError(f"--{'units' if args.units is not None else 'dt'} applies to a record file, not to the "
                         f"library record {args.name}")
    e = library.entry(args.name)
    m = motion_measures(library.load(args.name))
    out = {**_entry_json(e), "pfa": m.pfa, "pfv": m.pfv, "pfd": m.pfd, "T_m": m.mean_period,
           "T_pred": m.predominant_period}
    if args.json:
        print(json.dumps(out))
    else:
        for k, v in out.items():
            print(f"{k:>12}: {v}")
        print("       units: pfa m/s², pfv m/s, pfd m, T_m and T_pred s (see opsrock.intensity.records)")
    return 0


def _file_show(args: argparse.Namespace) -> int:
    """``records show FILE``: the record's sampling, PFA (m/s² and g), PFV, PFD, periods and 5 %-damped
    spectrum at :data:`SHOW_PERIODS` (:mod:`opsrock.intensity.records`)."""
    from opsrock.intensity.records import (SPECTRUM_DAMPING, SPECTRUM_PERIODS,  # lazy: scipy
                                           motion_measures, response_spectrum, spectrum_seconds)

    rec = _record(args)
    periods = len(SPECTRUM_PERIODS) + len(SHOW_PERIODS)
    estimate = (spectrum_seconds(rec.values.size, len(SPECTRUM_PERIODS))
                + spectrum_seconds(rec.values.size, len(SHOW_PERIODS)))
    told = None
    if estimate > LONG_SHOW_S:
        print(f"opsrock records: {rec.values.size:,} samples ({rec.duration:,.0f} s at dt {rec.dt:g} s): its response "
              f"spectra at {periods} periods take about {_minutes(estimate)}", file=sys.stderr, flush=True)
        told = _SpectrumProgress(periods)
    m = motion_measures(rec, progress=told)
    spec = response_spectrum(rec, periods=np.asarray(SHOW_PERIODS), progress=None if told is None else told.then)
    out = {"name": rec.name, "source": rec.info.source, "units_in_file": rec.info.units_in_file, "dt": rec.dt,
           "npts": int(rec.values.size), "duration": rec.duration, "pfa": m.pfa, "pfa_g": m.pfa / G, "pfv": m.pfv,
           "pfd": m.pfd, "T_m": m.mean_period, "T_pred": m.predominant_period,
           "spectrum": {"damping": SPECTRUM_DAMPING, "period": spec["period"].tolist(), "psa": spec["psa"].tolist()}}
    if args.json:
        print(json.dumps(out))
        return 0
    for k, v in out.items():
        if k != "spectrum":
            print(f"{k:>13}: {v}")
    print("        units: values converted from units_in_file to m/s²; dt, duration, T_m and T_pred s; "
          "pfa m/s², pfa_g g, pfv m/s, pfd m (see opsrock.intensity.records)")
    print(f"pseudo-acceleration spectrum, {100 * SPECTRUM_DAMPING:g} % damping:")
    print(f"{'period s':>10} {'PSA m/s²':>10} {'PSA g':>8}")
    for t, a in zip(spec["period"], spec["psa"]):
        print(f"{t:>10g} {a:>10.4g} {a / G:>8.4g}")
    return 0


class _SpectrumProgress:
    """The progress of a long ``records show`` on stderr, terminal or not: a line every progress interval
    (``OPSROCK_PROGRESS_INTERVAL``, as campaigns), with the periods done of ``total``."""

    def __init__(self, total: int) -> None:
        from opsrock.campaign.run import progress_interval

        self.total, self.offset, self.interval = total, 0, progress_interval()
        self.last = time.monotonic()

    def __call__(self, done: int, _of: int) -> None:
        now = time.monotonic()
        if now - self.last >= self.interval:
            self.last = now
            print(f"opsrock records: spectra {self.offset + done}/{self.total} periods", file=sys.stderr, flush=True)

    def then(self, done: int, of: int) -> None:
        """The second spectrum's progress, after the first's ``total - of`` periods."""
        self.offset = self.total - of
        self(done, of)


def _minutes(seconds: float) -> str:
    return f"{seconds:.0f} s" if seconds < 120 else f"{seconds / 60:.0f} min"


def _records_plot(args: argparse.Namespace) -> int:
    from opsrock.analysis.record_curves import record_curves  # lazy: scipy.integrate, for plot only
    from opsrock.plots.records import plot_record  # lazy: matplotlib, only for this subcommand

    out = output_file("--out", args.out, ".png")
    if (args.building_period is None) != (args.storeys is None):
        raise UsageError("--building-period and --storeys go together")
    rec = _record(args)
    floor = None if args.building_period is None else floor_motion(
        rec, ShearBuilding("building", args.building_period, args.storeys))
    plot_record(record_curves(rec), out, floor=None if floor is None else record_curves(floor))
    print(f"wrote {out}")
    return 0


__all__ = ["records"]
