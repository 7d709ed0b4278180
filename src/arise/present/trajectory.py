"""A trace as few timed vertices as keep linear interpolation within a tolerance of it.

OpenSCENARIO players interpolate a timed polyline linearly; keeping only the vertices
where the motion bends keeps a 20-second run small while every step of the trace stays
within the tolerance of the exported path.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from arise.validate.types import TracePoint

TOLERANCE_M = 0.02


@dataclass(frozen=True)
class Vertex:
    time: float
    x: float
    y: float
    heading: float  # OpenSCENARIO's: 0 = +x, counter-clockwise, radians in (-pi, pi]


def osc_heading(scenic_heading: float) -> float:
    """Scenic faces +y at 0; OpenSCENARIO and OpenDRIVE face +x."""
    angle = math.remainder(scenic_heading + math.pi / 2, 2 * math.pi)
    return round(angle, 4) + 0.0  # never -0.0


def _deviation(points: list[TracePoint], first: int, last: int) -> float:
    a, b = points[first], points[last]
    span = b.step - a.step
    worst = 0.0
    for point in points[first + 1 : last]:
        share = (point.step - a.step) / span if span else 0.0
        x = a.x + (b.x - a.x) * share
        y = a.y + (b.y - a.y) * share
        worst = max(worst, math.hypot(point.x - x, point.y - y))
    return worst


def simplify(
    points: list[TracePoint], timestep: float, tolerance: float = TOLERANCE_M
) -> list[Vertex]:
    """Timed vertices through the first and last point; between two kept vertices every
    trace point is within `tolerance` metres of the straight, uniformly timed segment.
    A tolerance of 0 keeps every step."""
    if not points:
        return []
    kept = [0]
    start = 0
    while start < len(points) - 1:
        end = start + 1
        if tolerance > 0:
            while end + 1 < len(points) and _deviation(points, start, end + 1) <= tolerance:
                end += 1
        kept.append(end)
        start = end
    return [
        Vertex(
            time=round(points[i].step * timestep, 4),
            x=points[i].x,
            y=points[i].y,
            heading=osc_heading(points[i].heading),
        )
        for i in kept
    ]
