"""The board: every job the server knows (finished ones read back from disk), the lanes
they wait in, and the one place a job is created, cancelled or listed."""

from __future__ import annotations

import re
import shutil
import threading
from collections.abc import Callable

from arise.serve.choices import ModelChoice
from arise.serve.errors import BadInput, Conflict, NotFound
from arise.serve.events import JobEvent, StateEvent
from arise.serve.jobs import Job, JobState
from arise.serve.lanes import Lane, Runner
from arise.serve.store import RunStore, new_id

_MODEL_NAME = re.compile(r"^[\w.:/@+-]{1,120}$")

#: Builds the runner of one model's lane (a warm Generator in the server).
RunnerFactory = Callable[[ModelChoice], Runner]


class JobBoard:
    def __init__(
        self,
        store: RunStore,
        choices: list[ModelChoice],
        make_runner: RunnerFactory,
        max_queued: int,
    ) -> None:
        self.store = store
        self.choices = choices
        self._make_runner = make_runner
        self._max_queued = max_queued
        self._lock = threading.Lock()
        self._lanes: dict[str, Lane] = {}
        self._jobs: dict[str, Job] = {job.id: job for job in store.load_jobs()}

    def choose(self, provider: str | None, model: str | None) -> ModelChoice:
        """The model a request asks for: a listed provider, with its model or another
        model name for an HTTP provider. The first ready choice when none is named."""
        if not provider:
            ready = [c for c in self.choices if c.ready]
            if not ready:
                raise BadInput("no model is ready on this server; see `arise llm info`")
            provider = ready[0].provider
        listed = next((c for c in self.choices if c.provider == provider), None)
        if listed is None:
            known = ", ".join(c.provider for c in self.choices)
            raise BadInput(f"unknown provider {provider!r}; this server offers: {known}")
        if not listed.ready:
            raise BadInput(f"{listed.label} cannot answer here: {listed.note}")
        if not model or model == listed.model:
            return listed
        if listed.provider in ("local", "replay"):
            raise BadInput(f"{listed.provider} has one model here: {listed.model}")
        if not _MODEL_NAME.match(model):
            raise BadInput(f"{model!r} is not a model name")
        return ModelChoice(listed.provider, model, f"{listed.provider}: {model}", True)

    def submit(self, description: str, choice: ModelChoice) -> Job:
        job = Job(
            id=new_id(), description=description, provider=choice.provider, model=choice.model
        )
        with self._lock:
            while job.id in self._jobs:  # two jobs in one second with the same random part
                job.id = new_id()
            lane = self._lane(choice)
            self._jobs[job.id] = job
        queued = StateEvent(state=JobState.QUEUED)
        job.add_event(queued)
        self._changed(job, queued)
        try:
            lane.submit(job)
        except Exception:
            with self._lock:
                del self._jobs[job.id]
            shutil.rmtree(self.store.folder(job.id), ignore_errors=True)
            raise
        return job

    def _lane(self, choice: ModelChoice) -> Lane:
        lane = self._lanes.get(choice.key)
        if lane is None:
            lane = Lane(
                choice.key,
                lambda: self._make_runner(choice),
                lambda job: self.store.folder(job.id, create=True),
                self._changed,
                self._max_queued,
            )
            self._lanes[choice.key] = lane
        return lane

    def _changed(self, job: Job, event: JobEvent) -> None:
        """Keep the disk in step: every event appended, the job file at each change of state."""
        self.store.append_event(job, event)
        if isinstance(event, StateEvent):
            self.store.save_job(job)

    def get(self, job_id: str) -> Job:
        job = self._jobs.get(job_id)
        if job is None:
            raise NotFound(f"no job {job_id!r}")
        return job

    def cancel(self, job_id: str) -> Job:
        job = self.get(job_id)
        if job.finished_state:
            raise Conflict(f"job {job_id} has already {job.state.value}")
        lane = self._lanes.get(job.key)
        if lane is not None:
            lane.cancel(job)
        return job

    def position(self, job: Job) -> int | None:
        lane = self._lanes.get(job.key)
        return lane.position(job) if lane and job.state is JobState.QUEUED else None

    def describe(self, job: Job) -> dict[str, object]:
        return {**job.as_dict(), "position": self.position(job)}

    def jobs(self) -> list[Job]:
        """Newest first."""
        with self._lock:
            return sorted(self._jobs.values(), key=lambda job: (job.created, job.id), reverse=True)

    def queue(self) -> list[dict[str, object]]:
        """Per model: the running job and how many wait."""
        with self._lock:
            lanes = list(self._lanes.values())
        return [
            {
                "key": lane.key,
                "running": lane.current.id if lane.current else None,
                "waiting": lane.waiting(),
            }
            for lane in lanes
        ]

    def close(self) -> None:
        with self._lock:
            lanes = list(self._lanes.values())
        for lane in lanes:
            lane.close()
