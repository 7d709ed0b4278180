"""Warm worker processes that run checks in isolation.

Each worker is its own session (process group) with an address-space limit; a check
that outlives its wall-clock limit gets the whole group killed, and the worker that ran
it is replaced. Workers are recycled after a number of checks to keep memory flat.
"""

from __future__ import annotations

import contextlib
import json
import os
import queue
import select
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from typing import Any

from arise.validate.types import Diagnostic, Stage

READY_TIMEOUT = 120.0  # seconds for a cold worker to import Scenic on a busy machine
KILL_GRACE = 3.0  # seconds after the time limit before the process group is killed

StageCallback = Callable[[str], None]


class WorkerDied(Exception):
    def __init__(self, diagnostic: Diagnostic):
        super().__init__(diagnostic.message)
        self.diagnostic = diagnostic


class Worker:
    """One child process running `arise.validate.worker`."""

    def __init__(self, memory_mb: int):
        env = dict(os.environ, ARISE_WORKER_MEMORY_MB=str(memory_mb),
                   PYGAME_HIDE_SUPPORT_PROMPT="hide", MPLBACKEND="Agg",
                   SDL_VIDEODRIVER="dummy", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
        self.process = subprocess.Popen(
            [sys.executable, "-m", "arise.validate.worker"],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
            start_new_session=True, env=env,
        )
        self.checks_done = 0
        self._buffer = b""
        message = self._read_message(time.monotonic() + READY_TIMEOUT)
        if message is None or message.get("event") != "ready":
            self.kill()
            raise RuntimeError("a validator worker did not start; run "
                               "`python -m arise.validate.worker` to see why")

    @property
    def alive(self) -> bool:
        return self.process.poll() is None

    def _read_message(self, deadline: float) -> dict[str, Any] | None:
        """Next JSON line from the worker, or None at the deadline or on exit."""
        assert self.process.stdout is not None
        fd = self.process.stdout.fileno()
        while b"\n" not in self._buffer:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                return None
            ready, _, _ = select.select([fd], [], [], min(remaining, 0.5))
            if not ready:
                continue
            chunk = os.read(fd, 65536)
            if not chunk:
                return None
            self._buffer += chunk
        line, self._buffer = self._buffer.split(b"\n", 1)
        return json.loads(line)

    def run(self, request: dict[str, Any], timeout: float,
            on_stage: StageCallback | None = None) -> dict[str, Any]:
        """Send one check; return the worker's result dict or raise WorkerDied."""
        assert self.process.stdin is not None
        stage = Stage.GATE.value
        try:
            self.process.stdin.write((json.dumps(request) + "\n").encode())
            self.process.stdin.flush()
        except BrokenPipeError:
            raise WorkerDied(self._death(stage, timeout)) from None
        deadline = time.monotonic() + timeout + KILL_GRACE
        while True:
            message = self._read_message(deadline)
            if message is None:
                raise WorkerDied(self._death(stage, timeout))
            if message.get("event") == "stage":
                stage = message["stage"]
                if on_stage:
                    on_stage(stage)
            elif message.get("event") == "result":
                self.checks_done += 1
                return dict(message["result"])

    def _death(self, stage: str, timeout: float) -> Diagnostic:
        timed_out = self.alive
        self.kill()
        code = self.process.returncode
        if timed_out:
            return Diagnostic(stage=Stage(stage), error_type="Timeout",
                              message=f"the check did not finish within {timeout:g} s "
                                      f"(killed in the {stage} stage)",
                              hint="an endless loop or a very slow computation in the "
                                   "script; make loops `wait`, or raise --timeout.")
        how = f"signal {-code}" if code is not None and code < 0 else f"exit code {code}"
        memory = code is not None and code in (-signal.SIGKILL, -signal.SIGSEGV)
        return Diagnostic(stage=Stage(stage), error_type="WorkerCrashed",
                          message=f"the validator process died in the {stage} stage ({how})",
                          hint=("the script probably exhausted memory" if memory else
                                "the script crashed the interpreter"))

    def kill(self) -> None:
        if self.process.poll() is None:
            try:
                os.killpg(self.process.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                self.process.kill()
        self.process.wait()
        for stream in (self.process.stdin, self.process.stdout):
            if stream is not None:
                with contextlib.suppress(OSError):
                    stream.close()


class WorkerPool:
    """A few warm workers shared by the checks of one run; thread-safe."""

    def __init__(self, size: int = 1, memory_mb: int = 1536, recycle_after: int = 50):
        self.size = max(1, size)
        self.memory_mb = memory_mb
        self.recycle_after = recycle_after
        self._idle: queue.LifoQueue[Worker] = queue.LifoQueue()
        self._started = 0
        self._closed = False
        self._lock = threading.Lock()

    def _take(self) -> Worker:
        try:
            return self._idle.get_nowait()
        except queue.Empty:
            pass
        with self._lock:
            may_start = self._started < self.size
            if may_start:
                self._started += 1
        if may_start:
            try:
                return Worker(self.memory_mb)
            except Exception:
                with self._lock:
                    self._started -= 1
                raise
        return self._idle.get()

    def _give_back(self, worker: Worker, healthy: bool) -> None:
        if healthy and worker.alive and worker.checks_done < self.recycle_after \
                and not self._closed:
            self._idle.put(worker)
            return
        worker.kill()
        with self._lock:
            self._started -= 1

    def warm(self) -> None:
        """Start every worker now, so the first checks do not pay for start-up."""
        workers = [self._take() for _ in range(self.size - self._idle.qsize())]
        for worker in workers:
            self._idle.put(worker)

    def run(self, request: dict[str, Any], timeout: float,
            on_stage: StageCallback | None = None) -> dict[str, Any]:
        worker = self._take()
        try:
            result = worker.run(request, timeout, on_stage)
        except WorkerDied:
            self._give_back(worker, healthy=False)
            raise
        except BaseException:
            self._give_back(worker, healthy=False)
            raise
        diagnostic = result.get("diagnostic") or {}
        fragile = diagnostic.get("error_type") in ("MemoryError", "CheckTimeout", "Timeout")
        self._give_back(worker, healthy=not fragile)
        return result

    def close(self) -> None:
        self._closed = True
        while True:
            try:
                self._idle.get_nowait().kill()
            except queue.Empty:
                break

    def __enter__(self) -> WorkerPool:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
