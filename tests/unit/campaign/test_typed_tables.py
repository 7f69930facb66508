"""The typed case table (:func:`opsrock.campaign.cases.read_cases`), a fit's status
(:func:`opsrock.inventory.fits.fit_status`) and the solver declarations the campaign engine and the studies
read instead of solver names (:mod:`opsrock.solvers.registry`). Every expected value is written here."""

from __future__ import annotations

import math

import pytest

from opsrock.campaign.cases import CONTACT_COLUMNS, PLAN_COLUMNS, read_cases
from opsrock.errors import InputError
from opsrock.inventory.fits import FIT_STATUSES, fit_status
from opsrock.solvers.registry import METHODS, RESULT_COLUMN_GROUPS, plan_solver, planar_solver


def test_cases_read_back_with_their_types(tmp_path):
    path = tmp_path / "cases.csv"
    path.write_text("case_id,block,overturned,rocked,status,reason,overturned_over,theta_max\n"
                    "a,1,True,True,ok,,corner,0.25\nb,2,False,False,failed,boom,,nan\n")
    cases = read_cases(path)
    assert cases["overturned"].dtype == bool and cases["rocked"].dtype == bool
    assert cases["overturned"].tolist() == [True, False]
    assert cases["block"].tolist() == ["1", "2"]  # a name that looks like a number stays text
    assert cases["reason"].tolist() == ["", "boom"] and cases["overturned_over"].tolist() == ["corner", ""]
    assert cases["theta_max"].iloc[0] == 0.25 and math.isnan(cases["theta_max"].iloc[1])
    assert read_cases(path, usecols=["case_id", "overturned"]).columns.tolist() == ["case_id", "overturned"]


def test_a_case_table_with_a_non_boolean_overturned_is_refused(tmp_path):
    path = tmp_path / "cases.csv"
    path.write_text("case_id,overturned\na,True\nb,maybe\n")
    with pytest.raises(InputError, match="column 'overturned' must hold booleans, got 'maybe'"):
        read_cases(path)


@pytest.mark.parametrize("ok, median, x_max, n_exceeded, n_cases, status", [
    (True, 0.5, 1.0, 10, 20, "fitted"),
    (True, 2.0, 1.0, 2, 20, "extrapolated"),  # the median beyond the largest demand of the cases
    (False, math.nan, 1.0, 0, 20, "never"),
    (False, math.nan, 1.0, 20, 20, "always"),
    (False, math.nan, 1.0, 7, 20, "no fit"),
    (True, math.nan, 1.0, 7, 20, "no fit"),  # "ok" without a finite median is no fit
])
def test_a_fit_has_its_status(ok, median, x_max, n_exceeded, n_cases, status):
    assert fit_status(ok, median, x_max, n_exceeded, n_cases) == status and status in FIT_STATUSES


def test_the_solvers_declare_what_the_engine_reads():
    assert all(set(e.result_columns) <= set(RESULT_COLUMN_GROUPS) for e in METHODS.values())
    # a solver that writes the plan columns models motion in plan; the box in plan needs a block's depth (the
    # cylinder's round base has none: its width is the diameter)
    for entry in METHODS.values():
        assert ("plan" in entry.result_columns) == entry.plan
        assert ("depth" in entry.block_needs) == (entry.plan and entry.model == "rigid3d")
        assert ("contact" in entry.result_columns) == entry.friction  # every solver of a slipping base
        assert entry.default_restitution_factor == (None if entry.restitution else 1.0)
    assert METHODS[plan_solver()].plan
    for friction in (False, True):
        entry = METHODS[planar_solver(friction)]
        assert not entry.plan and entry.friction == friction and entry.restitution and entry.compiled


def test_a_scene_s_columns_are_those_its_solver_declares():
    from opsrock.campaign.grid import Grid
    from opsrock.campaign.scene import BlockSpec, Scene

    grid = Grid(freq_ratio=(2.0,), pfa_ratio=(1.5,))
    spec = BlockSpec(name="b", width=0.4, height=1.6, restitution_factor=1.0, depth=0.5)
    for name, entry in METHODS.items():
        columns = Scene("s", "", (spec,), grid, solver=name).columns
        assert set(CONTACT_COLUMNS) <= set(columns) if "contact" in entry.result_columns else \
            not set(CONTACT_COLUMNS) & set(columns)
        assert set(PLAN_COLUMNS) <= set(columns) if "plan" in entry.result_columns else \
            not set(PLAN_COLUMNS[3:]) & set(columns)
