"""Which map file a script ran on: the registry's answer, carried in every check result."""

from __future__ import annotations

from pydantic import BaseModel


class MapChoice(BaseModel):
    """Which map file a script ran on, and whether it was a substitute."""

    requested: str | None
    name: str
    path: str
    substituted: bool = False
    reason: str | None = None
