"""A trace as few timed vertices as keep linear interpolation within a tolerance of it.

OpenSCENARIO players interpolate a timed polyline linearly; keeping only the vertices
where the motion bends keeps a 20-second run small while every step of the trace stays
within the tolerance of the exported path.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

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


#: Below this many points a segment's deviation is computed in Python: numpy's call
#: overhead would dominate (a zigzag keeps every point and tests only tiny segments).
_VECTOR_FROM = 48


class _Track:
    """The points of a trace as arrays, and the deviation of any straight timed segment."""

    def __init__(self, points: list[TracePoint]):
        self.points = points
        self.steps = np.fromiter((p.step for p in points), float, len(points))
        self.xs = np.fromiter((p.x for p in points), float, len(points))
        self.ys = np.fromiter((p.y for p in points), float, len(points))
        # Every three-point segment's deviation at once: on a jagged trace (noise, or a
        # forged zigzag) most segments end there, and one Python call per point would not.
        self.three_point = np.zeros(len(points))
        if len(points) >= 3:
            steps, xs, ys = self.steps, self.xs, self.ys
            span = steps[2:] - steps[:-2]
            share = np.divide(
                steps[1:-1] - steps[:-2], span, out=np.zeros_like(span), where=span != 0
            )
            x = xs[:-2] + (xs[2:] - xs[:-2]) * share
            y = ys[:-2] + (ys[2:] - ys[:-2]) * share
            self.three_point[:-2] = np.hypot(xs[1:-1] - x, ys[1:-1] - y)

    def deviation(self, first: int, last: int) -> float:
        """The farthest any point between `first` and `last` is from where the uniformly
        timed segment between them puts it at its step."""
        if last - first < _VECTOR_FROM:
            return self._deviation_small(first, last)
        steps, xs, ys = self.steps, self.xs, self.ys
        span = steps[last] - steps[first]
        inner = slice(first + 1, last)
        share = (steps[inner] - steps[first]) / span if span else np.zeros(last - first - 1)
        x = xs[first] + (xs[last] - xs[first]) * share
        y = ys[first] + (ys[last] - ys[first]) * share
        return float(np.max(np.hypot(xs[inner] - x, ys[inner] - y)))

    def _deviation_small(self, first: int, last: int) -> float:
        points = self.points
        a, b = points[first], points[last]
        span = b.step - a.step
        worst = 0.0
        for point in points[first + 1 : last]:
            share = (point.step - a.step) / span if span else 0.0
            x = a.x + (b.x - a.x) * share
            y = a.y + (b.y - a.y) * share
            worst = max(worst, math.hypot(point.x - x, point.y - y))
        return worst

    def segment_end(self, start: int, tolerance: float) -> int:
        """A far end of a segment from `start` that keeps every point within `tolerance`.

        Galloping (ends 2, 4, 8, ... points on) and then bisecting between the last end
        that held and the first that did not: O(L log L) for a segment of L points where
        extending one point at a time was O(L^2). The end found is never nearer than the
        first end one-at-a-time extension would stop at, and it always holds."""
        last = len(self.points) - 1
        if start + 2 <= last and self.three_point[start] > tolerance:
            return start + 1
        good, bad = start + 1, None  # two neighbouring points: nothing lies between them
        while good < last:
            probe = min(start + 2 * (good - start), last)
            if self.deviation(start, probe) <= tolerance:
                good = probe
            else:
                bad = probe
                break
        if bad is None:
            return good
        while bad - good > 1:
            middle = (good + bad) // 2
            if self.deviation(start, middle) <= tolerance:
                good = middle
            else:
                bad = middle
        return good


def simplify(
    points: list[TracePoint], timestep: float, tolerance: float = TOLERANCE_M
) -> list[Vertex]:
    """Timed vertices through the first and last point; between two kept vertices every
    trace point is within `tolerance` metres of the straight, uniformly timed segment.
    A tolerance of 0 keeps every step.

    O(n log n) for n points, so a trace with tens of thousands of steps (a long run, or a
    forged one) exports in well under a second per agent."""
    if not points:
        return []
    track = _Track(points) if tolerance > 0 else None
    kept = [0]
    start = 0
    while start < len(points) - 1:
        end = track.segment_end(start, tolerance) if track is not None else start + 1
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
