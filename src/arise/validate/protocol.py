"""The messages a worker sends its pool, one JSON line each, as typed models.

The worker's channel carries what a script's process wrote, so the pool reads each line
once into `WorkerMessage` (strict types, no unknown fields, a known `event`) and refuses
anything else as a protocol violation. Nothing here is ever unpickled or executed. A
result's payload stays a plain dict, bounded by the line's size limit: the facts in it
are held to the strict `WorkerResult` schema later (`arise.validate.api`).
"""

from __future__ import annotations

import json
from enum import StrEnum
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter, ValidationError
from pydantic_core import PydanticSerializationError

from arise.errors import AriseError
from arise.validate.types import SandboxReport, Stage


class WorkerEvent(StrEnum):
    """What a worker's message says."""

    READY = "ready"  # the worker is confined and waits for scripts (its first message)
    STAGE = "stage"  # the check entered a stage
    RESULT = "result"  # the check's result
    CHILD_DIED = "child_died"  # the script's process ended without a result


class _Message(BaseModel):
    # strict: a "3" is not a 3; constants: a NaN in a result stays a NaN on the wire, for
    # the strict result schema to refuse (not a null it might accept).
    model_config = ConfigDict(extra="forbid", strict=True, ser_json_inf_nan="constants")


class Ready(_Message):
    """Sent once, before any script ran: which confinement the worker reached."""

    event: Literal[WorkerEvent.READY] = WorkerEvent.READY
    pid: int
    sandbox: SandboxReport


class StageEntered(_Message):
    event: Literal[WorkerEvent.STAGE] = WorkerEvent.STAGE
    stage: Stage


class Result(_Message):
    """The check's result as the script's process sent it (untrusted until validated)."""

    event: Literal[WorkerEvent.RESULT] = WorkerEvent.RESULT
    result: dict[str, Any]


class ChildDied(_Message):
    """The fork server's word that the script's process ended without a result."""

    event: Literal[WorkerEvent.CHILD_DIED] = WorkerEvent.CHILD_DIED
    code: int
    flooded: bool = False
    garbled: bool = False  # it wrote lines that were not its protocol


WorkerMessage = Ready | StageEntered | Result | ChildDied
# Validated by its `event` first: an unknown event is refused by name, not by each shape.
# mypy reports this Annotated-as-a-value as `arg-type` from a warm cache and as
# `maybe-unrecognized-str-typeform` from a cold one, so the ignore names no code.
_WORKER_MESSAGES: TypeAdapter[WorkerMessage] = TypeAdapter(
    Annotated[WorkerMessage, Field(discriminator="event")]  # type: ignore
)


class ProtocolError(AriseError):
    """A line on a worker's channel that is not one of its messages."""


def parse_message(line: bytes | str) -> WorkerMessage:
    """One line into its message; raises ProtocolError for anything else (not JSON, an
    unknown event, a missing or extra field, a wrong type, nesting too deep)."""
    try:
        return _WORKER_MESSAGES.validate_json(line)
    except ValidationError:
        raise ProtocolError("not a worker message") from None


def dump_message(message: WorkerMessage) -> str:
    """One message as its line (with the newline)."""
    return json_line(message)


def json_line(message: BaseModel) -> str:
    """A model as one JSON line. A lone surrogate (a script may raise an error that
    holds one) becomes U+FFFD, so the message still goes through and still parses."""
    try:
        return message.model_dump_json() + "\n"
    except PydanticSerializationError:
        text = json.dumps(message.model_dump(mode="json"), ensure_ascii=False)
        return text.encode("utf-16", "surrogatepass").decode("utf-16", "replace") + "\n"
