"""Load an opsrock fragility export with pelicun and compare every parameter (run in a venv that has
pelicun; pelicun 3.10 needs scipy < 1.16 and pandas < 3, so it cannot share opsrock's venv).

    python tools/pelicun_load.py fragility_pelicun.csv     # exit 0 if every value round-trips
"""

import csv
import sys

from pelicun.assessment import Assessment

path = sys.argv[1]
rows = list(csv.DictReader(open(path, newline="")))
asmnt = Assessment({"PrintLog": False, "Verbose": False})
asmnt.damage.load_model_parameters([path], {r["ID"] for r in rows})
params = asmnt.damage.ds_model.damage_params
bad = 0
for r in rows:
    for col, key in ((("LS1", "Theta_0"), "LS1-Theta_0"), (("LS1", "Theta_1"), "LS1-Theta_1")):
        got, want = float(params.loc[r["ID"], col]), float(r[key])
        if abs(got - want) > 1e-12 * abs(want):
            print(f"{r['ID']} {key}: pelicun read {got!r}, file has {want!r}")
            bad += 1
    if params.loc[r["ID"], ("Demand", "Type")] != r["Demand-Type"]:
        print(f"{r['ID']}: demand type {params.loc[r['ID'], ('Demand', 'Type')]!r} != {r['Demand-Type']!r}")
        bad += 1
print(f"pelicun loaded {len(rows)} components from {path}: {bad} mismatches")
sys.exit(1 if bad or not rows else 0)
