"""Blocks wider than Housner's rocking model allows (width/height >= sqrt(2) for a homogeneous block, e_R <= 0):
valid blocks that land flat after an impact (e = 0) and, with friction mu < tan(alpha), can only slide
(docs/guide/modelling.md, "Wide blocks")."""

from __future__ import annotations

import dataclasses
import math

import pytest

from opsrock import Block, OneSinePulse
from opsrock.constants import G
from opsrock.errors import ModelNotSupported
from opsrock.excitations.pulses import RectangularPulse
from opsrock.published import newmark_1965 as nm
from opsrock.restitution import RestitutionDistribution
from opsrock.solvers import friction, simulate
from opsrock.solvers.registry import solver_names
from opsrock.validation.sdof_records import noise_record

DESK = Block(2.0, 1.0, name="desk")  # tan(alpha) = 2, e_R = 1 - 1.5 sin²(alpha) = -0.2


def test_a_wide_block_is_valid_and_lands_flat():
    assert DESK.e_R == pytest.approx(1.0 - 1.5 * 0.8, rel=1e-14)  # sin²(atan 2) = 4/5
    assert DESK.lands_flat and DESK.e == 0.0
    # the factor cannot give a rebound the angular momentum does not allow
    assert Block(2.0, 1.0, restitution_factor=1.0).e == 0.0
    # the boundary: sin²(alpha) = 2/3 exactly at width/height = sqrt(2)
    assert Block(math.sqrt(2.0) * 1.001, 1.0).lands_flat and not Block(math.sqrt(2.0) * 0.999, 1.0).lands_flat
    # a restitution given explicitly is the user's model and is kept (its solvers use it)
    assert Block(1.6, 1.0, restitution=0.5).e == 0.5


def test_a_restitution_distribution_leaves_a_wide_block_flat():
    dist = RestitutionDistribution(mean=0.95, std=0.05, low=0.8, high=1.1, seed=1)
    factor = dist.sample("desk/r1", DESK.e_R)
    assert factor == 0.95 and dataclasses.replace(DESK, restitution_factor=factor).e == 0.0


@pytest.mark.parametrize("solver", ["friction", "moreau_jean"])
@pytest.mark.parametrize("a_g, t1", [(3.0, 0.2), (0.8, 0.5)])
def test_wide_block_with_low_friction_only_slides_as_newmark(solver, a_g, t1):
    """mu = 0.5 < tan(alpha) = 2: the floor can push the base with at most mu m g, whose moment about the centre
    of mass, mu m g h, stays below the weight's m g b: the block never uplifts, even under 3 g (1.5 times its
    no-slip uplift threshold g tan(alpha) = 2 g), and slides as Newmark's rigid block: slide = (a_p - mu g) t1² a_p / (2 mu g)
    for a rectangular pulse (opsrock.published.newmark_1965). Tolerances: the friction solver integrates the
    slide in closed-form segments (measured 3e-15: 1e-12); Moreau-Jean's steps (measured 7e-13 and 1e-9: 1e-8)."""
    block = dataclasses.replace(DESK, friction=0.5, **({"restitution_factor": 1.0} if solver == "moreau_jean" else {}))
    r = simulate(block, RectangularPulse.from_duration(a_g * G, t1), solver=solver)
    assert r.ok and not r.rocked and r.theta_max < 1e-15
    assert r.contact.first_mode == "slide"
    ref = nm.rectangular_slide(a_g * G, t1, 0.5)
    assert -r.contact.slide_residual == pytest.approx(ref, rel=1e-12 if solver == "friction" else 1e-8)


def test_wide_block_with_low_friction_never_uplifts_under_a_record():
    """The same condition under a broadband record (synthetic noise scaled to 2 g, four times mu g): slides, never
    rocks."""
    rec = noise_record(seed=3).scaled_to_pfa(2.0 * G)
    r = friction.solve(dataclasses.replace(DESK, friction=0.5), rec)
    assert r.ok and not r.rocked and r.theta_max == 0.0 and r.contact.slide_max > 0.0


def test_wide_block_without_slip_lands_flat():
    """No slip (friction None): a pulse above g tan(alpha) rocks the desk; each impact stops the rotation (e = 0)
    so it rests until the floor lifts it again. The event-driven solver logs theta' = 0 after every impact; the
    compiled one agrees on theta_max to 1e-8 (their agreement on rocking blocks; measured 4e-9 and 2e-10), and
    Moreau-Jean, whose e_n = 0 corner impulses land the block flat by themselves, to 2e-3 (its first-order steps;
    measured 1.0e-3 and 6.6e-4)."""
    block = Block(1.5, 1.0)  # e_R = -0.038
    for freq_ratio in (2.0, 4.0):
        pulse = OneSinePulse.from_ratios(block, pfa_ratio=1.3, freq_ratio=freq_ratio)
        ref = simulate(block, pulse, solver="housner")
        assert ref.ok and ref.rocked and not ref.overturned and ref.n_impacts >= 1
        assert all(after == 0.0 for after in ref.impacts.theta_dot_after)
        fast = simulate(block, pulse, solver="housner_fast")
        assert fast.theta_max == pytest.approx(ref.theta_max, rel=1e-8)
        mj = simulate(Block(1.5, 1.0, restitution_factor=1.0), pulse, solver="moreau_jean")
        assert mj.ok and mj.theta_max == pytest.approx(ref.theta_max, rel=2e-3)


def test_wide_block_rocking_with_friction_agrees_between_friction_solvers():
    """mu = 2 > tan(alpha) = 1.5 (kinetic 1.3): it rocks and slides at impacts; the friction solver and Moreau-Jean
    (independent impact laws, both e_n = 0) agree on theta_max to 2e-3 (Moreau-Jean's first-order steps; measured
    9e-4 and 8e-4)."""
    block = Block(1.5, 1.0, friction=2.0, friction_kinetic=1.3)
    for freq_ratio in (2.0, 4.0):
        pulse = OneSinePulse.from_ratios(block, pfa_ratio=1.3, freq_ratio=freq_ratio)
        a = simulate(block, pulse, solver="friction")
        b = simulate(dataclasses.replace(block, restitution_factor=1.0), pulse, solver="moreau_jean")
        assert a.ok and b.ok and a.rocked
        assert b.theta_max == pytest.approx(a.theta_max, rel=2e-3)


def test_the_sdof_model_refuses_a_block_that_lands_flat():
    """Its damper keeps e² of the energy per passage: no finite damper keeps none (registry: flat_landing)."""
    assert set(solver_names(flat_landing=False)) == {"opensees", "sdof"}
    pulse = OneSinePulse.from_ratios(DESK, pfa_ratio=1.3, freq_ratio=2.0)
    for solver in ("sdof", "opensees"):
        with pytest.raises(ModelNotSupported, match=r"lands flat \(e = 0\): use solver 'housner'") as info:
            simulate(DESK, pulse, solver=solver)
        assert info.value.argument == "solver"
    # with its restitution given, the model is the user's
    assert simulate(Block(1.6, 1.0, restitution=0.5), pulse, solver="sdof").ok


def test_the_friction_solver_refuses_a_restitution_it_cannot_apply():
    with pytest.raises(ModelNotSupported, match="land it flat") as info:
        friction.solve(Block(1.6, 1.0, restitution=0.5, friction=0.5), OneSinePulse(3.0, 10.0))
    assert info.value.argument == "restitution"


def test_a_scene_refuses_the_rebound_when_it_is_loaded(tmp_path):
    """The same refusal from the registry's check, when the scene is loaded (not case by case)."""
    from opsrock.campaign.scene import load_scene
    from opsrock.errors import SceneError

    (tmp_path / "blocks.toml").write_text('[[block]]\nname = "crate"\nwidth = 1.6\nheight = 1.0\nrestitution = 0.5\n'
                                          'friction = 0.5\n')
    (tmp_path / "scene.toml").write_text('name = "t"\nblocks = "blocks.toml"\n[solver]\nname = "friction"\n'
                                         '[grid.freq_ratio]\nvalues = [3.0]\n[grid.pfa_ratio]\nvalues = [1.5]\n')
    with pytest.raises(SceneError, match="land it flat") as info:
        load_scene(tmp_path / "scene.toml")
    assert info.value.field == "solver.name"
