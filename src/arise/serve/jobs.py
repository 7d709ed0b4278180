"""A job: one description on its way through one model, and who is waiting to hear of it.

The job's state changes only through its methods, under its lock; each change and each
progress event is kept (`events`) and wakes every page that follows the job (`Signal`).
"""

from __future__ import annotations

import asyncio
import threading
import time
from dataclasses import dataclass, field
from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, Field

from arise.generate.run import RunStatus
from arise.limits import MAX_MESSAGE
from arise.serve.events import JobEvent, StateEvent
from arise.serve.events import JobState as JobState  # where it was; its events carry it

FINISHED = frozenset({JobState.DONE, JobState.FAILED, JobState.CANCELLED})


class Signal:
    """Wakes coroutines in any event loop from any thread: `notify()` from the job's
    thread, `await wait(version)` in the server's loop. The version counts notifications,
    so a waiter that read it before looking at the job misses none."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._waiters: set[tuple[asyncio.AbstractEventLoop, asyncio.Event]] = set()
        self.version = 0

    def notify(self) -> None:
        with self._lock:
            self.version += 1
            waiters = list(self._waiters)
        for loop, event in waiters:
            try:
                loop.call_soon_threadsafe(event.set)
            except RuntimeError:  # that loop is closed: its waiter is gone
                with self._lock:
                    self._waiters.discard((loop, event))

    async def wait(self, since: int, timeout: float) -> None:
        """Return when the version is past `since`, or after `timeout` seconds."""
        entry = (asyncio.get_running_loop(), asyncio.Event())
        with self._lock:
            if self.version != since:
                return
            self._waiters.add(entry)
        try:
            await asyncio.wait_for(entry[1].wait(), timeout)
        except TimeoutError:
            pass
        finally:
            with self._lock:
                self._waiters.discard(entry)


@dataclass
class Job:
    """One generation request. `events` holds, in order, the pipeline's progress events
    and a `state` event at each change of state (`arise.serve.events`)."""

    id: str
    description: str
    provider: str
    model: str
    created: float = field(default_factory=time.time)
    state: JobState = JobState.QUEUED
    started: float | None = None
    finished: float | None = None
    message: str | None = None
    run_status: str | None = None  # the run's RunStatus, once it ended
    events: list[JobEvent] = field(default_factory=list)
    cancel_requested: threading.Event = field(default_factory=threading.Event, repr=False)
    signal: Signal = field(default_factory=Signal, repr=False)
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    @property
    def key(self) -> str:
        return f"{self.provider}/{self.model}"

    @property
    def finished_state(self) -> bool:
        return self.state in FINISHED

    def add_event(self, event: JobEvent) -> None:
        with self._lock:
            self.events.append(event)
        self.signal.notify()

    def events_after(self, seen: int) -> list[JobEvent]:
        with self._lock:
            return list(self.events[seen:])

    def move(self, state: JobState, message: str | None = None) -> StateEvent | None:
        """The one way a job changes state: returns the `state` event it added, or None
        (and nothing changes) once the job has finished."""
        with self._lock:
            if self.state in FINISHED:
                return None
            self.state = state
            now = time.time()
            if state is JobState.RUNNING:
                self.started = now
            if state in FINISHED:
                self.finished = now
            if message is not None:
                self.message = message
            cut = None if self.message is None else self.message[:MAX_MESSAGE]
            event = StateEvent(state=state, message=cut)
            self.events.append(event)
        self.signal.notify()
        return event

    def as_dict(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "description": self.description,
            "provider": self.provider,
            "model": self.model,
            "key": self.key,
            "state": self.state.value,
            "created": self.created,
            "started": self.started,
            "finished": self.finished,
            "message": self.message,
            "run_status": self.run_status,
        }

    @classmethod
    def from_dict(cls, data: object) -> Job:
        """A job read back from a run folder's job.json: untrusted, so validated
        (ValueError for anything that is not a job record)."""
        record = JobRecord.model_validate(data)
        return cls(
            id=record.id,
            description=record.description,
            provider=record.provider,
            model=record.model,
            created=record.created,
            state=record.state,
            started=record.started,
            finished=record.finished,
            message=record.message,
            run_status=record.run_status.value if record.run_status else None,
        )


Time = Annotated[float, Field(ge=0, allow_inf_nan=False)]


class JobRecord(BaseModel):
    """What job.json may hold: bounded strings, finite times, known states."""

    model_config = ConfigDict(extra="ignore")

    id: str = Field(max_length=64)
    description: str = Field(max_length=100_000)
    provider: str = Field(max_length=200)
    model: str = Field(max_length=200)
    created: Time = 0.0
    state: JobState = JobState.FAILED
    started: Time | None = None
    finished: Time | None = None
    message: str | None = Field(default=None, max_length=10_000)
    run_status: RunStatus | None = None
