"""A hard cap on the tasks (processes and threads) of one worker, even when run as root.

RLIMIT_NPROC does not bind root (the kernel exempts uid 0 whatever its namespace), and CI
runs as root, so a thread bomb needs another limit. The kernel's own is the cgroup `pids`
controller: the parent puts each worker into a cgroup of its own with `pids.max`. Where
no writable pids hierarchy exists (a normal user, most containers), the worker's
RLIMIT_NPROC inside its own user namespace binds instead, and the parent's watchdog
(`count_tasks`) stops a worker whose task count runs away.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass
from pathlib import Path

import psutil

MAX_TASKS = 256

_HIERARCHIES = (
    Path("/sys/fs/cgroup/pids"),  # cgroup v1
    Path("/sys/fs/cgroup"),
)  # cgroup v2, when pids is enabled below the root


@dataclass(frozen=True)
class TaskLimit:
    """A pids cgroup holding one worker; remove it once the worker is gone."""

    folder: Path

    def describe(self) -> str:
        return f"tasks: cgroup pids.max={MAX_TASKS} ({self.folder})"

    def release(self) -> None:
        with contextlib.suppress(OSError):
            self.folder.rmdir()


def _usable(root: Path) -> bool:
    if root.name == "pids":
        return (root / "cgroup.procs").exists()
    controls = root / "cgroup.subtree_control"
    try:
        return "pids" in controls.read_text().split()
    except OSError:
        return False


def limit_tasks(pid: int) -> TaskLimit | None:
    """Cap the tasks of process `pid` and its descendants; None where we cannot."""
    for root in _HIERARCHIES:
        if not _usable(root):
            continue
        folder = root / f"arise-worker-{pid}"
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


def cleanup_stale() -> None:
    """Remove cgroups of workers that no longer exist (a killed parent leaves them)."""
    for root in _HIERARCHIES:
        for folder in root.glob("arise-worker-*") if root.is_dir() else ():
            pid = folder.name.rsplit("-", 1)[-1]
            if pid.isdigit() and not psutil.pid_exists(int(pid)):
                with contextlib.suppress(OSError):
                    folder.rmdir()
