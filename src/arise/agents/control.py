"""The control laws the built-in agents use, as plain functions with known answers.

- `idm_acceleration`: the Intelligent Driver Model (M. Treiber, A. Hennecke, D. Helbing,
  "Congested traffic states in empirical observations and microscopic simulations",
  Phys. Rev. E 62, 2000): a car-following law that keeps a desired speed on a free road
  and a safe, speed-dependent gap behind a leader, braking harder the faster it closes.
- `pure_pursuit_curvature`: pure pursuit (R. C. Coulter, "Implementation of the Pure
  Pursuit Path Tracking Algorithm", CMU-RI-TR-92-01, 1992): steer along the circular arc
  that passes through a point of the path one look-ahead distance away.
- `RoutePath`: the geometry both need: where the ego is along its route and how far
  ahead something on the route is.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from dataclasses import dataclass


@dataclass(frozen=True)
class IdmParameters:
    """The model's parameters; the defaults are the paper's city-traffic values, with a
    comfortable deceleration a little above its 1.67 m/s^2."""

    max_acceleration: float = 1.5  # a, m/s^2
    comfortable_deceleration: float = 2.0  # b, m/s^2
    minimum_gap: float = 2.0  # s0, m
    time_headway: float = 1.5  # T, s
    exponent: float = 4.0  # delta


def idm_acceleration(
    speed: float,
    desired_speed: float,
    gap: float | None = None,
    leader_speed: float = 0.0,
    p: IdmParameters | None = None,
) -> float:
    """dv/dt = a [1 - (v/v0)^delta - (s*/s)^2], s* = s0 + max(0, v T + v dv / (2 sqrt(a b))),
    with dv = v - v_leader the closing speed. `gap` None: a free road (no interaction
    term). A gap at or below zero gives the hardest braking the formula allows (the
    caller clips it to what the car can do)."""
    p = p or IdmParameters()
    free = 1.0 - (max(speed, 0.0) / desired_speed) ** p.exponent if desired_speed > 0 else -1.0
    if gap is None:
        return p.max_acceleration * free
    closing = speed - leader_speed
    wanted = p.minimum_gap + max(
        0.0,
        speed * p.time_headway
        + speed * closing / (2 * math.sqrt(p.max_acceleration * p.comfortable_deceleration)),
    )
    ratio = wanted / max(gap, 0.01)
    return p.max_acceleration * (free - ratio * ratio)


def pure_pursuit_curvature(
    x: float, y: float, heading: float, target: tuple[float, float]
) -> float:
    """Curvature (1/m, positive to the left) of the arc from the vehicle's position,
    tangent to its heading (Scenic's: 0 = +y, counter-clockwise), through `target`:
    2 sin(alpha) / l_d, alpha the target's bearing from the heading, l_d its distance."""
    dx, dy = target[0] - x, target[1] - y
    distance = math.hypot(dx, dy)
    if distance < 1e-6:
        return 0.0
    bearing = math.atan2(dy, dx) - (heading + math.pi / 2)
    alpha = math.atan2(math.sin(bearing), math.cos(bearing))
    return 2 * math.sin(alpha) / distance


class RoutePath:
    """A polyline with arc lengths: project a point on it, find the point at a distance."""

    def __init__(self, points: list[tuple[float, float]] | tuple[tuple[float, float], ...]):
        self.points = list(points) or [(0.0, 0.0)]
        self.stations = [0.0]
        for a, b in zip(self.points, self.points[1:], strict=False):
            self.stations.append(self.stations[-1] + math.dist(a, b))

    @property
    def length(self) -> float:
        return self.stations[-1]

    def project(
        self, x: float, y: float, near: float | None = None, window: float = 30.0
    ) -> tuple[float, float]:
        """(station, lateral distance) of the polyline's nearest point to (x, y); with
        `near`, only segments within `window` metres of that station are searched (so a
        route that passes a point twice is not confused)."""
        best = (0.0, math.inf)
        first, last = 0, len(self.points) - 1
        if near is not None:  # only the segments within the window (the stations are sorted)
            first = max(0, bisect_right(self.stations, near - window) - 1)
            last = min(last, bisect_right(self.stations, near + window))
        for i in range(first, last):
            a, b = self.points[i], self.points[i + 1]
            ax, ay = a
            vx, vy = b[0] - ax, b[1] - ay
            length2 = vx * vx + vy * vy
            t = (
                0.0
                if length2 == 0
                else max(0.0, min(1.0, ((x - ax) * vx + (y - ay) * vy) / length2))
            )
            px, py = ax + t * vx, ay + t * vy
            distance = math.hypot(x - px, y - py)
            if distance < best[1]:
                best = (self.stations[i] + t * math.sqrt(length2), distance)
        if len(self.points) == 1:
            best = (0.0, math.dist(self.points[0], (x, y)))
        return best

    def point_at(self, station: float) -> tuple[float, float]:
        """The point `station` metres along; before the start the first point, past the
        end the path goes on straight along its last segment (a driver who reaches the end
        of its route keeps its direction rather than turning back to the last point)."""
        if station <= 0 or len(self.points) == 1:
            return self.points[0]
        if station >= self.length:
            (ax, ay), (bx, by) = self.points[-2], self.points[-1]
            span = math.hypot(bx - ax, by - ay)
            if span == 0:
                return self.points[-1]
            extra = station - self.length
            return (bx + (bx - ax) / span * extra, by + (by - ay) / span * extra)
        i = bisect_right(self.stations, station) - 1
        a, b = self.points[i], self.points[i + 1]
        span = self.stations[i + 1] - self.stations[i]
        t = 0.0 if span == 0 else (station - self.stations[i]) / span
        return (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))

    def heading_at(self, station: float) -> float:
        """The path's heading (Scenic's convention) at `station`."""
        a = self.point_at(station - 0.5)
        b = self.point_at(station + 0.5)
        if a == b:
            return 0.0
        return math.atan2(b[1] - a[1], b[0] - a[0]) - math.pi / 2
