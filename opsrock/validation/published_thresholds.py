"""Validation case 7: the published overturning thresholds of the rocking literature.

Every row is one published boundary (or one we computed where the paper's number was not available
to us), found by :func:`opsrock.analysis.threshold.overturning_intervals` with ``housner_fast`` and compared
with (a) the number the paper prints, (b) an independent reference: the paper's closed form, or the
closed-form event solution of the linearised equation (:mod:`opsrock.published.linearised`), or
the event-driven ``housner`` solver for the exact equation, and (c) the OpenSees SDOF model near the
exact rigid-body boundary (not linearised, damper band: its distance is reported, not tested).

Outputs: ``table.csv`` (full precision), ``table.md`` (rounded for reading), ``thresholds.png``
(the four minimum-overturning charts, redrawn).
"""

from __future__ import annotations

import csv
import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from opsrock.analysis.threshold import OverturningIntervals, boundary, overturning_intervals
from opsrock.block import Block
from opsrock.constants import G
from opsrock.published import (
    housner_1963,
    linearised,
    makris_konstantinidis_2003,
    makris_roussos_2000,
    zhang_makris_2001,
)
from opsrock.published.reference import PublishedValue

#: Tolerance of housner_fast against an independent reference of the same equation (relative): the
#: boundary is bracketed to 1e-6 and RK4 with steps of 0.02/p moves theta_max by < 2e-8 alpha.
REFERENCE_TOLERANCE: float = 1e-5
#: Half-width of the bracket (relative) in which ``housner`` and OpenSees look for the same boundary.
CHECK_BRACKET: float = 2e-3

#: The block of the linearised rows (the linearised boundaries in a/(g alpha) do not depend on it).
LINEAR_BLOCK: tuple[float, float] = (0.5, 2.0)


def _block_from(alpha: float, p: float, e: float) -> Block:
    """The block of slenderness ``alpha`` (rad) and frequency parameter ``p`` (rad/s)."""
    R = 3.0 * G / (4.0 * p * p)
    return Block(2.0 * R * math.sin(alpha), 2.0 * R * math.cos(alpha), restitution=e)


@dataclass(frozen=True)
class Row:
    """One compared boundary.

    ``branch`` picks it from the overturning intervals: ``first`` (lower edge of the first),
    ``window_low`` (upper edge of the first: a safe window starts), ``window_high`` (lower edge of
    the second), ``last`` (lower edge of the open-ended last: overturning without impact).
    ``unit`` is ``"g_alpha"`` (a/(g alpha)) or ``"g"``.
    """

    key: str
    source: str
    pulse: str
    equations: str
    freq_ratio: float
    block: Block
    branch: str
    unit: str
    published: float | None
    tolerance: float | None
    tolerance_reason: str
    reference: Callable[[], float] | None
    reference_kind: str
    role: str = "test"


def _pick(res: OverturningIntervals, branch: str) -> float:
    iv = res.intervals
    try:
        return {"first": lambda: iv[0][0], "window_low": lambda: iv[0][1], "window_high": lambda: iv[1][0],
                "last": lambda: iv[-1][0]}[branch]()
    except IndexError:
        return math.nan


def _in_unit(row: Row, pfa_ratio: float) -> float:
    b = row.block
    return pfa_ratio * b.tan_alpha / b.alpha if row.unit == "g_alpha" else pfa_ratio * b.uplift_acceleration / G


def _to_pfa_ratio(row: Row, value: float) -> float:
    b = row.block
    return value * b.alpha / b.tan_alpha if row.unit == "g_alpha" else value * G / b.uplift_acceleration


def _pub(values: tuple[PublishedValue, ...], key: str) -> PublishedValue:
    return next(v for v in values if v.key == key)


def rows() -> list[Row]:
    """The compared boundaries, in the order of the case README's table."""
    lin = Block(*LINEAR_BLOCK, restitution=0.9)
    h63 = _pub(housner_1963.VALUES, "housner1963_rect_pt1_1")
    mr = _pub(makris_roussos_2000.VALUES, "makris_roussos2000_half_sine_1")
    zm = _pub(zhang_makris_2001.VALUES, "zhang_makris2001_no_impact_5")
    loco = zhang_makris_2001.LOCOMOTIVE
    loco_block = _block_from(loco["alpha"], loco["p"], loco["restitution"])
    loco_nu = loco["omega_p"] / loco["p"]
    zm_iv = {}

    def zm_mode1(i: int, j: int) -> float:
        if "iv" not in zm_iv:
            zm_iv["iv"] = zhang_makris_2001.intervals(5.0, 0.9)
        return zm_iv["iv"][i][j]

    out = [
        Row(h63.key, h63.source, "rectangular", "linearised", math.pi / h63.parameters["p_t1"], lin, "first", "g_alpha",
            h63.value, h63.tolerance, h63.tolerance_reason, lambda: housner_1963.minimum_overturning(1.0),
            "closed form 1/(1 - exp(-p t1))"),
        Row(mr.key, mr.source, "half-sine", "linearised", 1.0, lin, "first", "g_alpha", mr.value, mr.tolerance,
            mr.tolerance_reason, lambda: makris_roussos_2000.minimum_overturning(1.0), "closed form (no impact)"),
        Row(zm.key, zm.source, "one-sine", "linearised", 5.0, lin, "last", "g_alpha", zm.value, zm.tolerance,
            zm.tolerance_reason, lambda: zhang_makris_2001.minimum_no_impact(5.0), "closed form (no impact)"),
        Row("zhang_makris2001_mode1_5", "Zhang and Makris (2001), one-sine, e = 0.9: overturning after one impact",
            "one-sine", "linearised", 5.0, lin, "first", "g_alpha", None, None, "published value not available to us",
            lambda: zm_mode1(0, 0), "closed-form event solution"),
        Row("zhang_makris2001_window_5", "Zhang and Makris (2001), one-sine, e = 0.9: safe window starts",
            "one-sine", "linearised", 5.0, lin, "window_low", "g_alpha", None, None, "published value not available to us",
            lambda: zm_mode1(0, 1), "closed-form event solution"),
    ]
    for v, branch in zip(zhang_makris_2001.VALUES[1:], ("first", "window_low", "window_high")):
        out.append(Row(v.key, v.source, "one-sine", "exact", loco_nu, loco_block, branch, "g", v.value, v.tolerance,
                       v.tolerance_reason, None, "housner (event-driven scipy)"))
    first = zhang_makris_2001.VALUES[1]
    out.append(Row("zhang_makris2001_locomotive_linearised", first.source + ", linearised reading", "one-sine",
                   "linearised", loco_nu, loco_block, "first", "g", first.value, first.tolerance,
                   "the linearised equation does not give this example (shown, not tested)",
                   None, "housner (event-driven scipy)", role="reading"))
    mk_e = makris_konstantinidis_2003.restitution()
    for p in makris_konstantinidis_2003.P_VALUES:
        nu = 2.0 * math.pi / makris_konstantinidis_2003.T_P / p
        blk = _block_from(makris_konstantinidis_2003.ALPHA, p, mk_e)
        src = f"Makris and Konstantinidis (2003), one-cosine, T_p = 2 s, alpha = 15 deg, p = {p:g} rad/s, e = e_R"
        out += [
            Row(f"mk2003_p{p:g}_linearised", src + ", linearised", "one-cosine", "linearised", nu, blk, "first", "g",
                None, None, "published value not available to us",
                lambda nu=nu: linearised.intervals(nu, "one-cosine", mk_e)[0][0] * makris_konstantinidis_2003.ALPHA,
                "closed-form event solution"),
            Row(f"mk2003_p{p:g}_no_impact", src + ", linearised, without impact", "one-cosine", "linearised", nu, blk,
                "last", "g", None, None, "published value not available to us",
                lambda nu=nu: makris_konstantinidis_2003.minimum_no_impact(nu) * makris_konstantinidis_2003.ALPHA,
                "closed form (no impact)"),
            Row(f"mk2003_p{p:g}_exact", src + ", exact equation", "one-cosine", "exact", nu, blk, "first", "g",
                None, None, "published value not available to us", None, "housner (event-driven scipy)"),
        ]
    return out


#: OpenSees scans: amplitudes up to this PFA / (g tan alpha) (every row's boundary lies below 15),
#: this many points (spacing 2 %), boundaries to this relative width.
OPENSEES_SCAN: tuple[float, int, float] = (20.0, 150, 1e-4)
_OPENSEES_CACHE: dict = {}


def _opensees_intervals(row: Row) -> OverturningIntervals:
    key = (row.block, row.freq_ratio, row.pulse)
    if key not in _OPENSEES_CACHE:
        top, n, rtol = OPENSEES_SCAN
        _OPENSEES_CACHE[key] = overturning_intervals(row.block, row.freq_ratio, shape=row.pulse, solver="opensees",
                                                     pfa_ratio_max=top, n_scan=n, rtol=rtol)
    return _OPENSEES_CACHE[key]


def _opensees_distance(row: Row, exact: OverturningIntervals) -> tuple[float, float, str]:
    """(exact rigid-body boundary of the row's branch, the OpenSees boundary of the same kind nearest
    to it, OpenSees' intervals), in the row's unit. The SDOF model is not linearised and has its
    damper band, so its branches can move, merge or vanish: the nearest edge of the same kind
    (an interval's start, or its end for ``window_low``) is the one compared."""
    xe = _pick(exact, row.branch)
    ops = _opensees_intervals(row)
    text = ";".join(f"[{_in_unit(row, a):.5g},{'inf' if math.isinf(b) else f'{_in_unit(row, b):.5g}'}]"
                    for a, b in ops.intervals)
    edges = [b for a, b in ops.intervals if math.isfinite(b)] if row.branch == "window_low" else [a for a, b in ops.intervals]
    if not math.isfinite(xe) or not edges:
        return (_in_unit(row, xe) if math.isfinite(xe) else math.nan), math.nan, text
    xo = min(edges, key=lambda x: abs(math.log(x / xe)))
    return _in_unit(row, xe), _in_unit(row, xo), text


def evaluate(row: Row, quick: bool = False) -> dict:
    """Compare one row: housner_fast, its reference, the published value, and (full form) OpenSees."""
    t0 = time.perf_counter()
    res = overturning_intervals(row.block, row.freq_ratio, shape=row.pulse, equations=row.equations)
    ours = _in_unit(row, _pick(res, row.branch))
    if row.reference is not None:
        ref = row.reference()
    elif quick:
        ref = math.nan
    else:
        x = _pick(res, row.branch)
        ref = _in_unit(row, boundary(row.block, row.freq_ratio, x * (1 - CHECK_BRACKET), x * (1 + CHECK_BRACKET),
                                     shape=row.pulse, solver="housner", equations=row.equations))
    d_pub = ours / row.published - 1.0 if row.published else math.nan
    d_ref = ours / ref - 1.0 if math.isfinite(ref) else math.nan
    ok_pub = row.published is None or abs(d_pub) <= row.tolerance
    ok_ref = not math.isfinite(ref) or abs(d_ref) <= REFERENCE_TOLERANCE
    out = {
        "key": row.key, "source": row.source, "pulse": row.pulse, "equations": row.equations,
        "freq_ratio": row.freq_ratio, "alpha": row.block.alpha, "p": row.block.p, "e": row.block.e,
        "branch": row.branch, "unit": "a/(g alpha)" if row.unit == "g_alpha" else "a (g)",
        "published": row.published if row.published is not None else math.nan,
        "housner_fast": ours, "reference": ref, "reference_kind": row.reference_kind if math.isfinite(ref) else "not run",
        "rel_diff_published": d_pub, "tolerance": row.tolerance if row.tolerance is not None else math.nan,
        "tolerance_reason": row.tolerance_reason, "rel_diff_reference": d_ref,
        "reference_tolerance": REFERENCE_TOLERANCE, "intervals": ";".join(
            f"[{_in_unit(row, a):.6g},{'inf' if math.isinf(b) else f'{_in_unit(row, b):.6g}'}]" for a, b in res.intervals),
        "role": row.role, "passed": bool(ok_pub and ok_ref) if row.role == "test" else True,
    }
    if not quick:
        exact = res if row.equations == "exact" else overturning_intervals(row.block, row.freq_ratio, shape=row.pulse)
        xe, xo, ops = _opensees_distance(row, exact)
        out.update({"exact_rigid_body": xe, "opensees": xo,
                    "opensees_rel_to_exact": xo / xe - 1.0 if math.isfinite(xo) else math.nan, "opensees_intervals": ops})
    out["wall_time_s"] = time.perf_counter() - t0
    return out


def _fmt(v, digits: int = 5) -> str:
    if isinstance(v, float):
        return "" if math.isnan(v) else f"{v:.{digits}g}"
    return str(v)


def _markdown(results: list[dict]) -> str:
    cols = [("key", "case"), ("role", "role"), ("unit", "unit"), ("published", "published"), ("housner_fast", "ours (housner_fast)"),
            ("rel_diff_published", "diff"), ("tolerance", "tol"), ("reference", "reference"),
            ("reference_kind", "reference is"), ("rel_diff_reference", "diff"), ("opensees_rel_to_exact", "OpenSees vs exact")]
    cols = [c for c in cols if c[0] in results[0]]
    lines = ["| " + " | ".join(h for _, h in cols) + " |", "|" + "---|" * len(cols)]
    for r in results:
        lines.append("| " + " | ".join(_fmt(r[k], 3 if k.startswith(("rel", "opensees_rel", "tol")) else 6)
                                        for k, _ in cols) + " |")
    return "\n".join(lines) + "\n"


def run(out_dir: Path, quick: bool = False) -> dict:
    """Regenerate the case into ``out_dir``; quick: housner_fast and the closed forms only, a coarse chart."""
    from opsrock.analysis.charts import literature_charts
    from opsrock.plots.thresholds import plot_threshold_charts

    out_dir = Path(out_dir)
    results = [evaluate(r, quick=quick) for r in rows()]
    keys = list(results[0])
    with open(out_dir / "table.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys, lineterminator="\n")
        w.writeheader()
        w.writerows(results)
    (out_dir / "table.md").write_text(_markdown(results))
    t0 = time.perf_counter()
    data = literature_charts(n=40 if quick else 200, n_scan=150 if quick else 300)
    chart_s = time.perf_counter() - t0
    plot_threshold_charts(data, out_dir / "thresholds.png")
    tested = [r for r in results if r["role"] == "test"]
    return {"passed": all(r["passed"] for r in tested), "n_rows": len(results),
            "n_published_compared": sum(1 for r in tested if not math.isnan(r["published"])),
            "max_rel_diff_published": max(abs(r["rel_diff_published"]) for r in tested if not math.isnan(r["published"])),
            "max_rel_diff_reference": max((abs(r["rel_diff_reference"]) for r in tested
                                           if not math.isnan(r["rel_diff_reference"])), default=math.nan),
            "chart_solves": sum(d.n_solves for d in data.values()), "chart_seconds": chart_s}
