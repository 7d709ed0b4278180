"""Progress of a run as typed events: the CLI, the benchmark and a web page read the same.

`event_dict` is the one JSON form of an event (what a server would send as an SSE `data:`
line); its keys are those of the untyped dicts these events replace.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import asdict, dataclass
from enum import StrEnum
from typing import Any, ClassVar

from arise.generate.run import AttemptKind, RunStatus


class RunStage(StrEnum):
    EXTRACT = "extract"
    RETRIEVE = "retrieve"
    ASSEMBLE = "assemble"
    VALIDATE = "validate"
    REPAIR = "repair"


@dataclass(frozen=True)
class StageStarted:
    """A stage begins; `attempt` is the index of the attempt it will produce, if any."""

    stage: RunStage
    attempt: int | None = None
    error: str | None = None  # for a repair: the diagnostic being repaired, on one line

    event: ClassVar[str] = "stage"


@dataclass(frozen=True)
class AttemptChecked:
    """An attempt was validated."""

    index: int
    kind: AttemptKind
    ok: bool
    detail: str
    error: str | None = None

    event: ClassVar[str] = "attempt"


@dataclass(frozen=True)
class RunFinished:
    status: RunStatus
    summary: str

    event: ClassVar[str] = "done"


ProgressEvent = StageStarted | AttemptChecked | RunFinished
Progress = Callable[[ProgressEvent], None]


def event_dict(event: ProgressEvent) -> dict[str, Any]:
    """`{"event": "stage" | "attempt" | "done", ...fields}`, JSON-serialisable; fields that
    are None are left out."""
    fields = {
        key: (value.value if isinstance(value, StrEnum) else value)
        for key, value in asdict(event).items()
        if value is not None
    }
    return {"event": event.event, **fields}


def ignore(event: ProgressEvent) -> None:
    """A Progress that listens to nothing."""
