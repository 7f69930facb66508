"""Fragility-level model-form error on records: the SDOF model's fragility curves against the rigid
body's, per intensity measure, with their bootstrap intervals.

Inputs are the ``ims.csv`` tables of two record fragility reports of the same scene (``opsrock
fragility RUN --out DIR``): one run with the rigid body (``housner_fast``), one with the SDOF model
(``--solver opensees``). For each IM the script lists both MLE medians and dispersions with their
95 % record-bootstrap intervals and says whether each SDOF value lies inside the rigid body's interval
(and the reverse), and the ratio of medians.

    opsrock run fema-far-field-ida --out R_rigid
    opsrock run fema-far-field-ida --out R_sdof --solver opensees
    opsrock fragility R_rigid --out F_rigid --robustness-sets 0
    opsrock fragility R_sdof --out F_sdof --robustness-sets 0
    python validation/model_form/records_fragility.py F_rigid/ims.csv F_sdof/ims.csv \\
        validation/model_form/records_fragility.csv
"""

import sys

import pandas as pd


def compare(rigid: pd.DataFrame, sdof: pd.DataFrame) -> pd.DataFrame:
    """One row per IM: medians, dispersions, intervals, and whether each lies in the other's interval."""
    cols = ["im", "n_overturned", "mu", "mu_lo", "mu_hi", "beta", "beta_lo", "beta_hi"]
    m = rigid[cols].merge(sdof[cols], on="im", suffixes=("_rigid", "_sdof"))
    m["mu_ratio"] = m["mu_sdof"] / m["mu_rigid"]
    m["mu_sdof_in_rigid_ci"] = (m["mu_sdof"] >= m["mu_lo_rigid"]) & (m["mu_sdof"] <= m["mu_hi_rigid"])
    m["beta_sdof_in_rigid_ci"] = (m["beta_sdof"] >= m["beta_lo_rigid"]) & (m["beta_sdof"] <= m["beta_hi_rigid"])
    m["mu_cis_overlap"] = (m["mu_lo_sdof"] <= m["mu_hi_rigid"]) & (m["mu_lo_rigid"] <= m["mu_hi_sdof"])
    m["beta_cis_overlap"] = (m["beta_lo_sdof"] <= m["beta_hi_rigid"]) & (m["beta_lo_rigid"] <= m["beta_hi_sdof"])
    return m


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print("usage: records_fragility.py RIGID_IMS_CSV SDOF_IMS_CSV OUT_CSV", file=sys.stderr)
        return 2
    from pathlib import Path

    from opsrock._files import atomic_csv
    from opsrock.analysis.record_columns import read_record_table  # its units row skipped (none in an older one)

    out = compare(read_record_table(argv[0]), read_record_table(argv[1]))
    atomic_csv(Path(argv[2]), out)
    with pd.option_context("display.width", 200, "display.max_columns", 30):
        print(out[["im", "mu_rigid", "mu_sdof", "mu_ratio", "mu_sdof_in_rigid_ci", "mu_cis_overlap",
                   "beta_rigid", "beta_sdof", "beta_sdof_in_rigid_ci", "beta_cis_overlap"]].to_string(index=False))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
