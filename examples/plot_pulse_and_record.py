"""
One block under a pulse and under a record, with two solvers
============================================================

A 0.4 x 2.2 m block (a bookcase) under a one-sine pulse and under a floor motion of the shipped example
building, solved by the paper's SDOF model in OpenSees (``opensees``) and by the exact rigid-body equation
with Housner's impacts (``housner``). Each result is a :class:`opsrock.RockingResult`: the rotation history,
its peak and the verdict.
"""

from importlib.resources import files

import matplotlib.pyplot as plt

from opsrock import Block, OneSinePulse, simulate
from opsrock.excitations.readers import read_record

block = Block(width=0.40, height=2.20)  # 2b x 2h (m)
pulse = OneSinePulse.from_ratios(block, pfa_ratio=4.0, freq_ratio=6.0)  # PFA = 4 g tan(alpha), omega_p = 6 p

# A floor motion of the shipped example (roof of a three-storey building, AT2 file in g), scaled so its PFA
# is three times the block's uplift acceleration g tan(alpha).
motions = files("opsrock.data") / "examples" / "floor-motions"
record = read_record(motions / "northridge-f3-d1.AT2").scaled_to_pfa(3.0 * 9.81 * block.width / block.height)

fig, axes = plt.subplots(2, 1, figsize=(7, 5.5), layout="constrained")
for ax, excitation, title in ((axes[0], pulse, "one-sine pulse"), (axes[1], record, record.name)):
    for solver in ("opensees", "housner"):
        result = simulate(block, excitation, solver=solver)
        print(f"{title:>20s} {solver:>8s}: {result.verdict}, theta_max/alpha = {result.theta_max_over_alpha:.3f}")
        ax.plot(result.time, result.theta / result.alpha, label=f"{solver}: {result.verdict}")
    ax.set(title=title, xlabel="time (s)", ylabel="theta / alpha")
    ax.legend()
plt.show()
