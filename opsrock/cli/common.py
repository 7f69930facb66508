"""What the handlers share: the error path from a library argument to
the option that gave it, and the block, pulse and model options of ``simulate`` and ``threshold``.

The rules of the physics live in the library (:class:`~opsrock.block.Block` checks the friction
coefficients, the solvers their settings); here options are only turned into arguments, and a library
error that carries the argument at fault (:attr:`opsrock.errors.OpsrockError.argument`) is told under the
option's name (:func:`named_options`), never by matching its text.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Iterator, Mapping
from contextlib import contextmanager

from opsrock.block import Block
from opsrock.constants import EQUATIONS, G
from opsrock.errors import OpsrockError, UsageError
from opsrock.excitations import PULSE_SHAPES
from opsrock.limits import check, scaled_input
from opsrock.model import DAMPER_LAWS, LEVERS, SDOFModel
from opsrock.restitution import law_factor
from opsrock.solvers.registry import METHODS, solver_names

#: Arguments of :class:`~opsrock.block.Block`, the solvers' settings and the restitution laws -> the option
#: that gives each.
BLOCK_OPTIONS: dict[str, str] = {
    "width": "--width", "height": "--height", "mass": "--mass", "restitution": "--restitution",
    "restitution_factor": "--restitution-law", "restitution_law": "--restitution-law", "friction": "--friction",
    "friction_kinetic": "--friction-kinetic", "step": "--step", "equations": "--equations", "delta": "--delta",
    "lever": "--lever", "damper": "--damper",
}


@contextmanager
def named_options(options: Mapping[str, str]) -> Iterator[None]:
    """Tell a library error under the option the user gave: one whose ``argument`` is a key of ``options``
    becomes a :class:`~opsrock.errors.UsageError` ``"<option>: <the library's message>"``."""
    try:
        yield
    except OpsrockError as exc:
        option = options.get(exc.argument or "")
        if option is None:
            raise
        raise UsageError(f"{option}: {exc}") from None


@contextmanager
def given_by(option: str) -> Iterator[None]:
    """Tell any library error of the block under ``option`` (the one option its inputs came from)."""
    try:
        yield
    except UsageError:
        raise
    except OpsrockError as exc:
        raise UsageError(f"{option}: {exc}") from None


def _models(model: str) -> str:
    return ", ".join(n for n in solver_names() if METHODS.get(n).model == model)


def check_model_args(args: argparse.Namespace) -> None:
    """Options that do not go together or name no choice: UsageError naming them. The default solver
    is ``friction`` when the block may slide or the floor moves vertically."""
    moves_vertically = getattr(args, "vertical", None) is not None or getattr(args, "vertical_record", None) is not None
    if args.solver is None:
        slides = args.friction is not None or args.friction_kinetic is not None
        args.solver = "friction" if (slides or moves_vertically) else args.default_solver
    info = METHODS.get(args.solver)
    if info is None:
        raise UsageError(f"--solver must be one of {', '.join(solver_names())}; got {args.solver!r}")
    if args.pulse not in PULSE_SHAPES:
        raise UsageError(f"--pulse must be one of {', '.join(PULSE_SHAPES)}; got {args.pulse!r}")
    if args.duration is not None and args.pulse != "rectangular":
        raise UsageError(f"--duration applies to --pulse rectangular, not --pulse {args.pulse} (use --freq or --freq-ratio)")
    for option, value, allowed in (("--lever", args.lever, LEVERS), ("--damper", args.damper, DAMPER_LAWS),
                                   ("--equations", args.equations, EQUATIONS)):
        if value is not None and value not in allowed:
            raise UsageError(f"{option} must be one of {', '.join(allowed)}; got {value!r}")
    if info.model != "sdof" and (args.delta is not None or args.lever is not None or args.damper is not None):
        raise UsageError(f"--delta, --lever and --damper apply to the SDOF models ({_models('sdof')}), not "
                         f"--solver {args.solver}")
    if info.model != "rigid" and args.equations is not None:
        raise UsageError(f"--equations applies to the rigid-body solvers ({_models('rigid')}), not --solver {args.solver}")
    if not info.friction:  # the solvers with friction (models friction, rigid3d) take vertical motion too
        given = [o for o, v in (("--friction", args.friction), ("--friction-kinetic", args.friction_kinetic),
                                ("--vertical", getattr(args, "vertical", None)),
                                ("--vertical-record", getattr(args, "vertical_record", None))) if v is not None]
        if given:
            raise UsageError(f"{given[0]} needs --solver friction: {args.solver} models no-slip rocking under "
                             "horizontal floor motion")


def make_block(args: argparse.Namespace) -> Block:
    """The block of --width/--height/--mass/--restitution(-law)/--friction(-kinetic); the block checks them."""
    with named_options(BLOCK_OPTIONS):
        factor = {} if args.restitution_law is None else {"restitution_factor": law_factor(args.restitution_law)}
        return Block(width=args.width, height=args.height, mass=args.mass, restitution=args.restitution,
                     friction=args.friction, friction_kinetic=args.friction_kinetic, **factor)


def pulse_omega(args: argparse.Namespace, block: Block) -> float:
    """omega_p (rad/s) of --freq, --freq-ratio or --duration (rectangular: pi / t1)."""
    if args.freq_ratio is not None:
        return scaled_input("--freq-ratio", args.freq_ratio, "omega_p", block.p)
    if args.duration is not None:
        return scaled_input("--duration", math.pi / check("duration", args.duration, shown_as="--duration"), "omega_p", 1.0)
    return scaled_input("--freq", args.freq, "omega_p", 2.0 * math.pi)


def pulse_pfa(args: argparse.Namespace, block: Block) -> float:
    """The peak floor acceleration (m/s²) of --pfa (g) or --pfa-ratio (g tan alpha)."""
    if args.pfa_ratio is not None:
        return scaled_input("--pfa-ratio", args.pfa_ratio, "pfa", block.uplift_acceleration)
    return scaled_input("--pfa", args.pfa, "pfa", G)


def model_settings(args: argparse.Namespace) -> dict:
    """Solver settings of --delta, --lever, --damper, --step and --equations (the solver checks them; the
    SDOF model checks --delta first, as the solver's model)."""
    if args.delta is not None:
        with given_by("--delta"):
            SDOFModel(delta=args.delta)
    given = {"equations": args.equations, "delta": args.delta, "lever": args.lever, "damper": args.damper,
             "step": args.step}
    return {k: v for k, v in given.items() if v is not None}


def need_frequency(args: argparse.Namespace) -> None:
    """A pulse needs its frequency."""
    if args.freq is None and args.freq_ratio is None and args.duration is None:
        raise UsageError("give the pulse frequency: --freq (Hz) or --freq-ratio"
                         + (" or --duration (s)" if args.pulse == "rectangular" else ""))


__all__ = ["BLOCK_OPTIONS", "check_model_args", "given_by", "make_block", "model_settings",
           "named_options", "need_frequency", "pulse_omega", "pulse_pfa"]
