"""Where a picture looks: at the interaction, not at the whole map.

The interaction is the ego's first contact, else its closest approach to another agent.
The frame holds the ego and that agent from a few seconds before to a little after it, and
the ego's start when that still fits, so the approach is visible and the road stays legible.
"""

from __future__ import annotations

import math

from arise.render.model import Contact, Point, Role, Track, Window

BEFORE_S = 4.0  # seconds of approach kept in the frame
AFTER_S = 2.0  # seconds after the interaction
MARGIN_M = 8.0
MIN_SIZE_M = 40.0
MAX_SIZE_M = 160.0  # beyond this the agents become specks: the ego's start is left out


def focus(tracks: list[Track], contacts: list[Contact]) -> tuple[int | None, str | None]:
    """The step and the other agent of the interaction (None: no ego or nobody else)."""
    ego = next((t for t in tracks if t.role is Role.EGO), None)
    if ego is None:
        return None, None
    for contact in sorted(contacts, key=lambda c: c.step):
        if ego.name in (contact.first, contact.second):
            other = contact.second if contact.first == ego.name else contact.first
            return contact.step, other
    best: tuple[float, int, str] | None = None
    for track in tracks:
        if track is ego or (track.role is Role.PROP and not _moves(track)):
            continue
        for step, (a, b) in enumerate(zip(ego.poses, track.poses, strict=False)):
            gap = math.hypot(a.x - b.x, a.y - b.y)
            if best is None or gap < best[0]:
                best = (gap, step, track.name)
    if best is None:
        return None, None
    return best[1], best[2]


def _moves(track: Track) -> bool:
    first, last = track.poses[0], track.poses[-1]
    return math.hypot(first.x - last.x, first.y - last.y) > 0.5


def _bounds(points: list[Point]) -> Window:
    xs = [p[0] for p in points]
    ys = [p[1] for p in points]
    return Window(min(xs), min(ys), max(xs), max(ys))


def _fit(window: Window, aspect: float) -> Window:
    """Grow the short side so width / height == aspect, and to at least MIN_SIZE_M."""
    cx, cy = (window.xmin + window.xmax) / 2, (window.ymin + window.ymax) / 2
    width = max(window.width, MIN_SIZE_M)
    height = max(window.height, MIN_SIZE_M / aspect)
    if width / height < aspect:
        width = height * aspect
    else:
        height = width / aspect
    return Window(cx - width / 2, cy - height / 2, cx + width / 2, cy + height / 2)


def frame(
    tracks: list[Track],
    timestep: float,
    focus_step: int | None,
    partner: str | None,
    aspect: float = 4 / 3,
) -> Window:
    """The window of a picture of these tracks with the given width / height ratio."""
    everything = [(p.x, p.y) for t in tracks for p in t.poses]
    if not everything:
        return _fit(Window(-20, -20, 20, 20), aspect)
    ego = next((t for t in tracks if t.role is Role.EGO), None)
    if ego is None or focus_step is None:
        return _fit(_bounds(everything).grown(MARGIN_M), aspect)
    involved = [t for t in tracks if t is ego or t.name == partner]
    first = max(0, focus_step - round(BEFORE_S / timestep))
    last = focus_step + round(AFTER_S / timestep)
    core = [(p.x, p.y) for t in involved for p in t.poses[first : last + 1]] or [
        (ego.poses[0].x, ego.poses[0].y)
    ]
    start = (ego.poses[0].x, ego.poses[0].y)
    window = _bounds([*core, start]).grown(MARGIN_M)
    if max(window.width, window.height) > MAX_SIZE_M:
        window = _bounds(core).grown(MARGIN_M)
    if max(window.width, window.height) > MAX_SIZE_M:
        anchor = core[min(len(core) - 1, focus_step - first)]
        half = MAX_SIZE_M / 2
        window = Window(anchor[0] - half, anchor[1] - half, anchor[0] + half, anchor[1] + half)
    return _fit(window, aspect)
