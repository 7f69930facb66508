"""Inputs: Block, OneSinePulse, Record, SDOFModel — derived quantities and input checks."""

from __future__ import annotations

import math

import numpy as np
import pytest

from opsrock import Block, OneSinePulse, Record, SDOFModel
from opsrock.constants import G
from opsrock.model import lever_coefficient, restoring_moment


def test_block_derived_quantities_match_hand_computation():
    # 2b = 0.6, 2h = 2.0: b = 0.3, h = 1.0 -> R = sqrt(1.09), alpha = atan(0.3) (docs/guide/modelling.md s.2)
    b = Block(width=0.6, height=2.0, mass=80.0)
    assert b.R == pytest.approx(math.sqrt(1.09), rel=1e-15)
    assert b.alpha == pytest.approx(math.atan(0.3), rel=1e-15)
    assert b.p == pytest.approx(math.sqrt(3 * 9.81 / (4 * math.sqrt(1.09))), rel=1e-15)
    assert b.I_O == pytest.approx(4 / 3 * 80.0 * 1.09, rel=1e-15)
    # Eq. 9 and the paper's e = 0.95 e_R
    assert b.e_R == pytest.approx(1 - 1.5 * math.sin(math.atan(0.3)) ** 2, rel=1e-15)
    assert b.e == pytest.approx(0.95 * b.e_R, rel=1e-15)
    # Eq. 4: uplift at g tan(alpha) = g b / h
    assert b.uplift_acceleration == pytest.approx(9.81 * 0.3, rel=1e-15)


def test_restitution_factor_is_overridable():
    assert Block(0.6, 2.0, restitution_factor=1.0).e == pytest.approx(Block(0.6, 2.0).e_R)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"width": -0.4, "height": 2.0}, "width"),
        ({"width": 0.4, "height": 0.0}, "height"),
        ({"width": 0.4, "height": float("nan")}, "height"),
        ({"width": float("inf"), "height": 2.0}, "width"),
        ({"width": 0.4, "height": 2.0, "mass": -1.0}, "mass"),
        ({"width": 0.4, "height": 2.0, "restitution_factor": 1.5}, "restitution_factor"),
        ({"width": 0.4, "height": 2.0, "restitution_factor": 0.0}, "restitution_factor"),
    ],
)
def test_bad_block_input_names_the_argument(kwargs, name):
    with pytest.raises(ValueError, match=name):
        Block(**kwargs)


def test_block_refuses_non_numbers_and_takes_wide_blocks():
    with pytest.raises(TypeError, match="width"):
        Block(width="wide", height=2.0)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="height"):
        Block(width=0.4, height=True)  # type: ignore[arg-type]
    # e_R = 1 - 1.5 sin²(alpha) <= 0 for alpha >= asin(sqrt(2/3)) = 0.9553 rad (width/height >= 1.414): a valid
    # block (issue 32) that lands flat, e = 0 (docs/guide/modelling.md, "Wide blocks")
    wide = Block(width=3.0, height=2.0)
    assert wide.e_R == pytest.approx(1 - 1.5 * math.sin(math.atan(1.5)) ** 2, rel=1e-14) and wide.e_R < 0.0
    assert wide.lands_flat and wide.e == 0.0


@pytest.mark.parametrize("kwargs, name", [
    ({"cm_height": 2.5}, "cm_height"), ({"cm_height": 0.0}, "cm_height"), ({"cm_height": math.nan}, "cm_height"),
    ({"cm_height": -0.1}, "cm_height"), ({"radius_of_gyration": 0.0}, "radius_of_gyration"),
    ({"radius_of_gyration": math.inf}, "radius_of_gyration"),
    # all the mass at the far corner from a centre of mass 0.1 m up: r <= hypot(0.25, 1.9) = 1.9164 m
    ({"cm_height": 0.1, "radius_of_gyration": 1.92}, "radius_of_gyration"),
])
def test_impossible_mass_distributions_are_refused(kwargs, name):
    with pytest.raises(ValueError, match=name) as info:
        Block(0.5, 2.0, **kwargs)
    assert info.value.argument == name


def test_mass_distribution_closed_forms():
    """R, alpha, I_O (parallel axes), p = sqrt(m g R / I_O), e_R = 1 - 2 m b² / I_O from their definitions, and
    the uplift acceleration g b / h_cm (round-off only: 1e-15)."""
    b = Block(0.5, 2.0, mass=3.0, cm_height=0.7, radius_of_gyration=0.5)
    R = math.hypot(0.25, 0.7)
    assert not b.homogeneous and b.h_cm == 0.7 and b.r_gyration == 0.5
    assert b.R == pytest.approx(R, rel=1e-15) and b.alpha == pytest.approx(math.atan(0.25 / 0.7), rel=1e-15)
    assert b.I_O == pytest.approx(3.0 * (0.25 + R * R), rel=1e-15)
    assert b.p == pytest.approx(math.sqrt(3.0 * 9.81 * R / b.I_O), rel=1e-15)
    assert b.e_R == pytest.approx(1.0 - 2.0 * 3.0 * 0.0625 / b.I_O, rel=1e-15)
    assert b.uplift_acceleration == pytest.approx(9.81 * 0.25 / 0.7, rel=1e-15)


def test_pulse_from_ratios_round_trips_and_derived_values():
    b = Block(0.4, 2.2)
    pulse = OneSinePulse.from_ratios(b, pfa_ratio=3.0, freq_ratio=2.5)
    assert pulse.pfa_ratio(b) == pytest.approx(3.0, rel=1e-14)
    assert pulse.freq_ratio(b) == pytest.approx(2.5, rel=1e-14)
    assert pulse.T_p == pytest.approx(2 * math.pi / (2.5 * b.p), rel=1e-14)
    # PFV conventions (docs/guide/modelling.md s.2): harmonic amplitude PFA/omega_p, and the true peak 2 PFA/omega_p
    assert pulse.PFV == pytest.approx(pulse.pfa / pulse.omega_p, rel=1e-15)
    assert pulse.pfv("peak") == pytest.approx(2 * pulse.pfa / pulse.omega_p, rel=1e-15)
    with pytest.raises(ValueError, match="convention"):
        pulse.pfv("rms")


def test_pulse_peak_velocity_equals_integral_of_acceleration():
    # The floor velocity from rest peaks at T_p/2 at 2 PFA/omega_p (docs/guide/modelling.md s.2); trapezoid
    # integration on 20001 points is accurate to ~1e-8 relative.
    pulse = OneSinePulse(pfa=3.0, omega_p=7.0)
    t = np.linspace(0.0, pulse.T_p, 20001)
    a = pulse.acceleration(t)
    v = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * np.diff(t))])
    assert v.max() == pytest.approx(pulse.pfv("peak"), rel=1e-6)
    assert abs(v[-1]) < 1e-6  # a full sine cycle returns the floor velocity to zero


def test_pulse_acceleration_is_zero_outside_pulse():
    pulse = OneSinePulse(pfa=2.0, omega_p=3.0)
    assert pulse.acceleration(-0.1) == 0.0
    assert pulse.acceleration(pulse.T_p + 1e-9) == 0.0
    assert pulse.acceleration(pulse.T_p / 4) == pytest.approx(2.0, rel=1e-14)
    assert pulse.acceleration(0.5 * pulse.T_p / 2) > 0  # positive first half (tips to negative theta)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [({"pfa": 0.0, "omega_p": 1.0}, "pfa"), ({"pfa": 1.0, "omega_p": -2.0}, "omega_p"),
     ({"pfa": float("nan"), "omega_p": 1.0}, "pfa")],
)
def test_bad_pulse_input_names_the_argument(kwargs, name):
    with pytest.raises(ValueError, match=name):
        OneSinePulse(**kwargs)


def test_pulse_ratio_constructor_checks_ratios():
    with pytest.raises(ValueError, match="pfa_ratio"):
        OneSinePulse.from_ratios(Block(0.4, 2.0), pfa_ratio=-1, freq_ratio=2)
    with pytest.raises(ValueError, match="freq_ratio"):
        OneSinePulse.from_ratios(Block(0.4, 2.0), pfa_ratio=2, freq_ratio=0)


def test_record_interpolates_and_is_immutable():
    rec = Record(dt=0.01, values=[0.0, 1.0, -1.0, 0.5])
    assert rec.duration == pytest.approx(0.03)
    assert rec.pfa == 1.0
    assert rec.acceleration(0.005) == pytest.approx(0.5)
    assert rec.acceleration(1.0) == 0.0
    with pytest.raises(ValueError):
        rec.values[0] = 3.0
    with pytest.raises(ValueError, match="values"):
        Record(dt=0.01, values=[0.0, float("nan")])
    with pytest.raises(ValueError, match="dt"):
        Record(dt=0.0, values=[0.0, 1.0])


def test_spring_table_follows_sine_law_and_has_stiff_branch():
    block = Block(0.5, 1.15, mass=10.0)
    model = SDOFModel(table_points=30)
    theta, moment = model.spring_table(block)
    assert np.all(np.diff(theta) > 0)
    # tabulated points lie exactly on Eq. 5
    assert np.allclose(moment, restoring_moment(block, theta), rtol=0, atol=1e-12)
    # the table reaches past pi/2 + alpha so an overturning block never runs off it (docs/guide/modelling.md s.4)
    assert theta[-1] > math.pi / 2 + block.alpha and theta[0] < -(math.pi / 2 + block.alpha)
    # between tabulated points the chord error of a sine is <= spacing²/8 · m g R (second derivative <= 1)
    fine = np.linspace(model.theta_e(block), theta[-1], 20001)
    chord = np.interp(fine, theta, moment)
    spacing = np.diff(theta[theta > 0]).max()
    bound = spacing**2 / 8 * block.mass * 9.81 * block.R
    assert np.max(np.abs(chord - restoring_moment(block, fine))) <= bound * (1 + 1e-9)


def test_lever_options():
    block = Block(0.4, 2.0, mass=3.0)
    # housner: m R cos(alpha) (Figure 2b lumped mass); printed: I_O cos(alpha)/R = 4/3 of it (Eq. 6)
    assert lever_coefficient(block, "housner") == pytest.approx(3.0 * block.R * math.cos(block.alpha))
    assert lever_coefficient(block, "printed") / lever_coefficient(block, "housner") == pytest.approx(4 / 3)
    # with the housner lever, the excitation moment equals the peak restoring moment exactly at g tan(alpha)
    assert lever_coefficient(block) * block.uplift_acceleration == pytest.approx(block.mass * G * block.R * math.sin(block.alpha))
    with pytest.raises(ValueError, match="lever"):
        SDOFModel(lever="other")


def test_damping_coefficient_gives_velocity_ratio_e_across_band():
    # Eq. 8: I_O dv/dtheta = -c_D over a band of width 2 delta alpha -> v2 = v1 - (1-e)|v1| = e v1
    block = Block(0.6, 2.0)
    model = SDOFModel(delta=0.01)
    v1 = 1.7
    c = model.damping_coefficient(block, v1)
    v2 = v1 - c * 2 * model.band(block) / block.I_O
    assert v2 / v1 == pytest.approx(block.e, rel=1e-14)


@pytest.mark.parametrize(("kwargs", "name"), [({"delta": 0.0}, "delta"), ({"delta": 1.2}, "delta"),
                                               ({"theta_e_ratio": 0.5}, "theta_e_ratio"),
                                               ({"table_points": 2}, "table_points")])
def test_bad_model_settings_name_the_argument(kwargs, name):
    with pytest.raises(ValueError, match=name):
        SDOFModel(**kwargs)
