"""Probe: how much theta_max moves when a floor motion is scaled by 1 + eps (eps = 1e-6 .. 1e-3).

The synthetic family of the SDOF-on-records work: 20-s band-passed noise (0.5-6 Hz, dt 0.01 s,
2-s ramps), two seeds, three blocks, PFA / (g tan alpha) = 1.3, 2.0, 3.5; the rigid body
(housner_fast) and the paper's SDOF model (opensees). A response that moves by tenths of alpha under
a 1e-6 change of the amplitude cannot be compared case by case between two implementations.

    .venv/bin/python tools/sensitivity_probe.py     # prints one line per case, writes sensitivity_probe.json
"""
import json

import numpy as np
from scipy import signal

from opsrock.block import Block
from opsrock.excitations import Record
from opsrock.solvers import simulate


def noise_record(seed, duration=20.0, dt=0.01, band=(0.5, 6.0)):
    rng = np.random.default_rng(seed)
    sos = signal.butter(4, band, btype="bandpass", fs=1 / dt, output="sos")
    a = signal.sosfiltfilt(sos, rng.standard_normal(int(duration / dt)))
    env = np.minimum(1.0, np.minimum(np.arange(a.size) * dt / 2.0, (a.size - np.arange(a.size)) * dt / 2.0))
    return Record(dt, a * env, name=f"noise{seed}", units="m/s2")

blocks = [Block(0.4, 2.2, name="b1"), Block(0.6, 2.0, name="b2"), Block(0.5, 1.15, name="b3")]
eps = (0.0, 1e-6, 1e-5, 1e-4, 1e-3)
rows = []
for seed in (1, 2):
    base = noise_record(seed)
    for b in blocks:
        for level in (1.3, 2.0, 3.5):
            rec = base.scaled(level * b.uplift_acceleration / base.pfa)
            row = {"record": base.name, "block": b.name, "level": level}
            for solver in ("housner_fast", "opensees"):
                th = [simulate(b, rec.scaled(1 + e), solver).theta_max_over_alpha for e in eps]
                row[solver] = th
            rows.append(row)
            print(row["record"], b.name, level, "rigid", [round(x, 4) for x in row["housner_fast"]], "ops", [round(x, 4) for x in row["opensees"]], flush=True)
json.dump(rows, open("sensitivity_probe.json", "w"), indent=1)
