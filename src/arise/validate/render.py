"""scene.png in the worker: the still of `arise.render`, the drawing the replays use too."""

from __future__ import annotations

import os
import tempfile
from typing import Any

from arise.render.raster import still_png
from arise.validate.picture import scene_of
from arise.validate.types import AgentTrace, Collision


def draw_scene(
    network: Any,
    agents: list[AgentTrace],
    path: str,
    title: str = "",
    collisions: list[Collision] | None = None,
    timestep: float = 0.1,
) -> str:
    """Write a PNG of the scene at its interaction, framed on it, atomically."""
    data = still_png(scene_of(agents, collisions or [], timestep, title, network))
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    handle, temporary = tempfile.mkstemp(suffix=".png", dir=folder)
    try:
        with os.fdopen(handle, "wb") as out:
            out.write(data)
        os.replace(temporary, path)
    finally:
        if os.path.exists(temporary):
            os.unlink(temporary)
    return path
