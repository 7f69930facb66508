"""Pulse scenes: blocks x a grid of pulses, the ``[grid]`` and ``[pulse]`` tables of a scene.

Layout (see ``docs/guide/scenes.md``)::

    [pulse]                             # optional, default shape "one-sine"
    shape = "one-sine"                  # rectangular, half-sine, one-sine, one-cosine, ricker

    [grid.freq_ratio]                   # omega_p / p (IM1): start/stop/num ...
    start = 0.5
    stop = 10.0
    num = 10
    [grid.pfa_ratio]                    # PFA / (g tan alpha) (IM2): ... or an explicit list
    values = [1.0, 2.0, 5.0]

Each case is one block under one pulse; its stable id is ``<block>/f<i>/a<j>`` with 1-based,
zero-padded indices into the two axes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence

from opsrock.campaign.cases import PULSE_COLUMNS, PulseCase
from opsrock.campaign.toml import TomlFile
from opsrock.errors import OpsrockError
from opsrock.excitations import PULSE_SHAPES, pulse_class

_GRID_AXES = ("freq_ratio", "pfa_ratio")


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
    """

    freq_ratio: tuple[float, ...]
    pfa_ratio: tuple[float, ...]
    shape: str = "one-sine"

    #: Columns of the scene's ``cases.csv``.
    columns = PULSE_COLUMNS

    @property
    def size(self) -> int:
        """Number of pulses per block."""
        return len(self.freq_ratio) * len(self.pfa_ratio)

    @property
    def n_per_block(self) -> int:
        """Cases per block."""
        return self.size

    def fingerprint(self) -> dict[str, Any]:
        """The grid's part of the scene's fingerprint (the shape only when it is not the paper's, so the
        digests of the scenes written before the pulse family, and their stores, stay valid)."""
        return {"freq_ratio": list(self.freq_ratio), "pfa_ratio": list(self.pfa_ratio),
                **({"pulse_shape": self.shape} if self.shape != "one-sine" else {})}

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
        out = []
        for spec in blocks:
            for i, fr in enumerate(self.freq_ratio, start=1):
                for j, ar in enumerate(self.pfa_ratio, start=1):
                    case_id = f"{spec.name}/f{i:0{wf}d}/a{j:0{wa}d}"
                    block = spec.block_for(case_id)
                    out.append(PulseCase(case_id=case_id, block=block,
                                         pulse=make(block, pfa_ratio=ar, freq_ratio=fr), freq_ratio=fr,
                                         pfa_ratio=ar, pfv_convention=pfv_convention))
        return out


def parse_grid(f: TomlFile, grid_raw: Any, pulse_raw: Any, blocks: Sequence[Any]) -> Grid:
    """Validate the ``[grid]`` and ``[pulse]`` tables of the scene file ``f`` for ``blocks``: every pulse
    of the grid must be a valid pulse for every block."""
    shape = _pulse_shape(f, pulse_raw)
    f.table("grid", grid_raw, "a table with [grid.freq_ratio] and [grid.pfa_ratio]")
    f.keys("grid", grid_raw, allowed=set(_GRID_AXES), required=set(_GRID_AXES))
    grid = Grid(**{axis: f.axis(f"grid.{axis}", grid_raw[axis]) for axis in _GRID_AXES}, shape=shape)
    _check_pulses(f, blocks, grid)
    return grid


def _pulse_shape(f: TomlFile, pulse_raw: Any) -> str:
    f.table("pulse", pulse_raw, "a table [pulse] with shape")
    f.keys("pulse", pulse_raw, allowed={"shape"})
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


__all__ = ["Grid", "parse_grid"]
