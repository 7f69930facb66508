"""
A rocking spectrum
==================

The peak rotation of a block over a grid of one-sine pulses, in the paper's dimensionless ratios
``omega_p / p`` (pulse frequency over the block's frequency parameter) and ``PFA / (g tan alpha)``,
solved at once by the compiled rigid-body solver ``housner_fast``
(:func:`opsrock.solvers.housner_fast.solve_grid`). Overturned cases are shown in grey. The full spectrum
of ``make reproduce`` uses 100 x 100 pulses per block; this quick form uses 60 x 60.
"""

import matplotlib.pyplot as plt
import numpy as np

from opsrock import Block
from opsrock.solvers.housner_fast import solve_grid

block = Block(width=0.40, height=2.20)
e = block.e  # the paper's restitution, 0.95 of Housner's e_R (the default)
freq_ratio = np.linspace(1.0, 10.0, 60)
pfa_ratio = np.linspace(1.0, 8.0, 60)
F, A = np.meshgrid(freq_ratio, pfa_ratio)

grid = solve_grid(block.alpha, e, A, F)
peak = np.where(grid.overturned, np.nan, grid.theta_max / block.alpha)
print(f"{grid.overturned.sum()} of {grid.overturned.size} pulses overturn the block")

fig, ax = plt.subplots(figsize=(6.5, 4.5), layout="constrained")
ax.pcolormesh(F, A, np.where(grid.overturned, 1.0, np.nan), cmap="Greys", vmin=0, vmax=2, shading="auto")
mesh = ax.pcolormesh(F, A, peak, cmap="viridis", vmin=0, vmax=1, shading="auto")
fig.colorbar(mesh, label="theta_max / alpha (safe cases)")
ax.set(xlabel="omega_p / p", ylabel="PFA / (g tan alpha)",
       title=f"{block.width} x {block.height} m block, e = {e:.3f}: grey overturns")
plt.show()
