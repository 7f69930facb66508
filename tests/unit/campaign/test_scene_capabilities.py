"""A scene whose solver cannot meet one of its needs is refused when the scene is made (issue 31), for every
combination: each solver x a block that slips x a vertical floor motion x the restitution (default factor,
Housner's, ``e`` set, a distribution) x ``end_time`` (free rocking's span) -- loading only, nothing solved.

The expectations are written out here from what each solver models (docs/guide/solvers.md), not read from the
registry, so that a declaration that drifts from what the solvers do fails this test.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from opsrock.campaign.grid import Grid
from opsrock.campaign.records import Floor, Intensity, RecordSet
from opsrock.campaign.scene import BlockSpec, Scene
from opsrock.errors import SceneError
from opsrock.excitations import Record
from opsrock.restitution import RestitutionDistribution
from opsrock.solvers import SOLVERS

NO_SLIP = {"opensees", "sdof", "housner", "housner_fast"}  # no friction, no vertical motion
HOUSNER_ONLY = {"moreau_jean", "rigid3d", "cylinder3d"}  # e = e_H and no other
END_TIME_FREE_ONLY = {"housner_fast", "friction", "moreau_jean", "rigid3d", "cylinder3d"}  # end_time only without a floor motion

RESTITUTIONS = ("default", "housner", "e", "distribution")


def _spec(friction: bool, restitution: str) -> BlockSpec:
    kw = {"restitution_factor": 1.0} if restitution == "housner" else {"restitution": 0.8} if restitution == "e" else {}
    if restitution == "distribution":
        kw = {"restitution_factor": 1.0, "restitution_distribution": _DISTRIBUTION}
    # a depth for rigid3d, which needs it (test_a_box_without_depth_is_refused_for_rigid3d); planar solvers ignore it
    return BlockSpec(name="b", width=0.4, height=1.6, friction=0.5 if friction else None, depth=0.6, **kw)


#: Draws of e / e_R around Housner's own (mean 1): check_model alone, on the mean block, would let it through.
_DISTRIBUTION = RestitutionDistribution(1.0, 0.02, 0.95, 1.05, 7, "normal")


def _design(vertical: bool) -> dict:
    if not vertical:
        return {"grid": Grid(freq_ratio=(2.0,), pfa_ratio=(3.0,))}
    t = np.arange(200) * 0.01
    rec = Record(dt=0.01, values=np.sin(2 * np.pi * t), name="r", vertical=0.5 * np.sin(2 * np.pi * t))
    records = RecordSet(grounds=(rec,), floors=(Floor(None, 0),), intensity=Intensity("cloud", "", (1.0,)),
                        source="test", vertical="synthetic")
    return {"grid": None, "records": records}


def _expected(solver: str, friction: bool, vertical: bool, restitution: str, end_time: bool) -> str | None:
    """The scene key the refusal names, or None: the scene loads."""
    if end_time and solver in END_TIME_FREE_ONLY:
        return "solver.settings.end_time"
    if vertical and solver in NO_SLIP:
        return "records.vertical"
    if restitution == "distribution" and solver in HOUSNER_ONLY:
        return "solver.name"
    if friction and solver in NO_SLIP:
        return "solver.name"
    if restitution in ("default", "e") and solver in HOUSNER_ONLY:
        return "solver.name"
    return None


MATRIX = list(itertools.product(SOLVERS, (False, True), (False, True), RESTITUTIONS, (False, True)))


def test_every_need_a_solver_cannot_meet_is_refused_when_the_scene_is_made():
    wrong = []
    for solver, friction, vertical, restitution, end_time in MATRIX:
        expected = _expected(solver, friction, vertical, restitution, end_time)
        settings = {"end_time": 5.0} if end_time else {}
        try:
            Scene(name="m", path="m.toml", blocks=(_spec(friction, restitution),), solver=solver,
                  solver_settings=settings, **_design(vertical))
            got = None
        except SceneError as exc:
            got = exc.field
            if "m.toml" not in str(exc) or len(str(exc).splitlines()) != 1:
                wrong.append(f"{solver} {friction} {vertical} {restitution} {end_time}: message {exc}")
        if got != expected:
            wrong.append(f"{solver} friction={friction} vertical={vertical} restitution={restitution} "
                         f"end_time={end_time}: refused at {got}, expected {expected}")
    assert len(MATRIX) == len(SOLVERS) * 2 * 2 * 4 * 2
    assert not wrong, "\n".join(wrong)


def test_a_box_without_depth_is_refused_for_rigid3d():
    spec = BlockSpec(name="b", width=0.4, height=1.6, restitution_factor=1.0)
    with pytest.raises(SceneError, match="block 'b' has no depth") as info:
        Scene(name="m", path="m.toml", blocks=(spec,), solver="rigid3d", **_design(False))
    assert info.value.field == "solver.name"


def test_with_solver_checks_the_scene_again():
    scene = Scene(name="m", path="m.toml", blocks=(_spec(False, "default"),), solver="housner", **_design(False))
    with pytest.raises(SceneError, match="moreau_jean.*restitution_factor = 0.95"):
        scene.with_solver("moreau_jean")
    assert scene.with_solver("friction").solver == "friction"


def test_a_history_need_reads_the_registry(monkeypatch):
    from dataclasses import replace

    from opsrock.campaign.needs import Needs
    from opsrock.solvers import registry

    monkeypatch.setitem(registry.METHODS, "housner", replace(registry.METHODS["housner"], histories=False))
    with pytest.raises(SceneError, match="needs.answer = 'histories'.*no time histories"):
        Scene(name="m", path="m.toml", blocks=(_spec(False, "default"),), solver="housner",
              needs=Needs(answer="histories"), **_design(False))
