"""The ``opsrock`` command line.

    opsrock simulate --width 2B --height 2H (--pfa G | --pfa-ratio X) (--freq HZ | --freq-ratio Y) ...
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
    p = sub.add_parser("simulate", help="one block, one one-sine pulse", description="Simulate one block under one one-sine pulse.")
    p.add_argument("--width", required=True, type=_finite("--width"), help="full width 2b (m)")
    p.add_argument("--height", required=True, type=_finite("--height"), help="full height 2h (m)")
    p.add_argument("--mass", type=_finite("--mass"), default=1.0, help="mass (kg); scales moments only (default 1)")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--pfa", type=_finite("--pfa"), help="peak floor acceleration (g)")
    g.add_argument("--pfa-ratio", type=_finite("--pfa-ratio"), help="PFA / (g tan alpha)")
    f = p.add_mutually_exclusive_group(required=True)
    f.add_argument("--freq", type=_finite("--freq"), help="pulse frequency (Hz)")
    f.add_argument("--freq-ratio", type=_finite("--freq-ratio"), help="omega_p / p")
    p.add_argument("--solver", default="opensees", help="opensees (default), sdof, housner, housner_fast")
    p.add_argument("--delta", type=_finite("--delta"), help="damper band, fraction of alpha (SDOF models)")
    p.add_argument("--dt", type=_finite("--dt"), help="time step (s) (opensees)")
    p.add_argument("--lever", help="excitation lever: housner (m R cos alpha, default) or printed (I_O cos alpha / R)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="draw the rotation history and the model hysteresis (Figure 3)")
    p.set_defaults(func=_simulate)


def _simulate(args: argparse.Namespace) -> int:
    from opsrock.block import Block
    from opsrock.excitation import OneSinePulse
    from opsrock.model import LEVERS, SDOFModel
    from opsrock.solvers import SOLVERS, simulate

    if args.solver not in SOLVERS:
        raise UsageError(f"--solver must be one of {', '.join(SOLVERS)}; got {args.solver!r}")
    if args.lever is not None and args.lever not in LEVERS:
        raise UsageError(f"--lever must be one of {', '.join(LEVERS)}; got {args.lever!r}")
    if args.plot is not None:
        from opsrock._paths import output_file

        try:
            output_file("--plot", args.plot, ".png")
        except ValueError as exc:
            raise UsageError(str(exc)) from None
    sdof_like = args.solver in ("opensees", "sdof")
    if not sdof_like and (args.delta is not None or args.lever is not None):
        raise UsageError(f"--delta and --lever apply to the SDOF models (opensees, sdof), not --solver {args.solver}")
    if args.dt is not None and args.solver != "opensees":
        raise UsageError(f"--dt applies to --solver opensees only, not --solver {args.solver}")
    try:
        block = Block(width=args.width, height=args.height, mass=args.mass)
        from opsrock.constants import G
        from opsrock.limits import scaled_input

        if args.pfa_ratio is not None:
            pfa = scaled_input("--pfa-ratio", args.pfa_ratio, "pfa", block.uplift_acceleration)
        else:
            pfa = scaled_input("--pfa", args.pfa, "pfa", G)
        if args.freq_ratio is not None:
            omega_p = scaled_input("--freq-ratio", args.freq_ratio, "omega_p", block.p)
        else:
            omega_p = scaled_input("--freq", args.freq, "omega_p", 2.0 * math.pi)
        pulse = OneSinePulse(pfa=pfa, omega_p=omega_p)
        settings = {}
        if args.delta is not None:
            SDOFModel(delta=args.delta)  # checks the value, naming the argument
            settings["delta"] = args.delta
        if args.lever is not None:
            settings["lever"] = args.lever
        if args.dt is not None:
            settings["dt"] = args.dt
    except (ValueError, TypeError) as exc:
        raise UsageError(str(exc)) from None
    try:
        # the solvers check their settings before any work and raise only for bad settings;
        # a solver failure is a failed result, never an exception
        result = simulate(block, pulse, solver=args.solver, **settings)
    except (ValueError, TypeError) as exc:
        raise UsageError(str(exc)) from None
    summary = result.summary()
    out = {
        "theta_max": summary["theta_max"],
        "theta_max_over_alpha": summary["theta_max_over_alpha"],
        "overturned": summary["overturned"],
        "rocked": summary["rocked"],
        "verdict": summary["verdict"],
        "status": summary["status"],
        "reason": summary["reason"],
        "solver": summary["solver"],
        "alpha": block.alpha,
        "R": block.R,
        "p": block.p,
        "e": block.e,
        "e_R": block.e_R,
        "pfa": pulse.pfa,
        "pfa_ratio": pulse.pfa_ratio(block),
        "omega_p": pulse.omega_p,
        "freq_ratio": pulse.freq_ratio(block),
        "T_p": pulse.T_p,
        "n_steps": summary["n_steps"],
        "n_impacts": summary["n_impacts"],
        "wall_time_s": summary["wall_time_s"],
        "settings": summary["settings"],
    }
    if args.plot:
        from opsrock.plots.response import plot_response

        plot_response(result, block, pulse, args.plot)
    if args.json:
        print(json.dumps(out, default=str))
    else:
        print(
            f"block 2b x 2h = {block.width:g} x {block.height:g} m: alpha = {block.alpha:.4f} rad, "
            f"R = {block.R:.4f} m, p = {block.p:.4f} rad/s, e = {block.e:.4f}\n"
            f"pulse PFA = {pulse.pfa:.4g} m/s² ({out['pfa_ratio']:.3g} g tan alpha), "
            f"omega_p = {pulse.omega_p:.4g} rad/s ({out['freq_ratio']:.3g} p), T_p = {pulse.T_p:.4g} s\n"
            f"{result.solver}: {result.verdict}; theta_max = {result.theta_max:.5g} rad "
            f"= {result.theta_max_over_alpha:.4g} alpha; {result.n_steps} steps in {result.wall_time_s:.3f} s"
            + (f"\nfailed: {result.reason}" if not result.ok else "")
        )
    return 0 if result.ok else EXIT_FAILED


# --- subcommands provided by other modules ------------------------------------------------------
#: Subcommands implemented elsewhere: name -> (module, add-arguments function, run function, help).
_EXTERNAL = {
    "run": ("opsrock.campaign", "add_run_arguments", "run_command", "run every case of a scene"),
    "reproduce": ("opsrock.reproduce", "add_arguments", "run_command", "every figure and table of the paper"),
    "validate": ("opsrock.validation", "add_arguments", "run_command", "regenerate the validation cases"),
    "bench": ("opsrock.bench", "add_arguments", "run_command", "benchmarks: ratios measured in one run"),
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
    except KeyboardInterrupt:
        print("opsrock: interrupted (finished cases are kept; re-run the same command to resume)", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
