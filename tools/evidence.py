"""Write opsrock/data/evidence/solvers.csv: what each solver's default costs and how accurate it is,
derived from the validation cases' and the benchmarks' own outputs (never retyped).

    .venv/bin/python tools/evidence.py          # rewrite the shipped table from validation/ and bench/
    .venv/bin/python tools/evidence.py --check  # exit 1 if the shipped table differs (tests call it)

Rows: one per solver at its default settings. ``numerical_error_alpha`` is the largest error in
theta_max / alpha against the solver's own converged model on validation case 5's pulses (friction:
validation case 11's largest well-conditioned difference to the Moreau-Jean time stepper, the larger of
the two implementations' errors); ``record_seconds_per_cpu_second`` is the cost on the four FEMA P695 roof
motions of ``opsrock bench`` (records, friction); ``model_form_*`` the SDOF model against the rigid body on
the 207 broadband records of validation case 9 (all cases: p95 of |d theta_max| / alpha and verdict
agreement). ``source`` names the files and rows.
"""

from __future__ import annotations

import csv
import io
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "opsrock" / "data" / "evidence" / "solvers.csv"

#: solver -> (model, label of its default settings in validation/speed_accuracy/speed_accuracy.csv,
#: its entry in bench/results.json: (benchmark, key)).
SOLVERS = {
    "housner_fast": ("rigid", "housner_fast max_step=0.02/p", ("records", "housner_fast")),
    "housner": ("rigid", "housner rtol=1e-10", ("records", "housner")),
    "opensees": ("sdof", "opensees newmark adaptive dtmax=0.002", ("records", "opensees")),
    "sdof": ("sdof", "sdof rtol=1e-10", ("records", "sdof")),
    "friction": ("friction", None, ("friction", "friction_no_slip")),
    "moreau_jean": ("friction", None, ("friction", "moreau_jean_mu0.4")),
}
COLUMNS = ("solver", "model", "numerical_error_alpha", "record_seconds_per_cpu_second", "model_form_p95_alpha",
           "model_form_verdict_agreement", "source")


def _csv(path: Path) -> list[dict]:
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def _metric(path: Path, name: str) -> float:
    return float(next(r["value"] for r in _csv(path) if r["metric"] == name))


def rows() -> list[dict]:
    speed = {r["label"]: r for r in _csv(ROOT / "validation/speed_accuracy/speed_accuracy.csv")}
    bench = json.loads((ROOT / "bench/results.json").read_text())
    sdof_rec = ROOT / "validation/sdof_records/summary.csv"
    fric = ROOT / "validation/friction/summary.csv"
    out = []
    for solver, (model, label, (bname, key)) in SOLVERS.items():
        if label is not None:
            err, src = float(speed[label]["max_error_over_alpha"]), f"validation/speed_accuracy/speed_accuracy.csv [{label}]"
        else:
            err, src = _metric(fric, "agreement_max_d_theta_over_alpha"), "validation/friction/summary.csv"
        cost = float(bench[bname][key]["record_seconds_per_cpu_second"])
        mf = ({} if model != "sdof" else {
            "model_form_p95_alpha": _metric(sdof_rec, f"{solver}_vs_rigid_p95_all"),
            "model_form_verdict_agreement": _metric(sdof_rec, f"{solver}_vs_rigid_verdicts_all")})
        out.append({"solver": solver, "model": model, "numerical_error_alpha": repr(err),
                    "record_seconds_per_cpu_second": repr(cost),
                    "model_form_p95_alpha": repr(mf.get("model_form_p95_alpha", 0.0)),
                    "model_form_verdict_agreement": repr(mf.get("model_form_verdict_agreement", 1.0)),
                    "source": f"{src}; bench/results.json [{bname}][{key}]"
                              + ("; validation/sdof_records/summary.csv" if mf else "")})
    return out


def text() -> str:
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=COLUMNS, lineterminator="\n")
    w.writeheader()
    w.writerows(rows())
    return buf.getvalue()


if __name__ == "__main__":
    new = text()
    if "--check" in sys.argv:
        sys.exit(0 if OUT.is_file() and OUT.read_text() == new else 1)
    OUT.write_text(new)
    print(f"wrote {OUT}")
