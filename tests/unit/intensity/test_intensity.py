"""The nine intensity measures of the paper's Table 1."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from opsrock import Block, OneSinePulse
from opsrock.intensity import (
    IM_NAMES,
    IMS,
    add_intensity_measures,
    get_im,
    intensity_measures,
    intensity_measures_array,
)

# Hand computation for one block and one pulse (g = 9.81 m/s², docs/guide/modelling.md section 2):
# block 0.4 m x 1.6 m: b = 0.2, h = 0.8, tan(alpha) = 0.25,
#   R = sqrt(0.04 + 0.64) = 0.824621 m, p = sqrt(3 * 9.81 / (4 * 0.824621)) = 2.987018 rad/s,
#   sin²(alpha) = 0.0625 / 1.0625 = 0.0588235, e_R = 1 - 1.5 * 0.0588235 = 0.9117647;
# pulse PFA = 0.5 g = 4.905 m/s², omega_p = 2 pi rad/s (1 Hz, T_p = 1 s), PFV = PFA / omega_p:
#   IM1 = 6.283185 / 2.987018 = 2.103497
#   IM2 = 4.905 / (9.81 * 0.25) = 2 exactly
#   IM3 = 2.987018 * 0.780655 / 2.4525 = 0.950798
#   IM4 = 1.484 * 2^1.644 * 2.103497^-2.013 = 1.038114
#   IM5 = 0.063 * 2^2.954 * 2.103497^-0.942 = 0.242310
#   IM6 = 2^0.52 * 2.103497^-0.48 = 1.003514
#   IM7 = 2^0.6 * 2.103497^-0.4 = 1.125748
#   IM8 = 0.9117647^4 * 0.950798 = 0.657081
#   IM9 = 4.905 * 1^2 / (0.824621 * 0.25) = 23.792745
# (evaluated with a pocket calculator's worth of plain Python floats, 6-7 digits kept;
# the tolerance 1e-6 relative covers that rounding and nothing else).
HAND = {
    "IM1": 2.1034973, "IM2": 2.0, "IM3": 0.9507975, "IM4": 1.0381140, "IM5": 0.2423103,
    "IM6": 1.0035140, "IM7": 1.1257481, "IM8": 0.6570814, "IM9": 23.792745,
}


@pytest.fixture()
def block_and_pulse():
    return Block(width=0.4, height=1.6), OneSinePulse(pfa=0.5 * 9.81, omega_p=2 * math.pi)


def test_metadata_declares_nine_ims_once():
    assert IM_NAMES == tuple(f"IM{i}" for i in range(1, 10))
    assert [im.name for im in IMS] == list(IM_NAMES)
    # IM1 (frequency ratio) is the only IM under which overturning falls as it grows
    # (paper Section 4.3, Table 2: overturned cases at low omega_p/p).
    assert [im.name for im in IMS if im.decreasing] == ["IM1"]
    assert {im.name for im in IMS if im.depends_on_pfv} == {"IM3", "IM8"}
    assert get_im("IM9").meaning == "Dimensionless floor displacement"
    with pytest.raises(ValueError, match="IM10"):
        get_im("IM10")


@pytest.mark.parametrize("name", IM_NAMES)
def test_formulas_against_hand_values(block_and_pulse, name):
    block, pulse = block_and_pulse
    ims = intensity_measures(block, pulse)
    assert ims[name] == pytest.approx(HAND[name], rel=1e-6)


def test_peak_convention_doubles_only_the_velocity_ims(block_and_pulse):
    # PFV "peak" = 2 PFA / omega_p (velocity of a one-sine pulse at T_p/2): IM3 and IM8 are
    # linear in PFV, the others do not contain it. Exact up to rounding (1e-12).
    block, pulse = block_and_pulse
    amp = intensity_measures(block, pulse, "amplitude")
    peak = intensity_measures(block, pulse, "peak")
    for name in IM_NAMES:
        factor = 2.0 if name in ("IM3", "IM8") else 1.0
        assert peak[name] == pytest.approx(factor * amp[name], rel=1e-12)
    with pytest.raises(ValueError, match="pfv_convention"):
        intensity_measures(block, pulse, "rms")


def test_identities_for_one_sine_pulses():
    # For any block and pulse: IM3 = IM2 / IM1 (PFV = PFA/omega_p), IM8 = e_R^4 IM3, and
    # IM9 = PFA (2 pi / omega_p)² / (R tan a) = 4 pi² IM2 g / (R p² IM1²) = (16 pi²/3) IM2 / IM1²
    # since p² = 3 g / (4 R). Closed forms, exact up to rounding (1e-12).
    rng = np.random.default_rng(1)
    width = rng.uniform(0.2, 1.0, 50)
    height = rng.uniform(1.0, 3.0, 50)
    blocks = [Block(w, h) for w, h in zip(width, height)]
    pfa = rng.uniform(0.5, 20.0, 50)
    omega = rng.uniform(1.0, 60.0, 50)
    ims = intensity_measures_array(
        [b.alpha for b in blocks], [b.R for b in blocks], [b.p for b in blocks],
        [b.e_R for b in blocks], pfa, omega,
    )
    e_r = np.array([b.e_R for b in blocks])
    np.testing.assert_allclose(ims["IM3"], ims["IM2"] / ims["IM1"], rtol=1e-12)
    np.testing.assert_allclose(ims["IM8"], e_r**4 * ims["IM3"], rtol=1e-12)
    np.testing.assert_allclose(ims["IM9"], 16 * math.pi**2 / 3 * ims["IM2"] / ims["IM1"] ** 2,
                               rtol=1e-12)
    # the scalar path agrees with the vectorised one
    one = intensity_measures(blocks[7], OneSinePulse(pfa[7], omega[7]))
    for name in IM_NAMES:
        assert one[name] == pytest.approx(ims[name][7], rel=1e-14)


def test_im1_orientation_faster_pulse_lowers_im1_dependent_ims(block_and_pulse):
    # Raising omega_p at fixed PFA raises IM1 and lowers every IM with a negative IM1
    # exponent (IM3-IM9): the direction in which overturning becomes harder. IM2 is unchanged.
    block, _ = block_and_pulse
    slow = intensity_measures(block, OneSinePulse(5.0, 5.0))
    fast = intensity_measures(block, OneSinePulse(5.0, 10.0))
    assert fast["IM1"] == pytest.approx(2 * slow["IM1"])
    assert fast["IM2"] == pytest.approx(slow["IM2"])
    for name in IM_NAMES[2:]:
        assert fast[name] < slow[name]


def test_array_input_checks_name_the_argument():
    with pytest.raises(ValueError, match="pfa"):
        intensity_measures_array(0.2, 1.0, 3.0, 0.9, [1.0, -1.0], 5.0)
    with pytest.raises(ValueError, match="alpha"):
        intensity_measures_array(2.0, 1.0, 3.0, 0.9, 1.0, 5.0)
    with pytest.raises(ValueError, match="omega_p"):
        intensity_measures_array(0.2, 1.0, 3.0, 0.9, 1.0, np.nan)


def test_add_intensity_measures_to_a_cases_table(block_and_pulse):
    block, pulse = block_and_pulse
    df = pd.DataFrame([{**block.describe(), "pfa": pulse.pfa, "omega_p": pulse.omega_p}])
    out = add_intensity_measures(df)
    for name in IM_NAMES:
        assert out[name].iloc[0] == pytest.approx(HAND[name], rel=1e-6)
    assert "IM1" not in df.columns  # a copy, the input is untouched
    with pytest.raises(KeyError, match="omega_p"):
        add_intensity_measures(df.drop(columns="omega_p"))
