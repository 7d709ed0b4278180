"""What a picture can show: a bounded number of agents and of poses per agent.

A trace may come from a run folder anyone handed over, or from a script that forged it:
hundreds of agents and tens of thousands of steps are valid input, and drawing all of it
would take minutes per replay (every GIF frame redraws every agent and its trail) and
write an HTML page of hundreds of megabytes, for a picture that cannot show more anyway.
`bounded` keeps the agents that matter (the ego, those in contact, the nearest to where
the picture looks) and every n-th step, and says in the scene's notes what it left out.
Real runs (a few agents, a few hundred steps) pass through unchanged.
"""

from __future__ import annotations

import math
from dataclasses import replace

from arise.render.model import Contact, Role, Scene, Track

#: Agents drawn: more than a legend or a frame can tell apart.
MAX_DRAWN_AGENTS = 24
#: Poses drawn per agent; beyond this, every n-th step (a scrub step of the HTML replay
#: then spans n steps of the trace).
MAX_DRAWN_POSES = 2000
#: Contact markers drawn (each is redrawn on every frame).
MAX_DRAWN_CONTACTS = 32


def bounded(scene: Scene) -> Scene:
    """The scene a picture draws: at most MAX_DRAWN_AGENTS tracks of at most
    MAX_DRAWN_POSES poses and MAX_DRAWN_CONTACTS contacts. Idempotent; a scene within
    the budget is returned as it is."""
    tracks, contacts, notes = scene.tracks, scene.contacts, list(scene.notes)
    if len(tracks) > MAX_DRAWN_AGENTS:
        tracks = _chosen(scene)
        notes.append(
            f"{len(tracks)} of {len(scene.tracks)} agents drawn: the ego, those in contact "
            "and the nearest to the interaction"
        )
    names = {t.name for t in tracks}
    contacts = [c for c in contacts if c.first in names and c.second in names]
    if len(contacts) > MAX_DRAWN_CONTACTS:
        notes.append(f"first {MAX_DRAWN_CONTACTS} of {len(contacts)} contacts drawn")
        contacts = sorted(contacts, key=lambda c: c.step)[:MAX_DRAWN_CONTACTS]
    longest = max((len(t.poses) for t in tracks), default=0)
    unchanged = tracks is scene.tracks and len(contacts) == len(scene.contacts)
    if unchanged and longest <= MAX_DRAWN_POSES:
        return scene
    scene = replace(scene, tracks=tracks, contacts=contacts, notes=notes)
    return _thinned(scene)


def _chosen(scene: Scene) -> list[Track]:
    """The agents worth drawing, in their original order: the ego, then those in contact
    with it, then those in any contact, then the nearest to the middle of the picture at
    the step it is about."""
    ego = next((t.name for t in scene.tracks if t.role is Role.EGO), None)
    with_ego = {
        n for c in scene.contacts if ego in (c.first, c.second) for n in (c.first, c.second)
    }
    in_contact = {n for c in scene.contacts for n in (c.first, c.second)}
    window = scene.window
    cx, cy = (window.xmin + window.xmax) / 2, (window.ymin + window.ymax) / 2
    step = scene.focus_step if scene.focus_step is not None else scene.steps

    def rank(track: Track) -> tuple[int, float]:
        pose = scene.pose(track, step)
        distance = math.hypot(pose.x - cx, pose.y - cy)
        if track.role is Role.EGO:
            return (0, distance)
        return (1 if track.name in with_ego else 2 if track.name in in_contact else 3, distance)

    keep = {id(t) for t in sorted(scene.tracks, key=rank)[:MAX_DRAWN_AGENTS]}
    return [t for t in scene.tracks if id(t) in keep]


def _thinned(scene: Scene) -> Scene:
    """Every n-th pose, so no track has more than MAX_DRAWN_POSES; the last pose of each
    track is kept, so the picture ends where the trace does."""
    longest = max((len(t.poses) for t in scene.tracks), default=0)
    if longest <= MAX_DRAWN_POSES:
        return scene
    every = math.ceil(longest / (MAX_DRAWN_POSES - 1))

    def drawn_step(step: int) -> int:  # never before the step it stands for
        return math.ceil(step / every)

    tracks = [
        replace(
            t,
            poses=[
                t.poses[min(i * every, len(t.poses) - 1)]
                for i in range(drawn_step(len(t.poses) - 1) + 1)
            ],
        )
        for t in scene.tracks
    ]
    contacts = [Contact(c.first, c.second, drawn_step(c.step), c.where) for c in scene.contacts]
    note = f"{scene.steps} steps of {scene.timestep:g} s, drawn every {every} steps"
    return replace(
        scene,
        tracks=tracks,
        contacts=contacts,
        steps=drawn_step(scene.steps),
        timestep=scene.timestep * every,
        focus_step=None if scene.focus_step is None else drawn_step(scene.focus_step),
        notes=[note, *scene.notes],
        drawn_every=every,
        trace_seconds=scene.steps * scene.timestep,
    )
