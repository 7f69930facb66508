"""Colombo et al.'s free-rocking experiments on limestone blocks: the shipped per-impact and per-trial
tables, and the impacts as flat arrays.

Data: Colombo, C. et al., *Experimental dataset on the free-rocking response of masonry blocks*,
University of Minho, DOI 10.60756/uminho-jh25, CC BY 4.0; shipped in ``opsrock/data/experiments/``
(its ``SOURCE.md`` gives the attribution, the licence and how the tables were derived). 12 geometries
(B = 0.05 m, H = 0.20-0.75 m), 134 distinct trials, 7,519 impacts, each with its measured
angular-velocity ratio after/before. Validation case ``experiments`` (:mod:`opsrock.validation.experiments`)
analyses them; the restitution law ``colombo-limestone`` (:mod:`opsrock.restitution`) is
fitted on them.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np
import pandas as pd

#: The shipped tables and their SHA-256 digests (opsrock/data/experiments/SOURCE.md).
DATA_FILES: dict[str, tuple[str, str]] = {
    "events": ("limestone-rocking-events.csv", "632e88d735f56ad661035dda7cb703869799cdf73d6e5a4fcbc3290b949cf668"),
    "trials": ("limestone-rocking-trials.csv", "5c53c38e7ca4b92156f8e62a82edd77d6b271c324210685a74fa1e1e1a74fa57"),
}
#: Expected counts: impact rows, trials, distinct trials, geometries.
N_EVENT_ROWS, N_TRIALS, N_UNIQUE_TRIALS, N_GROUPS = 7545, 135, 134, 12
#: The duplicate trial (excluded) and the trial it copies.
DUPLICATE: tuple[str, str] = ("BlockGroup_1_n13", "BlockGroup_1_n7")


def data_file(kind: str) -> Path:
    """Path of a shipped table: ``kind`` is ``"events"`` or ``"trials"`` (no unit)."""
    return Path(str(resources.files("opsrock.data"))) / "experiments" / DATA_FILES[kind][0]


def sha256(path: Path) -> str:
    """SHA-256 hex digest of the file at ``path`` (a path)."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def load_events(path: Path | None = None) -> pd.DataFrame:
    """The per-impact table (every row, the duplicate trial included).

    Parameters
    ----------
    path : pathlib.Path, optional
        The CSV (default the shipped one).
    """
    return pd.read_csv(path or data_file("events"), dtype={"duplicate_of": str})


def load_trials(path: Path | None = None) -> pd.DataFrame:
    """The per-trial table (every row).

    Parameters
    ----------
    path : pathlib.Path, optional
        The CSV (default the shipped one).
    """
    return pd.read_csv(path or data_file("trials"), dtype={"duplicate_of": str})


@dataclass(frozen=True)
class EventArrays:
    """The impacts of a set of trials as flat arrays, rows contiguous per trial and in impact order.

    Parameters
    ----------
    group : ndarray of int
        Geometry 1-12 (no unit).
    trial : ndarray of int
        Trial code, contiguous and non-decreasing (no unit); a resample numbers its draws afresh.
    event : ndarray of int
        Impact number within the trial, 1..n (no unit).
    ratio : ndarray
        Measured angular-velocity ratio after/before (dimensionless).
    e_R : ndarray
        Housner's ratio of the trial's geometry (dimensionless).
    alpha : ndarray
        Slenderness ``atan(B/H)`` (rad).
    product : ndarray
        Running product of ``ratio`` within the trial (dimensionless).
    """

    group: np.ndarray
    trial: np.ndarray
    event: np.ndarray
    ratio: np.ndarray
    e_R: np.ndarray
    alpha: np.ndarray
    product: np.ndarray

    @property
    def q(self) -> np.ndarray:
        """``ratio / e_R`` per impact (dimensionless)."""
        return self.ratio / self.e_R

    def take(self, rows: np.ndarray, trial: np.ndarray) -> "EventArrays":
        """The rows ``rows`` (indices, no unit) relabelled with trial codes ``trial`` (no unit)."""
        return EventArrays(self.group[rows], trial, self.event[rows], self.ratio[rows], self.e_R[rows],
                           self.alpha[rows], self.product[rows])


def analysis_arrays(events: pd.DataFrame, keep_duplicate: bool = False) -> EventArrays:
    """The impacts analysed: the duplicate trial dropped (unless ``keep_duplicate``), sorted.

    Parameters
    ----------
    events : pandas.DataFrame
        The per-impact table (:func:`load_events`).
    keep_duplicate : bool
        Keep the rows of the duplicate trial (only to show that dropping it changes nothing).
    """
    ev = events if keep_duplicate else events[events["duplicate_of"].isna()]
    ev = ev.sort_values(["group", "trial", "event"], kind="stable")
    code = pd.factorize(ev["source_id"])[0]
    ratio = ev["measured_source_angular_ratio"].to_numpy(float)
    product = ev.assign(r=ratio).groupby("source_id", sort=False)["r"].cumprod().to_numpy(float)
    b, h = ev["B_m"].to_numpy(float), ev["H_m"].to_numpy(float)
    return EventArrays(ev["group"].to_numpy(int), code, ev["event"].to_numpy(int), ratio,
                       ev["predicted_ideal_angular_ratio"].to_numpy(float), np.arctan(b / h), product)


__all__ = ["DATA_FILES", "DUPLICATE", "N_EVENT_ROWS", "N_GROUPS", "N_TRIALS", "N_UNIQUE_TRIALS", "EventArrays",
           "analysis_arrays", "data_file", "load_events", "load_trials", "sha256"]
