"""Export fitted overturning fragilities in the damage-model CSV form of FEMA P-58 / pelicun.

One component per block, floor and demand (:func:`component_id`), one limit state (``LS1``:
overturned), lognormal: ``Theta_0`` the median, ``Theta_1`` the dispersion ``beta``. Demands are
given in SI units that pelicun knows (``Peak Floor Acceleration`` in ``mps2``, ``Peak Floor
Velocity`` in ``mps``), so no convention of ``g`` enters (pelicun's g is 9.80665 m/s², ours 9.81). ``Demand-Offset`` 0 (the floor the block
stands on) and ``Demand-Directional`` 1 (the block rocks about one axis: use the demand of that
direction). The file loads with ``Assessment.damage.load_model_parameters([path], ids)``.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

from opsrock._files import atomic_write
from opsrock.errors import InputError

#: Our demand column -> (pelicun demand type, pelicun unit).
PELICUN_DEMANDS: dict[str, tuple[str, str]] = {
    "pfa": ("Peak Floor Acceleration", "mps2"),
    "pfv": ("Peak Floor Velocity", "mps"),
}
#: Columns of the exported CSV, in pelicun's order.
COLUMNS: tuple[str, ...] = ("ID", "Incomplete", "Demand-Type", "Demand-Unit", "Demand-Offset",
                            "Demand-Directional", "LS1-Family", "LS1-Theta_0", "LS1-Theta_1")


@dataclass(frozen=True)
class ComponentFragility:
    """One exported component.

    Parameters
    ----------
    component_id : str
        pelicun component ID (:func:`component_id`: ``opsrock.<block>.<floor>.<DEMAND>``).
    demand : str
        ``"pfa"`` or ``"pfv"`` (:data:`PELICUN_DEMANDS`).
    median : float
        Median demand at overturning (m/s² for PFA, m/s for PFV), > 0.
    beta : float
        Lognormal dispersion (dimensionless), > 0.
    """

    component_id: str
    demand: str
    median: float
    beta: float

    def __post_init__(self) -> None:
        if self.demand not in PELICUN_DEMANDS:
            raise InputError(f"demand must be one of {', '.join(PELICUN_DEMANDS)}; got {self.demand!r}")
        for name in ("median", "beta"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"{name} must be positive and finite for {self.component_id}, got {v!r}")


def component_id(block: str, floor: str, demand: str, state: str = "") -> str:
    """``opsrock.<block>.<floor>.<PFA|PFV>``, or ``opsrock.<block>.<floor>.<state>.<PFA|PFV>`` (``state`` e.g.
    ``SLIDE50MM``): a pelicun component has one fragility wherever it stands, and a block's differs by floor,
    so each block gets one component per floor (the floor as the campaign names it: ``ground``,
    ``b3.f2``)."""
    return f"opsrock.{block}.{floor}.{state + '.' if state else ''}{demand.upper()}"


def write_pelicun_csv(components: list[ComponentFragility], path: str | Path) -> Path:
    """Write the components to ``path`` (through a temporary file: nothing half-written)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)

    def write(fh) -> None:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(COLUMNS)
        for c in components:
            dtype, unit = PELICUN_DEMANDS[c.demand]
            w.writerow([c.component_id, 0, dtype, unit, 0, 1, "lognormal", repr(float(c.median)), repr(float(c.beta))])

    atomic_write(path, write, durable=False)
    return path


def read_pelicun_csv(path: str | Path) -> list[ComponentFragility]:
    """Read back a file written by :func:`write_pelicun_csv` (our own reader, for round trips
    without pelicun)."""
    by_type = {v: k for k, v in PELICUN_DEMANDS.items()}
    out = []
    with open(path, newline="") as fh:
        for row in csv.DictReader(fh):
            demand = by_type[(row["Demand-Type"], row["Demand-Unit"])]
            out.append(ComponentFragility(row["ID"], demand, float(row["LS1-Theta_0"]), float(row["LS1-Theta_1"])))
    return out
