"""A pelicun damage assessment of FEMA P-58's nine unanchored items on the floors of the contents study, run
twice: with FEMA P-58's E.20.22 fragilities and with opsrock's (the study's ``pelicun/`` folder). Runs in a venv
that has pelicun 3.10 (``.pelicun-venv``; pelicun pins scipy < 1.16 and pandas < 3, so it cannot share opsrock's
venv); it does not import opsrock.

    python tools/pelicun_assess.py STUDY/pelicun [--fema FILE] [--repeat 100] [--seed 0]
                                   [--nondirectional-multiplier 1.2] [--out FILE.json]

Inputs, all in the folder (written by the study's one pelicun writer, ``opsrock.inventory.pelicun``):

* ``mapping.csv`` (a ``Units`` row after its header): each opsrock component (``pelicun_id``, one per item and
  floor, each physical unit once), its FEMA item (``fema_id``), pelicun ``location`` (1 the ground floor, ``n + 1``
  floor slab ``n``), ``quantity`` and whether it was ``exported`` (``status`` says why not);
* ``demands.csv``: the demand sample, one realisation per record (``PFV-<n>-1``, m/s; pelicun's default
  ``Demand-Offset`` of -1 for floor demands gives a component at location ``n + 1`` the demand ``PFV-n``);
* ``fragility.csv`` and ``config.json``: opsrock's non-directional components and the multiplier that makes their
  demand the one they were fitted in (``NonDirectionalMultipliers``, 1.0), and the building's storeys.

Both runs place the same units: each item's ``quantity`` at its location, as that many blocks (each unit damaged
on its own capacity draw). FEMA's fragilities come from pelicun's own copy of the FEMA P-58 database
(``PelicunDefault/FEMA P-58/fragility.csv``) unless ``--fema`` names a file; the database marks them
non-directional, and pelicun multiplies their demand by ``--nondirectional-multiplier`` (default 1.2, as pelicun's
default). Each record is repeated ``--repeat`` times so that pelicun's sampling of the capacities averages out; the
expected number of overturned items is pelicun's mean over the realisations. Beside it the exact expectation over
the records, ``sum quantity * mean_r Phi(ln(m d_r / theta) / beta)``, with ``m`` each run's multiplier, checks that
pelicun did what we think. Exit status 1 if they differ by more than the sampling allows.

An item that never overturned within the study's levels has no opsrock component (``mapping.csv`` says so); it
counts as never overturning here, and the output lists it.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.special import ndtr

FEMA_DEFAULT = "PelicunDefault/FEMA P-58/fragility.csv"


def read_demands(path: Path) -> tuple[pd.DataFrame, pd.Series]:
    """The realisations (rows) of each ``PFV-<loc>-<dir>`` column, and their units."""
    raw = pd.read_csv(path, index_col=0)
    units = raw.loc["Units"]
    values = raw.drop(index="Units").astype(float).reset_index(drop=True)
    return values, units


def pelicun_sample(values: pd.DataFrame, units: pd.Series, repeat: int) -> pd.DataFrame:
    """The demand sample for pelicun: every realisation ``repeat`` times, with the ``Units`` row."""
    big = pd.concat([values] * repeat, ignore_index=True)
    columns = pd.MultiIndex.from_tuples([tuple(c.split("-")) for c in big.columns], names=["type", "loc", "dir"])
    big.columns = columns
    unit_row = pd.DataFrame([list(units)], index=["Units"], columns=columns, dtype=object)
    return pd.concat([big.astype(object), unit_row])


def marginals(inventory: pd.DataFrame, ids: pd.Series) -> pd.DataFrame:
    """pelicun's component marginals: ``ids[i]`` placed ``count`` times at its location, non-directional (direction
    0), as ``count`` blocks (each unit overturns or not on its own capacity, not all of a floor's together)."""
    return pd.DataFrame({"Units": "ea", "Location": inventory["location"].astype(str).to_numpy(),
                         "Direction": "0", "Theta_0": inventory["count"].astype(float).to_numpy(),
                         "Blocks": inventory["count"].astype(int).to_numpy()},
                        index=pd.Index(ids.to_numpy(), name="ID"))


def run_pelicun(cmp: pd.DataFrame, fragility: str, sample: pd.DataFrame, stories: int, seed: int,
                multiplier: float) -> pd.Series:
    """One damage assessment; the mean number of components in damage state 1 per ``(ID, location)``."""
    from pelicun.assessment import Assessment

    asmnt = Assessment({"PrintLog": False, "Verbose": False, "Seed": seed,
                        "NonDirectionalMultipliers": {"ALL": multiplier}})
    asmnt.stories = stories
    asmnt.demand.load_sample(sample)
    n = asmnt.demand.sample.shape[0]
    asmnt.asset.load_cmp_model({"marginals": cmp})
    asmnt.asset.generate_cmp_sample(n)
    asmnt.damage.load_model_parameters([fragility], set(cmp.index))
    asmnt.damage.calculate()
    ds = asmnt.damage.ds_model.sample
    ds1 = ds.loc[:, ds.columns.get_level_values("ds") == "1"]
    return ds1.T.groupby(level=["cmp", "loc"]).sum().T.mean(axis=0)


def fragility_params(path: str) -> pd.DataFrame:
    """``LS1-Theta_0``, ``LS1-Theta_1`` and ``Demand-Directional`` of a damage-model CSV (pelicun resolves
    ``PelicunDefault/...``)."""
    if path.startswith("PelicunDefault/"):
        from pelicun.file_io import substitute_default_path

        path = substitute_default_path([path])[0]
    return pd.read_csv(path, index_col=0)


def exact(inv: pd.DataFrame, ids: pd.Series, params: pd.DataFrame, values: pd.DataFrame,
          multiplier: float) -> np.ndarray:
    """Expected overturned count of each inventory row, by direct sum over the records."""
    out = []
    for (_, row), cid in zip(inv.iterrows(), ids):
        theta, beta = float(params.loc[cid, "LS1-Theta_0"]), float(params.loc[cid, "LS1-Theta_1"])
        mult = 1.0 if int(params.loc[cid, "Demand-Directional"]) else multiplier
        d = values[f"PFV-{int(row['location']) - 1}-1"].to_numpy(float)
        out.append(float(row["count"]) * float(np.mean(ndtr(np.log(mult * d / theta) / beta))))
    return np.array(out)


def study_table(path: Path) -> pd.DataFrame:
    """A table of the study with its ``Units`` row (the second line, pelicun's tabular form) skipped."""
    return pd.read_csv(path, dtype={"floor": str}, skiprows=[1])


def placed(mapping: pd.DataFrame) -> tuple[pd.DataFrame, pd.Series]:
    """The units both runs place (``fema_id``, ``floor``, ``location``, ``count``) and opsrock's component of each
    (``""``: none, because the item never overturned within the study's levels); ``SystemExit`` if one has none
    for another reason."""
    exported = mapping["exported"].astype(str).str.lower() == "true"
    never = mapping["status"].astype(str).str.contains("never")
    bad = mapping[~exported & ~never]
    if len(bad):
        raise SystemExit(f"no opsrock component for {list(zip(bad['item'], bad['floor']))} (mapping.csv says why)")
    inv = pd.DataFrame({"fema_id": mapping["fema_id"], "floor": mapping["floor"], "location": mapping["location"],
                        "count": mapping["quantity"]})
    return inv, pd.Series(np.where(exported, mapping["pelicun_id"], ""), dtype=object)


def assess(folder: Path, fema: str, repeat: int, seed: int, multiplier: float) -> pd.DataFrame:
    """Both assessments; one row per item and floor."""
    config = json.loads((folder / "config.json").read_text())
    own = float(config["DL"]["Options"]["NonDirectionalMultipliers"]["ALL"])
    stories = int(config["DL"]["Asset"]["NumberOfStories"])
    inv, ids = placed(study_table(folder / "mapping.csv"))
    values, units = read_demands(folder / "demands.csv")
    sample = pelicun_sample(values, units, repeat)
    out = inv.copy()
    for name, cids, frag, mult in (("fema", inv["fema_id"], fema, multiplier),
                                   ("opsrock", ids, str(folder / "fragility.csv"), own)):
        have = (cids != "").to_numpy()
        got = run_pelicun(marginals(inv[have], cids[have]), frag, sample, stories, seed, mult)
        out[f"{name}_id"] = cids.to_numpy()
        out[f"{name}_pelicun"] = [float(got.get((i, str(loc)), math.nan)) if i else 0.0
                                  for i, loc in zip(cids, inv["location"])]
        out[f"{name}_exact"] = 0.0
        out.loc[have, f"{name}_exact"] = exact(inv[have], cids[have], fragility_params(frag), values, mult)
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("folder", type=Path, help="the contents study's pelicun/ folder")
    ap.add_argument("--fema", default=FEMA_DEFAULT, help=f"FEMA P-58 damage models (default {FEMA_DEFAULT!r})")
    ap.add_argument("--repeat", type=int, default=100, help="realisations per record (default 100)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--nondirectional-multiplier", type=float, default=1.2,
                    help="pelicun's demand multiplier of non-directional components, FEMA's items (default 1.2)")
    ap.add_argument("--out", type=Path, help="also write the results (JSON)")
    args = ap.parse_args(argv)
    table = assess(args.folder, args.fema, args.repeat, args.seed, args.nondirectional_multiplier)
    n_real = args.repeat * len(read_demands(args.folder / "demands.csv")[0])
    print(f"pelicun damage assessment: {int(table['count'].sum())} items, {n_real} realisations "
          f"({args.repeat} per record), each unit once; FEMA's demands x "
          f"{args.nondirectional_multiplier:g} (non-directional); expected number overturned (pelicun / exact)")
    never = sorted(set(table.loc[table["opsrock_id"] == "", "fema_id"]))
    if never:
        print(f"never overturned within the study's levels (no opsrock component, counted 0): {', '.join(never)}")
    by_item = table.groupby("fema_id")[["count", "fema_pelicun", "fema_exact", "opsrock_pelicun", "opsrock_exact"]].sum()
    by_floor = table.groupby("floor", sort=False)[["count", "fema_pelicun", "fema_exact", "opsrock_pelicun",
                                                   "opsrock_exact"]].sum()
    with pd.option_context("display.width", 140, "display.float_format", "{:.2f}".format):
        print(by_item.to_string(), "\n")
        print(by_floor.to_string(), "\n")
    total = table[["count", "fema_pelicun", "fema_exact", "opsrock_pelicun", "opsrock_exact"]].sum()
    print(f"total: FEMA P-58 {total['fema_pelicun']:.2f} (exact {total['fema_exact']:.2f}), opsrock "
          f"{total['opsrock_pelicun']:.2f} (exact {total['opsrock_exact']:.2f}) of {int(total['count'])} items")
    # pelicun's mean samples the capacities: each item is one Bernoulli draw per realisation (variance at most
    # 1/4), so the total's mean has a standard error of at most sqrt(n_items / 4 / n_real); allow four of them
    tol = 4.0 * math.sqrt(total["count"] / 4.0 / n_real)
    bad = [k for k in ("fema", "opsrock") if abs(total[f"{k}_pelicun"] - total[f"{k}_exact"]) > tol]
    if args.out:
        args.out.write_text(json.dumps({"fema": args.fema, "repeat": args.repeat,
                                        "nondirectional_multiplier": args.nondirectional_multiplier,
                                        "realisations": n_real, "total": total.to_dict(),
                                        "by_item": by_item.reset_index().to_dict("records"),
                                        "by_floor": by_floor.reset_index().to_dict("records"),
                                        "rows": table.to_dict("records")}, indent=1))
    if bad:
        print(f"pelicun's mean differs from the exact expectation by more than {tol:.2f} for {bad}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
