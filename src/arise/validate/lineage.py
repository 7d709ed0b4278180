"""Who started a validation worker, so that the next run can tell a leftover from a live one.

A parent killed with SIGKILL cannot clean up. Its workers end themselves (they watch
their parent), but should one survive, the next run must know whose it is: the parent
writes its own pid and start time into what it creates (the worker's command line
`--parent PID.TICKS`, its cgroup's and scratch folder's names). A mark whose process is
gone, or whose pid now belongs to a process started at another time, is a dead parent;
only then is anything of it killed or removed, so a concurrent run's workers stay alive.
"""

from __future__ import annotations

import contextlib
import os
from dataclasses import dataclass
from pathlib import Path

import psutil

WORKER_MODULE = "arise.validate.worker"
PARENT_FLAG = "--parent"


@dataclass(frozen=True)
class ParentMark:
    """A process by pid and start time (clock ticks after boot; 0 when unknown)."""

    pid: int
    started: int = 0

    def __str__(self) -> str:
        return f"{self.pid}.{self.started}"

    @classmethod
    def parse(cls, text: str) -> ParentMark | None:
        """`PID.TICKS`, or a bare `PID` (written before marks had a start time)."""
        pid, _, started = text.partition(".")
        if not pid.isdigit() or not (started.isdigit() or started == ""):
            return None
        return cls(int(pid), int(started or 0))

    @classmethod
    def of(cls, pid: int) -> ParentMark | None:
        """The mark of a running process, None when there is none (or a zombie)."""
        state = _stat(pid)
        if state is None:
            return cls(pid) if psutil.pid_exists(pid) else None
        status, started = state
        return None if status in ("Z", "X", "x") else cls(pid, started)

    def alive(self) -> bool:
        """Whether this very process still runs (a reused pid is another process)."""
        now = ParentMark.of(self.pid)
        return now is not None and (not self.started or not now.started or now == self)


def _stat(pid: int) -> tuple[str, int] | None:
    """State letter and start time of a process from /proc (None off Linux or when gone)."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except (OSError, ValueError):
        return None
    fields = text[text.rindex(")") + 2 :].split()  # the name may hold spaces and ')'
    try:
        return fields[0], int(fields[19])
    except (IndexError, ValueError):
        return None


def own_mark() -> ParentMark:
    mark = ParentMark.of(os.getpid())
    return mark if mark is not None else ParentMark(os.getpid())


def worker_command(python: str, parent: ParentMark) -> list[str]:
    """How the pool starts a worker: the module, and whose it is."""
    return [python, "-m", WORKER_MODULE, PARENT_FLAG, str(parent)]


def recorded_parent(argv: list[str]) -> ParentMark | None:
    """The parent a worker's command line (or `sys.argv`) records, if any."""
    for index, word in enumerate(argv[:-1]):
        if word == PARENT_FLAG:
            return ParentMark.parse(argv[index + 1])
    return None


def is_worker(cmdline: list[str]) -> bool:
    return any(
        word == "-m" and following == WORKER_MODULE
        for word, following in zip(cmdline, cmdline[1:], strict=False)
    )


def orphaned_workers() -> list[psutil.Process]:
    """Processes of this user that are our workers (or the children they fork) and whose
    recorded parent is dead. A worker started by hand records no parent and is left alone."""
    uid = os.getuid()
    found = []
    for process in psutil.process_iter(["uids", "cmdline"]):
        uids, cmdline = process.info["uids"], process.info["cmdline"] or []
        if uids is None or uids.real != uid or not is_worker(cmdline):
            continue
        parent = recorded_parent(cmdline)
        if parent is not None and not parent.alive():
            found.append(process)
    return found


def kill_orphaned_workers() -> list[int]:
    """SIGKILL every orphaned worker; returns their pids. psutil refuses to signal a pid
    that was reused since it was listed."""
    killed = []
    for process in orphaned_workers():
        with contextlib.suppress(psutil.Error):
            process.kill()
            killed.append(process.pid)
    return killed
