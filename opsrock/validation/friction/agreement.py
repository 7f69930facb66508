"""The two implementations of the block with friction against each other: the event-driven ``friction``
solver and the Moreau-Jean time stepper ``moreau_jean``, on pulses and on records, with and without
vertical motion.

Both run Housner's impact (``restitution_factor = 1``: the time stepper's zero normal restitution gives
``e_H`` and cannot give less, docs/guide/friction.md). A case is **ill-conditioned**, and set apart with its
count, if its answer is not defined to the comparison's tolerance: the ``friction`` solver's
``theta_max`` moves by more than :data:`THETA_TOL` alpha, or its slide by more than :data:`SLIDE_TOL`,
or its response changes, when the floor motion is scaled by ``1 + eps`` for ``eps`` in
:data:`opsrock.analysis.sensitivity.DEFAULT_EPS` (the test of validation case 9); or ``moreau_jean``
moves by as much when its step is halved (its own discretisation). On the others the two must agree
in response on >= 99 % of the cases, and within :data:`THETA_TOL` alpha and :data:`SLIDE_TOL` of slide
(peak and residual) on >= 99 % of the cases neither overturns.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from opsrock.block import Block
from opsrock.constants import G
from opsrock.excitations import OneSinePulse, Record, RectangularPulse

#: Tolerances of the comparison: theta_max (alpha) and slide (m), the issue's targets.
THETA_TOL, SLIDE_TOL = 0.005, 0.001
#: Share of the well-conditioned cases that must agree.
TARGET = 0.99
#: Block height (m) and slendernesses b/h of the comparison.
HEIGHT = 1.8
SLENDERNESS: tuple[float, ...] = (0.2, 0.35, 0.5)
#: Floor frictions (static = kinetic; inf: no slip).
FRICTIONS: tuple[float, ...] = (0.25, 0.4, 0.6, math.inf)
#: Pulses: one-sine at these PFA (g) and frequencies (Hz); constant vertical accelerations (g).
PULSE_PFA_G: tuple[float, ...] = (0.3, 0.6, 1.0)
PULSE_HZ: tuple[float, ...] = (1.0, 3.0)
PULSE_VERTICAL_G: tuple[float, ...] = (0.0, -0.25, 0.25)
#: Records: band-passed noise (validation case 9's records), PFA (g), frictions, with and without a
#: vertical motion of 2/3 the amplitude from another seed.
RECORD_SEEDS: tuple[int, ...] = tuple(range(1, 9))
RECORD_PFA_G: tuple[float, ...] = (0.4, 0.8)
RECORD_FRICTIONS: tuple[float, ...] = (0.3, 0.5, math.inf)


@dataclass(frozen=True)
class Case:
    """One comparison case: a block and an excitation, with labels for the table."""

    kind: str
    label: str
    block: Block
    excitation: object
    b_over_h: float
    mu: float
    vertical_g: float


def _block(r: float, mu: float) -> Block:
    return Block(r * HEIGHT, HEIGHT, restitution_factor=1.0, friction=None if mu == math.inf else mu,
                 name=f"bh{r:g}_mu{mu:g}")


def pulse_cases(quick: bool = False) -> list[Case]:
    """One-sine pulses (quick: two blocks, three frictions, two amplitudes, one frequency, two vertical)."""
    pfas, hzs, verts = ((0.6, 1.0), (3.0,), (0.0, -0.25)) if quick else (PULSE_PFA_G, PULSE_HZ, PULSE_VERTICAL_G)
    slender, frictions = ((0.2, 0.5), (0.25, 0.6, math.inf)) if quick else (SLENDERNESS, FRICTIONS)
    out = []
    for r in slender:
        for mu in frictions:
            for a in pfas:
                for hz in hzs:
                    for v in verts:
                        pulse = OneSinePulse(a * G, 2.0 * math.pi * hz, vertical=v * G)
                        out.append(Case("pulse", f"one-sine {a:g} g {hz:g} Hz av {v:+g} g", _block(r, mu), pulse,
                                        r, mu, v))
    # the rectangular pulse of the sliding closed form, for the two implementations too
    for r in SLENDERNESS:
        pulse = RectangularPulse.from_duration(0.5 * G, 0.3)
        out.append(Case("pulse", "rectangular 0.5 g 0.3 s", _block(r, 0.2), pulse, r, 0.2, 0.0))
    return out


def record_cases(quick: bool = False) -> list[Case]:
    """Noise records, with and without a vertical motion (quick: one seed, one level, two blocks, two
    frictions)."""
    from opsrock.validation.sdof_records import noise_record

    seeds, pfas = ((1,), (0.8,)) if quick else (RECORD_SEEDS, RECORD_PFA_G)
    slender, frictions = ((0.2, 0.5), (0.3, math.inf)) if quick else (SLENDERNESS, RECORD_FRICTIONS)
    out = []
    for seed in seeds:
        base = noise_record(seed)
        vertical = noise_record(seed + 100).values
        vertical = vertical / np.max(np.abs(vertical)) * np.max(np.abs(base.values)) * 2.0 / 3.0
        for with_vertical in (False, True):
            rec = Record(base.dt, base.values, name=base.name, vertical=vertical if with_vertical else None,
                         units="m/s2")
            for r in slender:
                for mu in frictions:
                    for a in pfas:
                        scaled = rec.scaled_to_pfa(a * G)
                        out.append(Case("record", f"{base.name} {a:g} g" + (" +vertical" if with_vertical else ""),
                                        _block(r, mu), scaled, r, mu, scaled.pfa_vertical / G))
    return out


def _summary(res) -> tuple[float, float, float, str]:
    """``(theta_max / alpha, slide_max, slide_residual, response)`` of a result (NaN where it failed)."""
    if not res.ok:
        return math.nan, math.nan, math.nan, "failed"
    c = res.contact
    return res.theta_max_over_alpha, c.slide_max, c.slide_residual, res.response


def _moved(a: tuple, b: tuple) -> bool:
    """Whether two answers differ beyond the tolerances (response, theta_max unless overturned, slide)."""
    if a[3] != b[3]:
        return True
    if a[3] == "overturned":
        return False
    return abs(a[0] - b[0]) > THETA_TOL or abs(a[1] - b[1]) > SLIDE_TOL or abs(a[2] - b[2]) > SLIDE_TOL


def _scaled(excitation, factor: float):
    import dataclasses

    if isinstance(excitation, Record):
        return excitation.scaled(factor)
    return dataclasses.replace(excitation, pfa=excitation.pfa * factor)


def compare_case(case: Case) -> dict:
    """Both implementations on one case, with the conditioning tests; one table row."""
    from opsrock.analysis.sensitivity import DEFAULT_EPS
    from opsrock.solvers import friction, moreau_jean

    ev = friction.solve(case.block, case.excitation)
    mj = moreau_jean.solve(case.block, case.excitation)
    a, b = _summary(ev), _summary(mj)
    perturbed = [_summary(friction.solve(case.block, _scaled(case.excitation, 1.0 + e))) for e in DEFAULT_EPS]
    sensitive = any(_moved(a, p) for p in perturbed)
    mj_fine = _summary(moreau_jean.solve(case.block, case.excitation, dtau=0.5 * mj.settings["dtau"]))
    unconverged = _moved(b, mj_fine)
    both_standing = a[3] != "overturned" and b[3] != "overturned"
    return {
        "kind": case.kind, "case": case.label, "b_over_h": case.b_over_h, "mu": case.mu, "vertical_g": case.vertical_g,
        "response_friction": a[3], "response_moreau_jean": b[3],
        "theta_max_over_alpha_friction": a[0], "theta_max_over_alpha_moreau_jean": b[0],
        "slide_max_friction": a[1], "slide_max_moreau_jean": b[1],
        "slide_residual_friction": a[2], "slide_residual_moreau_jean": b[2],
        "reason_friction": ev.reason, "reason_moreau_jean": mj.reason,
        "first_mode_friction": ev.contact.first_mode if ev.ok else "",
        "first_mode_moreau_jean": mj.contact.first_mode if mj.ok else "",
        "energy_residual_friction": ev.contact.energy["residual"] if ev.ok else math.nan,
        "sensitive": sensitive, "moreau_jean_unconverged": unconverged,
        "well_conditioned": not (sensitive or unconverged) and ev.ok and mj.ok,
        "same_response": a[3] == b[3],
        "d_theta_over_alpha": abs(a[0] - b[0]) if both_standing else math.nan,
        "d_slide_max": abs(a[1] - b[1]) if both_standing else math.nan,
        "d_slide_residual": abs(a[2] - b[2]) if both_standing else math.nan,
        "wall_friction_s": ev.wall_time_s, "wall_moreau_jean_s": mj.wall_time_s,
    }


def agreement_metrics(rows: list[dict]) -> dict:
    """Counts and shares over the well-conditioned rows, per kind and in all."""
    out: dict = {}
    for kind in ("pulse", "record", "all"):
        sel = [r for r in rows if kind in ("all", r["kind"])]
        good = [r for r in sel if r["well_conditioned"]]
        standing = [r for r in good if not math.isnan(r["d_theta_over_alpha"])]
        close = [r for r in standing if r["d_theta_over_alpha"] <= THETA_TOL and r["d_slide_max"] <= SLIDE_TOL
                 and r["d_slide_residual"] <= SLIDE_TOL]
        out[kind] = {
            "n_cases": len(sel), "n_ill_conditioned": len(sel) - len(good),
            "n_failed": sum(r["response_friction"] == "failed" or r["response_moreau_jean"] == "failed" for r in sel),
            "n_well_conditioned": len(good),
            "response_agreement": sum(r["same_response"] for r in good) / len(good) if good else math.nan,
            "n_standing": len(standing),
            "close_share": len(close) / len(standing) if standing else math.nan,
            "max_d_theta_over_alpha": max((r["d_theta_over_alpha"] for r in standing), default=math.nan),
            "max_d_slide_m": max((max(r["d_slide_max"], r["d_slide_residual"]) for r in standing), default=math.nan),
        }
    return out


__all__ = ["Case", "SLIDE_TOL", "TARGET", "THETA_TOL", "agreement_metrics", "compare_case", "pulse_cases",
           "record_cases"]
