"""One lane per model: its jobs wait in order and run one at a time in the lane's thread,
on a Generator that stays warm (the model loaded, the knowledge base indexed) between jobs.

A queued job that is cancelled leaves the queue at once; a running one stops at its next
progress event (a model call or a check already under way finishes first).
"""

from __future__ import annotations

import logging
import threading
from collections import deque
from collections.abc import Callable
from pathlib import Path
from typing import Protocol

from arise.errors import AriseError
from arise.generate.events import ProgressEvent, RunFinished
from arise.generate.run import Generation
from arise.serve.errors import JobCancelled, QueueFull
from arise.serve.events import JobEvent, from_progress
from arise.serve.jobs import Job, JobState

log = logging.getLogger("arise.serve")


class Runner(Protocol):
    """What a lane runs jobs on: `Generator` in the server, a scripted fake in tests."""

    def generate(
        self,
        description: str,
        out_dir: Path | None = None,
        progress: Callable[[ProgressEvent], None] | None = None,
    ) -> Generation: ...

    def close(self) -> None: ...


#: Called with a job and the event it just got (a progress event, or a `state` event).
OnChange = Callable[[Job, JobEvent], None]


class Lane:
    def __init__(
        self,
        key: str,
        make_runner: Callable[[], Runner],
        folder_of: Callable[[Job], Path],
        on_change: OnChange,
        max_queued: int,
    ) -> None:
        self.key = key
        self._make_runner = make_runner
        self._folder_of = folder_of
        self._on_change = on_change
        self._max_queued = max_queued
        self._runner: Runner | None = None
        self._queue: deque[Job] = deque()
        self._ready = threading.Condition()
        self._closing = False
        self.current: Job | None = None
        self._thread = threading.Thread(target=self._loop, name=f"lane {key}", daemon=True)
        self._thread.start()

    # -- called from request handlers -----------------------------------------------------
    def submit(self, job: Job) -> None:
        with self._ready:
            if len(self._queue) >= self._max_queued:
                raise QueueFull(
                    f"{len(self._queue)} jobs are already waiting for {self.key}; "
                    "try again when some have finished"
                )
            self._queue.append(job)
            self._ready.notify()

    def position(self, job: Job) -> int | None:
        """1 for the next job to run, None when it is not waiting."""
        with self._ready:
            for index, waiting in enumerate(self._queue):
                if waiting is job:
                    return index + 1
        return None

    def waiting(self) -> int:
        with self._ready:
            return len(self._queue)

    def cancel(self, job: Job) -> None:
        """Take a queued job out, or ask a running one to stop at its next event."""
        job.cancel_requested.set()
        with self._ready:
            queued = job in self._queue
            if queued:
                self._queue.remove(job)
        if queued:
            self._moved(job, JobState.CANCELLED, "cancelled before it started")

    def close(self) -> None:
        with self._ready:
            self._closing = True
            for job in self._queue:
                job.cancel_requested.set()
            self._ready.notify_all()
        if self.current is not None:
            self.current.cancel_requested.set()
        self._thread.join(timeout=5)
        if self._runner is not None and not self._thread.is_alive():
            self._runner.close()

    # -- the lane's thread ----------------------------------------------------------------
    def _loop(self) -> None:
        while True:
            with self._ready:
                while not self._queue and not self._closing:
                    self._ready.wait()
                if self._closing:
                    return
                job = self._queue.popleft()
                self.current = job
            ending: tuple[JobState, str | None] | None = None
            try:
                ending = self._run(job)
            finally:
                self.current = None  # before the job's end is told: the queue is free
                if ending is not None:
                    self._moved(job, *ending)

    def _moved(self, job: Job, state: JobState, message: str | None = None) -> bool:
        event = job.move(state, message)
        if event is not None:
            self._on_change(job, event)
        return event is not None

    def _run(self, job: Job) -> tuple[JobState, str | None] | None:
        """Run one job; how it ended (None: it had ended before it could start)."""
        if job.cancel_requested.is_set():
            return JobState.CANCELLED, "cancelled before it started"
        if not self._moved(job, JobState.RUNNING):
            return None

        def progress(event: ProgressEvent) -> None:
            if job.cancel_requested.is_set() and not isinstance(event, RunFinished):
                raise JobCancelled("cancelled")
            data = from_progress(event)
            job.add_event(data)
            self._on_change(job, data)

        try:
            if self._runner is None:
                self._runner = self._make_runner()
            run = self._runner.generate(job.description, self._folder_of(job), progress)
        except JobCancelled:
            return JobState.CANCELLED, "cancelled while running"
        except AriseError as error:  # e.g. a knowledge base or map folder that cannot load
            return JobState.FAILED, str(error)
        except Exception as error:  # noqa: BLE001  (a bug: the page gets one line, the log the rest)
            log.exception("job %s failed", job.id)
            return (
                JobState.FAILED,
                f"internal error ({type(error).__name__}); the server's log has the details",
            )
        job.run_status = run.status.value
        return (JobState.DONE if run.ok else JobState.FAILED), run.summary()
