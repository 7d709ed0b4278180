"""Red lights and stop signs run, from the ego's crossings of the signals' stop lines.

A stop line is a segment across the lanes it controls, at a junction's edge. The traffic
it stops travels into the junction: with a road network, the side of the line that lies
in a junction says which way that is, whatever the order of the segment's ends in the
trace. Without one (or where both sides or neither are in a junction) the order says it:
(p1, p2) with p1 on the right edge and p2 on the left as the stopping traffic sees them,
so that it travels along p1->p2 turned clockwise by a right angle. A crossing the other
way (an oncoming car) is none.

The ego crosses a line when its rear point (the middle of its back edge) passes it, as in
CARLA's red-light test, which looks at the vehicle's tail: a car that stops with its nose
over the line has not run it. A red light is run by a crossing while the light is red; a
stop sign by a crossing with no step slower than `STOPPED_MPS` while the ego's front was
in the stopping zone before the line.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np

from arise.agents.types import LightState, SignalKind, SignalTrace
from arise.drive.metrics_road import RoadQueries
from arise.drive.metrics_track import Floats, Track

#: Slower than this is stopped (m/s).
STOPPED_MPS = 0.5
#: The stopping zone: the ego's front from this far before the line ...
STOP_ZONE_BEFORE_M = 5.0
#: ... to this far past it (a nose a little over the line has still stopped).
STOP_ZONE_PAST_M = 1.0
#: A crossing this far beyond either end of the line still counts (the line is drawn from
#: lane edges; a car on the edge marking is still in the lane).
LINE_END_SLACK_M = 0.5
#: How far either side of a stop line's middle the road network is asked for a junction.
JUNCTION_PROBE_M = 2.0


class _Line:
    """A stop line's frame: `past(x, y)` < 0 before it, `across(x, y)` along it from p1."""

    def __init__(self, signal: SignalTrace, road: RoadQueries | None) -> None:
        (x1, y1), (x2, y2) = signal.stop_line
        self.span = float(np.hypot(x2 - x1, y2 - y1))
        if self.span and road is not None and _junction_behind(signal, road):
            (x1, y1), (x2, y2) = (x2, y2), (x1, y1)
        self.origin = (x1, y1)
        tx, ty = ((x2 - x1) / self.span, (y2 - y1) / self.span) if self.span else (0.0, 0.0)
        self.along = (tx, ty)
        self.travel = (ty, -tx)  # along p1->p2 turned clockwise

    def past(self, x: Floats, y: Floats) -> Floats:
        return (x - self.origin[0]) * self.travel[0] + (y - self.origin[1]) * self.travel[1]

    def across(self, x: Floats, y: Floats) -> Floats:
        return (x - self.origin[0]) * self.along[0] + (y - self.origin[1]) * self.along[1]


def _junction_behind(signal: SignalTrace, road: RoadQueries) -> bool:
    """The junction lies on the side the segment's order calls "before" the line."""
    (x1, y1), (x2, y2) = signal.stop_line
    span = math.hypot(x2 - x1, y2 - y1)
    nx, ny = (y2 - y1) / span, -(x2 - x1) / span
    mx, my = (x1 + x2) / 2, (y1 + y2) / 2
    ahead = road.in_junction(mx + JUNCTION_PROBE_M * nx, my + JUNCTION_PROBE_M * ny)
    behind = road.in_junction(mx - JUNCTION_PROBE_M * nx, my - JUNCTION_PROBE_M * ny)
    return behind and not ahead


def _crossings(line: _Line, x: Floats, y: Floats) -> list[int]:
    """Indices k at which the point went from before the line (k-1) to on or past it (k),
    through the segment."""
    if line.span == 0 or len(x) < 2:
        return []
    past = line.past(x, y)
    found = []
    for k in np.flatnonzero((past[:-1] < 0) & (past[1:] >= 0)) + 1:
        share = past[k - 1] / (past[k - 1] - past[k])
        at = line.across(
            np.array([x[k - 1] + share * (x[k] - x[k - 1])]),
            np.array([y[k - 1] + share * (y[k] - y[k - 1])]),
        )[0]
        if -LINE_END_SLACK_M <= at <= line.span + LINE_END_SLACK_M:
            found.append(int(k))
    return found


def red_lights_run(
    signals: Iterable[SignalTrace], ego: Track, road: RoadQueries | None = None
) -> int:
    """Crossings of a traffic light's stop line while it was red."""
    rear_x, rear_y = ego.along(-ego.length / 2)
    count = 0
    for signal in signals:
        if signal.kind is not SignalKind.TRAFFIC_LIGHT:
            continue
        for k in _crossings(_Line(signal, road), rear_x, rear_y):
            if signal.state_at(int(ego.steps[k])) is LightState.RED:
                count += 1
    return count


def stop_signs_run(
    signals: Iterable[SignalTrace], ego: Track, road: RoadQueries | None = None
) -> int:
    """Crossings of a stop sign's line without a stop in its stopping zone first."""
    rear_x, rear_y = ego.along(-ego.length / 2)
    front_x, front_y = ego.along(ego.length / 2)
    slow = ego.speed < STOPPED_MPS
    count = 0
    for signal in signals:
        if signal.kind is not SignalKind.STOP_SIGN:
            continue
        line = _Line(signal, road)
        front_past = line.past(front_x, front_y)
        in_zone = (front_past >= -STOP_ZONE_BEFORE_M) & (front_past <= STOP_ZONE_PAST_M)
        since = 0
        for k in _crossings(line, rear_x, rear_y):
            if not np.any(slow[since : k + 1] & in_zone[since : k + 1]):
                count += 1
            since = k + 1
    return count
