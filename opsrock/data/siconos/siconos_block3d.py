"""The rigid box of opsrock's ``rigid3d`` modelled in Siconos (INRIA, Apache-2.0): the independent reference of
validation case ``siconos3d``. Runs OUTSIDE the project venv, with Debian's ``python3-siconos`` 4.4 (numpy and
siconos only; ``make test-siconos`` makes ``.siconos-venv`` for it).

Model: a ``NewtonEulerDS`` (mass 1, the inertia about the centre of mass the case gives, body axes) starting at
rest with its centre of mass ``h`` above the floor; four interactions, one per base corner ``(+-b, +-d, -h)`` (body
frame), each a hand-written ``NewtonEuler3DR`` whose ``computeh`` gives the corner's height as the gap, the
corner as contact point, its floor projection as the second point and the normal ``+z`` (no Bullet collision);
``NewtonImpactFrictionNSL(0, 0, mu, 3)`` (Newton's law with ``e_n = 0``, isotropic Coulomb friction, one ``mu``:
static = kinetic in Siconos; ``mu = None`` is run with ``mu = 10``); a ``FrictionContact(3)`` problem solved by
NSGS; ``MoreauJeanOSI(theta = 0.5)`` time stepping. The floor's motion is the inertia force ``(-a_x, -a_y,
-(g + a_v))`` per unit mass on the centre of mass, set before every step to its value at the step's end (the
theta-scheme then blends the step's two ends).

Usage::

    python opsrock/data/siconos/siconos_block3d.py CASES.npz OUT.csv [--step 5e-4] [--only i,j,...]
    python opsrock/data/siconos/siconos_block3d.py CASES.npz --serve      # one case index per stdin line, a JSON line back

``CASES.npz`` (written by ``opsrock.validation.siconos3d.write_cases``): ``meta`` a JSON list of cases (``b``,
``d``, ``h`` in m, ``inertia`` (3, m² per unit mass), ``mu`` or null, ``dt`` (s), ``start``, ``n``, ``tail`` (s),
``av_tail`` (m/s², the vertical acceleration after the last sample: a pulse's constant vertical acts throughout)),
and ``ax``, ``ay``, ``av`` (m/s², concatenated samples; linear between samples; after the last the horizontal ones
are zero and the vertical one is ``av_tail``).

Early stop (exact for the verdict and the peak tilt): once the floor motion has ended the block's mechanical
energy per unit mass ``E = |v|²/2 + I_max |omega|²/2 + g' (z - h)`` (``g' = g + a_v`` after the motion) (an upper bound of it: the largest principal
inertia) can only fall (impacts and friction dissipate); at any tilt ``theta`` the centre of mass stands at least
``h cos theta + m sin theta`` above the floor (``m = min(b, d)``, the nearest base edge). So when ``E`` is below half of
``g' (h cos theta_max + m sin theta_max - h)`` and the base centre moves slower than 1 mm/s, the block can neither
tilt beyond ``theta_max`` nor overturn: the run stops there (``steps`` tells where). The factor 1/2 is a margin:
without it two probe cases stopped early by 1.5e-4 rad of peak tilt (the Moreau-Jean energy is not exactly
monotone); with it their outputs equal those of the full-tail run to every digit.

Output per case: overturned (tilt >= pi/2), peak tilt (rad), peak slide of the base centre (m), peak twist (rad),
wall time (s).
"""

import csv
import json
import math
import sys
import time

import numpy as np
import siconos.kernel as sk
import siconos.numerics as sn

G = 9.81
MU_INFINITE = 10.0
FIELDS = ("index", "overturned", "tilt_max", "slide_max", "twist_max", "wall_s", "steps", "status")


class CornerR(sk.NewtonEuler3DR):
    """A base corner against the floor ``z = 0``: gap = the corner's height."""

    def __init__(self, corner):
        self._c = np.asarray(corner, dtype=float)
        sk.NewtonEuler3DR.__init__(self)
        self.setRelPc1(list(self._c))
        self.setRelPc2([0.0, 0.0, 0.0])
        self.setRelNc([0.0, 0.0, 1.0])

    def computeh(self, time, q0, y):
        q = sk.SiconosVector(q0)
        w, x, yy, z = q[3], q[4], q[5], q[6]
        c = self._c
        # corner in the floor frame: X + R(q) c
        rz = 2.0 * (x * z - w * yy) * c[0] + 2.0 * (yy * z + w * x) * c[1] + (1.0 - 2.0 * (x * x + yy * yy)) * c[2]
        rx = (1.0 - 2.0 * (yy * yy + z * z)) * c[0] + 2.0 * (x * yy - w * z) * c[1] + 2.0 * (x * z + w * yy) * c[2]
        ry = 2.0 * (x * yy + w * z) * c[0] + (1.0 - 2.0 * (x * x + z * z)) * c[1] + 2.0 * (yy * z - w * x) * c[2]
        px, py, pz = q[0] + rx, q[1] + ry, q[2] + rz
        y[0] = pz
        pc1, pc2, nc = self.pc1(), self.pc2(), self.nc()  # Siconos's own vectors, written in place
        nc[0], nc[1], nc[2] = 0.0, 0.0, 1.0
        pc1[0], pc1[1], pc1[2] = px, py, pz
        pc2[0], pc2[1], pc2[2] = px, py, 0.0


def _quat_state(q):
    """Tilt (rad), twist (rad) and the rotation's ``R[:, 2]`` of the quaternion ``q = (w, x, y, z)``."""
    w, x, y, z = q
    cos_tilt = 1.0 - 2.0 * (x * x + y * y)
    tilt = math.acos(max(-1.0, min(1.0, cos_tilt)))
    twist = 2.0 * math.atan2(z, w)
    twist = (twist + math.pi) % (2.0 * math.pi) - math.pi
    col = (2.0 * (x * z + w * y), 2.0 * (y * z - w * x), cos_tilt)
    return tilt, twist, col


def _energy(q, v, i_max, h, g):
    """Upper bound of the mechanical energy per unit mass above rest (m²/s²) under gravity ``g`` (m/s²): see the
    module docstring."""
    return 0.5 * (v[0] ** 2 + v[1] ** 2 + v[2] ** 2) + 0.5 * i_max * (v[3] ** 2 + v[4] ** 2 + v[5] ** 2) + g * (q[2] - h)


def _tilt_energy(theta, h, m, g):
    """Least energy per unit mass above rest that brings the block to tilt ``theta`` (m²/s²) under gravity ``g``
    (m/s²); positive floor 1e-9."""
    return max(g * (h * math.cos(theta) + m * math.sin(theta) - h), 1e-9)


def run_case(case, ax, ay, av, step):
    """One case: ``dict`` of the outputs (see the module docstring)."""
    t0 = time.perf_counter()
    b, d, h = case["b"], case["d"], case["h"]
    mu = MU_INFINITE if case["mu"] is None else case["mu"]
    body = sk.NewtonEulerDS([0.0, 0.0, h, 1.0, 0.0, 0.0, 0.0], [0.0] * 6, 1.0, np.diag(case["inertia"]))
    fext = np.array([0.0, 0.0, -G])
    body.setFExtPtr(fext)
    nsds = sk.NonSmoothDynamicalSystem(0.0, 1e9)
    nsds.insertDynamicalSystem(body)
    law = sk.NewtonImpactFrictionNSL(0.0, 0.0, mu, 3)
    keep = []  # the Python relations must outlive the run (Siconos holds only C++ pointers to them)
    for sx, sy in ((1, 1), (-1, 1), (-1, -1), (1, -1)):
        rel = CornerR((sx * b, sy * d, -h))
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
    dt, n, av_tail = case["dt"], ax.size, case.get("av_tail", 0.0)
    t_end = (n - 1) * dt + case["tail"]
    steps = int(math.ceil(t_end / step))
    q, v = body.q(), body.twist()
    m, i_max, t_motion, g_tail = min(b, d), max(case["inertia"]), (n - 1) * dt, G + av_tail
    s_prev = (0.0, 0.0)
    tilt_max = slide_max = twist_max = 0.0
    overturned, status = False, "ok"
    for k in range(steps):
        t1 = (k + 1) * step
        j = t1 / dt
        i = int(j)
        if i < n - 1:
            f = j - i
            a = ((1 - f) * ax[i] + f * ax[i + 1], (1 - f) * ay[i] + f * ay[i + 1], (1 - f) * av[i] + f * av[i + 1])
        else:
            a = (0.0, 0.0, av_tail)
        fext[0], fext[1], fext[2] = -a[0], -a[1], -(G + a[2])
        body.setFExtPtr(fext)
        try:
            sim.computeOneStep()
            sim.nextStep()
        except Exception as exc:  # noqa: BLE001  a failed run is reported with its reason, not raised
            status = f"failed: {type(exc).__name__}: {exc}"[:200]
            break
        tilt, twist, col = _quat_state((q[3], q[4], q[5], q[6]))
        if not math.isfinite(tilt):
            status = "failed: non-finite state"
            break
        sx, sy = q[0] - h * col[0], q[1] - h * col[1]
        tilt_max = max(tilt_max, tilt)
        twist_max = max(twist_max, abs(twist))
        slide_max = max(slide_max, math.hypot(sx, sy))
        if tilt >= 0.5 * math.pi:
            overturned = True
            break
        base_speed = math.hypot(sx - s_prev[0], sy - s_prev[1]) / step
        s_prev = (sx, sy)
        if t1 > t_motion and base_speed < 1e-3 and _energy(q, v, i_max, h, g_tail) < 0.5 * _tilt_energy(tilt_max, h, m, g_tail):
            break
    return {"index": case["index"], "overturned": overturned, "tilt_max": tilt_max, "slide_max": slide_max,
            "twist_max": twist_max, "wall_s": time.perf_counter() - t0, "steps": k + 1, "status": status}


def load(path):
    """``(meta, ax, ay, av)`` of a case file."""
    data = np.load(path)
    return json.loads(str(data["meta"])), data["ax"], data["ay"], data["av"]


def _one(meta, ax, ay, av, i, step):
    c = meta[i]
    s = slice(c["start"], c["start"] + c["n"])
    return run_case(c, ax[s], ay[s], av[s], step)


def main(argv):
    meta, ax, ay, av = load(argv[1])
    step = float(argv[argv.index("--step") + 1]) if "--step" in argv else 5e-4
    if "--serve" in argv:
        for line in sys.stdin:
            print(json.dumps(_one(meta, ax, ay, av, int(line), step)), flush=True)
        return 0
    only = range(len(meta))
    if "--only" in argv:
        only = [int(v) for v in argv[argv.index("--only") + 1].split(",")]
    with open(argv[2], "w", newline="") as fh:
        w = csv.DictWriter(fh, FIELDS)
        w.writeheader()
        for i in only:
            row = _one(meta, ax, ay, av, i, step)
            w.writerow(row)
            fh.flush()
            print(json.dumps(row), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
