"""A hard cap on the tasks (processes and threads) of one worker, even when run as root.

RLIMIT_NPROC does not bind root (the kernel exempts uid 0 whatever its namespace), and CI
runs as root, so a thread bomb needs another limit. The kernel's own is the cgroup `pids`
controller: the parent puts each worker into a cgroup of its own with `pids.max`. Where
no writable pids hierarchy exists (a normal user, most containers), the worker's
RLIMIT_NPROC inside its own user namespace binds instead, and the parent's watchdog
(`count_tasks`) stops a worker whose task count runs away.

The cgroup is also how leftovers are found: it holds every process a worker forked, and
its name records the parent (`arise-worker-PARENT.TICKS-PID`, see `lineage`). Removing
one kills what is still in it first (`cgroup.kill`, or SIGKILL to each member on cgroup
v1), so a worker of a killed run cannot outlive the next run's start.
"""

from __future__ import annotations

import contextlib
import signal
import time
from dataclasses import dataclass
from pathlib import Path

import psutil

from arise.validate.lineage import ParentMark, own_mark

MAX_TASKS = 256
PREFIX = "arise-worker-"
EMPTY_WAIT = 2.0  # seconds for killed members to leave their cgroup

_HIERARCHIES = (
    Path("/sys/fs/cgroup/pids"),  # cgroup v1
    Path("/sys/fs/cgroup"),
)  # cgroup v2, when pids is enabled below the root


@dataclass(frozen=True)
class TaskLimit:
    """A pids cgroup holding one worker; release it once the worker is done with."""

    folder: Path

    def describe(self) -> str:
        return f"tasks: cgroup pids.max={MAX_TASKS} ({self.folder})"

    def release(self) -> None:
        """Kill whatever is still in the cgroup (a child that escaped its process group),
        then remove it."""
        remove_cgroup(self.folder)


def _usable(root: Path) -> bool:
    if root.name == "pids":
        return (root / "cgroup.procs").exists()
    controls = root / "cgroup.subtree_control"
    try:
        return "pids" in controls.read_text().split()
    except OSError:
        return False


def limit_tasks(pid: int, owner: ParentMark | None = None) -> TaskLimit | None:
    """Cap the tasks of process `pid` and its descendants; None where we cannot.
    `owner` (default: this process) is the parent the cgroup's name records."""
    owner = owner or own_mark()
    for root in _HIERARCHIES:
        if not _usable(root):
            continue
        folder = root / f"{PREFIX}{owner}-{pid}"
        try:
            folder.mkdir(exist_ok=True)
            (folder / "pids.max").write_text(str(MAX_TASKS))
            (folder / "cgroup.procs").write_text(str(pid))
        except OSError:
            with contextlib.suppress(OSError):
                folder.rmdir()
            continue
        return TaskLimit(folder)
    return None


def count_tasks(pid: int) -> int:
    """Threads of a process and all its descendants (0 once it is gone)."""
    try:
        process = psutil.Process(pid)
        return sum(p.num_threads() for p in [process, *process.children(recursive=True)])
    except psutil.Error:
        return 0


def members(folder: Path) -> list[int]:
    """Pids of the processes in a cgroup (none when it is gone)."""
    try:
        return [int(word) for word in (folder / "cgroup.procs").read_text().split()]
    except (OSError, ValueError):
        return []


def _in_cgroup(process: psutil.Process, folder: Path) -> bool:
    try:
        lines = Path(f"/proc/{process.pid}/cgroup").read_text().splitlines()
    except OSError:
        return False
    return any(line.rsplit(":", 1)[-1] == f"/{folder.name}" for line in lines)


def kill_members(folder: Path) -> None:
    """SIGKILL every process in a cgroup and wait (briefly) until it is empty."""
    with contextlib.suppress(OSError):
        (folder / "cgroup.kill").write_text("1")  # cgroup v2, Linux >= 5.14: atomic
    deadline = time.monotonic() + EMPTY_WAIT
    while (pids := members(folder)) and time.monotonic() < deadline:
        for pid in pids:  # cgroup v1: one by one, again for any forked meanwhile
            with contextlib.suppress(psutil.Error, OSError):
                process = psutil.Process(pid)
                if _in_cgroup(process, folder):  # not a pid reused since it was listed
                    process.send_signal(signal.SIGKILL)
        time.sleep(0.02)


def remove_cgroup(folder: Path) -> None:
    kill_members(folder)
    with contextlib.suppress(OSError):
        folder.rmdir()


def _stale(folder: Path) -> bool:
    """A cgroup whose parent is dead, or (a live parent's) whose worker is gone and
    which is empty. Names without a parent (`arise-worker-PID`, an older arise) are
    stale once their worker is gone."""
    owner_text, _, pid_text = folder.name.removeprefix(PREFIX).rpartition("-")
    if not pid_text.isdigit():
        return False
    worker_gone = not psutil.pid_exists(int(pid_text))
    if not owner_text:
        return worker_gone
    owner = ParentMark.parse(owner_text)
    if owner is None:
        return False
    return not owner.alive() or (worker_gone and not members(folder))


def cleanup_stale() -> None:
    """Kill what is left in the cgroups of dead parents (a parent killed with SIGKILL
    cannot), then remove those cgroups."""
    for root in _HIERARCHIES:
        for folder in root.glob(f"{PREFIX}*") if root.is_dir() else ():
            if folder.is_dir() and _stale(folder):
                remove_cgroup(folder)
