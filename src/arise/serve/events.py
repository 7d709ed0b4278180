"""A job's events as typed models: what the page's event stream sends and events.jsonl
keeps.

Four kinds, one discriminated union on `event`: a change of the job's state, and the
generator's own progress events (`arise.generate.events`) in their JSON form. Events read
back from a run folder are untrusted (anyone may hand one over), so each line is
validated into the union (known kinds and enums, bounded strings, no unknown fields)
and anything else is skipped.
"""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, StringConstraints, TypeAdapter, ValidationError

from arise.generate.events import ProgressEvent, RunStage, event_dict
from arise.generate.run import AttemptKind, RunStatus
from arise.limits import MAX_MESSAGE

Text = Annotated[str, StringConstraints(max_length=MAX_MESSAGE)]
Index = Annotated[int, Field(ge=0, le=10_000)]


class JobState(StrEnum):
    """Where a job is (`arise.serve.jobs`); here, because its state events carry it."""

    QUEUED = "queued"
    RUNNING = "running"
    DONE = "done"  # the run ended with a script that executed
    FAILED = "failed"  # the run ended without one (its message says why)
    CANCELLED = "cancelled"


class EventKind(StrEnum):
    STATE = "state"  # the job's state changed
    STAGE = "stage"  # the generator entered a stage
    ATTEMPT = "attempt"  # an attempt was validated
    DONE = "done"  # the generator's run ended


class _Event(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


class StateEvent(_Event):
    event: Literal[EventKind.STATE] = EventKind.STATE
    state: JobState
    message: Text | None = None


class StageEvent(_Event):
    event: Literal[EventKind.STAGE] = EventKind.STAGE
    stage: RunStage
    attempt: Index | None = None
    error: Text | None = None


class AttemptEvent(_Event):
    event: Literal[EventKind.ATTEMPT] = EventKind.ATTEMPT
    index: Index
    kind: AttemptKind
    ok: bool
    detail: Text
    error: Text | None = None


class DoneEvent(_Event):
    event: Literal[EventKind.DONE] = EventKind.DONE
    status: RunStatus
    summary: Text


JobEvent = StateEvent | StageEvent | AttemptEvent | DoneEvent
_JOB_EVENTS: TypeAdapter[JobEvent] = TypeAdapter(
    Annotated[JobEvent, Field(discriminator="event")]  # type: ignore  # see protocol.py
)


def from_progress(progress: ProgressEvent) -> JobEvent:
    """The generator's event as the job's (long texts cut to the bound, not refused:
    a live run must not fail over the length of its own message)."""
    data = {
        key: value[:MAX_MESSAGE] if isinstance(value, str) else value
        for key, value in event_dict(progress).items()
    }
    return _JOB_EVENTS.validate_python(data)


def read_event(line: str | bytes) -> JobEvent | None:
    """One line of events.jsonl as its event; None for anything else (a line cut short
    by a killed server, or one that is not ours)."""
    try:
        return _JOB_EVENTS.validate_json(line)
    except ValidationError:
        return None


def event_data(event: JobEvent) -> dict[str, Any]:
    """The JSON form sent and kept: a state event always says its message (null
    included); a progress event leaves out fields that are None, as `event_dict` does."""
    return event.model_dump(mode="json", exclude_none=not isinstance(event, StateEvent))


def event_json(event: JobEvent) -> str:
    return event.model_dump_json(exclude_none=not isinstance(event, StateEvent))
