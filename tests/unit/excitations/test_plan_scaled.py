"""PlanMotion.scaled: both horizontal components times the factor, the vertical floor motion unchanged (the copy
the amplitude test of opsrock.analysis.sensitivity scales)."""

import numpy as np

from opsrock.constants import G
from opsrock.excitations import OneSinePulse, Record
from opsrock.excitations.plan import PlanMotion


def test_scaled_pulse_pair_keeps_the_vertical_and_the_azimuth():
    first = OneSinePulse(0.5 * G, 6.0, vertical=-0.2 * G)
    second = OneSinePulse(0.3 * G, 9.0)
    m = PlanMotion(first, second, 30.0)
    s = m.scaled(1.01)
    t = np.linspace(0.0, 1.0, 101)
    # components are linear in the two accelerations: exactly 1.01 x, to round-off
    for a, b in zip(s.components(t), m.components(t)):
        np.testing.assert_allclose(a, 1.01 * b, rtol=1e-13, atol=1e-13)
    assert s.vertical == m.vertical == -0.2 * G
    assert s.azimuth == 30.0


def test_scaled_record_keeps_its_vertical_samples():
    values = 2.0 * np.sin(np.linspace(0.0, 6.0, 200))
    vertical = 0.6 * np.cos(np.linspace(0.0, 6.0, 200))
    rec = Record(0.01, values, name="synthetic", vertical=vertical)
    s = PlanMotion(rec, rec.with_vertical(None), -45.0).scaled(0.99)
    np.testing.assert_array_equal(s.vertical, vertical)
    np.testing.assert_allclose(s.first.values, 0.99 * values, rtol=1e-15)
    np.testing.assert_allclose(s.second.values, 0.99 * values, rtol=1e-15)
