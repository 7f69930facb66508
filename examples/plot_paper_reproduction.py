"""
The paper's reproduction, in a quick form
=========================================

``make reproduce`` (``opsrock reproduce``) runs the whole of Liu, Huang & Liu (2023): a validation gate
(the OpenSees model against an independent solver and closed forms), the paper's 400 one-sine pulses on its
four blocks in OpenSees, the dense overturning spectra, the fragility fits of its Tables 2 and 3, every
figure, and a report (:func:`opsrock.analysis.reproduce.reproduce`). This quick form leaves out the dense
spectra and draws fewer random block sets for the robustness of the IM ranking; the 400 OpenSees cases and
the tables are the full ones.
"""

import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

from opsrock.analysis.reproduce import ReproduceSettings, reproduce

out = Path(tempfile.mkdtemp()) / "results"
res = reproduce(out, ReproduceSettings(spectrum_scene=None, robustness_sets=20), progress=False)
print("validation gate passed:", res.gate.passed)
print({k: round(v, 1) for k, v in res.timings.items()})
print(res.table2.head(9).to_string(index=False))

# %%
# Two of the figures it wrote: the cases of the paper's Figure 6a and the fragility curves of Figure 10.
print(sorted(p.name for p in (out / "figures").glob("*.png")))
fig, axes = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
for ax, name in zip(axes, ("fig6a_cases.png", "fig10_fragility.png")):
    ax.imshow(plt.imread(out / "figures" / name))
    ax.set_axis_off()
    ax.set_title(name)
plt.show()
