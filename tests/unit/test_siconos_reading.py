"""Siconos's results CSV read with the project's one boolean parser (issue 42: no text re-parsing of ``overturned``):
``True``/``False`` as booleans, anything else refused naming the column, never read as False."""

from __future__ import annotations

import pytest

from opsrock.errors import InputError
from opsrock.validation.siconos3d_compare import read_siconos

HEADER = "index,overturned,tilt_max,slide_max,twist_max,wall_s,steps,status\n"


def test_verdicts_are_booleans(tmp_path):
    path = tmp_path / "s.csv"
    path.write_text(HEADER + "0,True,1.5,0.0,0.0,0.1,10,ok\n1,False,0.25,0.01,0.0,0.1,10,ok\n")
    rows = read_siconos(path, 1e-4)
    assert rows[0]["overturned"] is True and rows[1]["overturned"] is False
    assert rows[1]["tilt_max"] == 0.25 and rows[0]["step"] == 1e-4


def test_a_verdict_that_is_not_a_boolean_is_refused(tmp_path):
    path = tmp_path / "s.csv"
    path.write_text(HEADER + "0,yes,1.5,0.0,0.0,0.1,10,ok\n")
    with pytest.raises(InputError, match="overturned"):
        read_siconos(path, 1e-4)
