"""Raster pictures with matplotlib (Agg): the still PNG and the frames of the GIF.

The road, the ego's whole path and its start, and the legend are drawn once; each frame
then only redraws the agents, their trails, contacts and the clock (blitting), which keeps
a 20-second replay to a few seconds of drawing.
"""

from __future__ import annotations

import io
import math
from collections.abc import Iterator
from typing import Any

import numpy as np

from arise.render import style
from arise.render.budget import bounded
from arise.render.model import Area, LineKind, Pose, Role, Scene

MAP_INCHES = (8.0, 6.0)  # the map axes; 4:3 like the window framing picks
SIDE_INCHES = 2.5  # the legend panel right of the map: it covers no road


def literal(text: str) -> str:
    """Text matplotlib draws as written: a `$` would start mathtext, whose parser fails
    on a name such as `a$\\x$` (an agent, a script or a title comes from the trace)."""
    return text.replace("$", "\\$")


def box_corners(pose: Pose, width: float, length: float) -> list[tuple[float, float]]:
    """An agent's footprint with a nose at its front, so its heading shows."""
    fx, fy = -math.sin(pose.heading), math.cos(pose.heading)
    sx, sy = fy, -fx
    hl, hw = length / 2, width / 2
    nose = min(hl * 0.35, 1.0)

    def at(forward: float, side: float) -> tuple[float, float]:
        return (pose.x + forward * fx + side * sx, pose.y + forward * fy + side * sy)

    return [at(-hl, -hw), at(-hl, hw), at(hl - nose, hw), at(hl, 0.0), at(hl - nose, -hw)]


def _area_path(area: Area) -> Any:
    from matplotlib.path import Path

    vertices: list[tuple[float, float]] = []
    codes: list[int] = []
    for ring in [area.exterior, *area.holes]:
        if len(ring) < 3:
            continue
        vertices.extend(ring)
        codes.extend(
            [int(Path.MOVETO)] + [int(Path.LINETO)] * (len(ring) - 2) + [int(Path.CLOSEPOLY)]
        )
    return Path(vertices, codes) if vertices else None


def _figure(scene: Scene, dpi: int) -> tuple[Any, Any, Any]:
    # A Figure with its own Agg canvas, not pyplot: no global state, safe in any thread.
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    width = MAP_INCHES[0] + SIDE_INCHES
    fig = Figure(figsize=(width, MAP_INCHES[1] + 0.5), dpi=dpi)
    FigureCanvasAgg(fig)
    fig.patch.set_facecolor("white")
    left = 0.05
    ax = fig.add_axes(
        (left, 0.06, MAP_INCHES[0] / width - left, MAP_INCHES[1] / (MAP_INCHES[1] + 0.5) - 0.06)
    )
    side = fig.add_axes((MAP_INCHES[0] / width + 0.01, 0.06, SIDE_INCHES / width - 0.02, 0.86))
    side.axis("off")
    ax.set_facecolor(style.BACKGROUND)
    window = scene.window
    ax.set_xlim(window.xmin, window.xmax)
    ax.set_ylim(window.ymin, window.ymax)
    ax.set_aspect("equal", adjustable="box")
    ax.tick_params(labelsize=7)
    ax.set_xlabel("x (m)", fontsize=7)
    ax.set_ylabel("y (m)", fontsize=7)
    fig.suptitle(literal(scene.title), fontsize=10, x=0.05, ha="left", y=0.985)
    return fig, ax, side


def _draw_roads(ax: Any, scene: Scene) -> None:
    from matplotlib.patches import PathPatch

    order = list(style.REGION_COLORS)
    for area in sorted(scene.outline.areas, key=lambda a: order.index(a.kind)):
        path = _area_path(area)
        if path is not None:
            ax.add_patch(
                PathPatch(path, facecolor=style.REGION_COLORS[area.kind], edgecolor="none")
            )
    for line in scene.outline.lines:
        xs, ys = zip(*line.points, strict=True)
        dashed = line.kind is LineKind.LANE
        ax.plot(
            xs,
            ys,
            color=style.LINE_COLORS[line.kind],
            linewidth=0.9 if dashed else 1.4,
            linestyle=(0, (4, 4)) if dashed else "-",
            solid_capstyle="butt",
        )


def _draw_ego_start(ax: Any, scene: Scene) -> None:
    """The ego's whole path (faint) and its start: an outline with an arrow and a word."""
    from matplotlib.patches import FancyArrow, Polygon

    ego = next((t for t in scene.tracks if t.role is Role.EGO), None)
    if ego is None:
        return
    xs = [p.x for p in ego.poses]
    ys = [p.y for p in ego.poses]
    ax.plot(xs, ys, color=style.PATH_COLOR, alpha=0.35, linewidth=1.2, linestyle=(0, (2, 2)))
    start = ego.poses[0]
    ax.add_patch(
        Polygon(
            box_corners(start, ego.width, ego.length),
            closed=True,
            fill=False,
            edgecolor=style.PATH_COLOR,
            linewidth=1.2,
            linestyle="--",
        )
    )
    fx, fy = -math.sin(start.heading), math.cos(start.heading)
    reach = max(ego.length, 3.0)
    ax.add_patch(
        FancyArrow(
            start.x + fx * ego.length / 2,
            start.y + fy * ego.length / 2,
            fx * reach,
            fy * reach,
            width=0.35,
            head_width=1.4,
            head_length=1.2,
            color=style.PATH_COLOR,
            length_includes_head=True,
        )
    )
    behind = (start.x - fx * (ego.length / 2 + 0.8), start.y - fy * (ego.length / 2 + 0.8))
    if abs(fx) >= abs(fy):  # text behind the box, away from where it drives
        align = {"ha": "right" if fx > 0 else "left", "va": "center"}
    else:
        align = {"ha": "center", "va": "top" if fy > 0 else "bottom"}
    ax.text(*behind, "ego start", fontsize=7, color=style.PATH_COLOR, clip_on=True, **align)


def _draw_legend(side: Any, scene: Scene, extra: list[str]) -> None:
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    handles: list[Any] = [
        Patch(
            facecolor=style.ROLE_COLORS[t.role],
            edgecolor="none",
            label=literal(style.legend_text(t)),
        )
        for t in scene.tracks
    ]
    if any(t.role is Role.EGO for t in scene.tracks):
        handles.append(
            Line2D([], [], color=style.PATH_COLOR, alpha=0.5, linestyle="--", label="ego path")
        )
    if scene.contacts:
        handles.append(
            Line2D([], [], color=style.CONTACT_COLOR, marker="X", linestyle="", label="contact")
        )
    side.legend(handles=handles, loc="upper left", fontsize=7, frameon=False, borderaxespad=0)
    if extra:
        side.text(
            0.0, 0.0, literal("\n".join(extra)), fontsize=7, va="bottom", ha="left", color="#333333"
        )


class _Agents:
    """The artists of the moving agents, updated in place each frame."""

    def __init__(self, ax: Any, scene: Scene, animated: bool):
        from matplotlib.patches import Polygon

        self.scene = scene
        self.items = []
        # The trails as arrays: a frame then shows a view of them, not a new list.
        self.paths = [
            (np.array([p.x for p in t.poses]), np.array([p.y for p in t.poses]))
            for t in scene.tracks
        ]
        for track in scene.tracks:
            color = style.ROLE_COLORS[track.role]
            (trail,) = ax.plot([], [], color=color, linewidth=1.6, animated=animated)
            body = Polygon(
                box_corners(track.poses[0], track.width, track.length),
                closed=True,
                facecolor=color,
                edgecolor="black",
                linewidth=0.6,
                animated=animated,
            )
            ax.add_patch(body)
            text = ax.annotate(
                literal(style.label(track)),
                (track.poses[0].x, track.poses[0].y),
                xytext=(6, 6),
                textcoords="offset points",
                fontsize=7,
                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.75},
                animated=animated,
                annotation_clip=True,
            )
            self.items.append((track, trail, body, text))
        self.contacts = [
            ax.plot(
                [c.where[0]],
                [c.where[1]],
                marker="X",
                markersize=11,
                color=style.CONTACT_COLOR,
                markeredgecolor="white",
                linestyle="",
                animated=animated,
                visible=False,
            )[0]
            for c in scene.contacts
        ]

    def show(self, step: int) -> list[Any]:
        artists: list[Any] = []
        for (track, trail, body, text), (xs, ys) in zip(self.items, self.paths, strict=True):
            pose = self.scene.pose(track, step)
            trail.set_data(xs[: step + 1], ys[: step + 1])
            body.set_xy(box_corners(pose, track.width, track.length))
            text.xy = (pose.x, pose.y)
            artists.extend((trail, body, text))
        for contact, marker in zip(self.scene.contacts, self.contacts, strict=True):
            marker.set_visible(step >= contact.step)
            artists.append(marker)
        return artists


#: Contacts listed by name beside the picture; the rest are counted.
MAX_LISTED_CONTACTS = 8


def notes(scene: Scene) -> list[str]:
    """The lines beside the picture: its length, what it leaves out, its contacts."""
    lines = [f"{scene.steps} steps of {scene.timestep:g} s"] if scene.drawn_every == 1 else []
    lines += scene.notes
    for contact in scene.contacts[:MAX_LISTED_CONTACTS]:
        lines.append(
            f"contact {contact.first}-{contact.second} at {scene.time_at(contact.step):.1f} s"
        )
    if len(scene.contacts) > MAX_LISTED_CONTACTS:
        lines.append(f"... and {len(scene.contacts) - MAX_LISTED_CONTACTS} more contacts")
    return lines


def still_png(scene: Scene, dpi: int = 100) -> bytes:
    """The scene at its interaction (or its end): trails so far, the ego's start and path,
    every agent at that moment, contacts, and a legend beside the map."""
    scene = bounded(scene)
    fig, ax, side = _figure(scene, dpi)
    _draw_roads(ax, scene)
    _draw_ego_start(ax, scene)
    step = scene.focus_step if scene.focus_step is not None else scene.steps
    _Agents(ax, scene, animated=False).show(step)
    moment = (
        "first contact"
        if scene.contacts and step == min(c.step for c in scene.contacts)
        else ("closest approach" if scene.focus_step is not None else "end")
    )
    _draw_legend(
        side, scene, [f"shown at t = {scene.time_at(step):.1f} s ({moment})", *notes(scene)]
    )
    out = io.BytesIO()
    fig.savefig(out, format="png", dpi=dpi)
    return out.getvalue()


def frames(scene: Scene, stride: int, dpi: int = 60) -> Iterator[np.ndarray]:
    """One RGB image every `stride` steps, from step 0 to the last step. Give it a scene
    within the drawing budget (`budget.bounded`): each frame redraws every agent."""
    fig, ax, side = _figure(scene, dpi)
    _draw_roads(ax, scene)
    _draw_ego_start(ax, scene)
    _draw_legend(side, scene, notes(scene))
    agents = _Agents(ax, scene, animated=True)
    clock = side.text(
        0.0, 0.32, "", fontsize=11, family="monospace", animated=True, transform=side.transAxes
    )
    canvas = fig.canvas
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    steps = list(range(0, scene.steps + 1, stride))
    if steps[-1] != scene.steps:
        steps.append(scene.steps)
    for step in steps:
        canvas.restore_region(background)
        for artist in agents.show(step):
            ax.draw_artist(artist)
        clock.set_text(f"t = {scene.time_at(step):.1f} s\nof {scene.seconds:.1f} s")
        side.draw_artist(clock)
        yield np.asarray(canvas.buffer_rgba())[:, :, :3].copy()
