"""
Sliding: the block on a floor with friction
===========================================

A block on a floor with Coulomb friction rests, slides, rocks, slides while rocking, or flies
(the ``friction`` solver; the :doc:`user guide's page on friction </guide/friction>`). With
``mu < b/h`` the block slides before it can rock; with ``mu > b/h`` it rocks as on a floor that never lets
it slip, unless the pulse is strong enough to make it slip as well. The same pulse on the same block with
three friction coefficients:
"""

import matplotlib.pyplot as plt

from opsrock import Block, OneSinePulse, simulate

fig, (ax_theta, ax_slide) = plt.subplots(2, 1, sharex=True, figsize=(7, 5.5), layout="constrained")
for mu in (0.2, 0.5, 0.8):
    block = Block(width=0.6, height=1.5, friction=mu)  # b/h = 0.4
    pulse = OneSinePulse.from_ratios(block, pfa_ratio=2.0, freq_ratio=4.0)  # PFA = 2 g tan(alpha) = 0.8 g
    result = simulate(block, pulse, solver="friction")
    print(f"mu = {mu}: {result.verdict}, theta_max/alpha = {result.theta_max_over_alpha:.3f}, "
          f"largest slide {abs(result.slide).max() * 1000:.1f} mm")
    ax_theta.plot(result.time, result.theta / result.alpha, label=f"mu = {mu}")
    ax_slide.plot(result.time, result.slide * 1000, label=f"mu = {mu}")
ax_theta.set(ylabel="theta / alpha", title="0.6 x 1.5 m block, one-sine pulse of 0.8 g")
ax_slide.set(xlabel="time (s)", ylabel="slide (mm)")
ax_theta.legend()
plt.show()
