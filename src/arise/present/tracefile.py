"""`trace.json`: the trace a run's outputs were drawn from, saved beside them so a replay
or an export later needs no new simulation. It names the script it belongs to by hash: a
script edited since is checked again instead of trusting an old trace."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

from pydantic import BaseModel, ValidationError

from arise.present.files import write_text_atomic
from arise.validate.types import MapChoice, SimulationFacts

TRACE_FILE = "trace.json"
TRACE_VERSION = 1


class SavedTrace(BaseModel):
    version: int = TRACE_VERSION
    script_sha256: str
    map: MapChoice | None = None
    simulation: SimulationFacts
    # How the trace was made (seed, steps), so it can be made again.
    seed: int | None = None
    steps: int | None = None


def script_digest(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def write_trace(folder: Path, trace: SavedTrace) -> Path:
    return write_text_atomic(folder / TRACE_FILE, trace.model_dump_json(indent=1) + "\n")


def read_trace(folder: Path, script_text: str) -> SavedTrace | None:
    """The saved trace of exactly this script, or None (absent, unreadable or stale)."""
    path = folder / TRACE_FILE
    if not path.is_file():
        return None
    try:
        trace = SavedTrace.model_validate(json.loads(path.read_text(encoding="utf-8")))
    except (OSError, ValueError, ValidationError):
        return None
    if trace.version != TRACE_VERSION or trace.script_sha256 != script_digest(script_text):
        return None
    return trace
