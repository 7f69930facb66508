"""``opsrock simulate``: one block under one pulse or record, through :func:`opsrock.solvers.simulate`."""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys

from opsrock._files import output_file
from opsrock.block import Block
from opsrock.cli import EXIT_FAILED
from opsrock.cli.common import (
    BLOCK_OPTIONS,
    check_model_args,
    given_by,
    make_block,
    model_settings,
    named_options,
    need_frequency,
    pulse_omega,
    pulse_pfa,
)
from opsrock.constants import G
from opsrock.errors import UsageError
from opsrock.excitations import library, pulse_class
from opsrock.excitations.building import ShearBuilding, floor_motion
from opsrock.excitations.readers import read_record
from opsrock.excitations.records import Record, check_plausible_record, check_sampling
from opsrock.excitations.vertical import synthetic_vertical, with_vertical
from opsrock.limits import ACCEPT_OPTION, check_plausible, check_plausible_sizes, scaled_input
from opsrock.solvers import simulate as solve
from opsrock.solvers.common import LONG_SOLVE_S, event_driven_estimate
from opsrock.solvers.registry import METHODS

#: The mass-distribution options of ``opsrock simulate`` by the :class:`Block` argument they set.
MASS_OPTIONS: dict[str, str] = {"cm_height": "--cm-height", "radius_of_gyration": "--radius-of-gyration"}

#: Options of ``--record`` that mean nothing without it.
RECORD_ONLY = ("units", "dt", "building_period", "storeys", "damping", "floor", "vertical_record")


def _check_args(args: argparse.Namespace) -> None:
    check_model_args(args)
    if args.plot is not None:
        output_file("--plot", args.plot, ".png")
    if args.record is None:
        extra = [n for n in RECORD_ONLY if getattr(args, n) is not None]
        if extra or args.scale is not None:
            name = "--" + (extra[0] if extra else "scale").replace("_", "-")
            raise UsageError(f"{name} applies to --record only" + (" (the OpenSees time step is --step)"
                                                                   if name == "--dt" else ""))
        if args.pfa is None and args.pfa_ratio is None:
            raise UsageError("give the pulse amplitude: --pfa (g) or --pfa-ratio")
        need_frequency(args)
        return
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


def _pulse(args: argparse.Namespace, block: Block):
    vertical = 0.0 if args.vertical is None else scaled_input("--vertical", args.vertical, "vertical", G)
    return pulse_class(args.pulse)(pfa=pulse_pfa(args, block), omega_p=pulse_omega(args, block), vertical=vertical)


def _vertical(args: argparse.Namespace, rec: Record) -> Record:
    """``rec`` with the vertical motion of ``--vertical-record`` (a record file or reference, or synthetic)."""
    source = args.vertical_record
    if source is None:
        return rec
    if source == "synthetic" and not library.is_reference(args.record):
        raise UsageError(f"--vertical-record synthetic needs a library --record (fema-p695:SET/NAME), got "
                         f"{args.record!r}")
    with given_by("--vertical-record"):
        if source == "synthetic":
            return synthetic_vertical(args.record)
        vertical = read_record(source, units=args.units, dt=args.dt)
    check_plausible_record(vertical, what=f"--vertical-record {source}", option=ACCEPT_OPTION,
                           confirm=args.accept_implausible)
    with given_by("--vertical-record"):
        return with_vertical(rec, vertical)


def _floor(args: argparse.Namespace, rec: Record) -> Record:
    """The floor motion of ``--building-period``/``--storeys``/``--floor`` (the ground's without them)."""
    if args.building_period is None:
        return rec
    floor = "roof" if args.floor is None else int(args.floor) if str(args.floor).isdigit() else args.floor
    building = ShearBuilding("building", args.building_period, args.storeys,
                             damping=0.05 if args.damping is None else args.damping)
    with named_options({"floor": "--floor"}):
        return floor_motion(rec, building, floor)


def _record(args: argparse.Namespace, block: Block) -> tuple[Record, float]:
    """The record of ``--record`` on its floor, scaled as asked, and the scale factor."""
    with given_by("--record"):
        rec = read_record(args.record, units=args.units, dt=args.dt)
    check_plausible_record(rec, what=f"--record {args.record}", option=ACCEPT_OPTION, confirm=args.accept_implausible)
    rec = _floor(args, _vertical(args, rec))
    with given_by("--record"):
        check_sampling(rec, block)
    if args.pfa is None and args.pfa_ratio is None:
        with given_by("--scale"):
            factor = args.scale or 1.0
            return rec.scaled(factor), factor
    name, target = ("--pfa", args.pfa * G) if args.pfa is not None else ("--pfa-ratio",
                                                                          args.pfa_ratio * block.uplift_acceleration)
    with given_by(name):
        return rec.scaled_to_pfa(target), rec.scale_to(target)


def _block(args: argparse.Namespace) -> Block:
    """The block of the block options, with the mass distribution of ``--cm-height`` and
    ``--radius-of-gyration`` (None: a homogeneous block's); the block checks them."""
    block = make_block(args)
    given = {name: getattr(args, name) for name in MASS_OPTIONS if getattr(args, name) is not None}
    if not given:
        return block
    with named_options(MASS_OPTIONS):
        return dataclasses.replace(block, **given)


def simulate(args: argparse.Namespace) -> int:
    """``opsrock simulate``: one block under one pulse or record, through :func:`opsrock.solvers.simulate`."""
    _check_args(args)
    _check_plausible(args)
    block = _block(args)
    excitation, scale = (_pulse(args, block), None) if args.record is None else _record(args, block)
    _announce_long_solve(args.solver, excitation)
    # the solvers check their settings before any work and raise only for bad settings;
    # a solver failure is a failed result, never an exception
    with named_options(BLOCK_OPTIONS):
        result = solve(block, excitation, solver=args.solver, **model_settings(args))
    out = _summary(result, block, excitation, scale)
    if args.plot:
        from opsrock.plots.response import plot_response  # lazy: matplotlib, only for --plot

        plot_response(result, block, excitation, args.plot)
    print(json.dumps(out, default=str) if args.json else _text(result, block, excitation, out))
    return 0 if result.ok else EXIT_FAILED


def _check_plausible(args: argparse.Namespace) -> None:
    """--width, --height and --pfa beyond the plausibility bounds, refused unless --accept-implausible (a
    record file is checked as read, :func:`_record`)."""
    check_plausible_sizes({"--width": args.width, "--height": args.height}, option=ACCEPT_OPTION,
                          confirm=args.accept_implausible)
    if args.pfa is not None:
        check_plausible("pfa", args.pfa * G, what="--pfa", option=ACCEPT_OPTION, confirm=args.accept_implausible,
                        declared="g")


def _announce_long_solve(solver: str, excitation) -> None:
    """One line on stderr before a solve of an event-driven solver (housner, sdof) expected to run past
    :data:`~opsrock.solvers.common.LONG_SOLVE_S`: how long, and the solver of the same model that is fast."""
    info = METHODS[solver]
    if info.compiled or info.needs_opensees:
        return
    estimate = event_driven_estimate(excitation)
    if estimate <= LONG_SOLVE_S:
        return
    faster = next(n for n, i in METHODS.items() if i.model == info.model and (i.compiled or i.needs_opensees))
    minutes = f"{estimate / 60:.0f} min" if estimate < 7200 else f"{estimate / 3600:.1f} h"
    print(f"opsrock simulate: {solver} integrates the {len(excitation.breakpoints()):,} sample intervals of the "
          f"record one by one while the block rocks: up to about {minutes}; --solver {faster} solves the same model "
          "in seconds",
          file=sys.stderr, flush=True)


def _summary(result, block: Block, excitation, scale: float | None) -> dict:
    summary = result.summary()
    out = {k: summary[k] for k in ("theta_max", "theta_max_over_alpha", "overturned", "rocked", "verdict",
                                   "status", "reason", "solver")}
    out.update(alpha=block.alpha, R=block.R, p=block.p, e=block.e, e_R=block.e_R, pfa=excitation.pfa,
               pfa_ratio=excitation.pfa / block.uplift_acceleration)
    if not block.homogeneous:
        out.update(cm_height=block.h_cm, radius_of_gyration=block.r_gyration, I_O=block.I_O)
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
        out.update(response=result.response, **result.contact.columns(),
                   slip_velocity_end=result.contact.slip_velocity_end, energy=dict(result.contact.energy))
    return out


def _text(result, block, excitation, out) -> str:
    mass = "" if block.homogeneous else (f", centre of mass {block.h_cm:g} m up, radius of gyration "
                                         f"{block.r_gyration:.4g} m")
    head = (f"block 2b x 2h = {block.width:g} x {block.height:g} m{mass}: alpha = {block.alpha:.4f} rad, "
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
            f"residual {c.slide_residual:.4g} m"
            + (f"; still sliding at {c.slip_velocity_end:.4g} m/s when the run ended (friction too small to stop "
               "it within max_free_time; docs/guide/friction.md)" if c.still_sliding else ""))


__all__ = ["simulate"]
