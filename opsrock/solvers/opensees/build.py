"""The OpenSees models: the rotational SDOF model of Eq. 5-8 and the lumped-mass form of Figure 2b.

Everything here runs inside :func:`opsrock.opensees_session.fresh_model` (the one owner of OpenSees
state). The spring is ``ElasticMultiLinear`` with the model's table (path-independent, negative
slopes); the damper ``Viscous`` with its coefficient as an OpenSees parameter (``DAMPER_PARAM``),
changed by ``updateParameter``; the floor acceleration a time series exact for every pulse shape
(``Trig``, ``Rectangular``) and linear between a record's samples (``Path``).
"""

from __future__ import annotations

import math

import numpy as np

from opsrock.block import Block
from opsrock.excitations import Excitation, HarmonicPulse, Record, RectangularPulse
from opsrock.opensees_session import ops
from opsrock.solvers.opensees.settings import OpenSeesSettings

#: OpenSees tags of the model's materials, elements, damper parameter, time series and load pattern.
SPRING_MAT, DAMPER_MAT = 1, 2
SPRING_ELE, DAMPER_ELE = 1, 2
DAMPER_PARAM = 1
SERIES, PATTERN = 1, 1


def define_time_series(excitation: Excitation, step: float) -> None:
    """Define time series ``SERIES`` giving the floor acceleration ``a(t)`` (m/s^2)."""
    if isinstance(excitation, HarmonicPulse):
        # Trig: factor * sin(2 pi (t - tStart) / period + shift) on [tStart, tEnd], zero outside:
        # exact for the half-sine, one-sine and one-cosine pulses.
        ops.timeSeries("Trig", SERIES, 0.0, excitation.duration, excitation.T_p, "-factor", excitation.pfa,
                       "-shift", excitation.PHASE)
    elif isinstance(excitation, RectangularPulse):
        # Rectangular: factor on [tStart, tEnd], zero outside: exact.
        ops.timeSeries("Rectangular", SERIES, 0.0, excitation.duration, "-factor", excitation.pfa)
    elif isinstance(excitation, Record):
        # Path with constant dt interpolates linearly and is zero after the last sample.
        ops.timeSeries("Path", SERIES, "-dt", excitation.dt, "-values", *map(float, excitation.values))
    else:
        t = np.union1d(np.arange(0.0, excitation.duration + step, step), excitation.breakpoints())
        t = t[t <= excitation.duration]
        a = excitation.acceleration(t)
        t = np.append(t, excitation.duration + step)
        a = np.append(a, 0.0)
        ops.timeSeries("Path", SERIES, "-time", *map(float, t), "-values", *map(float, a))

def define_analysis(settings: OpenSeesSettings, algorithm: str, constraints: str = "Plain") -> None:
    ops.constraints(constraints)
    ops.numberer("Plain")
    # BandGeneral: a general (non-symmetric-positive) solver; the spring's tangent is negative
    # beyond the stiff branch, so SPD solvers are wrong here.
    ops.system("BandGeneral")
    ops.test("NormDispIncr", settings.tol, settings.max_iter)
    _set_integrator(settings)
    set_algorithm(settings, algorithm)
    ops.analysis("Transient")

def _set_integrator(settings: OpenSeesSettings) -> None:
    rho = float(settings.rho_inf)
    if settings.integrator == "newmark":
        ops.integrator("Newmark", 0.5, 0.25)
    elif settings.integrator == "hht":
        # OpenSees HHT alpha in [2/3, 1] (1 = Newmark); rho_inf = alpha / (2 - alpha).
        ops.integrator("HHT", 2.0 * rho / (1.0 + rho))
    elif settings.integrator == "generalized_alpha":
        # Chung & Hulbert (1993): alpha_m = (2 - rho) / (1 + rho), alpha_f = 1 / (1 + rho) in
        # OpenSees' convention (alpha = 1 means no shift).
        ops.integrator("GeneralizedAlpha", (2.0 - rho) / (1.0 + rho), 1.0 / (1.0 + rho))
    else:
        ops.integrator("CentralDifference")

def set_algorithm(settings: OpenSeesSettings, algorithm: str) -> None:
    if settings.integrator == "central_difference":
        ops.algorithm("Linear")  # explicit: one solve with the mass matrix per step
    elif algorithm == "NewtonLineSearch":
        ops.algorithm("NewtonLineSearch")
    else:
        ops.algorithm(algorithm)

def build_sdof(block: Block, excitation: Excitation, settings: OpenSeesSettings) -> None:
    model = settings.model
    theta_tab, moment_tab = model.spring_table(block)
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(1, 0.0)
    ops.node(2, 0.0)
    ops.fix(1, 1)
    ops.mass(2, block.I_O)
    ops.uniaxialMaterial(
        "ElasticMultiLinear", SPRING_MAT, 0.0, "-strain", *map(float, theta_tab), "-stress", *map(float, moment_tab)
    )
    ops.uniaxialMaterial("Viscous", DAMPER_MAT, 1.0, 1.0)
    ops.element("zeroLength", SPRING_ELE, 1, 2, "-mat", SPRING_MAT, "-dir", 1)
    ops.element("zeroLength", DAMPER_ELE, 1, 2, "-mat", DAMPER_MAT, "-dir", 1)
    ops.parameter(DAMPER_PARAM, "element", DAMPER_ELE, "C")
    ops.updateParameter(DAMPER_PARAM, 0.0)
    define_time_series(excitation, settings.step)
    ops.pattern("Plain", PATTERN, SERIES)
    ops.load(2, -model.lever_arm(block))

def build_lumped(block: Block, excitation: Excitation, settings: OpenSeesSettings, geometry: str) -> None:
    model = settings.model
    theta_tab, moment_tab = model.spring_table(block)
    m, R = block.mass, block.R
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 0.0)  # pivot: translations fixed, rotation free
    ops.node(3, 0.0, R)  # centre of mass
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 1, 1, 0)
    # rotational mass about the centre of mass: m r² (m R² / 3 for a homogeneous block), so that I_O = m (r² + R²)
    ops.mass(3, m, m, m * R**2 / 3.0 if block.homogeneous else m * block.r_gyration**2)
    ops.uniaxialMaterial(
        "ElasticMultiLinear", SPRING_MAT, 0.0, "-strain", *map(float, theta_tab), "-stress", *map(float, moment_tab)
    )
    ops.uniaxialMaterial("Viscous", DAMPER_MAT, 1.0, 1.0)
    ops.element("zeroLength", SPRING_ELE, 1, 2, "-mat", SPRING_MAT, "-dir", 6)
    ops.element("zeroLength", DAMPER_ELE, 1, 2, "-mat", DAMPER_MAT, "-dir", 6)
    ops.parameter(DAMPER_PARAM, "element", DAMPER_ELE, "C")
    ops.updateParameter(DAMPER_PARAM, 0.0)
    ops.rigidLink("beam", 2, 3)
    define_time_series(excitation, settings.step)
    ops.pattern("Plain", PATTERN, SERIES)
    ops.load(3, m * math.cos(block.alpha), 0.0, 0.0)

def set_initial_state(block: Block, excitation: Excitation, settings: OpenSeesSettings, node: int, dof: int) -> None:
    th0, v0 = float(settings.theta0), float(settings.theta_dot0)
    if th0 == 0.0 and v0 == 0.0:
        return
    ops.setNodeDisp(node, dof, th0, "-commit")
    ops.setNodeVel(node, dof, v0, "-commit")
    # Consistent initial acceleration: I_O theta'' = -M_s(theta0) - Lambda a(0).
    th_tab, m_tab = settings.model.spring_table(block)
    m_s = float(np.interp(th0, th_tab, m_tab))
    a0 = float(excitation.acceleration(0.0))
    ops.setNodeAccel(node, dof, (-m_s - settings.model.lever_arm(block) * a0) / block.I_O, "-commit")


__all__ = ["DAMPER_ELE", "DAMPER_PARAM", "SPRING_ELE", "build_lumped", "build_sdof", "define_analysis",
           "define_time_series", "set_algorithm", "set_initial_state"]
