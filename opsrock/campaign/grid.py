"""Pulse scenes: blocks x a grid of pulses, the ``[grid]`` and ``[pulse]`` tables of a scene.

Layout (see ``docs/guide/scenes.md``)::

    [pulse]                             # optional, default shape "one-sine"
    shape = "one-sine"                  # rectangular, half-sine, one-sine, one-cosine, ricker
    azimuth = [0, 30, 45]               # optional (three dimensions, solver rigid3d): the block's azimuth in
                                        # plan, deg in [-360, 360], from the pulse's direction to its width;
                                        # a number or a list (a third axis of the grid)

    [grid.freq_ratio]                   # omega_p / p (IM1): start/stop/num ...
    start = 0.5
    stop = 10.0
    num = 10
    [grid.pfa_ratio]                    # PFA / (g tan alpha) (IM2): ... or an explicit list
    values = [1.0, 2.0, 5.0]

Each case is one block under one pulse; its stable id is ``<block>/f<i>/a<j>`` with 1-based,
zero-padded indices into the two axes, and ``/z<k>`` after it, ``k`` the index into ``azimuth``, when the
scene gives azimuths.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Sequence

from opsrock.campaign.cases import PULSE_COLUMNS, PulseCase
from opsrock.campaign.toml import MAX_AXIS_POINTS, TomlFile
from opsrock.errors import OpsrockError
from opsrock.excitations import PULSE_SHAPES, pulse_class

_GRID_AXES = ("freq_ratio", "pfa_ratio")

#: Largest |azimuth| of a block in plan (deg; :class:`opsrock.excitations.plan.PlanMotion`).
MAX_AZIMUTH: float = 360.0


def parse_azimuths(f: TomlFile, where: str, raw: Any) -> tuple[float, ...]:
    """The azimuths (deg) of a scene: a number or a non-empty list of distinct finite numbers in [-360, 360]
    (at most :data:`~opsrock.campaign.toml.MAX_AXIS_POINTS`); the refusal names ``where`` and the value."""
    values = raw if isinstance(raw, list) else [raw]
    if not values:
        raise f.error(where, raw, "must be an angle in degrees or a non-empty list of them")
    if len(values) > MAX_AXIS_POINTS:
        raise f.error(where, f"<{len(values)} values>", f"must give <= {MAX_AXIS_POINTS} values (MAX_AXIS_POINTS)")
    for v in values:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or abs(v) > MAX_AZIMUTH:
            raise f.error(where, v, f"must be an angle in degrees within [-{MAX_AZIMUTH:g}, {MAX_AZIMUTH:g}]")
    if len(set(values)) != len(values):
        raise f.error(where, raw, "names an azimuth twice")
    return tuple(float(v) for v in values)


def azimuth_id(k: int, n: int) -> str:
    """The azimuth part of a case id: ``/z<k>``, ``k`` 1-based and zero-padded to at least two digits."""
    return f"/z{k:0{max(2, len(str(n)))}d}"


@dataclass(frozen=True)
class Grid:
    """The pulse grid, in the dimensionless ratios of the overturning spectrum: the design of a pulse
    scene (the record scene's is :class:`opsrock.campaign.records.RecordSet`).

    Parameters
    ----------
    freq_ratio : tuple of float
        ``omega_p / p`` values (dimensionless, IM1), > 0, in run order.
    pfa_ratio : tuple of float
        ``PFA / (g tan alpha)`` values (dimensionless, IM2), > 0, in run order.
    shape : str
        Pulse shape, a key of :data:`opsrock.excitations.PULSE_SHAPES` (``[pulse] shape``).
    azimuth : tuple of float
        The block's azimuths in plan (deg, ``[pulse] azimuth``): a third axis; empty: planar cases.
    """

    freq_ratio: tuple[float, ...]
    pfa_ratio: tuple[float, ...]
    shape: str = "one-sine"
    azimuth: tuple[float, ...] = ()

    #: Columns of the scene's ``cases.csv``.
    columns = PULSE_COLUMNS

    @property
    def size(self) -> int:
        """Number of pulses per block (times the azimuths)."""
        return len(self.freq_ratio) * len(self.pfa_ratio) * max(1, len(self.azimuth))

    @property
    def n_per_block(self) -> int:
        """Cases per block."""
        return self.size

    def fingerprint(self) -> dict[str, Any]:
        """The grid's part of the scene's fingerprint (the shape only when it is not the paper's, so the
        digests of the scenes written before the pulse family, and their stores, stay valid)."""
        return {"freq_ratio": list(self.freq_ratio), "pfa_ratio": list(self.pfa_ratio),
                **({"pulse_shape": self.shape} if self.shape != "one-sine" else {}),
                **({"azimuth": list(self.azimuth)} if self.azimuth else {})}

    def cases(self, blocks: Sequence[Any], pfv_convention: str = "amplitude") -> list[PulseCase]:
        """Every case: by block (in order), then ``freq_ratio``, then ``pfa_ratio``.

        Parameters
        ----------
        blocks : sequence of BlockSpec
        pfv_convention : str
            PFV convention of IM3 and IM8 in the cases' rows.
        """
        nf, na = len(self.freq_ratio), len(self.pfa_ratio)
        wf, wa = max(2, len(str(nf))), max(2, len(str(na)))
        make = pulse_class(self.shape).from_ratios
        turns = [(azimuth_id(k, len(self.azimuth)), z) for k, z in enumerate(self.azimuth, start=1)] or [("", None)]
        out = []
        for spec in blocks:
            for i, fr in enumerate(self.freq_ratio, start=1):
                for j, ar in enumerate(self.pfa_ratio, start=1):
                    for tail, z in turns:
                        case_id = f"{spec.name}/f{i:0{wf}d}/a{j:0{wa}d}{tail}"
                        block = spec.block_for(case_id)
                        out.append(PulseCase(case_id=case_id, block=block,
                                             pulse=make(block, pfa_ratio=ar, freq_ratio=fr), freq_ratio=fr,
                                             pfa_ratio=ar, pfv_convention=pfv_convention, azimuth=z))
        return out


def parse_grid(f: TomlFile, grid_raw: Any, pulse_raw: Any, blocks: Sequence[Any]) -> Grid:
    """Validate the ``[grid]`` and ``[pulse]`` tables of the scene file ``f`` for ``blocks``: every pulse
    of the grid must be a valid pulse for every block."""
    shape = _pulse_shape(f, pulse_raw)
    f.table("grid", grid_raw, "a table with [grid.freq_ratio] and [grid.pfa_ratio]")
    f.keys("grid", grid_raw, allowed=set(_GRID_AXES), required=set(_GRID_AXES))
    azimuth = parse_azimuths(f, "pulse.azimuth", pulse_raw["azimuth"]) if "azimuth" in pulse_raw else ()
    grid = Grid(**{axis: f.axis(f"grid.{axis}", grid_raw[axis]) for axis in _GRID_AXES}, shape=shape,
                azimuth=azimuth)
    _check_pulses(f, blocks, grid)
    return grid


def _pulse_shape(f: TomlFile, pulse_raw: Any) -> str:
    f.table("pulse", pulse_raw, "a table [pulse] with shape")
    f.keys("pulse", pulse_raw, allowed={"shape", "azimuth"})
    shape = pulse_raw.get("shape", "one-sine")
    if shape not in PULSE_SHAPES:
        raise f.error("pulse.shape", shape, f"must be one of {', '.join(map(repr, PULSE_SHAPES))}")
    return shape


def _check_pulses(f: TomlFile, blocks: Sequence[Any], grid: Grid) -> None:
    """``PFA`` and ``omega_p`` grow with their ratios, so the extreme ratios of each axis decide."""
    for spec in blocks:
        block = spec.block
        for axis in _GRID_AXES:
            values = getattr(grid, axis)
            for ratio in (min(values), max(values)):
                # PFA depends only on pfa_ratio and omega_p only on freq_ratio: hold the other at 1.
                other = {a: 1.0 for a in _GRID_AXES if a != axis}
                try:
                    pulse_class(grid.shape).from_ratios(block, **{axis: ratio}, **other)
                except OpsrockError as exc:
                    raise f.error(f"grid.{axis}", ratio, f"gives no valid pulse for block {spec.name!r}: {exc}") from None


__all__ = ["Grid", "MAX_AZIMUTH", "azimuth_id", "parse_azimuths", "parse_grid"]
