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


#: A segment is first extended one point at a time (in Python, cheap for a few points),
#: then every end up to _WINDOW points on is measured at once (numpy); both find exactly
#: where one-at-a-time extension stops. Longer segments gallop.
_STEPWISE = 8
_WINDOW = 40


def _share(steps: np.ndarray, first: np.ndarray | float, span: np.ndarray) -> np.ndarray:
    """How far along a uniformly timed segment each step is (0 for a segment of no time)."""
    shape = np.broadcast(steps, span).shape
    return np.divide(steps - first, span, out=np.zeros(shape), where=span != 0)


class _Track:
    """The points of a trace as arrays, and the deviation of straight timed segments."""

    def __init__(self, points: list[TracePoint]):
        self.points = points
        self.last = len(points) - 1
        self.steps = np.fromiter((p.step for p in points), float, len(points))
        self.xs = np.fromiter((p.x for p in points), float, len(points))
        self.ys = np.fromiter((p.y for p in points), float, len(points))
        # Every three-point segment's deviation at once: on a jagged trace (noise, or a
        # forged zigzag) most segments end there, and one numpy call per point would not.
        self.three_point = [0.0] * len(points)
        if len(points) >= 3:
            steps, xs, ys = self.steps, self.xs, self.ys
            share = _share(steps[1:-1], steps[:-2], steps[2:] - steps[:-2])
            x = xs[:-2] + (xs[2:] - xs[:-2]) * share
            y = ys[:-2] + (ys[2:] - ys[:-2]) * share
            self.three_point[:-2] = np.hypot(xs[1:-1] - x, ys[1:-1] - y).tolist()

    def deviation(self, first: int, last: int) -> float:
        """The farthest any point between `first` and `last` is from where the uniformly
        timed segment between them puts it at its step."""
        steps, xs, ys = self.steps, self.xs, self.ys
        inner = slice(first + 1, last)
        share = _share(steps[inner], steps[first], np.asarray(steps[last] - steps[first]))
        x = xs[first] + (xs[last] - xs[first]) * share
        y = ys[first] + (ys[last] - ys[first]) * share
        return float(np.max(np.hypot(xs[inner] - x, ys[inner] - y), initial=0.0))

    def _stepwise_end(self, start: int, tolerance: float) -> tuple[int, bool]:
        """Where one-at-a-time extension from `start` stops, if it stops within _STEPWISE
        points (True), else the last end tried, which holds (False)."""
        points = self.points
        a = points[start]
        end = start + 1
        while end < min(start + _STEPWISE, self.last):
            b = points[end + 1]
            span = b.step - a.step
            for point in points[start + 1 : end + 1]:
                share = (point.step - a.step) / span if span else 0.0
                x = a.x + (b.x - a.x) * share
                y = a.y + (b.y - a.y) * share
                if math.hypot(point.x - x, point.y - y) > tolerance:
                    return end, True
            end += 1
        return end, end == self.last

    def _window_end(self, start: int, tolerance: float) -> tuple[int, bool]:
        """Where one-at-a-time extension from `start` stops, if it stops within _WINDOW
        points (True), else the window's far end, which holds (False). Every end in the
        window against every point before it: one array operation, not _WINDOW calls."""
        top = min(start + _WINDOW, self.last)
        ends = np.arange(start + _STEPWISE + 1, top + 1)  # nearer ends hold (stepwise)
        if ends.size == 0:
            return top, True
        inner = np.arange(start + 1, top)
        steps, xs, ys = self.steps, self.xs, self.ys
        share = _share(steps[inner][None, :], steps[start], (steps[ends] - steps[start])[:, None])
        x = xs[start] + (xs[ends] - xs[start])[:, None] * share
        y = ys[start] + (ys[ends] - ys[start])[:, None] * share
        gaps = np.hypot(xs[inner][None, :] - x, ys[inner][None, :] - y)
        gaps[inner[None, :] >= ends[:, None]] = 0.0  # a point past an end is not its concern
        failing = np.flatnonzero(gaps.max(axis=1) > tolerance)
        if failing.size:
            return int(ends[failing[0]]) - 1, True
        return top, top == self.last

    def segment_end(self, start: int, tolerance: float) -> int:
        """A far end of a segment from `start` that keeps every point within `tolerance`.

        Within _WINDOW points, exactly where extending the segment one point at a time
        stops. Past it, galloping (ends twice, four times, ... as far) and then bisecting
        between the last end that held and the first that did not: O(L log L) for a
        segment of L points where extending one point at a time was O(L^2). The end found
        is never nearer than the one-at-a-time end, and it always holds."""
        if start + 2 <= self.last and self.three_point[start] > tolerance:
            return start + 1
        good, done = self._stepwise_end(start, tolerance)
        if done:
            return good
        good, done = self._window_end(start, tolerance)
        if done:
            return good
        bad = None
        while good < self.last:
            probe = min(start + 2 * (good - start), self.last)
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
