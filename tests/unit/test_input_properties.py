"""Property tests (hypothesis): no input crashes the input classes or the scene loader with
anything but their documented errors, and no accepted input yields NaN in a derived quantity.

Documented errors: ``Block``, ``OneSinePulse``, ``SDOFModel`` raise ``ValueError`` or
``TypeError`` naming the argument; ``load_scene`` raises ``SceneError`` (a ``ValueError``).
"""

from __future__ import annotations

import json
import math
import os

import numpy as np
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from opsrock.block import Block
from opsrock.campaign.scene import SceneError, load_scene
from opsrock.excitations import OneSinePulse
from opsrock.model import LEVERS, SDOFModel
from _support import BLOCKS

# Anything a caller might pass: numbers of every size and sign, NaN, infinities, bools,
# strings, None, containers.
anything = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(min_value=-(10**30), max_value=10**30),
    st.booleans(),
    st.none(),
    st.text(max_size=5),
    st.lists(st.floats(), max_size=2),
    st.decimals(allow_nan=True, allow_infinity=True),
    st.fractions(),
)
number = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-(10**6), 10**6))

#: ``make test-fuzz`` (profile ``fuzz``) explores ten times the examples of ``make test``.
SCALE = 10 if os.environ.get("HYPOTHESIS_PROFILE") == "fuzz" else 1

BLOCK_PROPERTIES = ("b", "h", "R", "alpha", "tan_alpha", "p", "I_O", "e_R", "e", "uplift_acceleration",
                    "overturning_rotation_moment")  # fmt: skip


def _no_nan(values) -> bool:
    return not any(isinstance(v, float) and math.isnan(v) for v in values)


@settings(max_examples=100 * SCALE, deadline=None)
@given(width=st.one_of(number, anything), height=st.one_of(number, anything), mass=number, factor=number)
def test_block_accepts_or_raises_documented_errors(width, height, mass, factor):
    try:
        block = Block(width=width, height=height, mass=mass, restitution_factor=factor)
    except (ValueError, TypeError):
        return
    derived = [getattr(block, name) for name in BLOCK_PROPERTIES]
    assert _no_nan(derived), dict(zip(BLOCK_PROPERTIES, derived))
    # accepted blocks satisfy the model's own premises: a slender block rebounds with 0 < e <= e_R <= 1 (Eq. 9);
    # one too wide for Housner's law (alpha >= atan(sqrt(2)) = 0.9553 rad, e_R <= 0) lands flat with e = 0
    if block.lands_flat:
        assert block.alpha >= 0.9553 and block.e_R <= 0.0 and block.e == 0.0
    else:
        assert 0.0 <= block.alpha < 0.9553 and 0.0 < block.e <= block.e_R <= 1.0


@settings(max_examples=100 * SCALE, deadline=None)
@given(pfa=st.one_of(number, anything), omega_p=st.one_of(number, anything), t=st.floats(-1e3, 1e3))
# found by hypothesis on a fresh machine: omega_p * t overflowed outside the pulse
@example(pfa=1.0, omega_p=3.6e307, t=5.0)
def test_pulse_accepts_or_raises_documented_errors(pfa, omega_p, t):
    try:
        pulse = OneSinePulse(pfa=pfa, omega_p=omega_p)
    except (ValueError, TypeError):
        return
    values = [pulse.T_p, pulse.duration, pulse.pfv("amplitude"), pulse.pfv("peak"), pulse.frequency_hz,
              float(pulse.acceleration(t)), *pulse.breakpoints()]  # fmt: skip
    assert _no_nan(values), values
    # |a(t)| never exceeds PFA (a one-sine pulse)
    assert abs(float(pulse.acceleration(t))) <= pulse.pfa


@settings(max_examples=100 * SCALE, deadline=None)
@given(
    block_w=st.floats(1e-3, 1e3),
    aspect=st.floats(0.05, 1.4),
    pfa_ratio=st.one_of(number, anything),
    freq_ratio=st.one_of(number, anything),
)
def test_pulse_from_ratios_accepts_or_raises_documented_errors(block_w, aspect, pfa_ratio, freq_ratio):
    try:
        block = Block(width=block_w, height=block_w / aspect)
        pulse = OneSinePulse.from_ratios(block, pfa_ratio=pfa_ratio, freq_ratio=freq_ratio)
    except (ValueError, TypeError):
        return
    assert _no_nan([pulse.pfa, pulse.omega_p, pulse.T_p, pulse.pfa_ratio(block), pulse.freq_ratio(block)])


@settings(max_examples=100 * SCALE, deadline=None)
@given(
    delta=st.one_of(number, anything),
    theta_e_ratio=st.one_of(number, anything),
    table_points=st.one_of(st.integers(-5, 200), anything),
    lever=st.one_of(st.sampled_from(LEVERS), anything),
)
def test_sdof_model_accepts_or_raises_documented_errors(delta, theta_e_ratio, table_points, lever):
    try:
        model = SDOFModel(delta=delta, theta_e_ratio=theta_e_ratio, table_points=table_points, lever=lever)
    except (ValueError, TypeError):
        return
    block = Block(width=0.4, height=2.2)
    theta, moment = model.spring_table(block)
    values = [model.theta_e(block), model.band(block), model.lever_arm(block), model.damping_coefficient(block, 1.0)]
    assert _no_nan(values) and not np.isnan(theta).any() and not np.isnan(moment).any()
    assert np.all(np.diff(theta) > 0)  # ElasticMultiLinear needs strictly increasing strains


# --- scene files ------------------------------------------------------------------------------

VALID = {
    "name": "p",
    "blocks": str(BLOCKS),
    "pfv_convention": "amplitude",
    "solver": {"name": "housner", "settings": {"rtol": 1e-8}},
    "grid": {"freq_ratio": {"start": 0.5, "stop": 10.0, "num": 3}, "pfa_ratio": {"values": [1.0, 2.0]}},
}

# Dotted paths a mutation may replace (or delete) in the valid scene.
PATHS = ["name", "blocks", "pfv_convention", "solver", "solver.name", "solver.settings", "solver.settings.rtol",
         "grid", "grid.freq_ratio", "grid.freq_ratio.start", "grid.freq_ratio.stop", "grid.freq_ratio.num",
         "grid.pfa_ratio", "grid.pfa_ratio.values", "select", "extra"]  # fmt: skip

toml_scalar = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(-(2**63), 2**63 - 1),
    st.booleans(),
    st.text(max_size=8),
    st.sampled_from(["housner", "opensees", "peak", "bookcase", "sdof"]),
)
toml_value = st.recursive(
    toml_scalar,
    lambda inner: st.one_of(st.lists(inner, max_size=4), st.dictionaries(st.sampled_from("abc"), inner, max_size=2)),
    max_leaves=6,
)


def toml_literal(value) -> str:
    """A value as TOML (inline tables and arrays; strings as JSON, which TOML basic strings accept)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf") if math.isinf(value) else repr(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(toml_literal(v) for v in value) + "]"
    return "{" + ", ".join(f"{json.dumps(k)} = {toml_literal(v)}" for k, v in value.items()) + "}"


def to_toml(doc: dict) -> str:
    return "\n".join(f"{json.dumps(k)} = {toml_literal(v)}" for k, v in doc.items()) + "\n"


def mutate(doc: dict, path: str, value, delete: bool) -> dict:
    doc = json.loads(json.dumps(doc))
    *parents, last = path.split(".")
    node = doc
    for key in parents:
        if not isinstance(node.get(key), dict):
            node[key] = {}
        node = node[key]
    if delete:
        node.pop(last, None)
    else:
        node[last] = value
    return doc


@settings(max_examples=60 * SCALE, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(path=st.sampled_from(PATHS), value=toml_value, delete=st.booleans())
def test_scene_loader_accepts_or_raises_scene_error(tmp_path, path, value, delete):
    scene_file = tmp_path / "scene.toml"
    scene_file.write_text(to_toml(mutate(VALID, path, value, delete)))
    try:
        scene = load_scene(scene_file)
    except SceneError as err:
        assert str(err).startswith(f"{scene_file}: ") or str(err).startswith(str(BLOCKS))
        return
    cases = scene.cases()
    assert len(cases) == scene.n_cases > 0
    for c in cases:
        assert _no_nan([c.pulse.pfa, c.pulse.omega_p, c.freq_ratio, c.pfa_ratio])
        assert math.isfinite(c.pulse.pfa) and math.isfinite(c.pulse.omega_p)


@settings(max_examples=50 * SCALE, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(content=st.binary(max_size=200))
def test_scene_loader_survives_arbitrary_bytes(tmp_path, content):
    scene_file = tmp_path / "scene.toml"
    scene_file.write_bytes(content)
    try:
        load_scene(scene_file)
    except SceneError:
        pass
