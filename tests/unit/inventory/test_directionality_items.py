"""The directionality preset's items: the shipped inventories' boxes; a round item is left out, said in the report,
and refused when named (it has no orientation to turn: issue 45's cylinders go to the contents study's 3-D route)."""

from __future__ import annotations

import pytest

from opsrock.errors import InputError
from opsrock.inventory.directionality.study import DirectionalityDesign, left_out, round_items, study_items
from opsrock.inventory.directionality.summary import report_inputs
from opsrock.inventory.items import shipped_inventory


def test_every_box_of_the_shipped_inventories_and_no_round_item():
    shipped = [it for name in ("fema-p58-nine", "example") for it in shipped_inventory(name).items]
    boxes = [it.id for it in shipped if it.shape == "box"]
    assert round_items() == ("oxygen_cylinder",)  # the example's round item (issue 45)
    assert [s.id for s in study_items(DirectionalityDesign())] == boxes


def test_a_named_round_item_is_refused_naming_it_and_the_route_that_takes_it():
    with pytest.raises(InputError, match=r"\['oxygen_cylinder'\] have a round base.*--model 3d") as err:
        study_items(DirectionalityDesign(items=("bookcase", "oxygen_cylinder")))
    assert err.value.argument == "items"


def test_the_report_is_told_what_was_left_out():
    assert left_out(DirectionalityDesign()) == ("oxygen_cylinder",)
    assert left_out(DirectionalityDesign(items=("bookcase",))) == ()
    assert report_inputs(DirectionalityDesign(), {}, {}, [], ("oxygen_cylinder",)).left_out == ("oxygen_cylinder",)
