"""
Your inventory on your floor motions, into pelicun
==================================================

A loss assessor's two files, an **inventory** (one row per item type: size, mass distribution, friction,
floor, quantity, FEMA P-58 ID, repair cost) and a **motions manifest** (the floor acceleration histories of
their own response-history analysis), give each item's overturning and sliding fragility on each floor and
direction, and a ``pelicun/`` folder that pelicun 3.10 runs as it is. This is
``opsrock contents --inventory FILE --motions FILE --quick`` from Python
(:func:`opsrock.run_study`), on the example inventory and floor motions shipped
with opsrock; the quick form runs fewer IDA levels and bootstrap resamples than the full study.
"""

import tempfile
from importlib.resources import files
from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd

import opsrock

data = files("opsrock.data")
inventory = data / "inventories" / "example.csv"
motions = data / "examples" / "floor-motions" / "motions.csv"
print(pd.read_csv(inventory, comment="#")[["id", "width", "depth", "height"]].to_string(index=False))

out = Path(tempfile.mkdtemp()) / "my-building"
study = opsrock.run_study(inventory, motions, out, quick=True, options=opsrock.StudyOptions(progress=False))  # every core
print(f"{study.n_cases} cases ({study.n_failed} failed); report: {Path(study.report).name}")
print("pelicun folder:", sorted(p.name for p in (out / "pelicun").iterdir()))

# Each table has a Units row after its header (pelicun's tabular form): skipped here, the units are in the report
fits = pd.read_csv(study.tables["fits"], skiprows=[1], dtype={"floor": str, "direction": str})
shown = fits[fits.ok & (fits.demand == "pfa")][["item", "floor", "direction", "outcome", "median", "beta"]]
print("medians in g:")
print(shown.to_string(index=False, float_format="%.3f"))

# Each unit once, whatever the direction: expected units damaged (displaced or overturned) and repair cost per
# item and floor, the exact expectation over the records with the fragilities the pelicun folder holds.
expected = pd.read_csv(study.tables["expected"], skiprows=[1], dtype={"floor": str})
print(expected[["item", "floor", "quantity", "expected_damaged", "expected_overturned", "expected_cost"]]
      .to_string(index=False, float_format="%.3f"))

# %%
# The figures of the study's report, as written into its folder:
figures = sorted((out / "figures").glob("*.png"))
fig, axes = plt.subplots(len(figures), 1, figsize=(7, 3.2 * len(figures)), layout="constrained")
for ax, png in zip(axes, figures):
    ax.imshow(plt.imread(png))
    ax.set_axis_off()
    ax.set_title(png.stem)
plt.show()
