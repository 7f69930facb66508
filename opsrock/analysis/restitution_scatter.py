"""Does the measured scatter of restitution matter beside the record-to-record scatter?

The shipped FEMA P695 IDA scene (``fema-far-field-ida``: four blocks, the 44 far-field components at the
roofs of a 3- and an 8-storey building, ten levels of ``PFA / (g tan alpha)``, ``housner_fast``) is run
three times, identical but for the blocks' restitution:

* ``fixed``: the factor fitted on the limestone experiments (``restitution = "colombo-limestone"``);
* ``uncertain``: the same factor drawn per case from the data's spread
  (``restitution_factor = { distribution = "colombo-limestone", seed = SEED }``,
  :mod:`opsrock.restitution`);
* ``paper``: the paper's fixed 0.95, for scale.

Per block and floor, the overturning fragility in the scene's measure is fitted by maximum likelihood
on all cases with 95 % bootstrap intervals that resample whole records. The scatter of ``e`` matters
where the uncertain fit's median or beta leaves the fixed fit's interval; the dispersion it adds is
``sqrt(beta_uncertain² - beta_fixed²)`` where positive.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pandas as pd

from opsrock.campaign.cases import read_cases

#: The scene compared.
SCENE: str = "fema-far-field-ida"
#: Seed of the per-case draws; bootstrap resamples and seed of the fits.
SEED, N_BOOT = 20250617, 200
#: The variants: name -> (restitution law of every block, distribution table or None).
VARIANTS: dict[str, tuple[str | None, dict | None]] = {
    "fixed": ("colombo-limestone", None),
    "uncertain": (None, {"distribution": "colombo-limestone", "seed": SEED}),
    "paper": ("paper", None),
}


def variant_scene(name: str, scene=None):
    """The scene of variant ``name`` (a key of :data:`VARIANTS`), from the shipped scene or ``scene``."""
    from opsrock.campaign.scene import load_scene
    from opsrock.restitution import distribution_from_table, law_factor

    base = load_scene(SCENE) if scene is None else scene
    law, table = VARIANTS[name]
    blocks = []
    for spec in base.blocks:
        if table is not None:
            dist = distribution_from_table(table)
            blocks.append(dataclasses.replace(spec, restitution_factor=dist.mean, restitution=None,
                                              restitution_distribution=dist))
        else:
            blocks.append(dataclasses.replace(spec, restitution_factor=law_factor(law), restitution=None,
                                              restitution_distribution=None))
    return dataclasses.replace(base, name=f"{base.name}-{name}", blocks=tuple(blocks))


def _fit(group: pd.DataFrame, measure: str) -> dict:
    from opsrock.fragility.mle import fit_lognormal_mle

    ok = group[group["status"] == "ok"]
    y = ok["overturned"].to_numpy(bool)
    fit = fit_lognormal_mle(ok[measure].to_numpy(), y, n_boot=N_BOOT, seed=SEED, groups=ok["record"].to_numpy())
    return {"median": fit.mu, "median_lo": fit.mu_lo, "median_hi": fit.mu_hi, "beta": fit.beta,
            "beta_lo": fit.beta_lo, "beta_hi": fit.beta_hi, "n_cases": int(len(ok)), "n_overturned": int(y.sum()),
            "success": bool(fit.success)}


def compare(out_dir: str | Path, *, workers: int | None = None, progress: bool = False, scene=None) -> pd.DataFrame:
    """Run the three variants into ``out_dir/<variant>`` and fit them; one row per block, floor and variant,
    with the fixed variant's intervals beside each row and the verdict (``inside`` / ``outside``)."""
    from opsrock.campaign import run_campaign

    rows = []
    for name in VARIANTS:
        summary = run_campaign(variant_scene(name, scene), Path(out_dir) / name, workers=workers, progress=progress)
        cases = read_cases(summary.cases_csv)
        for (block, floor), group in cases.groupby(["block", "floor"], sort=True):
            rows.append({"variant": name, "block": block, "floor": floor, "measure": "level_value",
                         "mean_e": float(group["e"].mean()), "std_e": float(group["e"].std()),
                         **_fit(group, "level_value")})
    table = pd.DataFrame(rows)
    fixed = table[table["variant"] == "fixed"].set_index(["block", "floor"])
    for col in ("median_lo", "median_hi", "beta", "beta_lo", "beta_hi", "median"):
        table[f"fixed_{col}"] = [fixed.loc[(b, f), col] for b, f in zip(table["block"], table["floor"])]
    inside = ((table["median"] >= table["fixed_median_lo"]) & (table["median"] <= table["fixed_median_hi"])
              & (table["beta"] >= table["fixed_beta_lo"]) & (table["beta"] <= table["fixed_beta_hi"]))
    table["verdict"] = inside.map({True: "inside", False: "outside"})
    table["median_ratio"] = table["median"] / table["fixed_median"]
    table["added_beta"] = [math.sqrt(max(b * b - f * f, 0.0)) for b, f in zip(table["beta"], table["fixed_beta"])]
    return table


__all__ = ["N_BOOT", "SCENE", "SEED", "VARIANTS", "compare", "variant_scene"]
