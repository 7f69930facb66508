"""What many test modules share, importable from any folder of the suite (``pythonpath = ["tests"]`` in
pyproject.toml): the checkout's paths and a runner for the real console script.

Fixtures built on these live in ``conftest.py``; this module holds plain names and functions, so that
module-level tables (parametrised cases) can use them too.
"""

from __future__ import annotations

import glob
import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Mapping, Sequence

#: The checkout (the folder that holds ``opsrock/`` and ``tests/``), wherever it was cloned.
ROOT = Path(__file__).resolve().parents[1]
#: The package's shipped data.
DATA = ROOT / "opsrock" / "data"
#: The shipped blocks library.
BLOCKS = DATA / "blocks.toml"
#: The shipped scenes.
SCENES = DATA / "scenes"
#: Test data of the suite itself.
TEST_DATA = ROOT / "tests" / "data"
#: The console script of the environment that runs the tests (``python -m opsrock.cli`` where absent).
OPSROCK = Path(sys.executable).parent / "opsrock"


#: Root reads and writes whatever the permission bits say (CAP_DAC_OVERRIDE, CAP_DAC_READ_SEARCH); a test of
#: a read-only or unreadable path runs opsrock without those two capabilities (util-linux ``setpriv``), as
#: the same user: so the checkout and its venv stay reachable wherever the clone sits (a 0700 folder too),
#: where running as another user ('nobody') could not even start the interpreter.
WITHOUT_DAC = ["setpriv", "--inh-caps=-dac_override,-dac_read_search",
               "--bounding-set=-dac_override,-dac_read_search", "--"]


def load_tool(name: str):
    """The checkout's ``tools/<name>.py`` as a module (the tools are scripts, not part of the package)."""
    spec = importlib.util.spec_from_file_location(name, ROOT / "tools" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def permissions_bind_root() -> bool:
    """Whether :func:`opsrock_command` can make permission bits bind this user: not root, or root with
    ``setpriv`` to drop the capabilities that ignore them."""
    return os.geteuid() != 0 or shutil.which("setpriv") is not None


def opsrock_command(args: Sequence[str], bound_by_permissions: bool = False) -> list[str]:
    """The command line that runs ``opsrock ARGS`` through the installed console script; with
    ``bound_by_permissions``, under root without the capabilities that ignore permission bits
    (:data:`WITHOUT_DAC`; other users are bound anyway)."""
    head = [str(OPSROCK)] if OPSROCK.exists() else [sys.executable, "-m", "opsrock.cli"]
    cmd = [*head, *map(str, args)]
    return [*WITHOUT_DAC, *cmd] if bound_by_permissions and os.geteuid() == 0 else cmd


#: The start of the line a compiled solver prints on stderr when its numba kernel is about to be compiled from an
#: empty cache (:func:`opsrock.solvers._compile.announce_compile`).
COMPILE_NOTICE = "opsrock: compiling the "


def without_compile_notice(stderr: str) -> str:
    """``stderr`` without the compile notice: whether a test's run meets a cold numba cache depends on how far
    the suite's warm-up (conftest.py) has got, so a test of a quiet stderr leaves that line out."""
    return "".join(x for x in stderr.splitlines(keepends=True) if not x.startswith(COMPILE_NOTICE))


def run_opsrock(args: Sequence[str], cwd: str | os.PathLike | None = None, *, timeout: float = 120,
                env: Mapping[str, str] | None = None, bound_by_permissions: bool = False
                ) -> subprocess.CompletedProcess:
    """Run ``opsrock ARGS`` in ``cwd``, text output captured, no standard input; ``env`` is the whole
    environment (None: this one); ``bound_by_permissions``: see :func:`opsrock_command`."""
    return subprocess.run(opsrock_command(args, bound_by_permissions), cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, stdin=subprocess.DEVNULL, env=None if env is None else dict(env))


#: A record scene of the shipped bookcase and wardrobe with housner_fast, records in g at 0.01 s: format it
#: with ``name``, ``blocks`` (a blocks file), ``files`` (a TOML list of record paths) and ``levels`` (the IDA levels
#: of pfa_ratio, a TOML list or table).
RECORD_SCENE = """name = "{name}"
blocks = "{blocks}"
select = ["bookcase", "wardrobe"]
[solver]
name = "housner_fast"
[records]
files = {files}
units = "g"
dt = 0.01
ground = true
[records.intensity]
method = "ida"
measure = "pfa_ratio"
levels = {levels}
"""

#: Two blocks on a floor with friction 0.4: a stocky crate that slides, a slender shelf that rocks and slides.
FRICTION_BLOCKS = """
[[block]]
name = "crate"
width = 0.9
height = 1.2
reason = "stocky: slides before it could rock"
friction = 0.4

[[block]]
name = "shelf"
width = 0.5
height = 1.8
reason = "slender: rocks, overturns and slides"
friction = 0.4
"""

FRICTION_SCENE = """
name = "friction-records"
blocks = "blocks.toml"
[solver]
name = "{solver}"
[records]
glob = "rec/*.txt"
units = "g"
dt = 0.01
ground = true
[records.intensity]
method = "ida"
measure = "pfa_g"
levels = [0.5, 0.8, 1.2, 1.8, 2.6]
"""


def write_friction_campaign(folder: Path, solver: str = "friction") -> Path:
    """Write the inputs of a small record campaign with friction into ``folder``: ``rec/`` (six synthetic
    ground motions, a noisy sine of 1 to 3 Hz in a 6-s envelope, peak 1 g), ``blocks.toml``
    (:data:`FRICTION_BLOCKS`) and ``scene.toml`` (five PFA levels, 60 cases, solver ``solver``); the scene's path."""
    import numpy as np

    (folder / "rec").mkdir()
    rng = np.random.default_rng(0)
    t = np.arange(0.0, 6.0, 0.01)
    for k in range(6):
        a = np.sin(np.pi * t / t[-1]) ** 2 * (np.sin(2 * np.pi * (1.0 + 0.4 * k) * t) + 0.3 * rng.normal(size=t.size))
        np.savetxt(folder / "rec" / f"r{k}.txt", a / np.abs(a).max())
    (folder / "blocks.toml").write_text(FRICTION_BLOCKS)
    scene = folder / "scene.toml"
    scene.write_text(FRICTION_SCENE.format(solver=solver))
    return scene


def drawn_figure(module, fn, *args):
    """The matplotlib figure that ``fn(*args)`` (a figure function of ``module``, which imported
    ``save_figure``) draws, read back instead of written: ``module.save_figure`` is swapped for one that keeps
    the figure, then restored; the figure is closed (its artists stay readable)."""
    import matplotlib.pyplot as plt

    kept = {}
    real = module.save_figure
    module.save_figure = lambda fig, path: kept.setdefault("fig", fig) and path
    try:
        fn(*args)
    finally:
        module.save_figure = real
    plt.close(kept["fig"])
    return kept["fig"]


def library_mapped(pid: int, library: str) -> bool:
    """Has process ``pid`` loaded a shared library whose path contains ``library`` (``/proc/<pid>/maps``)? A
    readiness poll for "the command's imports are under way" (False once the process is gone)."""
    try:
        return library in Path(f"/proc/{pid}/maps").read_text()
    except OSError:
        return False



def case_rows(path: str | os.PathLike) -> list[dict[str, str]]:
    """The cases of a campaign's ``cases.csv`` as text, column -> cell, as written; asserts that its second row is
    the units row (first cell ``Units``, opsrock.campaign.cases.UNITS) and leaves it out."""
    import csv

    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert rows and next(iter(rows[0].values())) == "Units", f"{path}: no units row"
    return rows[1:]


#: Sources outside a kernel's own package that its compiled code reads (module-level constants numba freezes into
#: the machine code).
SHARED_KERNEL_SOURCES = ("constants.py", "limits.py", "solvers/forcing.py", "solvers/jitable.py", "solvers/scratch.py",
                         "solvers/status.py")


def drop_stale_kernels(package: Path) -> list[Path]:
    """Delete the numba cache entries of ``package`` (each folder's, ``solvers/rigid3d/__pycache__``) older than one
    of their folder's sources or of :data:`SHARED_KERNEL_SOURCES`; returns the index files deleted. numba checks a cached dispatcher against its own module's stamp only, so after
    an edit of a module its entry point calls (``rigid3d/step.py`` beside ``rigid3d/kernel.py``'s ``run``) a
    developer's tree would test the old machine code; a fresh clone has no cache and an installed release new files
    (docs/guide/layout.md). An index whose dispatcher has moved (its name holds the line) goes too: numba no longer
    reads it."""
    shared = max((package / name).stat().st_mtime for name in SHARED_KERNEL_SOURCES)
    dropped = []
    for cache in sorted({index.parent for index in package.rglob("__pycache__/*.nbi")}):
        newest = max([shared, *(p.stat().st_mtime for p in cache.parent.glob("*.py"))])
        for index in cache.glob("*.nbi"):
            if index.stat().st_mtime < newest:
                stem = index.name[:-len(".nbi")]
                for entry in (index, *cache.glob(f"{glob.escape(stem)}.*.nbc")):
                    entry.unlink(missing_ok=True)
                dropped.append(index)
    return dropped
