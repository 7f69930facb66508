"""Validation case ``friction``: the rigid block with Coulomb friction and vertical floor motion.

Three parts (``validation/friction/README.md`` derives every reference and tolerance):

1. **References** (:mod:`.references`): the no-slip limit against ``housner_fast``; Newmark's sliding
   block under rectangular and half-sine pulses with and without a constant vertical acceleration; the
   uplift threshold ``(g + a_v) tan(alpha)``; Housner's rectangular pulse with ``g -> g + a_v``; the
   energy balance of runs through every mode.
2. **Mode initiation** (:mod:`.diagram`): Shenton's diagram read off the solver's first mode, against
   the closed-form regions.
3. **Two implementations** (:mod:`.agreement`): the event-driven ``friction`` solver against the
   Moreau-Jean time stepper ``moreau_jean`` on pulses and records, ill-conditioned cases set apart.

``run(out_dir, quick)`` writes ``checks.csv``, ``diagram.csv``, ``agreement.csv``, ``summary.csv`` and
the figures ``diagram.png`` and ``agreement.png``, and returns the metrics with ``"passed"``.
"""

from __future__ import annotations

import csv
import math
import time
from pathlib import Path

from opsrock._files import atomic_write


def _write_csv(path: Path, rows: list[dict]) -> None:
    def write(fh):
        w = csv.DictWriter(fh, fieldnames=list(rows[0]), lineterminator="\n")
        w.writeheader()
        for r in rows:
            w.writerow({k: repr(v) if isinstance(v, float) else v for k, v in r.items()})

    atomic_write(path, write)


def plot_agreement(rows: list[dict], path: Path) -> Path:
    """theta_max / alpha and peak slide of the two implementations, well-conditioned cases in colour."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(9.5, 4.2))
    for ax, key, label in ((axes[0], "theta_max_over_alpha", "theta_max / alpha"), (axes[1], "slide_max", "peak slide (m)")):
        for good, colour in ((False, "#bbbbbb"), (True, "#1f77b4")):
            sel = [r for r in rows if r["well_conditioned"] == good and r["response_friction"] != "overturned"
                   and r["response_moreau_jean"] != "overturned"]
            ax.scatter([r[f"{key}_moreau_jean"] for r in sel], [r[f"{key}_friction"] for r in sel], s=10, c=colour,
                       label="well-conditioned" if good else "ill-conditioned")
        lim = max([1e-9] + [max(r[f"{key}_friction"], r[f"{key}_moreau_jean"]) for r in rows
                            if math.isfinite(r[f"{key}_friction"]) and math.isfinite(r[f"{key}_moreau_jean"])
                            and "overturned" not in (r["response_friction"], r["response_moreau_jean"])])
        ax.plot([0, lim], [0, lim], "k-", lw=0.8)
        ax.set_xlabel(f"moreau_jean: {label}")
        ax.set_ylabel(f"friction: {label}")
    axes[0].legend(frameon=False)
    fig.suptitle("The two implementations of the block with friction (cases that stay up)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def run(out_dir: str | Path, quick: bool = False) -> dict:
    """Run the case into ``out_dir``; the metrics, with ``"passed"``."""
    from opsrock.validation.friction import agreement, diagram, references

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    checks = references.checks(quick)
    cells = diagram.diagram(quick)
    dmet = diagram.diagram_metrics(cells)
    rows = [agreement.compare_case(c) for c in agreement.pulse_cases(quick) + agreement.record_cases(quick)]
    ametric = agreement.agreement_metrics(rows)["all"]
    checks.append({"check": "mode initiation: first mode = closed-form region (share of cells away from boundaries)",
                   "value": dmet["agreement"], "reference": 1.0, "tolerance": 0.0,
                   "passed": dmet["agreement"] == 1.0, "source": "Shenton (1996) regions, derived in the README"})
    for key, label in (("response_agreement", "responses equal"), ("close_share", "theta_max within 0.005 alpha "
                                                                                    "and slide within 1 mm")):
        checks.append({"check": f"friction vs moreau_jean, well-conditioned cases: {label} (share)",
                       "value": ametric[key], "reference": agreement.TARGET, "tolerance": 0.0,
                       "passed": bool(ametric[key] >= agreement.TARGET), "source": "the issue's target"})
    _write_csv(out / "checks.csv", checks)
    _write_csv(out / "diagram.csv", cells)
    _write_csv(out / "agreement.csv", rows)
    diagram.plot_diagram(cells, out / "diagram.png")
    plot_agreement(rows, out / "agreement.png")
    metrics = {"passed": all(c["passed"] for c in checks), "n_checks": len(checks),
               "n_failed_checks": sum(not c["passed"] for c in checks), "diagram_agreement": dmet["agreement"],
               **{f"agreement_{k}": v for k, v in ametric.items()}, "wall_time_s": time.perf_counter() - t0}
    _write_csv(out / "summary.csv", [{"metric": k, "value": v} for k, v in metrics.items()])
    return metrics


__all__ = ["plot_agreement", "run"]
