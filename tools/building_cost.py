"""Cost of the shear-building filter against the number of storeys: ``python tools/building_cost.py [N ...]``.

One 20-s record of seeded white noise (dt = 0.01 s), first period 0.1 N s (capped to the limits), the roof
motion; prints storeys, wall seconds, samples (with the free-vibration tail) and Newmark substeps per sample.
"""

import sys
import time

import numpy as np

from opsrock.excitations import Record
from opsrock.excitations.building import ShearBuilding, floor_motion, substeps

if __name__ == "__main__":
    record = Record(0.01, np.random.default_rng(1).standard_normal(2000))
    for n in [int(a) for a in sys.argv[1:]] or [3, 8, 25, 50, 100, 200]:
        building = ShearBuilding("b", min(max(0.1 * n, 0.1), 10.0), n)
        t0 = time.perf_counter()
        roof = floor_motion(record, building)
        print(f"{n:4d} storeys {time.perf_counter() - t0:7.2f} s  samples {roof.values.size}  "
              f"substeps {substeps(building, record.dt)}")
