"""The messages between the server and a check process, one JSON line each, as typed
models: two discriminated unions on `op`, one per direction.

The check process parses untrusted scripts and results, so the server reads each of its
lines once into `FromProcess` (strict types, no unknown fields, a known `op`) and stops
the process on anything else. Nothing is ever unpickled. Payloads that are validated
elsewhere stay plain dicts: a run request (`checker.held_request`), the worker's result
(the strict `WorkerResult` schema, in the check process) and the script's view.
"""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter, ValidationError

from arise.errors import AriseError
from arise.validate.protocol import json_line
from arise.validate.types import Diagnostic, SandboxReport


class Op(StrEnum):
    READY = "ready"
    CHECK = "check"
    RUN = "run"
    RAN = "ran"
    DIED = "died"
    REFUSED = "refused"
    BROKEN = "broken"
    DONE = "done"
    FAILED = "failed"


class _Message(BaseModel):
    # strict: a "3" is not a 3; constants: a NaN in a result stays a NaN on the wire.
    model_config = ConfigDict(extra="forbid", strict=True, ser_json_inf_nan="constants")


# --- process -> server -------------------------------------------------------------------
class Ready(_Message):
    op: Literal[Op.READY] = Op.READY
    pid: int


class Run(_Message):
    """Asks the server to run a request on its pool (held to the server's own options)."""

    op: Literal[Op.RUN] = Op.RUN
    request: dict[str, Any]


class Done(_Message):
    op: Literal[Op.DONE] = Op.DONE
    view: dict[str, Any]


class Failed(_Message):
    op: Literal[Op.FAILED] = Op.FAILED
    error: str
    internal: bool  # a bug of ours (the process goes), not a problem with the script


# --- server -> process -------------------------------------------------------------------
class Check(_Message):
    op: Literal[Op.CHECK] = Op.CHECK
    text: str
    folder: str
    map_dir: str | None
    timeout: float
    agent: str | None = None  # a built-in the server admitted (`serve.driving`)


class Ran(_Message):
    op: Literal[Op.RAN] = Op.RAN
    result: dict[str, Any]


class Died(_Message):
    op: Literal[Op.DIED] = Op.DIED
    diagnostic: Diagnostic
    sandbox: SandboxReport | None


class Refused(_Message):
    op: Literal[Op.REFUSED] = Op.REFUSED
    sandbox: SandboxReport


class Broken(_Message):
    op: Literal[Op.BROKEN] = Op.BROKEN
    error: str


FromProcess = Ready | Run | Done | Failed
ToProcess = Check | Ran | Died | Refused | Broken
_FROM_PROCESS: TypeAdapter[FromProcess] = TypeAdapter(
    Annotated[FromProcess, Field(discriminator="op")]  # type: ignore  # see protocol.py
)
_TO_PROCESS: TypeAdapter[ToProcess] = TypeAdapter(
    Annotated[ToProcess, Field(discriminator="op")]  # type: ignore  # see protocol.py
)


class MessageError(AriseError):
    """A line that is not one of the protocol's messages for its direction."""


def from_process(line: bytes | str) -> FromProcess:
    """A check process's line as its message; raises MessageError for anything else."""
    try:
        return _FROM_PROCESS.validate_json(line)
    except ValidationError:
        raise MessageError("not a check process message") from None


def to_process(line: bytes | str) -> ToProcess:
    """The server's line as its message; raises MessageError for anything else."""
    try:
        return _TO_PROCESS.validate_json(line)
    except ValidationError:
        raise MessageError("not a server message") from None


def encode(message: FromProcess | ToProcess) -> bytes:
    """One message as its line, with the newline."""
    return json_line(message).encode()
