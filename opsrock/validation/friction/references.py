"""The ``friction`` solver against what is known exactly: its no-slip limit, the closed forms of sliding,
the uplift threshold and Housner's rectangular pulse with ``g + a_v``, and the energy balance.

Each check is a row ``(check, value, reference, tolerance, passed, source)``; the derivations are in
``validation/friction/README.md``.
"""

from __future__ import annotations

import math

from opsrock.block import Block
from opsrock.constants import G
from opsrock.excitations import HalfSinePulse, OneSinePulse, RectangularPulse

#: Tolerances (see the README for why): no-slip limit against housner_fast (alpha); sliding closed
#: forms, relative (rectangular: exact polynomial integration; half-sine: RK4 at 200 steps a period);
#: energy residual relative to the work done.
TOL_NO_SLIP, TOL_RECT, TOL_HALF_SINE, TOL_ENERGY = 1e-7, 1e-12, 1e-8, 1e-7


def _row(check: str, value: float, reference: float, tolerance: float, source: str, passed: bool | None = None) -> dict:
    if passed is None:
        passed = bool(abs(value - reference) <= tolerance)
    return {"check": check, "value": value, "reference": reference, "tolerance": tolerance, "passed": bool(passed),
            "source": source}


def no_slip_limit(quick: bool = False) -> list[dict]:
    """Without friction (and with friction far above any demand) the block rocks as ``housner_fast``."""
    from opsrock.solvers import friction, housner_fast
    from opsrock.validation.sdof_records import noise_record

    worst, verdicts, n = 0.0, 0, 0
    base = Block(0.4, 1.6)
    pulses = [OneSinePulse.from_ratios(base, a, f) for a in (1.2, 1.5, 3.0, 6.0) for f in (1.0, 2.0, 4.0, 8.0)]
    records = [noise_record(s).scaled_to_pfa(x * base.uplift_acceleration) for s in ((1,) if quick else (1, 2, 3, 4))
               for x in (1.3, 2.5)]
    for exc in pulses + records:
        ref = housner_fast.solve(base, exc)
        for mu in (None, 5.0):
            res = friction.solve(Block(0.4, 1.6, friction=mu, friction_kinetic=None if mu is None else 1.2), exc)
            n += 1
            verdicts += res.verdict == ref.verdict
            if not ref.overturned and res.ok:
                worst = max(worst, abs(res.theta_max - ref.theta_max) / base.alpha)
    return [_row("no-slip limit: max |d theta_max| / alpha against housner_fast", worst, 0.0, TOL_NO_SLIP,
                 "housner_fast, the same rocking equation (validation case 8)"),
            _row("no-slip limit: verdicts equal to housner_fast's (share)", verdicts / n, 1.0, 0.0,
                 "housner_fast")]


def sliding_closed_forms() -> list[dict]:
    """A block that cannot rock (b/h = 0.5 > mu) under rectangular and half-sine pulses, with and without a
    constant vertical acceleration, against Newmark's sliding block."""
    from opsrock.published import newmark_1965
    from opsrock.solvers import friction

    rows = []
    for a_v in (0.0, -0.3 * G, 0.4 * G):
        for a_g, t1, mu in ((0.5, 0.3, 0.2), (0.45, 1.0, 0.25), (1.0, 0.1, 0.4)):
            r = friction.solve(Block(1.0, 2.0, friction=mu), RectangularPulse(a_g * G, math.pi / t1, vertical=a_v))
            ref = newmark_1965.rectangular_slide(a_g * G, t1, mu, a_v)
            rows.append(_row(f"rectangular {a_g:g} g {t1:g} s, mu {mu:g}, a_v {a_v / G:+.2g} g: slide (m)",
                             -r.contact.slide_residual, ref, TOL_RECT * ref, "Newmark (1965), closed form"))
        for a_g, hz in ((0.5, 2.0), (0.25, 2.0), (0.8, 0.5)):
            omega = 2.0 * math.pi * hz
            r = friction.solve(Block(1.0, 2.0, friction=0.2), HalfSinePulse(a_g * G, omega, vertical=a_v))
            ref = newmark_1965.half_sine_slide(a_g * G, omega, 0.2, a_v)
            rows.append(_row(f"half-sine {a_g:g} g {hz:g} Hz, mu 0.2, a_v {a_v / G:+.2g} g: slide (m)",
                             -r.contact.slide_residual, ref, TOL_HALF_SINE * ref, "closed form derived in the README"))
    return rows


def thresholds_with_vertical() -> list[dict]:
    """The uplift threshold ``(g + a_v) tan(alpha)`` and Housner's rectangular pulse with ``g -> g + a_v``."""
    from opsrock.published import housner_1963
    from opsrock.solvers import friction

    rows = []
    for a_v in (0.0, -0.3 * G, 0.3 * G):
        b = Block(0.6, 2.0, friction=0.6)
        thr = (G + a_v) * b.tan_alpha
        below = friction.solve(b, RectangularPulse(0.999 * thr, 10.0, vertical=a_v))
        above = friction.solve(b, RectangularPulse(1.001 * thr, 10.0, vertical=a_v))
        ok = (not below.rocked) and above.rocked and above.contact.first_mode == "rock"
        rows.append(_row(f"uplift at (g + a_v) tan(alpha), a_v {a_v / G:+.1g} g: 0.999 at rest, 1.001 rocks",
                         float(ok), 1.0, 0.0, "statics (README)", ok))
        s = Block(0.4, 2.0)
        p_v = math.sqrt(3.0 * (G + a_v) / (4.0 * s.R))
        a_min = (G + a_v) * s.alpha * housner_1963.minimum_overturning(1.0)
        safe = friction.solve(s, RectangularPulse(0.98 * a_min, math.pi * p_v, vertical=a_v))
        over = friction.solve(s, RectangularPulse(1.02 * a_min, math.pi * p_v, vertical=a_v))
        ok = safe.rocked and not safe.overturned and over.overturned
        rows.append(_row(f"Housner rectangular pulse p_v t1 = 1, a_v {a_v / G:+.1g} g: 0.98 safe, 1.02 overturns",
                         float(ok), 1.0, 0.0, "Housner (1963) with g -> g + a_v (README)", ok))
    return rows


def energy_balance(results) -> list[dict]:
    """The largest energy residual over ``results`` (friction solver), relative to the work done."""
    worst = 0.0
    for r in results:
        if not r.ok:
            continue
        e = r.contact.energy
        scale = abs(e["input_work"]) + e["friction_work"] + e["impact_loss"] + abs(e["initial"])
        if scale > 0.0:
            worst = max(worst, abs(e["residual"]) / scale)
    return [_row("energy balance: max |residual| / work over the comparison cases", worst, 0.0, TOL_ENERGY,
                 "identity of the equations (README); RK4 truncation")]


def energy_cases() -> list:
    """Runs with every mode and event (slide, rock, slide-rock, impacts, flight) whose energy is checked."""
    from opsrock.solvers import friction

    out = []
    for mu in (0.2, 0.32, 0.45, None):
        for a_v in (0.0, 0.2 * G, -0.2 * G):
            out.append(friction.solve(Block(0.6, 2.0, friction=mu), OneSinePulse(0.8 * G, 2.0 * math.pi * 1.5,
                                                                                 vertical=a_v)))
    out.append(friction.solve(Block(0.5, 1.5, friction=0.8), None, theta0=0.5 * math.atan(1 / 3), end_time=1.0))
    return out


def checks(quick: bool = False) -> list[dict]:
    """Every reference check of the case."""
    rows = no_slip_limit(quick) + sliding_closed_forms() + thresholds_with_vertical()
    rows += energy_balance(energy_cases())
    return rows


__all__ = ["TOL_ENERGY", "TOL_HALF_SINE", "TOL_NO_SLIP", "TOL_RECT", "checks", "energy_balance", "energy_cases",
           "no_slip_limit", "sliding_closed_forms", "thresholds_with_vertical"]
