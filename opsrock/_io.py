"""Atomic file writes: every output goes through a temporary file in the same folder and a rename,
so an interrupted run never leaves a half-written file. Data files keep full precision."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Callable

import pandas as pd


def atomic_write(path: Path, write: Callable[[Any], None], *, binary: bool = False, durable: bool = True) -> None:
    """Write ``path`` by ``write(file_handle)`` through a temporary file and an atomic rename.

    Parameters
    ----------
    path : Path
        Target file.
    write : callable
        Writes the content to the open handle.
    binary : bool, optional
        Open in binary mode.
    durable : bool, optional
        ``fsync`` the file and the folder, so the rename survives a power cut (the campaign's
        store needs it; reports do not).
    """
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    try:
        with (open(tmp, "wb") if binary else open(tmp, "w", newline="", encoding="utf-8")) as fh:
            write(fh)
            if durable:
                fh.flush()
                os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
    if durable:
        dir_fd = os.open(path.parent, os.O_RDONLY)
        try:
            os.fsync(dir_fd)
        finally:
            os.close(dir_fd)


def atomic_text(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically."""
    atomic_write(Path(path), lambda fh: fh.write(text), durable=False)


def atomic_csv(path: Path, df: pd.DataFrame) -> None:
    """Write ``df`` (no index) to ``path`` atomically, at full precision (``repr`` of every float)."""
    atomic_write(Path(path), lambda fh: df.to_csv(fh, index=False), durable=False)
