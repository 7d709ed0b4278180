"""Which map file a script ran on: the registry's answer, carried in every check result."""

from __future__ import annotations

import re
from typing import Annotated

from pydantic import BaseModel, ConfigDict, StringConstraints

from arise.limits import MAP_NAME_PATTERN, MAX_NOTE, MAX_PATH

#: A map's name is a file stem (`NAME.xodr` in the cache, in an export, in a run folder),
#: so it can never name another folder: no separators, no leading dot.
MapName = Annotated[str, StringConstraints(pattern=MAP_NAME_PATTERN)]
_SAFE_NAME = re.compile(MAP_NAME_PATTERN)


def is_safe_map_name(name: str) -> bool:
    return _SAFE_NAME.fullmatch(name) is not None


class MapChoice(BaseModel):
    """Which map file a script ran on, and whether it was a substitute.

    `path` is meaningful only in a choice the parent made itself (the registry's cached
    copy); a choice read back from a trace or a worker is found again by `name`.
    """

    model_config = ConfigDict(extra="forbid")

    # What the script named (a town, or a map file beside it).
    requested: Annotated[str, StringConstraints(max_length=MAX_PATH)] | None
    name: MapName
    path: Annotated[str, StringConstraints(max_length=MAX_PATH)]
    substituted: bool = False
    reason: Annotated[str, StringConstraints(max_length=MAX_NOTE)] | None = None
