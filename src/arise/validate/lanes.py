"""Lane changes, oncoming-lane use and weaving, read from an agent's trace with the road network.

Runs in the worker, where the scene's network is at hand. A point inside a junction is
skipped (connecting lanes overlap there and cross each other by design), a move into the
next road or a lane's own successor is a continuation, not a change, and a lane boundary
must be held for a few steps before it counts, so a point that lands on a lane-section seam
or a lane edge for one step changes nothing.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from arise.validate.types import LaneChange, TracePoint
from arise.vocabulary import Side

# Steps an agent's centre must stay in a new lane before the move counts (0.3 s at 0.1 s).
HOLD_STEPS = 3
# A move back across the boundary within this many seconds is weaving, not a lane change:
# a deliberate change and return keeps the other lane for longer.
WEAVE_SECONDS = 1.5
# A lane runs against the agent when its direction and the agent's travel differ by more
# than this (a car that crosses the road at right angles is in no lane's direction).
AGAINST_ANGLE = math.radians(120)
MOVED = 0.05  # metres between steps below which the heading, not the motion, gives travel


@dataclass(frozen=True)
class LaneReading:
    """What the road network says about one agent's trace."""

    changes: list[LaneChange] = field(default_factory=list)
    opposite_steps: int = 0

    @property
    def same_direction_changes(self) -> int:
        """Moves between lanes of one direction: the lane changes a driver would name."""
        return sum(1 for c in self.changes if not c.into_opposite and not c.from_opposite)


def find_weaving(changes: Sequence[LaneChange], timestep: float) -> bool:
    """True when some move across a lane boundary is undone within WEAVE_SECONDS."""
    window = WEAVE_SECONDS / timestep
    return any(
        later.side is not earlier.side and later.step - earlier.step <= window
        for earlier, later in zip(changes, changes[1:], strict=False)
    )


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


def _travel_headings(points: Sequence[TracePoint]) -> list[float]:
    """Heading of motion at each point (Scenic: 0 = +y); the body heading when standing."""
    headings = []
    for index, point in enumerate(points):
        heading = point.heading
        if index > 0:
            before = points[index - 1]
            dx, dy = point.x - before.x, point.y - before.y
            if math.hypot(dx, dy) > MOVED:
                heading = math.atan2(dy, dx) - math.pi / 2
        headings.append(heading)
    return headings


def _runs_against(lane: Any, point: TracePoint, travel: float) -> bool:
    try:
        found = lane.orientation[(point.x, point.y)]
        direction = float(getattr(found, "yaw", found))
    except Exception:  # no orientation here: say nothing rather than guess
        return False
    return abs(_wrap(direction - travel)) > AGAINST_ANGLE


def _side(old: Any, new: Any, point: TracePoint, travel: float) -> Side:
    here = (point.x, point.y)
    a = old.centerline.project(here)
    b = new.centerline.project(here)
    dx, dy = b[0] - a[0], b[1] - a[1]
    # Left of a heading h (0 = +y, counter-clockwise) is the direction (-cos h, -sin h).
    left = -dx * math.cos(travel) - dy * math.sin(travel)
    return Side.LEFT if left > 0 else Side.RIGHT


def _continues(old: Any, new: Any) -> bool:
    """The new lane is the old one's next piece, not a neighbour."""
    if getattr(old, "_successor", None) is new or getattr(new, "_successor", None) is old:
        return True
    return any(m.endLane is new or m.connectingLane is new for m in getattr(old, "maneuvers", ()))


def _neighbours(old: Any, new: Any) -> bool:
    return new.group is old.group or new.group is getattr(old.group, "_opposite", None)


def read_lanes(network: Any, points: Sequence[TracePoint]) -> LaneReading:
    """The lane changes and steps against traffic of one trace (outside junctions)."""
    travel = _travel_headings(points)
    changes: list[LaneChange] = []
    opposite_steps = 0
    current: Any = None
    current_against = False
    candidate: Any = None
    held = 0
    for point, heading in zip(points, travel, strict=True):
        here = (point.x, point.y)
        if network.intersectionAt(here) is not None:
            current, candidate, held = None, None, 0  # a junction ends one lane's story
            continue
        lane = network.laneAt(here)
        if lane is None:
            continue
        if lane is not current:
            held = held + 1 if lane is candidate else 1
            candidate = lane
            if held >= HOLD_STEPS:
                against = _runs_against(lane, point, heading)
                if (
                    current is not None
                    and _neighbours(current, lane)
                    and not _continues(current, lane)
                ):
                    changes.append(
                        LaneChange(
                            step=point.step,
                            side=_side(current, lane, point, heading),
                            into_opposite=against and not current_against,
                            from_opposite=current_against and not against,
                        )
                    )
                current, current_against, candidate, held = lane, against, None, 0
        else:
            candidate, held = None, 0
        if current_against:
            opposite_steps += 1
    return LaneReading(changes=changes, opposite_steps=opposite_steps)
