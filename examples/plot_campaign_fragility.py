"""
A campaign on your own records, and its fragility
=================================================

Your floor acceleration histories, in files of your own, run as a record campaign: a scene file with a
``[records]`` table (files, their units), the blocks, and an incremental dynamic analysis (IDA) that scales
each record to levels of ``PFA / (g tan alpha)``. :func:`opsrock.campaign.run_campaign` solves every case
(resumable: its store keeps each finished case), and a maximum-likelihood lognormal fit with a
record-bootstrap interval (:func:`opsrock.fragility.fit_lognormal_mle`) turns the outcomes into a fragility
curve. On the command line the same is ``opsrock run SCENE --out DIR`` then ``opsrock fragility DIR``.

Here "your records" are the roof motions of the shipped example building, written out as two-column CSV
files in m/s²; this quick form uses 2 blocks x 5 records x 8 levels = 80 cases.
"""

import tempfile
from importlib.resources import files
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from opsrock import run_campaign
from opsrock.campaign.cases import read_cases
from opsrock.excitations.readers import read_record
from opsrock.fragility import fit_lognormal_mle, fragility_probability

work = Path(tempfile.mkdtemp())
shipped = files("opsrock.data") / "examples" / "floor-motions"
manifest = pd.read_csv(shipped / "motions.csv", comment="#", dtype={"units": str})
(work / "records").mkdir()
for row in manifest[(manifest.floor == 3) & (manifest.direction == 1)].itertuples():
    units = row.units if isinstance(row.units, str) else None
    dt = row.dt if np.isfinite(row.dt) else None
    record = read_record(shipped / row.file, units=units, dt=dt)
    time = record.dt * np.arange(record.values.size)  # s; record.values are in m/s²
    pd.DataFrame({"time": time, "acceleration": record.values}).to_csv(
        work / "records" / f"{row.record}.csv", index=False)

blocks = files("opsrock.data") / "blocks.toml"
(work / "scene.toml").write_text(f'''
name = "my-records"
blocks = "{blocks}"
select = ["bookcase", "medicine_cabinet"]

[solver]
name = "housner_fast"

[records]
glob = "records/*.csv"
units = "m/s2"

[records.intensity]
method = "ida"
measure = "pfa_ratio"
levels = [1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0]
''')

summary = run_campaign(work / "scene.toml", work / "campaign", workers=1, progress=False)
print(f"{summary.n_cases} cases, {summary.n_failed} failed, in {summary.wall_time_s:.1f} s")

cases = read_cases(summary.cases_csv)  # the table, typed, its units row checked and skipped
fig, ax = plt.subplots(figsize=(6.5, 4.5), layout="constrained")
for block, group in cases[cases.rocked & (cases.status == "ok")].groupby("block"):
    fit = fit_lognormal_mle(group.pfa_ratio.to_numpy(), group.overturned.to_numpy(), n_boot=100,
                            groups=group.record.to_numpy())
    print(f"{block}: median PFA/(g tan alpha) = {fit.mu:.2f} [{fit.mu_lo:.2f}, {fit.mu_hi:.2f}], "
          f"beta = {fit.beta:.2f}")
    x = np.linspace(1.0, 7.0, 200)
    (line,) = ax.plot(x, fragility_probability(x, fit.mu, fit.beta), label=f"{block} (MLE)")
    levels = group.groupby("pfa_ratio").overturned.mean()
    ax.plot(levels.index, levels.to_numpy(), "o", color=line.get_color())
ax.set(xlabel="PFA / (g tan alpha)", ylabel="P(overturning)", title="IDA on five roof motions")
ax.legend()
plt.show()
