"""``opsrock threshold``: every amplitude interval in which one block overturns under one pulse."""

from __future__ import annotations

import argparse
import json
import math

from opsrock.analysis.threshold import overturning_intervals, pfa_g
from opsrock.cli.common import (
    BLOCK_OPTIONS,
    check_model_args,
    make_block,
    model_settings,
    named_options,
    need_frequency,
    pulse_omega,
)
from opsrock.limits import ACCEPT_OPTION, check_plausible_sizes, scaled_input


def threshold(args: argparse.Namespace) -> int:
    """``opsrock threshold``: :func:`opsrock.analysis.threshold.overturning_intervals` of one block and pulse."""
    check_model_args(args)
    need_frequency(args)
    check_plausible_sizes({"--width": args.width, "--height": args.height}, option=ACCEPT_OPTION,
                          confirm=args.accept_implausible)
    block = make_block(args)
    scaled_input("--pfa-ratio-max", args.pfa_ratio_max, "pfa", block.uplift_acceleration)
    settings = model_settings(args)
    with named_options(BLOCK_OPTIONS):
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


__all__ = ["threshold"]
