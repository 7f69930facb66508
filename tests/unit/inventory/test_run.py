"""One way into the contents study (:mod:`opsrock.inventory.run`): ``opsrock.run_study`` builds, for each set of
arguments, the design ``opsrock contents`` builds for the same options, and the route is read from the design. No
study runs here (the end-to-end tests run each route)."""

from __future__ import annotations

import pytest

import opsrock
from opsrock.errors import InputError
from opsrock.inventory.directionality.study import BOTH, DirectionalityDesign
from opsrock.inventory.directionality.study import quick as quick_both
from opsrock.inventory.fema import SWEEP_BUILDINGS, ContentsDesign
from opsrock.inventory.fema.design import quick as quick_fema
from opsrock.inventory.fema.study import FEMA_NINE
from opsrock.inventory.run import route_of, run_study, study_design
from opsrock.inventory.sources import BuildingSource


def test_the_top_level_run_study_is_this_one():
    assert opsrock.run_study is run_study


def test_no_files_is_fema_p58_s_preset_as_the_command_builds_it():
    """``opsrock contents`` with no option builds ContentsDesign(period 1.0, storeys 8, the sweep's buildings)
    (cli/contents.py); ``run_study()`` the same, so both run one method (it ran the nine through the inventory route
    before)."""
    assert study_design() == ContentsDesign(period=1.0, storeys=8, sweep=SWEEP_BUILDINGS)
    assert study_design(quick=True) == quick_fema(ContentsDesign(period=1.0, storeys=8, sweep=SWEEP_BUILDINGS))
    building = BuildingSource(period=0.5, storeys=4, floors=("roof",))
    assert study_design(building=building, sweep=()) == ContentsDesign(period=0.5, storeys=4, floors=("roof",))
    assert route_of(study_design()) is FEMA_NINE


def test_both_models_is_the_directionality_configuration():
    assert study_design(model="both") == DirectionalityDesign()
    assert study_design(model="both", quick=True) == quick_both(DirectionalityDesign())
    assert route_of(DirectionalityDesign()) is BOTH


@pytest.mark.parametrize("kwargs, argument", [({"model": "3-d"}, "model"), ({"nope": 1}, "settings"),
                                              ({"model": "both", "nope": 1}, "settings")])
def test_refusals_name_the_argument(kwargs, argument):
    with pytest.raises(InputError) as err:
        study_design(**kwargs)
    assert err.value.argument == argument


def test_a_design_of_no_configuration_is_refused():
    with pytest.raises(InputError, match="design must be"):
        route_of(object())
