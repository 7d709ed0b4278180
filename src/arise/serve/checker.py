"""Script checks off the server's event loop and out of its process.

Each check runs in a check process (`checkproc`), on a thread of its own that only waits
for it; the process asks the server's shared pool for the confined run. So `/api/health`
and every page answer while a check runs, is stuck in the validator, or is stuck parsing
(a process that does not answer within its budget is killed and replaced).

Concurrency is bounded: `slots` checks run at once (one process each), `max_waiting` more
may wait, and a further one is refused at once (503) instead of piling up.
"""

from __future__ import annotations

import logging
import os
import re
import select
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import anyio
import anyio.to_thread

from arise.serve.checkmsg import (
    Broken,
    Check,
    Died,
    Done,
    Failed,
    FromProcess,
    MessageError,
    Ran,
    Ready,
    Refused,
    Run,
    ToProcess,
    encode,
    from_process,
)
from arise.serve.checks import check_options
from arise.serve.errors import ServeError
from arise.validate import WorkerPool
from arise.validate.pool import SandboxRequired, WorkerDied

log = logging.getLogger("arise.serve")

#: Seconds a new check process may take to import what it needs on a busy machine.
READY_SECONDS = 120.0
#: The largest message the check process may send (a 256 KiB script's view is ~2 MB).
MAX_MESSAGE_BYTES = 32 * 1024 * 1024
#: Variables the check process does not get: it reads untrusted input and needs no keys.
_SECRET_ENV = re.compile(r"KEY|TOKEN|SECRET|PASSWORD|CREDENTIAL", re.IGNORECASE)


class ChecksBusy(ServeError):
    """Too many script checks are running or waiting already."""

    status = 503


class CheckFailed(ServeError):
    """The check could not be done for a reason the script's author can act on."""

    status = 422


class CheckStopped(ServeError):
    """The check process was stopped: it took too long, died or broke the protocol."""

    status = 500


class LineReader:
    """JSON lines from a pipe, each within a deadline and a size bound."""

    def __init__(self, fd: int) -> None:
        self.fd = fd
        self.buffer = bytearray()

    def read(self, deadline: float) -> bytes | None:
        """The next line; None once the deadline passed or the pipe closed."""
        poller = select.poll()
        poller.register(self.fd, select.POLLIN | select.POLLHUP)
        while b"\n" not in self.buffer:
            if len(self.buffer) > MAX_MESSAGE_BYTES:
                raise CheckStopped("the check process sent a message over its size bound")
            left = deadline - time.monotonic()
            if left <= 0 or not poller.poll(left * 1000):
                return None
            chunk = os.read(self.fd, 1 << 20)
            if not chunk:
                return None
            self.buffer += chunk
        line, _, rest = bytes(self.buffer).partition(b"\n")
        self.buffer = bytearray(rest)
        return line


class CheckProcess:
    """One check process and the thread-side end of its protocol."""

    def __init__(self) -> None:
        self.process = subprocess.Popen(
            [sys.executable, "-m", "arise.serve.checkproc"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            env={k: v for k, v in os.environ.items() if not _SECRET_ENV.search(k)},
            start_new_session=True,  # a Ctrl-C at the terminal goes to the server only
        )
        assert self.process.stdout is not None
        self.reader = LineReader(self.process.stdout.fileno())
        try:
            ready = self._receive(READY_SECONDS, "start")
        except BaseException:
            self.kill()
            raise
        if not isinstance(ready, Ready):
            self.kill()
            raise CheckStopped("the check process did not start")

    @property
    def pid(self) -> int:
        return self.process.pid

    def _send(self, message: ToProcess) -> None:
        assert self.process.stdin is not None
        try:
            self.process.stdin.write(encode(message))
            self.process.stdin.flush()
        except (BrokenPipeError, ValueError):
            raise CheckStopped("the check process ended unexpectedly") from None

    def _receive(self, budget: float, doing: str) -> FromProcess:
        line = self.reader.read(time.monotonic() + budget)
        if line is None:
            if self.process.poll() is None:
                raise CheckStopped(
                    f"the check was stopped: it did not {doing} within {budget:.0f} s "
                    "(an unusually long or repetitive script?)"
                )
            raise CheckStopped("the check process ended unexpectedly")
        try:
            return from_process(line)
        except MessageError:
            raise CheckStopped("the check process sent a malformed message") from None

    def check(
        self,
        text: str,
        folder: Path,
        pool: WorkerPool,
        map_dir: str | None,
        timeout: float,
        budget: float,
        agent: str | None = None,
    ) -> dict[str, Any]:
        """The check's view; raises CheckFailed (the process is still good) or
        CheckStopped (the process must go)."""
        self._send(
            Check(text=text, folder=str(folder), map_dir=map_dir, timeout=timeout, agent=agent)
        )
        while True:
            match self._receive(budget, "read the script and its result"):
                case Run(request=asked):
                    request = held_request(asked, text, map_dir, timeout, agent)
                    self._send(run_on_pool(pool, request, timeout))
                case Done(view=view):
                    return view
                case Failed(error=error, internal=internal):
                    line = (error.splitlines() or ["the check failed"])[0][:500]
                    raise (CheckStopped if internal else CheckFailed)(line or "the check failed")
                case _:
                    raise CheckStopped("the check process broke the protocol")

    def stop(self) -> None:
        """Kill the process (from any thread; its pipes stay to their owner)."""
        if self.process.poll() is None:
            self.process.kill()

    def kill(self) -> None:
        """Kill the process and close its pipes (by the thread that owns it)."""
        self.stop()
        self.process.wait()
        for stream in (self.process.stdin, self.process.stdout):
            if stream is not None:
                stream.close()


def held_request(
    request: object, text: str, map_dir: str | None, timeout: float, agent: str | None = None
) -> dict:
    """The check process's run request, held to what the server asked for: the same
    script, and the server's options, its agent included (a process may only add
    `require_sandbox`)."""
    if not isinstance(request, dict) or request.get("text") != text:
        raise CheckStopped("the check process asked to run another script")
    asked = request.get("options")
    if not isinstance(asked, dict) or not isinstance(request.get("map"), dict):
        raise CheckStopped("the check process sent a malformed run request")
    options = check_options(map_dir, timeout, agent).model_dump(mode="json")
    options["require_sandbox"] = bool(options["require_sandbox"] or asked.get("require_sandbox"))
    return {**request, "options": options}


def run_on_pool(pool: WorkerPool, request: dict[str, Any], timeout: float) -> ToProcess:
    """One run on the server's pool, as the message that answers the check process."""
    try:
        return Ran(result=pool.run(request, timeout))
    except WorkerDied as death:
        return Died(diagnostic=death.diagnostic, sandbox=death.sandbox)
    except SandboxRequired as refusal:
        return Refused(sandbox=refusal.sandbox)
    except Exception as error:  # noqa: BLE001  (a worker that cannot start: one line)
        log.warning("a script check's run failed: %s", error)
        return Broken(error=(str(error).splitlines() or [""])[0][:500])


class ScriptChecker:
    """The server's script checks: bounded, each in a check process, off the loop."""

    def __init__(
        self,
        pool: WorkerPool,
        *,
        budget: float,
        slots: int = 1,
        max_waiting: int = 8,
    ) -> None:
        """`budget`: seconds a check process may take on each of its parts (reading the
        script before the run; reading the worker's result and drawing the replay after)."""
        self.pool = pool
        self.slots = max(1, slots)
        self.max_waiting = max(0, max_waiting)
        self.budget = budget
        self._lock = threading.Lock()
        self._idle: list[CheckProcess] = []
        self._busy: set[CheckProcess] = set()
        self._closed = False
        self._admitted = 0  # changed only on the event loop
        self._running = 0
        self._limiter: anyio.CapacityLimiter | None = None

    def pids(self) -> list[int]:
        """The check processes alive now, idle or busy."""
        with self._lock:
            return sorted(p.pid for p in [*self._idle, *self._busy] if p.process.poll() is None)

    def counts(self) -> dict[str, int]:
        with self._lock:
            running = self._running
        return {"running": running, "waiting": max(0, self._admitted - running)}

    async def check(
        self, text: str, folder: Path, map_dir: str | None, timeout: float, agent: str | None = None
    ) -> dict[str, Any]:
        """Check `text` in a check process; 503 at once when the queue is full."""
        if self._closed:
            raise ChecksBusy("the server is stopping")
        if self._admitted >= self.slots + self.max_waiting:
            raise ChecksBusy(
                f"{self._admitted} script checks are running or waiting already; "
                "try again in a minute"
            )
        if self._limiter is None:
            self._limiter = anyio.CapacityLimiter(self.slots)
        self._admitted += 1
        try:
            return await anyio.to_thread.run_sync(
                self._check_now, text, folder, map_dir, timeout, agent, limiter=self._limiter
            )
        finally:
            self._admitted -= 1

    def _check_now(
        self, text: str, folder: Path, map_dir: str | None, timeout: float, agent: str | None
    ) -> dict[str, Any]:
        with self._lock:
            self._running += 1
        try:
            process = self._take()
            try:
                view = process.check(text, folder, self.pool, map_dir, timeout, self.budget, agent)
            except CheckFailed:
                self._give_back(process)
                raise
            except BaseException:
                self._drop(process)
                raise
            self._give_back(process)
            return view
        finally:
            with self._lock:
                self._running -= 1

    def _take(self) -> CheckProcess:
        with self._lock:
            if self._closed:
                raise ChecksBusy("the server is stopping")
            process = self._idle.pop() if self._idle else None
        if process is None or process.process.poll() is not None:
            process = CheckProcess()
        with self._lock:
            self._busy.add(process)
        return process

    def _give_back(self, process: CheckProcess) -> None:
        with self._lock:
            self._busy.discard(process)
            if not self._closed:
                self._idle.append(process)
                return
        process.kill()

    def _drop(self, process: CheckProcess) -> None:
        with self._lock:
            self._busy.discard(process)
        process.kill()

    def warm(self) -> None:
        """Start one check process now, so the first check does not wait for it."""
        process = CheckProcess()
        with self._lock:
            if not self._closed:
                self._idle.append(process)
                return
        process.kill()

    def close(self) -> None:
        """Kill every check process; a check under way ends with CheckStopped."""
        with self._lock:
            self._closed = True
            idle, busy = self._idle, list(self._busy)
            self._idle = []
        for process in busy:
            process.stop()  # its thread sees the end, reports it and closes the pipes
        for process in idle:
            process.kill()
