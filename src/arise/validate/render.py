"""A picture of the sampled scene and the trajectories, drawn headless with matplotlib."""

from __future__ import annotations

import os
import tempfile
from typing import Any

from arise.validate.facts import footprint
from arise.validate.types import AgentTrace, Collision

_COLORS = {
    "ego": "#d62728",
    "Pedestrian": "#2ca02c",
    "Bicycle": "#9467bd",
    "Motorcycle": "#8c564b",
    "Truck": "#ff7f0e",
}


def _draw_region(ax: Any, geometry: Any, **style: Any) -> None:
    polygons = getattr(geometry, "geoms", [geometry])
    for polygon in polygons:
        if polygon.is_empty or not hasattr(polygon, "exterior"):
            continue
        x, y = polygon.exterior.xy
        ax.fill(x, y, **style)


def draw_scene(
    network: Any,
    agents: list[AgentTrace],
    path: str,
    title: str = "",
    collisions: list[Collision] | None = None,
) -> str:
    """Write a PNG of the road network around the agents, with their paths; atomically."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from shapely.geometry import box

    xs = [p.x for a in agents for p in a.trajectory] or [0.0]
    ys = [p.y for a in agents for p in a.trajectory] or [0.0]
    margin = 20.0
    window = box(min(xs) - margin, min(ys) - margin, max(xs) + margin, max(ys) + margin)

    fig, ax = plt.subplots(figsize=(8, 8), dpi=100)
    if network is not None:
        for region, color in (
            (network.shoulderRegion, "#dddddd"),
            (network.sidewalkRegion, "#c6dbef"),
            (network.drivableRegion, "#bdbdbd"),
            (network.intersectionRegion, "#a8a8a8"),
        ):
            polygons = getattr(region, "polygons", None)
            if polygons is not None:
                _draw_region(ax, polygons.intersection(window), color=color, linewidth=0)
        for lane in network.lanes:
            line = lane.centerline.lineString
            if line.intersects(window):
                x, y = line.xy
                ax.plot(x, y, color="white", linewidth=0.6, linestyle="--")
    for agent in agents:
        color = _COLORS["ego"] if agent.is_ego else _COLORS.get(agent.kind, "#1f77b4")
        if not agent.trajectory:
            continue
        x = [p.x for p in agent.trajectory]
        y = [p.y for p in agent.trajectory]
        ax.plot(x, y, color=color, linewidth=1.5, label=f"{agent.name} ({agent.kind})")
        start = footprint(agent.trajectory[0], agent.width, agent.length)
        fx, fy = start.exterior.xy
        ax.fill(fx, fy, color=color, alpha=0.9)
        end = footprint(agent.trajectory[-1], agent.width, agent.length)
        ex, ey = end.exterior.xy
        ax.plot(ex, ey, color=color, linewidth=1)
        first = agent.trajectory[0]
        ax.annotate(
            agent.name, (first.x, first.y), fontsize=8, xytext=(4, 4), textcoords="offset points"
        )
    by_name = {agent.name: agent for agent in agents}
    for collision in collisions or []:
        hit = by_name.get(collision.first)
        if hit is not None and collision.step < len(hit.trajectory):
            point = hit.trajectory[collision.step]
            ax.plot(
                point.x,
                point.y,
                marker="X",
                color="black",
                markersize=12,
                label=f"contact {collision.first}-{collision.second} at {collision.time:g}s",
            )
    if agents:
        ax.legend(loc="upper right", fontsize=7, framealpha=0.8)
    ax.set_xlim(window.bounds[0], window.bounds[2])
    ax.set_ylim(window.bounds[1], window.bounds[3])
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    handle, temporary = tempfile.mkstemp(suffix=".png", dir=folder)
    os.close(handle)
    try:
        fig.savefig(temporary, bbox_inches="tight")
        os.replace(temporary, path)
    finally:
        plt.close(fig)
        if os.path.exists(temporary):
            os.unlink(temporary)
    return path
