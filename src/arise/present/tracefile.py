"""`trace.json`: the trace a run's outputs were drawn from, saved beside them so a replay
or an export later needs no new simulation. It names the script it belongs to by hash: a
script edited since is checked again instead of trusting an old trace.

A run folder may come from anyone, so a trace.json is untrusted: it is read only when it
is a regular file below `MAX_TRACE_FILE_BYTES`, validated by the strict schema of the
facts (`arise.validate.types`), and its map is found again by name, never by the path it
records (`arise.present.source`).
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field, StringConstraints, ValidationError

from arise.limits import MAX_STEPS, MAX_TRACE_FILE_BYTES
from arise.present.errors import PresentError
from arise.present.files import write_text_atomic
from arise.present.untrusted import UntrustedFileError, read_json
from arise.validate.types import MapChoice, SimulationFacts

TRACE_FILE = "trace.json"
TRACE_VERSION = 1


class TraceFileError(PresentError):
    """A run folder's trace.json belongs to its script but is no trace we accept."""


class SavedTrace(BaseModel):
    model_config = ConfigDict(extra="forbid")

    version: int = TRACE_VERSION
    script_sha256: Annotated[str, StringConstraints(pattern=r"^[0-9a-f]{64}$")]
    # As the run recorded it: only its name is used (the map is found again by name).
    map: MapChoice | None = None
    simulation: SimulationFacts
    # How the trace was made (seed, steps), so it can be made again.
    seed: Annotated[int, Field(ge=-(2**63), le=2**64)] | None = None
    steps: Annotated[int, Field(ge=0, le=MAX_STEPS)] | None = None


def script_digest(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def write_trace(folder: Path, trace: SavedTrace) -> Path:
    return write_text_atomic(folder / TRACE_FILE, trace.model_dump_json(indent=1) + "\n")


def load_trace_file(folder: Path, script_text: str) -> SavedTrace | None:
    """The saved trace of exactly this script; None when there is none, or it belongs to
    another script or another trace version (the script is then checked again).
    TraceFileError when it claims this script but is no valid trace."""
    path = folder / TRACE_FILE
    try:
        data = read_json(path, MAX_TRACE_FILE_BYTES)
    except FileNotFoundError:
        return None
    except UntrustedFileError as error:
        raise TraceFileError(f"{error}; delete it to check the script again") from None
    if not isinstance(data, dict):
        raise TraceFileError(f"{path} is not a trace; delete it to check the script again")
    if data.get("version") != TRACE_VERSION or data.get("script_sha256") != script_digest(
        script_text
    ):
        return None
    try:
        return SavedTrace.model_validate(data)
    except ValidationError as error:
        first = error.errors(include_url=False, include_input=False)[0]
        where = ".".join(str(part) for part in first["loc"][:6])
        raise TraceFileError(
            f"{path} is not a valid trace ({where}: {first['msg']}); "
            "delete it to check the script again"
        ) from None


def read_trace(folder: Path, script_text: str) -> SavedTrace | None:
    """The saved trace of exactly this script, or None (absent, unreadable, invalid or
    stale): for callers that can do without one."""
    try:
        return load_trace_file(folder, script_text)
    except TraceFileError:
        return None
