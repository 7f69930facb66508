"""Ground motion to floor motion: a linear N-storey shear building, built in OpenSeesPy.

Model
-----
``N`` lumped floor masses ``m_i`` on a fixed base, joined by storey springs ``k_i`` (one
horizontal degree of freedom per floor, ``zeroLength`` elements with ``Elastic`` materials),
classical modal damping ``zeta`` in every mode (OpenSees ``modalDamping`` after ``eigen``).
The ground acceleration ``a_g(t)`` enters as a ``UniformExcitation`` of a ``Path`` series (linear
between the record's samples); the floor motion is the *absolute* acceleration of a floor,
``a_i(t) = u_i''(t) + a_g(t)``, sampled at the record's own times.

Stiffness and mass: uniform by default (``m_i = 1``, ``k_i = k``), or the relative profiles the
user gives; either way the stiffnesses are scaled together so that the first period is the one
asked for (only the ratios of masses and stiffnesses, and ``T_1``, shape the floor motion).

Time step: Newmark average acceleration (no numerical damping), with ``n`` substeps per record
sample so that the step is at most ``T_N / 20`` of the highest mode (period error below
``(pi/20)^2 / 12`` = 0.2 %) and ``T_1 / 100`` of the first (8e-5). The test
``tests/unit/excitations/test_records.py`` checks the OpenSees floor motion against an independent modal
superposition (:func:`modal_floor_motion`: each mode solved exactly for the piecewise-linear
ground motion by ``scipy.signal.lsim``) and, for one storey, against the identity
``PFA = S_a(T, zeta)`` (absolute-acceleration spectrum).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from opsrock.errors import AnalysisError, InputError
from opsrock.excitations.records import Record
from opsrock.excitations.vertical import padded
from opsrock.limits import LIMITS, check, check_count, positive_finite

#: Newmark steps per period of the highest mode (see the module docstring).
STEPS_PER_PERIOD: int = 20

#: Newmark steps per first-mode period: the floor motion is dominated by the first mode, whose
#: period error ``(pi/100)^2/12 = 8e-5`` then shifts its phase by less than 0.2 % of a cycle over
#: the few cycles the damping remembers (``1/(2 pi zeta)`` = 3 cycles at 5 %).
STEPS_PER_FIRST_PERIOD: int = 100

#: The floor motion goes on after the ground motion stops, until the first mode has decayed to this
#: fraction of its amplitude: the ground record is padded with zeros for ``ln(1/FREE_DECAY) /
#: (zeta w_1)`` seconds (6.6 s for T_1 = 0.45 s at 5 %), at most :data:`MAX_FREE_VIBRATION`. A floor
#: record cut where the ground record ends would drop that shaking and leave the floor moving.
FREE_DECAY: float = 0.01

#: Longest free-vibration tail added to a floor motion (s).
MAX_FREE_VIBRATION: float = 60.0

#: Most storeys accepted (a shear building of more storeys is not a model of anything we filter). The
#: filter's cost grows faster than the storeys (the highest mode sets the substeps, the full damping
#: matrix the cost of a step): measured on a 20-s record (8,000 samples with the free-vibration tail),
#: 50 storeys 1.0 s, 100 storeys 2.4 s, 200 storeys 16.5 s (``python tools/building_cost.py``).
MAX_STOREYS: int = int(LIMITS["storeys"].high)


@dataclass(frozen=True)
class ShearBuilding:
    """A linear N-storey shear building with classical modal damping.

    Parameters
    ----------
    name : str
        Label used in case ids (letters, digits, ``_ . -``), e.g. ``"b3"``.
    period : float
        First (fundamental) period ``T_1`` (s), within :data:`opsrock.limits.LIMITS`.
    storeys : int
        Number of storeys ``N`` (1 .. :data:`MAX_STOREYS`).
    damping : float, optional
        Damping ratio of every mode (dimensionless). Default 0.05.
    masses : tuple of float, optional
        Floor masses bottom to top (relative; kg or any unit), ``N`` positive values. Default
        all equal.
    stiffnesses : tuple of float, optional
        Storey stiffnesses bottom to top (relative), ``N`` positive values, scaled together to
        give ``period``. Default all equal.
    """

    name: str
    period: float
    storeys: int
    damping: float = 0.05
    masses: tuple[float, ...] | None = None
    stiffnesses: tuple[float, ...] | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "period", check("period", self.period))
        check_count("storeys", self.storeys)
        object.__setattr__(self, "damping", check("damping", self.damping))
        for label in ("masses", "stiffnesses"):
            value = getattr(self, label)
            if value is None:
                continue
            arr = tuple(positive_finite(f"{label}[{i}]", v) for i, v in enumerate(value))
            if len(arr) != self.storeys:
                raise InputError(f"{label} must hold {self.storeys} values (one per storey), got {len(arr)}")
            object.__setattr__(self, label, arr)

    # --- matrices -------------------------------------------------------------------------
    @property
    def mass_vector(self) -> np.ndarray:
        """Floor masses bottom to top (relative)."""
        return np.ones(self.storeys) if self.masses is None else np.asarray(self.masses, float)

    @property
    def stiffness_vector(self) -> np.ndarray:
        """Storey stiffnesses bottom to top, scaled so that the first period is :attr:`period`."""
        import scipy.linalg

        k = np.ones(self.storeys) if self.stiffnesses is None else np.asarray(self.stiffnesses, float)
        lam1 = scipy.linalg.eigh(_stiffness_matrix(k), np.diag(self.mass_vector), eigvals_only=True)[0]
        return k * (2.0 * math.pi / self.period) ** 2 / lam1

    def modes(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Circular frequencies (rad/s), mass-normalised mode shapes (columns) and participation
        factors ``Gamma_j = phi_j^T M 1``, from scipy (independent of OpenSees)."""
        import scipy.linalg

        m = self.mass_vector
        lam, phi = scipy.linalg.eigh(_stiffness_matrix(self.stiffness_vector), np.diag(m))
        return np.sqrt(lam), phi, phi.T @ m

    def floor_index(self, floor: int | str | None) -> int:
        """1-based floor number of ``floor`` (``None`` or ``"roof"``: the top floor)."""
        if floor is None or floor == "roof":
            return self.storeys
        if isinstance(floor, bool) or not isinstance(floor, int) or not 1 <= floor <= self.storeys:
            raise InputError(f"floor must be 'roof' or an integer in 1..{self.storeys} for building "
                             f"{self.name!r}, got {floor!r}", argument="floor")
        return floor

    def floor_label(self, floor: int | str | None) -> str:
        """Case-id label of a floor, ``"<name>.f<n>"``."""
        return f"{self.name}.f{self.floor_index(floor)}"


def _stiffness_matrix(k: np.ndarray) -> np.ndarray:
    """Tridiagonal stiffness matrix of a shear building with storey stiffnesses ``k``."""
    n = k.size
    K = np.zeros((n, n))  # noqa: N806
    for i in range(n):
        K[i, i] += k[i]
        if i + 1 < n:
            K[i, i] += k[i + 1]
            K[i, i + 1] = K[i + 1, i] = -k[i + 1]
    return K


def substeps(building: ShearBuilding, dt: float) -> int:
    """Newmark substeps per record sample (dimensionless count): the step is at most
    ``T_N / STEPS_PER_PERIOD`` and ``T_1 / STEPS_PER_FIRST_PERIOD``."""
    omega = building.modes()[0]
    per_sample = max(dt * float(omega[-1]) * STEPS_PER_PERIOD, dt * float(omega[0]) * STEPS_PER_FIRST_PERIOD)
    return max(1, math.ceil(per_sample / (2.0 * math.pi) - 1e-9))


def free_vibration_samples(building: ShearBuilding, dt: float) -> int:
    """Zero samples appended to a ground record of step ``dt`` (s) before filtering (see :data:`FREE_DECAY`)."""
    omega1 = 2.0 * math.pi / building.period
    tail = MAX_FREE_VIBRATION if building.damping == 0.0 else min(
        MAX_FREE_VIBRATION, math.log(1.0 / FREE_DECAY) / (building.damping * omega1))
    return int(math.ceil(tail / dt))


def floor_motion(ground: Record, building: ShearBuilding, floor: int | str | None = None) -> Record:
    """Absolute floor acceleration of ``building`` under the ground motion ``ground`` (OpenSeesPy).

    Parameters
    ----------
    ground : Record
        Ground acceleration (m/s²).
    building : ShearBuilding
        The building.
    floor : int or "roof", optional
        Floor number (1 = first suspended floor) or ``"roof"`` (default).

    Returns
    -------
    Record
        The floor's absolute acceleration (m/s²) at the ground record's sample times, followed by
        the building's free vibration (:func:`free_vibration_samples`), named like the ground
        record, with ``info.floor`` set to ``"<building>.f<n>"``; its vertical motion is the ground's
        (:func:`floor_record`).

    Raises
    ------
    InputError
        A floor the building does not have (``argument`` ``"floor"``).
    AnalysisError
        The building's OpenSees analysis failed.
    """
    return floor_motions(ground, building, [floor])[0]


def floor_record(ground: Record, values: np.ndarray, label: str) -> Record:
    """The floor motion of ``ground`` whose horizontal acceleration is ``values`` (m/s²), at floor ``label``.

    The one place a floor record is made (:func:`floor_motions`, the campaign's cached floor motions): named
    like the ground record, with ``info.floor = label``, and moving vertically with the ground (the ground's
    vertical acceleration, m/s², zero over the free-vibration tail: a shear building has no vertical modes).
    """
    return Record(dt=ground.dt, values=values, name=ground.name, info=replace(ground.info, floor=label),
                  vertical=padded(ground.vertical, len(values)))


def floor_motions(ground: Record, building: ShearBuilding, floors) -> list[Record]:
    """Absolute accelerations (m/s²) of several floors from one analysis; see :func:`floor_motion`."""
    from opsrock.opensees_session import fresh_model

    index = [building.floor_index(f) for f in floors]
    n, m, k = building.storeys, building.mass_vector, building.stiffness_vector
    nsub = substeps(building, ground.dt)
    ag = np.concatenate([ground.values, np.zeros(free_vibration_samples(building, ground.dt))])
    out = np.zeros((len(index), ag.size))
    with fresh_model() as ops:
        ops.model("basic", "-ndm", 1, "-ndf", 1)
        ops.node(0, 0.0)
        ops.fix(0, 1)
        for i in range(1, n + 1):
            ops.node(i, 0.0)
            ops.mass(i, float(m[i - 1]))
            ops.uniaxialMaterial("Elastic", i, float(k[i - 1]))
            ops.element("zeroLength", i, i - 1, i, "-mat", i, "-dir", 1)
        ops.eigen("-fullGenLapack", n)
        ops.modalDamping(building.damping)
        ops.timeSeries("Path", 1, "-dt", ground.dt, "-values", *ag.tolist())
        ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
        # FullGeneral: modal damping makes the damping matrix full (a banded solver drops it and is wrong
        # by 10-66 %); the system is linear with a constant step, so it is factorised once (the same
        # factors every step, the same answer bit for bit, 4-6x faster; 200 storeys finish)
        for cmd in (("constraints", "Plain"), ("numberer", "Plain"), ("system", "FullGeneral"),
                    ("test", "NormDispIncr", 1e-12, 10), ("algorithm", "Linear", "-factorOnce"),
                    ("integrator", "Newmark", 0.5, 0.25), ("analysis", "Transient")):
            getattr(ops, cmd[0])(*cmd[1:])
        h = ground.dt / nsub
        for j in range(1, ag.size):
            if ops.analyze(nsub, h) != 0:
                raise AnalysisError(f"OpenSees failed on the shear building {building.name!r} at t = {j * ground.dt:g} s")
            for r, fl in enumerate(index):
                out[r, j] = ops.nodeAccel(fl, 1) + ag[j]
    out[:, 0] = ag[0]  # at rest at t = 0: the floor moves with the ground
    return [floor_record(ground, out[r], building.floor_label(fl)) for r, fl in enumerate(index)]


def modal_floor_motion(ground: Record, building: ShearBuilding, floor: int | str | None = None) -> np.ndarray:
    """The same floor acceleration (m/s²), free-vibration tail included, by modal superposition in
    scipy (the independent check).

    Each mode ``q_j'' + 2 zeta w_j q_j' + w_j² q_j = -Gamma_j a_g`` is solved by
    ``scipy.signal.lsim`` with linear interpolation of ``a_g`` between samples (exact for the
    piecewise-linear ground motion); ``a_i = a_g + sum_j phi_ij q_j''``.
    """
    import scipy.signal

    fl = building.floor_index(floor) - 1
    w, phi, gamma = building.modes()
    z = building.damping
    ag = np.concatenate([ground.values, np.zeros(free_vibration_samples(building, ground.dt))])
    t = np.arange(ag.size) * ground.dt
    acc = ag.copy()
    for j in range(building.storeys):
        # state [q, q'], output q'' = -w² q - 2 z w q' - Gamma a_g
        a = np.array([[0.0, 1.0], [-w[j] ** 2, -2.0 * z * w[j]]])
        b = np.array([[0.0], [-gamma[j]]])
        c = np.array([[-w[j] ** 2, -2.0 * z * w[j]]])
        d = np.array([[-gamma[j]]])
        _, y, _ = scipy.signal.lsim((a, b, c, d), ag, t, interp=True)
        acc += phi[fl, j] * np.asarray(y).ravel()
    return acc


__all__ = ["MAX_STOREYS", "STEPS_PER_PERIOD", "ShearBuilding", "floor_motion", "floor_motions", "floor_record",
           "modal_floor_motion", "substeps"]
