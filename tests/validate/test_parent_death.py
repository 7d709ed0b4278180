"""Workers die with their parent: a killed `arise check` leaves no process running a script,
and what it leaves on disk (a scratch folder, a cgroup) the next pool removes.

The scripts in tests/data/parent_kill/ swallow every interrupt, the worker's own time-out
included, so only a kill ends them: before, they kept a core busy after their parent
was killed.
"""

from __future__ import annotations

import signal
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

import psutil
import pytest

from arise.validate import WorkerPool
from arise.validate.lineage import ParentMark, is_worker, own_mark, recorded_parent
from arise.validate.pool import SCRATCH_PREFIX
from arise.validate.process_limit import PREFIX
from tests.conftest import DATA, REPO

ARISE = Path(sys.executable).parent / "arise"
SCRIPTS = DATA / "parent_kill"
HIERARCHIES = (Path("/sys/fs/cgroup/pids"), Path("/sys/fs/cgroup"))
START_LIMIT = 180.0  # seconds for a cold worker to start and reach the loop on a busy machine
GONE_LIMIT = 10.0  # seconds for the killed tree to disappear


def _workers(parent: psutil.Process) -> list[psutil.Process]:
    """Fork servers started by `parent`."""
    found = []
    for child in parent.children():
        try:
            if is_worker(child.cmdline()):
                found.append(child)
        except psutil.Error:
            continue
    return found


def _wait_for_script(parent: psutil.Process) -> tuple[psutil.Process, psutil.Process]:
    """The fork server and the child running the script, once the script has spun for a
    while (it is then past the gate and inside its endless loop)."""
    deadline = time.monotonic() + START_LIMIT
    while time.monotonic() < deadline:
        for server in _workers(parent):
            try:
                for child in server.children():
                    if sum(child.cpu_times()[:2]) > 1.5:
                        return server, child
            except psutil.Error:
                continue
        assert parent.is_running(), "arise check ended before the script ran"
        time.sleep(0.2)
    raise AssertionError("the worker never ran the script")


def _gone(process: psutil.Process) -> bool:
    try:
        return not process.is_running() or process.status() == psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return True


def _wait_gone(processes: list[psutil.Process]) -> list[psutil.Process]:
    """Those still running after GONE_LIMIT seconds."""
    deadline = time.monotonic() + GONE_LIMIT
    while (left := [p for p in processes if not _gone(p)]) and time.monotonic() < deadline:
        time.sleep(0.1)
    return left


def _cgroups_of(server: psutil.Process) -> list[Path]:
    return [
        folder
        for root in HIERARCHIES
        if root.is_dir()
        for folder in root.glob(f"{PREFIX}*-{server.pid}")
    ]


def _scratch_of(parent_pid: int) -> list[Path]:
    return list(Path(tempfile.gettempdir()).glob(f"{SCRATCH_PREFIX}{parent_pid}.*"))


def _start_check(script: Path) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [str(ARISE), "check", str(script), "--timeout", "60"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=REPO,
        start_new_session=True,  # our signals go to it alone, never to this test
    )


@pytest.mark.slow
@pytest.mark.parametrize("script", ["top_level_loop.scenic", "behavior_loop.scenic"])
def test_sigkill_of_the_parent_kills_its_workers(script: str) -> None:
    arise = _start_check(SCRIPTS / script)
    try:
        parent = psutil.Process(arise.pid)
        server, child = _wait_for_script(parent)
        assert recorded_parent(server.cmdline()) == ParentMark.of(arise.pid)
        assert _scratch_of(arise.pid), "the run has a scratch folder to leave behind"
        cgroups = _cgroups_of(server)
        arise.kill()  # no chance to clean up
        arise.communicate(timeout=30)
    finally:
        if arise.poll() is None:
            arise.kill()
            arise.wait()
    assert _wait_gone([server, child]) == [], "a worker outlived its killed parent"
    WorkerPool(size=1).close()  # the next run's start sweeps what the killed one left
    assert _scratch_of(arise.pid) == []
    assert [folder for folder in cgroups if folder.exists()] == []


@pytest.mark.slow
def test_sigterm_stops_a_check_at_once_and_cleans_up() -> None:
    arise = _start_check(SCRIPTS / "behavior_loop.scenic")
    try:
        parent = psutil.Process(arise.pid)
        server, child = _wait_for_script(parent)
        cgroups = _cgroups_of(server)
        arise.send_signal(signal.SIGTERM)
        _, stderr = arise.communicate(timeout=15)  # not after the 60 s time-out
    finally:
        if arise.poll() is None:
            arise.kill()
            arise.wait()
    assert arise.returncode == 128 + signal.SIGTERM
    assert "Traceback" not in stderr, stderr
    assert _wait_gone([server, child]) == []
    # Cleaned up by the run itself, not left for the next one.
    assert _scratch_of(arise.pid) == []
    assert [folder for folder in cgroups if folder.exists()] == []


PARENT_WITH_BACKGROUND_POOL = textwrap.dedent(
    """
    import time
    from arise.validate import WorkerPool

    pool = WorkerPool(size=1)
    pool.warm_in_background()  # started by a thread that then ends: no PDEATHSIG
    pool.wait_warm()
    print("warm", flush=True)
    time.sleep(600)
    """
)


@pytest.mark.slow
def test_a_worker_started_by_a_thread_dies_with_the_process() -> None:
    parent = subprocess.Popen(
        [sys.executable, "-c", PARENT_WITH_BACKGROUND_POOL],
        stdout=subprocess.PIPE,
        text=True,
        cwd=REPO,
        start_new_session=True,
    )
    try:
        assert parent.stdout is not None
        assert parent.stdout.readline().strip() == "warm"
        (server,) = _workers(psutil.Process(parent.pid))
        assert not _gone(server), "the worker died with the thread that started it"
        parent.kill()
        parent.wait()
    finally:
        if parent.poll() is None:
            parent.kill()
            parent.wait()
    assert _wait_gone([server]) == []


@pytest.mark.slow
def test_a_process_that_looks_like_an_orphaned_worker_is_killed_by_the_sweep() -> None:
    from arise.validate.pool import sweep_scratch

    gone = subprocess.Popen([sys.executable, "-c", "pass"])
    gone.wait()
    sleep = "import time; time.sleep(60)"
    command = [sys.executable, "-c", sleep, "-m", "arise.validate.worker", "--parent"]
    orphan = subprocess.Popen([*command, f"{gone.pid}.1"])
    ours = subprocess.Popen([*command, str(own_mark())])
    try:
        killed = sweep_scratch()
        # Killed by this sweep, or by a pool another test process started meanwhile.
        assert orphan.wait(10) == -signal.SIGKILL
        assert ours.pid not in killed and ours.poll() is None, "a live parent's worker"
    finally:
        for process in (orphan, ours):
            process.kill()
            process.wait()


def test_the_parent_death_signal_survives_the_namespace_steps(tmp_path: Path) -> None:
    """prctl(PR_SET_PDEATHSIG) is cleared when a process changes identity; entering a user
    namespace of our own must not count as one, or workers would not die with us."""
    code = textwrap.dedent(
        f"""
        import ctypes, signal
        from pathlib import Path
        from arise.validate.sandbox import enter_namespaces

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG
        problem = enter_namespaces(Path({str(tmp_path)!r}), 1 << 20, network=False)
        value = ctypes.c_int()
        libc.prctl(2, ctypes.byref(value), 0, 0, 0)  # PR_GET_PDEATHSIG
        print(problem, value.value)
        """
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.split()
    if out[0] != "None":
        pytest.skip(f"no namespaces here: {' '.join(out[:-1])}")
    assert int(out[-1]) == signal.SIGKILL
