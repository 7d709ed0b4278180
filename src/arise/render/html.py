"""The HTML replay: one self-contained file (inline script and style, the scene as JSON),
which plays, pauses and scrubs in any browser without fetching anything."""

from __future__ import annotations

import html
import json
import re
from importlib import resources
from typing import Any

from arise.render import style
from arise.render.budget import bounded
from arise.render.model import Scene
from arise.render.raster import notes


def _track(scene: Scene, index: int) -> dict[str, Any]:
    track = scene.tracks[index]
    return {
        "name": track.name,
        "kind": track.kind,
        "role": track.role.value,
        "label": style.label(track),
        "legend": style.legend_text(track),
        "width": round(track.width, 3),
        "length": round(track.length, 3),
        "x": [round(p.x, 2) for p in track.poses],
        "y": [round(p.y, 2) for p in track.poses],
        "h": [round(p.heading, 3) for p in track.poses],
        "v": [round(p.speed, 2) for p in track.poses],
    }


def scene_data(scene: Scene) -> dict[str, Any]:
    """The replay's data: what the page's script draws, in world metres."""
    window = scene.window
    return {
        "title": scene.title,
        "timestep": scene.timestep,
        "steps": scene.steps,
        "seconds": scene.seconds,
        "window": {
            "xmin": round(window.xmin, 2),
            "ymin": round(window.ymin, 2),
            "xmax": round(window.xmax, 2),
            "ymax": round(window.ymax, 2),
        },
        "outline": {
            "areas": [
                {"kind": a.kind.value, "exterior": a.exterior, "holes": a.holes}
                for a in scene.outline.areas
            ],
            "lines": [
                {"kind": line.kind.value, "points": line.points} for line in scene.outline.lines
            ],
        },
        "tracks": [_track(scene, i) for i in range(len(scene.tracks))],
        "contacts": [
            {"first": c.first, "second": c.second, "step": c.step, "where": list(c.where)}
            for c in scene.contacts
        ],
        "notes": notes(scene),
        "colors": {
            "background": style.BACKGROUND,
            "regions": {k.value: v for k, v in style.REGION_COLORS.items()},
            "lines": {k.value: v for k, v in style.LINE_COLORS.items()},
            "roles": {k.value: v for k, v in style.ROLE_COLORS.items()},
            "contact": style.CONTACT_COLOR,
            "path": style.PATH_COLOR,
        },
    }


def replay_html(scene: Scene) -> str:
    """The page of a scene, drawn within the budget (`budget.bounded`): a trace of
    hundreds of agents and thousands of steps stays a page of a few megabytes."""
    scene = bounded(scene)
    template = resources.files("arise.render").joinpath("replay_template.html").read_text("utf-8")
    # JSON inside <script>: no "<", ">" or "&" may reach the HTML parser as such.
    payload = (
        json.dumps(scene_data(scene), separators=(",", ":"))
        .replace("<", "\\u003c")
        .replace(">", "\\u003e")
        .replace("&", "\\u0026")
    )
    values = {"TITLE": html.escape(scene.title), "DATA": payload}
    # One pass, so a title that reads "__DATA__" stays a title.
    return re.sub(r"__(TITLE|DATA)__", lambda found: values[found.group(1)], template)
