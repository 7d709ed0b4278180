"""A trace of the validator as a drawable scene (`arise.render`), for the still picture in
the worker and the replays in the parent."""

from __future__ import annotations

from typing import Any

from arise.render.framing import focus, frame
from arise.render.model import Contact, Outline, Pose, Scene, Track
from arise.render.outline import outline_of
from arise.render.style import role_of
from arise.validate.types import AgentTrace, Collision


def track_of(agent: AgentTrace) -> Track:
    """An agent's poses indexed by step (a step the trace lacks repeats the one before)."""
    by_step = {p.step: p for p in agent.trajectory}
    poses: list[Pose] = []
    last = max(by_step) if by_step else -1
    for step in range(last + 1):
        point = by_step.get(step)
        if point is None:
            poses.append(poses[-1])
            continue
        poses.append(Pose(point.x, point.y, point.heading, point.speed))
    return Track(
        name=agent.name,
        kind=agent.kind,
        role=role_of(agent.kind, agent.is_ego, agent.behavior),
        width=agent.width,
        length=agent.length,
        poses=poses,
    )


def contacts_of(tracks: list[Track], collisions: list[Collision]) -> list[Contact]:
    by_name = {t.name: t for t in tracks}
    found = []
    for collision in collisions:
        first, second = by_name.get(collision.first), by_name.get(collision.second)
        if first is None or second is None or not first.poses or not second.poses:
            continue
        a = first.poses[min(collision.step, len(first.poses) - 1)]
        b = second.poses[min(collision.step, len(second.poses) - 1)]
        where = (round((a.x + b.x) / 2, 2), round((a.y + b.y) / 2, 2))
        found.append(Contact(collision.first, collision.second, collision.step, where))
    return found


def scene_of(
    agents: list[AgentTrace],
    collisions: list[Collision],
    timestep: float,
    title: str,
    network: Any = None,
) -> Scene:
    """The scene to draw: tracks, contacts, the frame on the interaction, and the road
    outline of `network` (a Scenic road network, or None) inside that frame."""
    tracks = [track_of(a) for a in agents if a.trajectory]
    contacts = contacts_of(tracks, collisions)
    step, partner = focus(tracks, contacts)
    window = frame(tracks, timestep, step, partner)
    steps = max((len(t.poses) - 1 for t in tracks), default=0)
    outline = outline_of(network, window.grown(5.0)) if network is not None else Outline()
    return Scene(
        title=title,
        timestep=timestep,
        steps=steps,
        tracks=tracks,
        outline=outline,
        window=window,
        contacts=contacts,
        focus_step=step,
    )
