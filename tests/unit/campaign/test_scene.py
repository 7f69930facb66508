"""Scene and blocks files: the shipped models, and every kind of bad input refused up front."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from opsrock.campaign.scene import MAX_AXIS_POINTS, Scene, SceneError, load_blocks, load_scene
from opsrock.constants import G
from _support import DATA

MODELS = DATA

BLOCKS_TOML = """\
[[block]]
name = "slender"
width = 0.40
height = 2.20
reason = "test"

[[block]]
name = "stocky"
width = 0.50
height = 1.15
"""

SCENE_TOML = """\
name = "t"
blocks = "blocks.toml"
pfv_convention = "amplitude"

[solver]
name = "housner"

[solver.settings]
rtol = 1e-8

[grid.freq_ratio]
start = 0.5
stop = 10.0
num = 4

[grid.pfa_ratio]
values = [1.5, 3.0]
"""


def write_scene(tmp_path: Path, scene: str = SCENE_TOML, blocks: str = BLOCKS_TOML) -> Path:
    (tmp_path / "blocks.toml").write_text(blocks)
    path = tmp_path / "scene.toml"
    path.write_text(scene)
    return path


# --- the shipped models -----------------------------------------------------------------------
def test_shipped_blocks_span_the_design_ranges():
    # docs/guide/modelling.md section 3: alpha about 0.18-0.42 rad, R about 0.6-1.3 m; the values these blocks were chosen to span
    # (alpha = atan(b/h), R = hypot(b, h)) to the 3 decimals they are quoted with.
    specs = {s.name: s.block for s in load_blocks(MODELS / "blocks.toml")}
    assert list(specs) == ["bookcase", "wardrobe", "medicine_cabinet", "equipment_rack"]
    expected = {
        "bookcase": (0.180, 1.118),
        "wardrobe": (0.291, None),
        "medicine_cabinet": (0.410, 0.627),
        "equipment_rack": (0.395, 1.300),
    }
    for name, (alpha, R) in expected.items():
        assert specs[name].alpha == pytest.approx(alpha, abs=5e-4)
        if R is not None:
            assert specs[name].R == pytest.approx(R, abs=5e-4)
    alphas = [b.alpha for b in specs.values()]
    radii = [b.R for b in specs.values()]
    assert 0.17 < min(alphas) and max(alphas) < 0.42
    assert 0.6 < min(radii) and max(radii) < 1.31


def test_paper_scene_is_the_regular_10x10_grid():
    # docs/guide/modelling.md section 3: omega_p/p 0.5..10, PFA/(g tan alpha) 1.0..10.5, ten equal steps of
    # 9.5/9 each; 4 blocks x 100 = 400 cases, of which the 40 at ratio 1.0 cannot uplift.
    scene = load_scene(MODELS / "scenes" / "paper.toml")
    assert scene.solver == "opensees" and scene.pfv_convention == "amplitude"
    assert scene.n_cases == 400 == len(scene.cases())
    for axis, (lo, hi) in {"freq_ratio": (0.5, 10.0), "pfa_ratio": (1.0, 10.5)}.items():
        values = getattr(scene.grid, axis)
        assert len(values) == 10
        steps = [b - a for a, b in zip(values, values[1:])]
        # equal steps to round-off of linspace (a few ulps of 10)
        assert all(s == pytest.approx(9.5 / 9, rel=1e-12) for s in steps)
        assert values[0] == lo and values[-1] == pytest.approx(hi, rel=1e-15)
    at_threshold = [c for c in scene.cases() if c.pfa_ratio == 1.0]
    assert len(at_threshold) == 40
    # Eq. 4: uplift needs PFA > g tan(alpha); at ratio 1.0 the pulse is exactly at the threshold.
    for c in at_threshold:
        assert c.pulse.pfa == pytest.approx(G * c.block.tan_alpha, rel=1e-15)


def test_spectrum_and_tiny_scenes_load():
    spectrum = load_scene(MODELS / "scenes" / "spectrum.toml")
    # the spectrum covers the paper's ranges, more densely than its 10 x 10 grid
    assert len(spectrum.blocks) == 4 and spectrum.grid.size > 100
    assert spectrum.n_cases == 4 * len(spectrum.grid.freq_ratio) * len(spectrum.grid.pfa_ratio)
    assert min(spectrum.grid.freq_ratio) == 0.5 and max(spectrum.grid.pfa_ratio) == pytest.approx(10.5)
    tiny = load_scene(MODELS / "scenes" / "tiny.toml")
    assert [b.name for b in tiny.blocks] == ["bookcase", "medicine_cabinet"]
    assert tiny.n_cases == 18


def test_cases_are_deterministic_and_match_their_ratios(tmp_path):
    scene = load_scene(write_scene(tmp_path))
    cases = scene.cases()
    assert [c.case_id for c in cases] == [c.case_id for c in load_scene(tmp_path / "scene.toml").cases()]
    assert cases[0].case_id == "slender/f01/a01" and cases[-1].case_id == "stocky/f04/a02"
    assert len({c.case_id for c in cases}) == len(cases) == 16
    for c in cases:
        # the pulse realises its ratios: omega_p = freq_ratio p, PFA = pfa_ratio g tan(alpha)
        assert c.pulse.omega_p / c.block.p == pytest.approx(c.freq_ratio, rel=1e-14)
        assert c.pulse.pfa / (G * c.block.tan_alpha) == pytest.approx(c.pfa_ratio, rel=1e-14)


def test_digest_ignores_names_but_not_physics(tmp_path):
    base = load_scene(write_scene(tmp_path))
    renamed = load_scene(write_scene(tmp_path, SCENE_TOML.replace('name = "t"', 'name = "other"')))
    assert renamed.digest() == base.digest()
    for old, new in [("rtol = 1e-8", "rtol = 1e-9"), ("num = 4", "num = 5"), ("amplitude", "peak")]:
        changed = load_scene(write_scene(tmp_path, SCENE_TOML.replace(old, new)))
        assert changed.digest() != base.digest(), (old, new)
    taller = load_scene(write_scene(tmp_path, blocks=BLOCKS_TOML.replace("2.20", "2.21")))
    assert taller.digest() != base.digest()


def test_with_solver_drops_foreign_settings(tmp_path):
    scene = load_scene(write_scene(tmp_path))
    assert scene.with_solver("housner").solver_settings == {"rtol": 1e-8}
    other = scene.with_solver("opensees")
    assert other.solver == "opensees" and other.solver_settings == {}


# --- bad inputs: every error names the file, the field and the value -----------------------------
BAD_SCENES = [
    # (replace old -> new in SCENE_TOML, expected field, expected value text)
    ('name = "t"', 'name = "t"\ncolour = "red"', "colour", "'red'"),
    ('blocks = "blocks.toml"\n', "", "blocks", "<missing>"),
    ('blocks = "blocks.toml"', 'blocks = "nope.toml"', "blocks", "'nope.toml'"),
    ('blocks = "blocks.toml"', "blocks = 3", "blocks", "3"),
    ("amplitude", "maximum", "pfv_convention", "'maximum'"),
    ('name = "housner"', 'name = "abaqus"', "solver.name", "'abaqus'"),
    ("rtol = 1e-8", "rtl = 1e-8", "solver.settings.rtl", "1e-08"),
    ("rtol = 1e-8", "rtol = 2.0", "solver.settings.rtol", "2.0"),
    ("rtol = 1e-8", "rtol = nan", "solver.settings.rtol", "nan"),
    ("num = 4", "num = 0", "grid.freq_ratio.num", "0"),
    ("num = 4", "num = 4.0", "grid.freq_ratio.num", "4.0"),
    ("num = 4", "num = true", "grid.freq_ratio.num", "True"),
    ("num = 4", f"num = {MAX_AXIS_POINTS + 1}", "grid.freq_ratio.num", str(MAX_AXIS_POINTS + 1)),
    ("num = 4", "", "grid.freq_ratio.num", "<missing>"),
    ("start = 0.5", "start = -0.5", "grid.freq_ratio.start", "-0.5"),
    ("start = 0.5", "start = 0.0", "grid.freq_ratio.start", "0.0"),
    ("stop = 10.0", "stop = inf", "grid.freq_ratio.stop", "inf"),
    ("stop = 10.0", "stop = nan", "grid.freq_ratio.stop", "nan"),
    ("stop = 10.0", "stop = 0.4", "grid.freq_ratio.stop", "0.4"),
    ("stop = 10.0", 'stop = "10"', "grid.freq_ratio.stop", "'10'"),
    ("values = [1.5, 3.0]", "values = []", "grid.pfa_ratio.values", "[]"),
    ("values = [1.5, 3.0]", 'values = [1.5, "3"]', "grid.pfa_ratio.values[1]", "'3'"),
    ("values = [1.5, 3.0]", "values = [1.5, -inf]", "grid.pfa_ratio.values[1]", "-inf"),
    ("values = [1.5, 3.0]", "values = [1.5, 1.5]", "grid.pfa_ratio.values", "[1.5, 1.5]"),
    ("values = [1.5, 3.0]", "values = [1.5]\nnum = 3", "grid.pfa_ratio.num", "3"),
    ("values = [1.5, 3.0]", "values = [1e308]", "grid.pfa_ratio", "1e+308"),
    ("[grid.pfa_ratio]\nvalues = [1.5, 3.0]\n", "", "grid.pfa_ratio", "<missing>"),
    ('name = "t"', 'name = "t"\nselect = ["tall"]', "select[0]", "'tall'"),
]


@pytest.mark.parametrize("old, new, field, value", BAD_SCENES)
def test_bad_scene_names_file_field_and_value(tmp_path, old, new, field, value):
    assert old in SCENE_TOML
    path = write_scene(tmp_path, SCENE_TOML.replace(old, new))
    with pytest.raises(SceneError) as info:
        load_scene(path)
    err = info.value
    assert err.field == field
    assert str(err).startswith(f"{path}: {field} = {value}: "), str(err)


BAD_BLOCKS = [
    ("width = 0.40", "width = 0.0", "block[0].width", "0.0"),
    ("width = 0.40", "width = -0.4", "block[0].width", "-0.4"),
    ("width = 0.40", "width = nan", "block[0].width", "nan"),
    ("height = 2.20", "height = inf", "block[0].height", "inf"),
    ("height = 2.20", 'height = "2.2"', "block[0].height", "'2.2'"),
    ("height = 2.20\n", "", "block[0].height", "<missing>"),
    ('name = "stocky"', 'name = "slender"', "block[1].name", "'slender'"),
    ('name = "stocky"', 'name = "a/b"', "block[1].name", "'a/b'"),
    ('reason = "test"', "colour = 1", "block[0].colour", "1"),
    ('reason = "test"', "restitution_factor = 1.5", "block[0]", "{'width': 0.4, 'height': 2.2}"),
    # a mass distribution the block cannot have (Block's own checks; issue 32: a block too stocky for Housner's
    # e_R is now a valid block that lands flat, tests/model/solvers/test_wide_blocks.py)
    ("width = 0.50", "width = 0.50\ncm_height = 2.0", "block[1].cm_height", "2.0"),
    ("width = 0.50", "width = 0.50\nradius_of_gyration = 5.0", "block[1].radius_of_gyration", "5.0"),
    ("width = 0.50", 'width = 0.50\ncm_height = "low"', "block[1].cm_height", "'low'"),
]


@pytest.mark.parametrize("old, new, field, value", BAD_BLOCKS)
def test_bad_blocks_name_file_field_and_value(tmp_path, old, new, field, value):
    assert old in BLOCKS_TOML
    path = write_scene(tmp_path, blocks=BLOCKS_TOML.replace(old, new))
    with pytest.raises(SceneError) as info:
        load_scene(path)
    blocks_file = str((tmp_path / "blocks.toml").resolve())
    assert info.value.field == field
    assert str(info.value).startswith(f"{blocks_file}: {field} = {value}: "), str(info.value)


@pytest.mark.parametrize(
    "content, problem",
    [("name = ", "not valid TOML"), (b"\xff\xfe\x00", "not valid TOML|not UTF-8"), (None, "no such file")],
)
def test_unreadable_scene_file(tmp_path, content, problem):
    path = tmp_path / "scene.toml"
    if isinstance(content, bytes):
        path.write_bytes(content)
    elif content is not None:
        path.write_text(content)
    with pytest.raises(SceneError, match=problem) as info:
        load_scene(path)
    assert info.value.field == "(file)" and str(path) in str(info.value)


def test_scene_error_is_a_value_error():
    # The CLI and callers may catch ValueError; SceneError must stay one.
    assert issubclass(SceneError, ValueError)


def test_scene_is_frozen(tmp_path):
    scene = load_scene(write_scene(tmp_path))
    assert isinstance(scene, Scene)
    with pytest.raises(AttributeError):
        scene.solver = "opensees"  # type: ignore[misc]
    assert all(math.isfinite(v) for v in scene.grid.freq_ratio + scene.grid.pfa_ratio)
