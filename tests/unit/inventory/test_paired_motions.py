"""Pairing a motion set's two horizontal directions for the three-dimensional solver
(opsrock.inventory.motions.paired_motions): every (record, floor) of the shipped example once, direction 1 as
the plan motion's first component and 2 as its second, and a record/floor with one direction refused naming
it."""

from __future__ import annotations

import numpy as np
import pytest

from opsrock.data import example_motions_manifest
from opsrock.errors import InputError
from opsrock.excitations.plan import PlanMotion
from opsrock.inventory.motions import MotionPair, MotionSet, paired_motions, read_motions


def test_each_record_and_floor_pairs_its_two_directions():
    motions = read_motions(example_motions_manifest())
    pairs = paired_motions(motions)
    keys = {(m.record, m.floor) for m in motions.motions}
    assert sorted((p.record, p.floor) for p in pairs) == sorted(keys)
    assert len(pairs) * 2 == len(motions.motions)  # the example has both directions everywhere
    for p in pairs:
        assert p.first.key == (p.record, p.floor, "1") and p.second.key == (p.record, p.floor, "2")
        assert p.name == f"{p.record}@{p.floor}"
    p = pairs[0]
    plan = p.plan(90.0)
    assert isinstance(plan, PlanMotion) and plan.azimuth == 90.0 and not plan.planar
    # at azimuth 90 the block's x axis is direction 2 and its y axis minus direction 1 (PlanMotion's frames)
    t = p.first.motion.time[:50]
    ax, ay = plan.components(t)
    np.testing.assert_allclose(ax, p.second.motion.acceleration(t), atol=1e-12)
    np.testing.assert_allclose(ay, -p.first.motion.acceleration(t), atol=1e-12)


def test_a_record_with_one_direction_is_refused_naming_it():
    motions = read_motions(example_motions_manifest())
    one = MotionSet(tuple(m for m in motions.motions if not (m.record == "northridge" and m.floor == "2"
                                                             and m.direction == "2")), "code")
    with pytest.raises(InputError, match=r"motions code: record 'northridge' on floor '2' has direction 1 only; "
                                         "two horizontal directions need both 1 and 2") as info:
        paired_motions(one)
    assert info.value.argument == "motions"


def test_a_pair_is_one_record_and_floor_in_directions_one_and_two():
    a, b = read_motions(example_motions_manifest()).motions[:2]  # northridge floors 1 and 2, direction 1
    with pytest.raises(InputError, match="a motion pair is direction 1 and 2 of one record and floor"):
        MotionPair(a, b)
