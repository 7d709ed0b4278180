"""The task cap of a worker: a pids cgroup where one can be made, the watchdog otherwise."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from arise.validate.lineage import ParentMark, own_mark
from arise.validate.process_limit import (
    MAX_TASKS,
    TaskLimit,
    cleanup_stale,
    count_tasks,
    limit_tasks,
)


@pytest.fixture()
def sleeper() -> subprocess.Popen[bytes]:
    child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
    yield child
    child.kill()
    child.wait()


def test_a_process_gets_its_own_capped_cgroup(sleeper: subprocess.Popen[bytes]) -> None:
    limit = limit_tasks(sleeper.pid)
    if limit is None:
        pytest.skip("no writable pids cgroup here (not root, or no pids controller)")
    try:
        assert (limit.folder / "pids.max").read_text().strip() == str(MAX_TASKS)
        members = (limit.folder / "cgroup.procs").read_text().split()
        assert str(sleeper.pid) in members
        assert "pids.max" in limit.describe()
    finally:
        sleeper.kill()
        sleeper.wait()
        limit.release()
    assert not limit.folder.exists()


def test_tasks_are_counted_across_the_process_tree(sleeper: subprocess.Popen[bytes]) -> None:
    assert count_tasks(sleeper.pid) >= 1
    sleeper.kill()
    sleeper.wait()
    assert count_tasks(sleeper.pid) == 0


def test_stale_cgroups_of_dead_workers_are_removed() -> None:
    child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(0.2)"])
    probe = limit_tasks(child.pid)
    if probe is None:
        child.kill()
        child.wait()
        pytest.skip("no writable pids cgroup here")
    assert child.wait(10) == 0  # the worker is gone; its (empty) cgroup is not
    assert probe.folder.exists()
    cleanup_stale()
    assert not probe.folder.exists()
    assert isinstance(probe, TaskLimit)


def test_scratch_folders_of_dead_parents_are_swept() -> None:
    from arise.validate.pool import SCRATCH_PREFIX, sweep_scratch

    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    leftover = Path(tempfile.mkdtemp(prefix=f"{SCRATCH_PREFIX}{child.pid}-"))
    mine = Path(tempfile.mkdtemp(prefix=f"{SCRATCH_PREFIX}{os.getpid()}-"))
    try:
        sweep_scratch()
        assert not leftover.exists() and mine.exists()
    finally:
        mine.rmdir()


def _dead_mark() -> ParentMark:
    """The mark of a parent that is gone (a pid reused since is another start time)."""
    gone = subprocess.Popen([sys.executable, "-c", "pass"])
    gone.wait()
    return ParentMark(gone.pid, 1)


def test_a_dead_parents_cgroup_is_emptied_then_removed(sleeper: subprocess.Popen[bytes]) -> None:
    limit = limit_tasks(sleeper.pid, _dead_mark())
    if limit is None:
        pytest.skip("no writable pids cgroup here")
    try:
        cleanup_stale()
        assert sleeper.wait(10) == -signal.SIGKILL, "the leftover in it was killed"
        assert not limit.folder.exists()
    finally:
        limit.release()


def test_a_live_parents_cgroup_is_left_alone(sleeper: subprocess.Popen[bytes]) -> None:
    limit = limit_tasks(sleeper.pid)
    if limit is None:
        pytest.skip("no writable pids cgroup here")
    try:
        assert str(own_mark()) in limit.folder.name
        cleanup_stale()
        assert limit.folder.exists() and sleeper.poll() is None
    finally:
        limit.release()
    assert sleeper.wait(10) == -signal.SIGKILL, "release kills what is left in the cgroup"
    assert not limit.folder.exists()
