"""``opsrock threshold``: the overturning intervals of one block along the amplitude axis of a pulse.

    opsrock threshold --width 2B --height 2H [--pulse SHAPE] (--freq HZ | --freq-ratio Y | --duration S)
                      [--restitution E] [--solver S] [--equations exact|linearised]
                      [--pfa-ratio-max X] [--n-scan N] [--rtol R] [--json]

Prints every amplitude interval in which the block overturns (the verdict is not monotonic in the
amplitude: safe windows lie above the first overturning amplitude), in ``PFA / (g tan alpha)``, in g
and in ``PFA / (g alpha)``, with the scan resolution and any amplitude the solver failed on.
"""

from __future__ import annotations

import argparse
import json
import math


def add_arguments(p: argparse.ArgumentParser) -> None:
    """Add the ``threshold`` options to ``p``."""
    from opsrock.cli import _finite, add_block_arguments, add_model_arguments, add_pulse_arguments
    from opsrock.threshold import DEFAULT_N_SCAN, DEFAULT_PFA_RATIO_MAX, DEFAULT_RTOL

    add_block_arguments(p)
    add_pulse_arguments(p)
    add_model_arguments(p, default_solver="housner_fast")
    p.add_argument("--pfa-ratio-max", type=_finite("--pfa-ratio-max"), default=DEFAULT_PFA_RATIO_MAX,
                   help=f"top of the scanned amplitudes, PFA / (g tan alpha) (default {DEFAULT_PFA_RATIO_MAX:g})")
    p.add_argument("--n-scan", type=int, default=DEFAULT_N_SCAN,
                   help=f"scanned amplitudes (default {DEFAULT_N_SCAN}); windows narrower than their spacing may be missed")
    p.add_argument("--rtol", type=_finite("--rtol"), default=DEFAULT_RTOL,
                   help=f"relative width of each refined boundary (default {DEFAULT_RTOL:g})")
    p.add_argument("--json", action="store_true", help="print one JSON object")


def run_command(args: argparse.Namespace) -> int:
    """Run ``opsrock threshold``; bad input raises the CLI's one-line usage error."""
    from opsrock.cli import UsageError, check_model_args, make_block, model_settings, pulse_omega
    from opsrock.threshold import overturning_intervals, pfa_g

    check_model_args(args)
    if args.freq is None and args.freq_ratio is None and args.duration is None:
        raise UsageError("give the pulse frequency: --freq (Hz) or --freq-ratio"
                         + (" or --duration (s)" if args.pulse == "rectangular" else ""))
    if args.n_scan < 3:
        raise UsageError(f"--n-scan must be an integer >= 3, got {args.n_scan!r}")
    try:
        block = make_block(args)
        freq_ratio = pulse_omega(args, block) / block.p
        settings = model_settings(args)
        equations = settings.pop("equations", "exact")
        res = overturning_intervals(block, freq_ratio, shape=args.pulse, solver=args.solver, equations=equations,
                                    pfa_ratio_max=args.pfa_ratio_max, n_scan=args.n_scan, rtol=args.rtol,
                                    settings=settings)
    except (ValueError, TypeError) as exc:
        raise UsageError(str(exc)) from None
    if args.json:
        out = res.as_dict()
        out.update(block={"width": block.width, "height": block.height, "alpha": block.alpha, "p": block.p, "e": block.e},
                   intervals_g=[[pfa_g(block, a), "inf" if math.isinf(b) else pfa_g(block, b)] for a, b in res.intervals])
        print(json.dumps(out))
    else:
        print(_text(res, block))
    return 0


def _text(res, block) -> str:
    from opsrock.threshold import pfa_g

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
