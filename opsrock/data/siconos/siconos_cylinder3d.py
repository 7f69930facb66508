"""The rigid cylinder of opsrock's ``cylinder3d`` modelled in Siconos (INRIA, Apache-2.0): the independent reference of
validation case ``siconos_cylinder``. Runs OUTSIDE the project venv, with Debian's ``python3-siconos`` 4.4 (numpy and
siconos only), as ``siconos_block3d.py`` beside it, whose corner relation, case file, quaternion helpers and output
columns it reuses.

Model: a ``NewtonEulerDS`` (mass 1, inertia ``diag(i_h, i_h, i_z)`` about the centre of mass, body axes) at rest with
its centre of mass ``h`` above the floor. Contacts, as ``cylinder3d``'s: ``RIM_POINTS`` points evenly round the rim
(body angles ``2 pi k / 16``), each a fixed body point against the floor (``siconos_block3d.CornerR``), carry the
flat base; one more interaction (:class:`LowestRimR`) has as its contact point the lowest point of the rim, found
again at every evaluation (body angle ``atan2(-R_21, -R_20)``), so that a tilted cylinder touches the floor where a
round base does and the contact runs round the rim as it wobbles (the fixed points stand above it by up to ``r (1
- cos(pi/16)) sin(tilt)``). ``NewtonImpactFrictionNSL(0, 0, mu, 3)`` (Newton's law with ``e_n = 0``: Housner's law on
a rim, as cylinder3d; one ``mu``, static = kinetic; ``mu = None`` is run with ``mu = 10``); ``FrictionContact(3)`` by
NSGS; ``MoreauJeanOSI(theta = 0.5)``. The floor's motion as in ``siconos_block3d.py``.

Differences from ``cylinder3d`` by construction: the flat base is a 16-gon here (its uplift threshold between two rim
points is ``cos(pi/16) = 0.981`` of the circle's), and nothing sets a rolling contact point back onto the floor (a
velocity-level contact lets it drift by ``O(dt²)`` a step).

Usage::

    python opsrock/data/siconos/siconos_cylinder3d.py CASES.npz OUT.csv [--step 5e-4] [--only i,j,...]

``CASES.npz`` as ``siconos_block3d.py``'s, each case with ``r``, ``h`` (m) and ``inertia`` ``(i_h, i_h, i_z)`` (m² per
unit mass) in place of ``b``, ``d``. Early stop as there, with the cylinder's lift ``g' (h cos theta + r sin theta -
h)`` (exact on a rim point). Output per case as there.
"""

import csv
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
import siconos.kernel as sk
import siconos.numerics as sn

sys.path.insert(0, str(Path(__file__).resolve().parent))
import siconos_block3d as box  # noqa: E402  (beside this file)

RIM_POINTS = 16


class LowestRimR(sk.NewtonEuler3DR):
    """The lowest point of the rim (radius ``r``, ``h`` below the centre of mass) against the floor ``z = 0``."""

    def __init__(self, r, h):
        self._r, self._h = float(r), float(h)
        sk.NewtonEuler3DR.__init__(self)
        self.setRelPc1([r, 0.0, -h])
        self.setRelPc2([0.0, 0.0, 0.0])
        self.setRelNc([0.0, 0.0, 1.0])

    def computeh(self, time, q0, y):
        q = sk.SiconosVector(q0)
        w, x, yy, z = q[3], q[4], q[5], q[6]
        r20, r21 = 2.0 * (x * z - w * yy), 2.0 * (yy * z + w * x)
        phi = math.atan2(-r21, -r20) if math.hypot(r20, r21) > 1e-14 else 0.0
        c = (self._r * math.cos(phi), self._r * math.sin(phi), -self._h)
        rx = (1.0 - 2.0 * (yy * yy + z * z)) * c[0] + 2.0 * (x * yy - w * z) * c[1] + 2.0 * (x * z + w * yy) * c[2]
        ry = 2.0 * (x * yy + w * z) * c[0] + (1.0 - 2.0 * (x * x + z * z)) * c[1] + 2.0 * (yy * z - w * x) * c[2]
        rz = r20 * c[0] + r21 * c[1] + (1.0 - 2.0 * (x * x + yy * yy)) * c[2]
        px, py, pz = q[0] + rx, q[1] + ry, q[2] + rz
        y[0] = pz
        pc1, pc2, nc = self.pc1(), self.pc2(), self.nc()
        nc[0], nc[1], nc[2] = 0.0, 0.0, 1.0
        pc1[0], pc1[1], pc1[2] = px, py, pz
        pc2[0], pc2[1], pc2[2] = px, py, 0.0


def _simulation(case, step):
    """The Siconos objects of one case: ``(sim, body, fext, keep)`` (``keep`` holds the Python relations alive)."""
    r, h = case["r"], case["h"]
    mu = box.MU_INFINITE if case["mu"] is None else case["mu"]
    body = sk.NewtonEulerDS([0.0, 0.0, h, 1.0, 0.0, 0.0, 0.0], [0.0] * 6, 1.0, np.diag(case["inertia"]))
    fext = np.array([0.0, 0.0, -box.G])
    body.setFExtPtr(fext)
    nsds = sk.NonSmoothDynamicalSystem(0.0, 1e9)
    nsds.insertDynamicalSystem(body)
    law = sk.NewtonImpactFrictionNSL(0.0, 0.0, mu, 3)
    rels = [box.CornerR((r * math.cos(2 * math.pi * k / RIM_POINTS), r * math.sin(2 * math.pi * k / RIM_POINTS), -h))
            for k in range(RIM_POINTS)] + [LowestRimR(r, h)]
    keep = []
    for rel in rels:
        inter = sk.Interaction(law, rel)
        keep.append((rel, inter))
        nsds.link(inter, body)
    osi = sk.MoreauJeanOSI(0.5)
    fc = sk.FrictionContact(3, sn.SICONOS_FRICTION_3D_NSGS)
    fc.numericsSolverOptions().iparam[sn.SICONOS_IPARAM_MAX_ITER] = 1000
    fc.numericsSolverOptions().dparam[sn.SICONOS_DPARAM_TOL] = 1e-10
    sim = sk.TimeStepping(nsds, sk.TimeDiscretisation(0.0, step), osi, fc)
    sim.setNewtonMaxIteration(20)
    sim.setNewtonTolerance(1e-10)
    return sim, body, fext, keep


def run_case(case, ax, ay, av, step):
    """One case: ``dict`` of the outputs (``siconos_block3d.FIELDS``)."""
    t0 = time.perf_counter()
    r, h = case["r"], case["h"]
    sim, body, fext, keep = _simulation(case, step)
    dt, n, av_tail = case["dt"], ax.size, case.get("av_tail", 0.0)
    steps = int(math.ceil(((n - 1) * dt + case["tail"]) / step))
    q, v = body.q(), body.twist()
    i_max, t_motion, g_tail = max(case["inertia"]), (n - 1) * dt, box.G + av_tail
    s_prev = (0.0, 0.0)
    tilt_max = slide_max = twist_max = 0.0
    overturned, status, k = False, "ok", 0
    for k in range(steps):
        t1 = (k + 1) * step
        i = int(t1 / dt)
        if i < n - 1:
            f = t1 / dt - i
            a = ((1 - f) * ax[i] + f * ax[i + 1], (1 - f) * ay[i] + f * ay[i + 1], (1 - f) * av[i] + f * av[i + 1])
        else:
            a = (0.0, 0.0, av_tail)
        fext[0], fext[1], fext[2] = -a[0], -a[1], -(box.G + a[2])
        body.setFExtPtr(fext)
        try:
            sim.computeOneStep()
            sim.nextStep()
        except Exception as exc:  # noqa: BLE001  a failed run is reported with its reason, not raised
            status = f"failed: {type(exc).__name__}: {exc}"[:200]
            break
        tilt, twist, col = box._quat_state((q[3], q[4], q[5], q[6]))
        if not math.isfinite(tilt):
            status = "failed: non-finite state"
            break
        sx, sy = q[0] - h * col[0], q[1] - h * col[1]
        tilt_max, twist_max = max(tilt_max, tilt), max(twist_max, abs(twist))
        slide_max = max(slide_max, math.hypot(sx, sy))
        if tilt >= 0.5 * math.pi:
            overturned = True
            break
        base_speed = math.hypot(sx - s_prev[0], sy - s_prev[1]) / step
        s_prev = (sx, sy)
        lift = max(g_tail * (h * math.cos(tilt_max) + r * math.sin(tilt_max) - h), 1e-9)
        if t1 > t_motion and base_speed < 1e-3 and box._energy(q, v, i_max, h, g_tail) < 0.5 * lift:
            break
    del keep
    return {"index": case["index"], "overturned": overturned, "tilt_max": tilt_max, "slide_max": slide_max,
            "twist_max": twist_max, "wall_s": time.perf_counter() - t0, "steps": k + 1, "status": status}


def main(argv):
    meta, ax, ay, av = box.load(argv[1])
    step = float(argv[argv.index("--step") + 1]) if "--step" in argv else 5e-4
    only = [int(v) for v in argv[argv.index("--only") + 1].split(",")] if "--only" in argv else range(len(meta))
    with open(argv[2], "w", newline="") as fh:
        w = csv.DictWriter(fh, box.FIELDS)
        w.writeheader()
        for i in only:
            c = meta[i]
            s = slice(c["start"], c["start"] + c["n"])
            row = run_case(c, ax[s], ay[s], av[s], step)
            w.writerow(row)
            fh.flush()
            print(json.dumps(row), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
