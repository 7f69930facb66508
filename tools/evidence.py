"""Write opsrock/data/evidence/solvers.csv (what each solver's default costs and how accurate it is) and
opsrock/data/evidence/model_form.csv (the SDOF model against the rigid body, for multi-fidelity
campaigns), derived from the validation cases' and the benchmarks' own outputs (never retyped).

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
OUT_MODEL_FORM = ROOT / "opsrock" / "data" / "evidence" / "model_form.csv"
MF_COLUMNS = ("solver", "screen_solvers", "p50", "p90", "p95", "n_safe_both", "n_screen_overturned",
              "n_overturned_to_safe", "n_screen_safe", "n_safe_to_overturned", "min_q_safe_to_overturned", "row_p50",
              "row_p90", "row_p95", "source")

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


def _counts(pairs: list[tuple[str, str]], thetas: list[float]) -> dict:
    flips = [q for (a, b), q in zip(pairs, thetas) if (a, b) == ("safe", "overturned")]
    return {"n_safe_both": pairs.count(("safe", "safe")),
            "n_screen_overturned": sum(a == "overturned" for a, _ in pairs),
            "n_overturned_to_safe": pairs.count(("overturned", "safe")),
            "n_screen_safe": sum(a == "safe" for a, _ in pairs),
            "n_safe_to_overturned": len(flips), "min_q_safe_to_overturned": repr(min(flips)) if flips else "nan"}


def model_form_rows() -> list[dict]:
    """The SDOF solvers against the rigid body on validation case 9's 207 records, and ``housner`` against
    ``housner_fast`` on case 8's 108 FEMA P695 cases."""
    case9 = ROOT / "validation/sdof_records"
    summary = {r["metric"]: r["value"] for r in _csv(case9 / "summary.csv")}
    cases = _csv(case9 / "cases.csv")
    out = []
    for solver in ("opensees", "sdof"):
        pairs = [(r["rigid_verdict"], r[f"{solver}_verdict"]) for r in cases]
        out.append({"solver": solver, "screen_solvers": "housner_fast housner",
                    **{f"p{p}": summary[f"{solver}_vs_rigid_{n}_all"] for p, n in ((50, "median"), (90, "p90"),
                                                                                  (95, "p95"))},
                    **_counts(pairs, [float(r["rigid_theta"]) for r in cases]),
                    **{f"row_p{p}": f"validation/sdof_records/summary.csv, row {solver}_vs_rigid_{n}_all"
                       for p, n in ((50, "median"), (90, "p90"), (95, "p95"))},
                    "source": f"validation/sdof_records/summary.csv rows {solver}_vs_rigid_median_all/_p90_all/"
                              f"_p95_all; cases.csv rigid_verdict x {solver}_verdict, rigid_theta"})
    pair = {r["pair"]: r for r in _csv(ROOT / "validation/records/summary.csv")}["housner_fast vs housner"]
    c8 = _csv(ROOT / "validation/records/cases.csv")
    pairs = [(r["housner_fast_verdict"], r["housner_verdict"]) for r in c8]
    out.append({"solver": "housner", "screen_solvers": "housner_fast", "p50": pair["median_dtheta_over_alpha"],
                "p90": "nan", "p95": pair["p95_dtheta_over_alpha"], **_counts(pairs, [0.0] * len(pairs)),
                "row_p50": "validation/records/summary.csv, row 'housner_fast vs housner', median_dtheta_over_alpha",
                "row_p90": "", "row_p95": "validation/records/summary.csv, row 'housner_fast vs housner', "
                                          "p95_dtheta_over_alpha",
                "source": "validation/records/summary.csv row 'housner_fast vs housner'; cases.csv "
                          "housner_fast_verdict x housner_verdict"})
    return out


def _write(rows_: list[dict], columns) -> str:
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=columns, lineterminator="\n")
    w.writeheader()
    w.writerows(rows_)
    return buf.getvalue()


def text() -> str:
    return _write(rows(), COLUMNS)


if __name__ == "__main__":
    files = {OUT: text(), OUT_MODEL_FORM: _write(model_form_rows(), MF_COLUMNS)}
    if "--check" in sys.argv:
        sys.exit(0 if all(p.is_file() and p.read_text() == t for p, t in files.items()) else 1)
    for path, content in files.items():
        path.write_text(content)
        print(f"wrote {path}")
