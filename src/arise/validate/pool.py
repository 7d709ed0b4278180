"""Warm, confined worker processes that run checks in isolation.

Each worker is its own session (process group) in a private scratch folder, with a
scrubbed environment (no API keys), and confines itself at the OS level before it reads a
script (`arise.validate.sandbox`); its first message says which confinement is active,
and the pool stamps that report on every result. A check that outlives its wall-clock
limit, fills its scratch folder or floods the pipe gets the whole group killed, and the
worker is replaced. Workers are recycled after a number of checks to keep memory flat.

Workers die with their parent, however it ends: each one watches it (a pidfd and its
request pipe) and kills its own process group when it goes, and each script's child has a
parent-death signal. SIGTERM, SIGHUP and SIGINT in the command line kill every worker at
once and unwind (`close_on_signals`). What a killed parent still leaves (a worker that
was importing Scenic, a scratch folder, a cgroup) the next pool kills and removes.
"""

from __future__ import annotations

import atexit
import contextlib
import json
import os
import queue
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from pathlib import Path
from types import FrameType
from typing import Any

from arise.agents.loader import check_agent_spec
from arise.agents.types import BuiltinAgent
from arise.errors import AriseError
from arise.paths import cache_dir
from arise.validate.lineage import ParentMark, kill_orphaned_workers, own_mark, worker_command
from arise.validate.process_limit import (
    MAX_TASKS,
    TaskLimit,
    cleanup_stale,
    count_tasks,
    limit_tasks,
)
from arise.validate.protocol import (
    ChildDied,
    ProtocolError,
    Ready,
    Result,
    StageEntered,
    WorkerMessage,
    parse_message,
)
from arise.validate.types import Diagnostic, SandboxReport, Stage

READY_TIMEOUT = 120.0  # seconds for a cold worker to import Scenic on a busy machine
KILL_GRACE = 3.0  # seconds after the time limit before the process group is killed
SCRATCH_QUOTA_BYTES = 256 * 1024 * 1024  # a script that writes more is stopped
MESSAGE_LIMIT_BYTES = 64 * 1024 * 1024  # one protocol line; a longer one is a flood
SCRATCH_PREFIX = "arise-worker-"  # then the parent's mark (`lineage`): leftovers are swept
# Variables a worker inherits; everything else (API keys above all) stays behind.
_PASSED_ENV = (
    "PATH",
    "LANG",
    "LC_ALL",
    "LC_CTYPE",
    "TZ",
    "PYTHONPATH",
    "PYTHONHASHSEED",
    "VIRTUAL_ENV",
    "ARISE_CACHE_DIR",
    "ARISE_MAP_DIR",
    "ARISE_WORKER_STDERR",
)

StageCallback = Callable[[Stage], None]


class WorkerDied(AriseError):
    """The worker was killed or died; the diagnostic says why, in the script's terms."""

    def __init__(self, diagnostic: Diagnostic):
        super().__init__(diagnostic.message)
        self.diagnostic = diagnostic
        self.sandbox: SandboxReport | None = None


class WorkerStartError(AriseError):
    """A worker could not start, or could not be confined as required."""


class PoolStopped(AriseError):
    """The run is being stopped (SIGTERM, SIGINT): no check starts, none gets a verdict."""

    def __init__(self) -> None:
        super().__init__("stopped: the run was interrupted")


def _worker_env(
    scratch: Path,
    memory_mb: int,
    connect_ports: tuple[int, ...],
    confine: bool,
    die_with_parent: bool,
    agent: str | None = None,
) -> dict[str, str]:
    env = {key: os.environ[key] for key in _PASSED_ENV if key in os.environ}
    env.update(
        HOME=str(scratch),
        TMPDIR=str(scratch),
        ARISE_WORKER_SCRATCH=str(scratch),
        ARISE_CACHE_DIR=str(cache_dir()),
        ARISE_WORKER_MEMORY_MB=str(memory_mb),
        ARISE_WORKER_SCRATCH_BYTES=str(SCRATCH_QUOTA_BYTES),
        ARISE_WORKER_CONNECT_PORTS=",".join(str(p) for p in connect_ports),
        ARISE_WORKER_CONFINE="1" if confine else "0",
        # A user's agent (a checked name, its file absolute): imported before confinement.
        ARISE_WORKER_AGENT=agent or "",
        # The kernel's parent-death signal fires when the THREAD that started the worker
        # ends, so only the main thread asks for it; the worker's own watch of its parent
        # holds either way.
        ARISE_WORKER_PDEATHSIG="1" if die_with_parent else "0",
        MPLCONFIGDIR=str(cache_dir() / "matplotlib"),
        MPLBACKEND="Agg",
        PYGAME_HIDE_SUPPORT_PROMPT="hide",
        SDL_VIDEODRIVER="dummy",
        OMP_NUM_THREADS="1",
        OPENBLAS_NUM_THREADS="1",
        PYTHONDONTWRITEBYTECODE="1",
    )
    return env


def sweep_scratch() -> list[int]:
    """Kill workers whose parent is gone (it was killed before it could), then remove
    scratch folders whose parent is gone; returns the pids killed."""
    killed = kill_orphaned_workers()
    for folder in Path(tempfile.gettempdir()).glob(f"{SCRATCH_PREFIX}*-*"):
        owner = ParentMark.parse(folder.name.removeprefix(SCRATCH_PREFIX).split("-", 1)[0])
        if owner is not None and not owner.alive():
            shutil.rmtree(folder, ignore_errors=True)
    return killed


def _folder_bytes(folder: Path) -> int:
    total = 0
    for root, _, files in os.walk(folder):
        for name in files:
            with contextlib.suppress(OSError):
                total += os.lstat(os.path.join(root, name)).st_size
    return total


def _kill_group(process: subprocess.Popen[bytes]) -> None:
    """SIGKILL a worker and anything it started (it leads its own session)."""
    if process.poll() is None:
        try:
            os.killpg(process.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            process.kill()


# This process's workers by pid: what a signal or exit kills. A process forked from this
# one inherits the dict (and the signal handlers), but not the workers: it skips them.
_live: dict[int, Worker] = {}
_stopping = False  # a terminating signal came: no check starts, none gets a verdict


class Worker:
    """One confined child process running `arise.validate.worker`."""

    def __init__(
        self,
        memory_mb: int,
        connect_ports: tuple[int, ...] = (),
        confine: bool = True,
        nice: int = 0,
        on_spawn: Callable[[subprocess.Popen[bytes]], None] | None = None,
        agent: str | None = None,
    ):
        self.connect_ports = connect_ports
        self.agent = agent  # the user's agent it imported before confinement, if any
        self.task_limit: TaskLimit | None = None
        self.owner = os.getpid()
        parent = own_mark()
        self.scratch = Path(tempfile.mkdtemp(prefix=f"{SCRATCH_PREFIX}{parent}-"))
        on_main_thread = threading.current_thread() is threading.main_thread()
        self.process = subprocess.Popen(
            worker_command(sys.executable, parent),
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            start_new_session=True,  # its own process group, which it kills if we die
            cwd=self.scratch,
            env=_worker_env(self.scratch, memory_mb, connect_ports, confine, on_main_thread, agent),
        )
        _live[self.process.pid] = self
        if _stopping:  # a signal came while it was being started
            self.kill()
            raise PoolStopped()
        if nice:
            with contextlib.suppress(OSError):  # a lower priority is only a courtesy
                os.setpriority(os.PRIO_PROCESS, self.process.pid, nice)
        if on_spawn is not None:
            on_spawn(self.process)  # lets the pool kill a start it no longer needs
        self.task_limit = limit_tasks(self.process.pid, parent) if confine else None
        self.checks_done = 0
        self._buffer = bytearray()
        try:
            message = self._read_message(time.monotonic() + READY_TIMEOUT)
        except WorkerDied:
            message = None
        if not isinstance(message, Ready):
            self.kill()
            raise WorkerStartError(
                "a validator worker did not start; run `python -m arise.validate.worker` to see why"
            )
        # Said before any script ran, so a script cannot forge it.
        self.sandbox = message.sandbox
        if confine:
            self.sandbox.notes.append(
                self.task_limit.describe()
                if self.task_limit
                else f"tasks: RLIMIT_NPROC in the worker's user namespace (not for root), and the "
                f"parent stops a worker with more than {MAX_TASKS} tasks"
            )

    @property
    def alive(self) -> bool:
        return self.process.poll() is None

    def _read_message(self, deadline: float) -> WorkerMessage | None:
        """Next message from the worker, or None at the deadline or on exit.

        Raises WorkerDied when the worker breaks the protocol (a flood, or a line that is
        not one of its messages) or writes more than its quota into the scratch folder.
        """
        assert self.process.stdout is not None
        fd = self.process.stdout.fileno()
        watched, searched = 0.0, 0
        while (end := self._buffer.find(b"\n", searched)) < 0:
            searched = len(self._buffer)
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                return None
            ready, _, _ = select.select([fd], [], [], min(remaining, 0.5))
            if time.monotonic() - watched >= 0.5:  # not on every chunk of a long result
                watched = time.monotonic()
                self._watch_limits()
            if not ready:
                continue
            chunk = os.read(fd, 65536)
            if not chunk:
                return None
            self._buffer += chunk
            if len(self._buffer) > MESSAGE_LIMIT_BYTES:
                raise WorkerDied(
                    self._refused("ProtocolViolation", "the worker flooded its result channel")
                )
        line = bytes(self._buffer[:end])
        del self._buffer[: end + 1]
        try:
            return parse_message(line)
        except ProtocolError:
            raise WorkerDied(
                self._refused(
                    "ProtocolViolation",
                    "the worker wrote something other than its protocol on its result channel",
                )
            ) from None

    def _watch_limits(self) -> None:
        """Stop a worker past its task or scratch limits (where the kernel cannot)."""
        if count_tasks(self.process.pid) > MAX_TASKS:
            raise WorkerDied(
                self._refused(
                    "ProcessLimitExceeded",
                    f"the script started more than {MAX_TASKS} threads or processes",
                )
            )
        if _folder_bytes(self.scratch) > SCRATCH_QUOTA_BYTES:
            raise WorkerDied(
                self._refused(
                    "DiskQuotaExceeded",
                    f"the script wrote more than "
                    f"{SCRATCH_QUOTA_BYTES // 2**20} MB into its scratch folder",
                )
            )

    def _refused(self, error_type: str, message: str) -> Diagnostic:
        self.kill()
        return Diagnostic(
            stage=Stage.SIMULATE,
            error_type=error_type,
            message=message,
            hint="the script did something a scenario never needs; the "
            "worker was stopped and replaced.",
        )

    def run(
        self, request: dict[str, Any], timeout: float, on_stage: StageCallback | None = None
    ) -> dict[str, Any]:
        """Send one check; return the worker's result dict or raise WorkerDied."""
        assert self.process.stdin is not None
        stage = Stage.GATE
        try:
            self.process.stdin.write((json.dumps(request) + "\n").encode())
            self.process.stdin.flush()
        except BrokenPipeError:
            raise WorkerDied(self._death(stage, timeout, timed_out=False)) from None
        deadline = time.monotonic() + timeout + KILL_GRACE
        while True:
            message = self._read_message(deadline)
            if message is None:  # the deadline passed, or the worker closed its channel
                raise WorkerDied(
                    self._death(stage, timeout, timed_out=time.monotonic() >= deadline)
                )
            match message:
                case StageEntered():
                    stage = message.stage
                    if on_stage:
                        on_stage(stage)
                case Result():
                    self.checks_done += 1
                    return message.result
                case ChildDied():
                    raise WorkerDied(self._child_death(stage, message))
                case Ready():  # said once, at the start: a second one is not the worker's
                    raise WorkerDied(
                        self._refused("ProtocolViolation", "the worker said it was ready twice")
                    )

    def _death(self, stage: Stage, timeout: float, timed_out: bool) -> Diagnostic:
        """Why the worker stopped answering: its deadline passed (a timeout), or it died
        before (a crash). Decided by the clock, not by whether it is still alive, which
        races with a worker that is dying."""
        self.kill()
        code = self.process.returncode
        if timed_out:
            return Diagnostic(
                stage=stage,
                error_type="Timeout",
                message=f"the check did not finish within {timeout:g} s "
                f"(killed in the {stage} stage)",
                hint="an endless loop or a very slow computation in the "
                "script; make loops `wait`, or raise --timeout.",
            )
        how = f"signal {-code}" if code is not None and code < 0 else f"exit code {code}"
        memory = code is not None and code in (-signal.SIGKILL, -signal.SIGSEGV)
        return Diagnostic(
            stage=stage,
            error_type="WorkerCrashed",
            message=f"the validator process died in the {stage} stage ({how})",
            hint=(
                "the script probably exhausted memory"
                if memory
                else "the script crashed the interpreter"
            ),
        )

    def _child_death(self, stage: Stage, message: ChildDied) -> Diagnostic:
        """The child that ran the script ended without a result (the server is fine)."""
        if message.flooded or message.garbled:
            what = "flooded" if message.flooded else "wrote its own lines on"
            return Diagnostic(
                stage=stage,
                error_type="ProtocolViolation",
                message=f"the script {what} the validator's result channel, and no result "
                "came through",
                hint="the script wrote on the validator's channel; remove that code.",
            )
        code = message.code
        how = f"signal {-code}" if code < 0 else f"exit code {code}"
        memory = code in (-signal.SIGKILL, -signal.SIGSEGV)
        return Diagnostic(
            stage=stage,
            error_type="WorkerCrashed",
            message=f"the process running the script died in the {stage} stage ({how}) "
            "without a result",
            hint=(
                "the script probably exhausted memory"
                if memory
                else "the script ended its own process"
            ),
        )

    def kill(self) -> None:
        """Kill the worker, its script's child and anything left in its cgroup; remove
        its scratch folder and cgroup."""
        _kill_group(self.process)
        self.process.wait()
        for stream in (self.process.stdin, self.process.stdout):
            if stream is not None:
                with contextlib.suppress(OSError):
                    stream.close()
        if self.task_limit is not None:
            self.task_limit.release()
        shutil.rmtree(self.scratch, ignore_errors=True)
        _live.pop(self.process.pid, None)


def _own_workers() -> list[Worker]:
    me = os.getpid()
    return [worker for worker in list(_live.values()) if worker.owner == me]


def _kill_all_now() -> None:
    """SIGKILL every worker of this process, without waiting or locking (a signal
    handler may run while any lock is held)."""
    for worker in _own_workers():
        _kill_group(worker.process)


def _on_terminate(signum: int, frame: FrameType | None) -> None:
    global _stopping
    again = _stopping
    _stopping = True
    _kill_all_now()
    if again:  # a second signal while unwinding: leave now (the next run sweeps)
        os._exit(128 + signum)
    if signum == signal.SIGINT:
        raise KeyboardInterrupt
    raise SystemExit(128 + signum)


def close_on_signals() -> None:
    """Make SIGTERM, SIGHUP and SIGINT stop this process cleanly: every worker is killed
    at once (not when its check times out), checks in flight end without a verdict
    (`PoolStopped`), and the stack unwinds as for Ctrl-C, so pools close and remove
    scratch folders and cgroups; the exit status is 128 + the signal (SIGINT stays a
    KeyboardInterrupt). Signals set to be ignored (nohup) stay ignored. Main thread only."""
    if threading.current_thread() is not threading.main_thread():
        return
    for signum in (signal.SIGTERM, signal.SIGHUP, signal.SIGINT):
        if signal.getsignal(signum) in (signal.SIG_DFL, signal.default_int_handler):
            signal.signal(signum, _on_terminate)


@atexit.register
def _kill_all_at_exit() -> None:
    """Workers no pool closed (an exception, a signal): killed, their scratch folders and
    cgroups removed, before the interpreter goes."""
    for worker in _own_workers():
        worker.kill()


class WorkerPool:
    """A few warm, confined workers shared by the checks of one run; thread-safe.

    `confine=False` exists only to measure what confinement costs (benchmarks); every
    result then says that no confinement was active, and `require_sandbox` refuses it.
    """

    def __init__(
        self,
        size: int = 1,
        memory_mb: int = 1536,
        recycle_after: int = 50,
        *,
        require_sandbox: bool = False,
        confine: bool = True,
        agent: str | None = None,
    ):
        self.size = max(1, size)
        # A user's agent the workers import before confinement (a canonical name from
        # `arise.agents.check_agent_spec`); a check that asks for another gets a new worker.
        self.agent = _preloaded(check_agent_spec(agent).text if agent else None)
        self.memory_mb = memory_mb
        self.recycle_after = recycle_after
        self.require_sandbox = require_sandbox
        self.confine = confine
        # What a killed parent left: cgroups (with anything still in them), workers that
        # outlived it, scratch folders.
        cleanup_stale()
        sweep_scratch()
        self._idle: queue.LifoQueue[Worker] = queue.LifoQueue()
        self._started = 0
        self._closed = False
        self._lock = threading.Lock()
        self._warming: threading.Thread | None = None
        self._starting: set[subprocess.Popen[bytes]] = set()

    def _spawned(self, process: subprocess.Popen[bytes]) -> None:
        """Track a worker process until it is ready; one spawned after close dies at once."""
        with self._lock:
            if not self._closed:
                self._starting.add(process)
                return
        _kill_group(process)

    def _take(
        self, connect_ports: tuple[int, ...], nice: int = 0, agent: str | None = None
    ) -> Worker:
        """An idle worker confined for these ports, or a new one."""
        if _stopping:
            raise PoolStopped()
        warming = self._warming
        if warming is not None and warming is not threading.current_thread():
            warming.join()  # its worker, or (if its start failed) the right to start one
        try:
            worker = self._idle.get_nowait()
        except queue.Empty:
            worker = None
        if worker is None:
            with self._lock:
                may_start = self._started < self.size
                if may_start:
                    self._started += 1
            if not may_start:
                worker = self._idle.get()
        else:
            may_start = False
        if worker is not None and (
            worker.connect_ports != connect_ports or (agent is not None and worker.agent != agent)
        ):
            worker.kill()  # its confinement allows other ports, or it lacks the agent
            worker, may_start = None, True
        if worker is None and may_start:
            spawned: list[subprocess.Popen[bytes]] = []

            def on_spawn(process: subprocess.Popen[bytes]) -> None:
                spawned.append(process)
                self._spawned(process)

            try:
                return Worker(
                    self.memory_mb,
                    connect_ports,
                    self.confine,
                    nice,
                    on_spawn,
                    agent=agent or self.agent,
                )
            except Exception:
                with self._lock:
                    self._started -= 1
                raise
            finally:
                with self._lock:
                    self._starting.difference_update(spawned)
        assert worker is not None
        return worker

    def _give_back(self, worker: Worker, healthy: bool) -> None:
        if (
            healthy
            and worker.alive
            and worker.checks_done < self.recycle_after
            and not self._closed
            and not _stopping
        ):
            self._idle.put(worker)
            return
        worker.kill()
        with self._lock:
            self._started -= 1

    def warm(self, nice: int = 0) -> None:
        """Start every worker now, so the first checks do not pay for start-up; `nice`
        lowers their CPU priority (for good: an unprivileged process cannot raise it)."""
        for _ in range(self.size - self._idle.qsize()):
            if self._closed:
                return
            self._idle.put(self._take((), nice))

    def warm_in_background(self, nice: int = 0) -> None:
        """Start the workers on a thread: their start-up (~5 s, mostly importing Scenic in
        the child) then overlaps the caller's own start-up, such as loading the model."""
        if self._warming is not None:
            return

        def start() -> None:
            # A start that fails here fails again in the first check, which reports it.
            with contextlib.suppress(Exception):
                self.warm(nice)

        self._warming = threading.Thread(target=start, name="arise-pool-warm", daemon=True)
        self._warming.start()

    def wait_warm(self) -> None:
        """Return once a background start (`warm_in_background`) has finished."""
        if self._warming is not None:
            self._warming.join()

    def sandbox(self) -> SandboxReport:
        """The confinement this pool's workers reach (starts one if none is warm)."""
        worker = self._take(())
        self._give_back(worker, healthy=True)
        return worker.sandbox

    def run(
        self, request: dict[str, Any], timeout: float, on_stage: StageCallback | None = None
    ) -> dict[str, Any]:
        """Run one check request; the result dict carries the worker's `sandbox` report.

        Raises WorkerDied (with a diagnostic) when the worker had to be killed, and
        SandboxRequired when confinement is required but incomplete.
        """
        options = request.get("options") or {}
        ports: tuple[int, ...] = ()
        if options.get("simulator") == "carla":
            port = int(options.get("carla_port", 2000))
            ports = (port, port + 1)  # CARLA's RPC port and its streaming port
        worker = self._take(ports, agent=_preloaded(options.get("agent")))
        if (self.require_sandbox or options.get("require_sandbox")) and not worker.sandbox.full:
            self._give_back(worker, healthy=True)
            raise SandboxRequired(worker.sandbox)
        try:
            result = worker.run(request, timeout, on_stage)
        except WorkerDied as death:
            self._give_back(worker, healthy=False)
            if _stopping:  # we killed it: that says nothing about the script
                raise PoolStopped() from None
            death.sandbox = worker.sandbox
            raise
        except BaseException:
            self._give_back(worker, healthy=False)
            raise
        diagnostic = result.get("diagnostic") or {}
        fragile = diagnostic.get("error_type") in ("MemoryError", "CheckTimeout", "Timeout")
        self._give_back(worker, healthy=not fragile)
        result["sandbox"] = worker.sandbox.model_dump(mode="json")
        return result

    def close(self) -> None:
        with self._lock:
            self._closed = True
            starting = list(self._starting)
        for process in starting:  # a start nobody will use: end it rather than wait ~5 s
            _kill_group(process)
        self.wait_warm()  # a worker still starting must not outlive the pool
        while True:
            try:
                self._idle.get_nowait().kill()
            except queue.Empty:
                break

    def __enter__(self) -> WorkerPool:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _preloaded(agent: object) -> str | None:
    """The agent a worker must import before confinement: a user's, not a built-in."""
    if not isinstance(agent, str) or agent in {b.value for b in BuiltinAgent}:
        return None
    return agent


class SandboxRequired(AriseError):
    """Confinement was required (`--require-sandbox`) but a mechanism is missing."""

    def __init__(self, sandbox: SandboxReport):
        super().__init__(
            "refusing to run the script: confinement is incomplete (missing: "
            + ", ".join(m.value for m in sandbox.missing)
            + ")"
        )
        self.sandbox = sandbox
