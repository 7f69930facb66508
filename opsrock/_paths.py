"""Checks of output paths given on the command line, made before any work starts.

Each raises ``ValueError`` with one line naming the argument and the path, so that a bad path is
refused up front instead of failing after the computation, half-written. Writability is probed by
creating and removing a file, which is right for every user, root included (``os.access`` says
yes to root on a read-only folder it could not write to on a read-only mount, and the reverse).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path


def _probe_writable(name: str, shown: str, folder: Path) -> None:
    try:
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".opsrock-write-probe-")
    except OSError as exc:
        raise ValueError(f"{name} {shown!r}: cannot write in folder {str(folder)!r} ({exc.strerror})") from None
    os.close(fd)
    os.unlink(probe)


def output_file(name: str, path: str | os.PathLike, suffix: str | None = None) -> Path:
    """Check that ``path`` can be written as a file, in an existing folder; return it.

    Parameters
    ----------
    name : str
        Argument name for the message (``"--plot"``).
    path : str or path-like
        The file to write.
    suffix : str, optional
        Required suffix, case-insensitive (``".png"``).
    """
    p = Path(path)
    shown = str(path)
    if suffix is not None and p.suffix.lower() != suffix:
        raise ValueError(f"{name} must name a {suffix} file, got {shown!r}")
    if p.is_dir():
        raise ValueError(f"{name} {shown!r} is a folder; give a file name")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        raise ValueError(f"{name} {shown!r}: folder {str(parent)!r} does not exist")
    _probe_writable(name, shown, parent)
    return p


def output_dir(name: str, path: str | os.PathLike) -> Path:
    """Check that ``path`` is, or can be created as, a writable folder; return it.

    Missing folders are not created here (the caller creates them once the inputs are known
    to be good); the nearest existing ancestor must be a writable folder.
    """
    p = Path(path)
    shown = str(path)
    if p.exists() and not p.is_dir():
        raise ValueError(f"{name} {shown!r} is a file, not a folder")
    ancestor = p
    while not ancestor.exists():
        if ancestor.parent == ancestor:
            break
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise ValueError(f"{name} {shown!r}: {str(ancestor)!r} is a file, not a folder")
    _probe_writable(name, shown, ancestor)
    return p


__all__ = ["output_dir", "output_file"]
