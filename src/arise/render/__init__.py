"""One drawing module for every picture of a run: the still PNG, the GIF and the HTML replay.

Everything here works on its own plain data (`model`): a road outline and agent tracks in
world metres. Callers turn whatever they hold (a Scenic network in the worker, a map file in
the parent, a saved trace) into that data, so the three outputs cannot drift apart.
"""

from __future__ import annotations

from arise.render.model import (
    Area,
    Contact,
    Line,
    LineKind,
    Outline,
    RegionKind,
    Role,
    Scene,
    Track,
    Window,
)

__all__ = [
    "Area",
    "Contact",
    "Line",
    "LineKind",
    "Outline",
    "RegionKind",
    "Role",
    "Scene",
    "Track",
    "Window",
]
