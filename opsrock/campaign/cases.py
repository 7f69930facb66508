"""The unit of work of a campaign, and the one table its results make (``cases.csv``).

A case is a block under one floor motion: a pulse of a grid (:class:`PulseCase`) or a scaled floor
motion of a record scene (:class:`RecordCase`). Both give the solver ``block`` and ``excitation``, and
``row()``: the scene-side columns of ``cases.csv`` (the block, the motion, the nine IMs). The solver's
side is a store row (:func:`result_row`, :func:`failed_row`, columns :data:`RESULT_COLUMNS`), and
:func:`case_table` joins the two, in the scene's case order.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping, Sequence

from opsrock._files import atomic_write, read_units, units_row_text
from opsrock.block import Block
from opsrock.excitations import Pulse, Record
from opsrock.excitations.plan import PlanMotion
from opsrock.result import RockingResult

#: Name of the assembled table in a campaign's folder.
CASES_FILE: str = "cases.csv"

#: The solver's columns of ``cases.csv``, after the scene's (units: rad; ``wall_time_s`` and ``cpu_time_s`` in s:
#: the case's solve, measured in the process that solved it, its wall-clock time and its thread's CPU time; the
#: CPU time is what a machine's load does not stretch, so cost ratios are taken on it).
RESULT_COLUMNS: tuple[str, ...] = (
    "theta_max", "theta_max_over_alpha", "overturned", "rocked", "status", "reason", "verdict", "solver",
    "wall_time_s", "cpu_time_s",
)  # fmt: skip

#: Columns a scene solved with friction adds (solvers of the ``friction`` model): the block's friction
#: coefficients (dimensionless; empty: no slip), the vertical floor motion's peak (m/s², 0 without one),
#: and what the block did: ``response`` (overturned / rocked / slid / at_rest / failed), ``first_mode``
#: (the mode it left rest into), ``time_sliding``, ``time_rocking`` and ``time_flight`` (s), ``slide_max`` and
#: ``slide_residual`` (m, the base's displacement relative to the floor, peak and final).
CONTACT_COLUMNS: tuple[str, ...] = (
    "friction", "friction_kinetic", "pfa_vertical", "response", "first_mode", "time_sliding", "time_rocking",
    "time_flight", "slide_max", "slide_residual",
)  # fmt: skip

#: The contact columns a solver fills (the others are the scene's).
_SOLVED_CONTACT_COLUMNS: tuple[str, ...] = CONTACT_COLUMNS[3:]

#: Columns a scene solved in three dimensions adds (solvers of the ``rigid3d`` model, after
#: :data:`CONTACT_COLUMNS`, whose ``slide_max`` and ``slide_residual`` are then the magnitudes of the base's
#: horizontal displacement, m): the block's full ``depth`` (m) and ``azimuth`` (deg, from motion axis 1 to its
#: width; :class:`~opsrock.excitations.plan.PlanMotion`), the second horizontal component's record (empty: none),
#: and what it did (:class:`~opsrock.result.PlanSummary`): ``tilt_max`` and ``twist_max`` (rad),
#: ``overturned_over`` (``edge``, ``corner``, a cylinder's ``rim`` or ``rolling``, or empty), and a cylinder's
#: ``time_rim`` and ``time_rolling`` (s: on one rim point, and of that rolling round the rim; 0 for a box; NaN for a
#: case stored before they were, store schema version 3).
PLAN_COLUMNS: tuple[str, ...] = ("depth", "azimuth", "record2", "tilt_max", "twist_max", "overturned_over",
                                 "time_rim", "time_rolling")

#: The plan columns a solver fills (the others are the scene's).
_SOLVED_PLAN_COLUMNS: tuple[str, ...] = PLAN_COLUMNS[3:]

#: The block's columns, first in every ``cases.csv`` (m, rad, m, rad/s; ``e``, ``e_R`` dimensionless).
BLOCK_COLUMNS: tuple[str, ...] = ("case_id", "block", "width", "height", "alpha", "R", "p", "e", "e_R")

#: The nine intensity measures of the paper's Table 1 (and their generalisation to records).
IM_COLUMNS: tuple[str, ...] = tuple(f"IM{k}" for k in range(1, 10))

#: Columns of ``cases.csv`` for a pulse scene, in order. Units: m, rad, m/s², rad/s, s, m/s; ratios
#: dimensionless.
PULSE_COLUMNS: tuple[str, ...] = (
    *BLOCK_COLUMNS, "pfa", "omega_p", "T_p", "pfv", "freq_ratio", "pfa_ratio", *IM_COLUMNS, *RESULT_COLUMNS,
)  # fmt: skip

#: Columns of ``cases.csv`` for a record scene, in order. Units: m, rad, m/s², m/s, m, s; ratios
#: dimensionless; ``level_value`` in the scene's measure.
RECORD_COLUMNS: tuple[str, ...] = (
    *BLOCK_COLUMNS,
    "record", "event", "component", "magnitude", "distance_km", "floor", "building_period",
    "level", "level_value", "scale",
    "pfa", "pfv", "pfd", "T_m", "T_pred", "pfa_ratio", *IM_COLUMNS, *RESULT_COLUMNS,
)  # fmt: skip

#: The column a multi-fidelity campaign adds last (:mod:`opsrock.campaign.multifidelity`): which stage's result
#: a case's row holds (screen, escalated, audit).
SOURCE_COLUMN: str = "source"

#: The unit of every column of ``cases.csv``, defined once, as its units row writes it: SI (``m/s2`` for m/s²),
#: ``rad``, ``deg``, ``km`` for ``distance_km``, ``-`` for a dimensionless number, ``""`` for text, labels and flags.
#: ``level_value`` is in the scene's intensity measure (:data:`MEASURE_UNITS`). These are the campaign's meanings:
#: the contents study's tables (:mod:`opsrock.inventory.columns`) use some of the same names (``status``,
#: ``floor``, ``pfa``) with their own meaning and unit (``pfa`` there in g).
UNITS: dict[str, str] = {
    # the block (BLOCK_COLUMNS)
    "case_id": "", "block": "", "width": "m", "height": "m", "alpha": "rad", "R": "m", "p": "rad/s", "e": "-",
    "e_R": "-",
    # a pulse (PULSE_COLUMNS)
    "pfa": "m/s2", "omega_p": "rad/s", "T_p": "s", "pfv": "m/s", "freq_ratio": "-", "pfa_ratio": "-",
    # a floor motion (RECORD_COLUMNS)
    "record": "", "event": "", "component": "", "magnitude": "-", "distance_km": "km", "floor": "",
    "building_period": "s", "level": "-", "level_value": "see measure", "scale": "-", "pfd": "m", "T_m": "s",
    "T_pred": "s",
    **dict.fromkeys(IM_COLUMNS, "-"),
    # the solver's (RESULT_COLUMNS)
    "theta_max": "rad", "theta_max_over_alpha": "-", "overturned": "", "rocked": "", "status": "", "reason": "",
    "verdict": "", "solver": "", "wall_time_s": "s", "cpu_time_s": "s",
    # with friction (CONTACT_COLUMNS)
    "friction": "-", "friction_kinetic": "-", "pfa_vertical": "m/s2", "response": "", "first_mode": "",
    "time_sliding": "s", "time_rocking": "s", "time_flight": "s", "slide_max": "m", "slide_residual": "m",
    # in three dimensions (PLAN_COLUMNS)
    "depth": "m", "azimuth": "deg", "record2": "", "tilt_max": "rad", "twist_max": "rad", "overturned_over": "",
    "time_rim": "s", "time_rolling": "s",
    SOURCE_COLUMN: "",
}  # fmt: skip

#: The unit of ``level_value`` for each intensity measure of a record scene
#: (:data:`opsrock.campaign.records.MEASURES`); ``""``: a pulse scene or a cloud (``level_value`` NaN).
MEASURE_UNITS: dict[str, str] = {"pfa_g": "g", "pfa_ratio": "-", "pfa_onset": "-", "": "-"}


def units_of(columns: Sequence[str], measure: str = "", extra: Mapping[str, str] | None = None) -> list[str]:
    """The units row of a ``cases.csv`` with these ``columns`` (:data:`UNITS`), ``level_value`` in ``measure``'s
    unit (:data:`MEASURE_UNITS`), the columns a scene of its own adds in its ``extra`` units (a study's scene:
    :attr:`opsrock.campaign.scene.Scene.units`); ``KeyError`` naming a column without a unit."""
    known = {**UNITS, **(extra or {})}
    missing = [c for c in columns if c not in known]
    if missing:
        raise KeyError(f"columns without a unit in opsrock.campaign.cases.UNITS or the scene's: {missing!r}")
    return [MEASURE_UNITS[measure] if c == "level_value" else known[c] for c in columns]


#: Columns that differ between two runs of the same campaign: measured, not computed. Two
#: ``cases.csv`` of the same scene and settings agree in every other column, whatever the
#: executor, the worker count and the interruptions.
IDENTITY_EXCLUDED: tuple[str, ...] = ("wall_time_s", "cpu_time_s")

#: Longest failure reason kept (characters); a reason is also folded onto one line.
MAX_REASON: int = 500

def _block_columns(case_id: str, b: Block) -> dict[str, Any]:
    return {"case_id": case_id, "block": b.name, "width": b.width, "height": b.height, "alpha": b.alpha,
            "R": b.R, "p": b.p, "e": b.e, "e_R": b.e_R, "friction": b.friction, "friction_kinetic": b.friction_kinetic}


@dataclass(frozen=True)
class PulseCase:
    """One block under one pulse of a grid.

    Parameters
    ----------
    case_id : str
        Stable id ``"<block>/f<i>/a<j>"``: ``i`` (``j``) is the 1-based index into the
        grid's ``freq_ratio`` (``pfa_ratio``) values, zero-padded to at least two digits.
    block : Block
        The block.
    pulse : Pulse
        The pulse (the scene's shape), ``PFA = pfa_ratio g tan(alpha)``, ``omega_p = freq_ratio p``.
    freq_ratio : float
        ``omega_p / p`` (dimensionless).
    pfa_ratio : float
        ``PFA / (g tan alpha)`` (dimensionless).
    pfv_convention : str
        PFV convention of IM3 and IM8 (:data:`opsrock.excitations.PFV_CONVENTIONS`).
    azimuth : float or None
        The block's azimuth in plan (deg, from the pulse's direction to its width:
        :class:`~opsrock.excitations.plan.PlanMotion`); None: the planar case (the pulse along the width).
    """

    case_id: str
    block: Block
    pulse: Pulse
    freq_ratio: float
    pfa_ratio: float
    pfv_convention: str = "amplitude"
    azimuth: float | None = None

    #: A pulse case can always be run (a record case may not: its scale factor).
    problem = ""

    @property
    def excitation(self) -> Pulse | PlanMotion:
        """What the solver gets: the pulse, or the pulse in plan at the case's azimuth."""
        return self.pulse if self.azimuth is None else PlanMotion(self.pulse, None, self.azimuth)

    def row(self) -> dict[str, Any]:
        """The scene-side columns of ``cases.csv`` (:data:`PULSE_COLUMNS` before the results)."""
        from opsrock.intensity import intensity_measures

        b, pulse = self.block, self.pulse
        ims = intensity_measures(b, pulse, pfv_convention=self.pfv_convention)
        return {**_block_columns(self.case_id, b), "pfa_vertical": abs(pulse.vertical), "pfa": pulse.pfa,
                "omega_p": pulse.omega_p, "T_p": pulse.T_p,
                "pfv": pulse.pfv(self.pfv_convention), "freq_ratio": self.freq_ratio, "pfa_ratio": self.pfa_ratio,
                **{k: ims[k] for k in IM_COLUMNS}, **_plan_columns(b, self.azimuth, None)}


@dataclass(frozen=True)
class RecordCase:
    """One block under one floor motion at one intensity level.

    Parameters
    ----------
    case_id : str
        ``<block>/<record>/<floor>/l<k>``.
    block : Block
        The block.
    motion : Motion
        The unscaled floor motion and its measures (:class:`opsrock.campaign.motions.Motion`).
    scale : float
        Factor on the motion (dimensionless).
    level : int
        1-based level index.
    level_value : float
        Target value of the scene's measure at this level (NaN for a cloud).
    problem : str
        Non-empty if the case cannot be run (a scale factor outside the limits, a floor motion that
        failed): it is stored failed with this reason.
    azimuth : float or None
        The block's azimuth in plan (deg, from the motion's axis 1 to its width); None: the planar case.
    motion2 : Motion or None
        The second horizontal component (along motion axis 2), scaled by the same factor; None: none.
    """

    case_id: str
    block: Block
    motion: Any = field(repr=False)
    scale: float
    level: int
    level_value: float
    problem: str = ""
    azimuth: float | None = None
    motion2: Any = field(default=None, repr=False)

    @property
    def excitation(self) -> Record | PlanMotion:
        """The scaled floor motion (m/s²), in plan with the second component and the azimuth if any."""
        rec = self.motion.record
        first = rec if self.scale == 1.0 else rec.scaled(self.scale)
        if self.azimuth is None and self.motion2 is None:
            return first
        second = None if self.motion2 is None else self.motion2.record.scaled(self.scale)
        return PlanMotion(first, second, 0.0 if self.azimuth is None else self.azimuth)

    def row(self) -> dict[str, Any]:
        """The scene-side columns of ``cases.csv`` (:data:`RECORD_COLUMNS` before the results)."""
        from opsrock.intensity.records import record_intensity_measures

        b, m = self.block, self.motion
        info = m.record.info
        ok = not self.problem
        meas = m.measures.scaled(self.scale) if ok else m.measures
        ims = record_intensity_measures(b.alpha, b.R, b.p, b.e_R, meas) if ok else {k: math.nan for k in IM_COLUMNS}
        return {
            **_block_columns(self.case_id, b),
            "record": m.ground, "event": info.event, "component": info.component,
            "magnitude": math.nan if info.magnitude is None else info.magnitude,
            "distance_km": math.nan if info.distance_km is None else info.distance_km,
            "floor": m.floor, "building_period": m.building_period,
            "level": self.level, "level_value": self.level_value, "scale": self.scale,
            "pfa": meas.pfa, "pfv": meas.pfv, "pfd": meas.pfd, "T_m": meas.mean_period,
            "T_pred": meas.predominant_period, "pfa_ratio": meas.pfa / b.uplift_acceleration, **ims,
            "pfa_vertical": m.record.pfa_vertical * self.scale,
            **_plan_columns(b, self.azimuth, None if self.motion2 is None else self.motion2.ground),
        }


def _plan_columns(block: Block, azimuth: float | None, record2: str | None) -> dict[str, Any]:
    """The scene's plan columns of a case (:data:`PLAN_COLUMNS`): depth (m, NaN for a planar block), azimuth
    (deg, 0 for a planar case) and the second component's record (None: none)."""
    return {"depth": math.nan if block.depth is None else block.depth,
            "azimuth": 0.0 if azimuth is None else azimuth, "record2": record2}


# --- store rows ---------------------------------------------------------------------------------------
def _one_line(text: str) -> str:
    text = " ".join(str(text).split())
    return text if len(text) <= MAX_REASON else text[: MAX_REASON - 3] + "..."


#: The code of a failure reason that no solver status names (an exception, a case that could not be run).
OTHER_REASON: str = "other"


def reason_code(reason: str | None) -> str:
    """The kind of a stored failure ``reason``, the same for every case that failed the same way, whatever
    numbers (times, budgets, settings) the reason holds: ``"lost"`` for a case lost to the infrastructure
    (:data:`~opsrock.campaign.executors.LOST_MARKERS`), ``"timeout"`` for a case budget's or ``max_wall_time``'s,
    else the failure kind (:data:`opsrock.solvers.status.FAILURES`) whose reason text begins it (a solver appends
    where and when), else :data:`OTHER_REASON`."""
    from opsrock.campaign.executors import is_lost
    from opsrock.solvers.status import FAILURES, REASONS, TIMEOUT

    text = " ".join(str(reason or "").split())
    if is_lost(text):
        return "lost"
    if text.startswith("timeout"):
        return FAILURES[TIMEOUT]
    for code, kind in FAILURES.items():
        if kind is not None and REASONS[code] and text.startswith(REASONS[code]):
            return kind
    return OTHER_REASON


def failed_row(case_id: str, solver: str, reason: str, wall_time_s: float = math.nan,
               cpu_time_s: float = math.nan) -> dict[str, Any]:
    """A store row for a case that produced no result (status ``"failed"``, verdict ``"failed"``); its wall and CPU
    times (s) until it failed, NaN if not measured (its worker died)."""
    return {
        "case_id": case_id, "status": "failed", "reason": _one_line(reason) or "failed without a reason",
        "verdict": "failed", "theta_max": math.nan, "theta_max_over_alpha": math.nan, "overturned": False,
        "rocked": False, "solver": solver, "wall_time_s": wall_time_s, "cpu_time_s": cpu_time_s, "n_steps": None,
        "n_impacts": None,
        "response": "failed", "first_mode": None, "time_sliding": math.nan, "time_rocking": math.nan,
        "time_flight": math.nan, "slide_max": math.nan, "slide_residual": math.nan,
        "tilt_max": math.nan, "twist_max": math.nan, "overturned_over": None, "time_rim": math.nan,
        "time_rolling": math.nan,
    }


def result_row(case_id: str, result: RockingResult, wall_time_s: float, cpu_time_s: float = math.nan) -> dict[str, Any]:
    """A store row from a solver's result, with the wall and CPU times (s) its solve took (:data:`RESULT_COLUMNS`)."""
    s = result.summary()
    contact = {"response": None, "first_mode": None, "time_sliding": math.nan, "time_rocking": math.nan,
               "time_flight": math.nan, "slide_max": math.nan, "slide_residual": math.nan}
    if result.contact is not None:
        contact = {"response": result.response, **result.contact.columns()}
    elif result.status == "failed":
        contact["response"] = "failed"
    plan = result.plan
    in_plan = ({"tilt_max": math.nan, "twist_max": math.nan, "overturned_over": None, "time_rim": math.nan,
                "time_rolling": math.nan} if plan is None else
               {"tilt_max": plan.tilt_max, "twist_max": plan.twist_max, "overturned_over": plan.overturned_over,
                "time_rim": plan.time_rim, "time_rolling": plan.time_rolling})
    return {
        "case_id": case_id, "status": s["status"], "reason": _one_line(s["reason"]), "verdict": s["verdict"],
        "theta_max": s["theta_max"], "theta_max_over_alpha": s["theta_max_over_alpha"],
        "overturned": s["overturned"], "rocked": s["rocked"], "solver": s["solver"], "wall_time_s": wall_time_s,
        "cpu_time_s": cpu_time_s, "n_steps": s["n_steps"], "n_impacts": s["n_impacts"], **contact, **in_plan,
    }


# --- the table --------------------------------------------------------------------------------------
def case_table(cases: Sequence, rows: Mapping[str, Mapping[str, Any]]) -> list[dict[str, Any]]:
    """The rows of ``cases.csv``: each case's scene-side columns joined to its stored result.

    Parameters
    ----------
    cases : sequence of PulseCase or RecordCase
        In the scene's order.
    rows : dict
        Stored rows keyed by ``case_id`` (:meth:`opsrock.campaign.store.ResultStore.rows`); every
        case must be there.
    """
    table = []
    for case in cases:
        if case.case_id not in rows:
            raise KeyError(f"case {case.case_id!r} has no stored result")
        stored = rows[case.case_id]
        table.append({**case.row(), **{col: stored[col] for col in RESULT_COLUMNS},
                      **{col: stored.get(col) for col in (*_SOLVED_CONTACT_COLUMNS, *_SOLVED_PLAN_COLUMNS)}})
    return table


def _format(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "True" if value else "False"
    if isinstance(value, float):
        return repr(value)  # shortest repr that round-trips: exact, and identical run to run
    return str(value)


def write_cases_csv(path: str | Path, table: Sequence[Mapping[str, Any]], columns: Sequence[str],
                    units: Sequence[str] | None = None) -> None:
    """Write a case table atomically (temporary file, fsync, ``os.replace``): the header ``columns``, the units row
    ``units`` (the scene's, :attr:`opsrock.campaign.scene.Scene.units`; default :func:`units_of` ``columns``), then
    the cases, every float at full precision (its shortest ``repr``)."""
    head = units_row_text(list(columns), units_of(columns) if units is None else list(units))

    def write(fh):
        fh.write(head)
        w = csv.writer(fh, lineterminator="\n")
        for rec in table:
            w.writerow([_format(rec[c]) for c in columns])

    atomic_write(Path(path), write)


#: Boolean columns of ``cases.csv`` (written ``True``/``False``): read back as booleans.
BOOL_COLUMNS: tuple[str, ...] = ("overturned", "rocked")

#: Text columns of ``cases.csv`` that may be empty (read back as ``""``, never NaN).
TEXT_COLUMNS: tuple[str, ...] = ("status", "reason", "verdict", "solver", "record", "record2", "response",
                                 "first_mode", "overturned_over", "block")


def as_bool(values: Any, name: str) -> "Any":
    """``values`` (a pandas Series) as a boolean NumPy array: booleans as they are; the text ``True``/``False``
    (any case), ``1``/``0`` parsed; anything else refused with :class:`~opsrock.errors.InputError` naming
    column ``name``."""
    from opsrock.errors import InputError

    if values.dtype == bool:
        return values.to_numpy()
    mapping = {"true": True, "false": False, "1": True, "0": False, "1.0": True, "0.0": False}
    out = values.astype(str).str.strip().str.lower().map(mapping)
    if out.isna().any():
        bad = values[out.isna()].iloc[0]
        raise InputError(f"column {name!r} must hold booleans, got {bad!r}")
    return out.to_numpy(dtype=bool)


def read_cases(path: str | Path, usecols: Sequence[str] | None = None) -> "Any":
    """A ``cases.csv`` read back with its types: every float exactly as written
    (:func:`opsrock._files.read_table`), :data:`BOOL_COLUMNS` as booleans, :data:`TEXT_COLUMNS` as text with
    ``""`` where empty. The one reader of a campaign's cases: nothing downstream parses them again.

    The units row (the second row, first cell ``Units``) is checked against :data:`UNITS` and skipped. A
    ``cases.csv`` written by an opsrock before the row (its second row a case: its first cell a ``case_id``,
    which always holds a ``/``, never ``Units``) is read as it is, to the same frame: its values were in the same
    units.

    Parameters
    ----------
    path : str or Path
        The ``cases.csv`` of a campaign.
    usecols : sequence of str, optional
        The columns to read (default: all).

    Returns
    -------
    pandas.DataFrame

    Raises
    ------
    InputError
        The units row gives a column another unit than :data:`UNITS` (one line naming the file and the column):
        the file is not a ``cases.csv`` as opsrock writes it.
    """
    from opsrock._files import read_table

    df = read_table(path, usecols=None if usecols is None else list(usecols), dtype=dict.fromkeys(TEXT_COLUMNS, str),
                    skiprows=units_row(path))
    return typed_cases(df)


def units_row(path: str | Path) -> list[int] | None:
    """The rows to skip to read the ``cases.csv`` at ``path`` as a table (``skiprows`` of
    :func:`pandas.read_csv`): ``[1]``, its units row, once checked against :data:`UNITS`; None for a ``cases.csv``
    of an opsrock before the row (its second row a case). ``InputError`` for a units row that gives a column
    another unit (one line naming the file and the column); columns :data:`UNITS` does not know are the user's
    own and pass."""
    from opsrock.errors import InputError

    header, units = read_units(path)
    if units is None:
        return None
    for col, unit in zip(header[1:], units[1:]):
        want = set(MEASURE_UNITS.values()) if col == "level_value" else {UNITS.get(col, unit)}
        if unit not in want:
            raise InputError(f"{path}: column {col!r} in {unit!r} in its units row, expected "
                             f"{' or '.join(map(repr, sorted(want)))}: not a cases.csv as opsrock writes it")
    return [1]


def typed_cases(df: "Any") -> "Any":
    """``df`` (a case table read as text or as pandas guessed) with :data:`BOOL_COLUMNS` booleans and
    :data:`TEXT_COLUMNS` text (``""`` where empty), in place; returned for chaining."""
    for col in BOOL_COLUMNS:
        if col in df.columns:
            df[col] = as_bool(df[col], col)
    for col in TEXT_COLUMNS:
        if col in df.columns:
            df[col] = [v if isinstance(v, str) else "" if v is None or v != v else str(v) for v in df[col]]
    return df


__all__ = ["BLOCK_COLUMNS", "BOOL_COLUMNS", "CASES_FILE", "CONTACT_COLUMNS", "IDENTITY_EXCLUDED", "IM_COLUMNS", "PLAN_COLUMNS", "PULSE_COLUMNS",
           "MEASURE_UNITS", "OTHER_REASON", "SOURCE_COLUMN", "UNITS", "units_of", "units_row", "PulseCase",
           "RECORD_COLUMNS",
           "RESULT_COLUMNS", "RecordCase", "TEXT_COLUMNS", "as_bool", "case_table", "failed_row", "read_cases", "reason_code", "result_row",
           "typed_cases", "write_cases_csv"]
