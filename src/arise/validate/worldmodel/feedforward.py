"""Steer for the curve ahead and damp by heading: what the offline lateral PID lacks.

Scenic's lateral PID sees only the cross-track error, so on a curve it must first lose
the path before it steers: a left turn at a junction lagged 0.8 m outside the arc, the
integral wound up, the car then cut inside and left the junction 34 degrees short of the
exit lane's heading, and lane following wove across the lane line. Town01's tight corners
ran wide for the same reason. CARLA's own agents avoid this with a look-ahead (pure
pursuit) on the waypoints ahead; here the steering that holds the curve of the path is
added to the PID's output, and the PID corrects only what is left. A heading term tops
the PID's damping up at low speed, where its derivative term is weak (`heading_damping`).

The behaviors pass the controller a cross-track error, not the path. The path is found
again in the road network: among the lane centrelines near the car and running its way
(or against it, for a car in the oncoming lane), the one whose signed distance to the car
equals the error the behavior measured. Where two paths still coincide (the straight and
the turning connecting lane at a junction's edge), the one kept from before wins, then the
straighter one; they part within a metre or two.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from shapely.geometry import LineString, Point
from shapely.strtree import STRtree

from arise.validate.worldmodel.linegeometry import line_direction, signed_curvatures, wrap_angle

SEARCH_RADIUS = 6.0  # metres from the car to the lane centrelines considered
MATCH_TOLERANCE = 0.08  # metres between the behavior's error and a centreline's distance
MAX_HEADING_ERROR = math.radians(60)
SAMPLE_STEP = 1.0  # metres between curvature samples along a centreline
CHORD = 3.0  # metres either side of a sample for the circle through three points
PREVIEW_TIME = 0.3  # s: the steering rate limit needs about that long to reach a new angle
MIN_PREVIEW = 0.5  # metres
KEPT_INDEXES = 4  # road networks whose lane index a worker keeps
DAMPING_RATIO = 0.8  # of the lateral loop, with the heading term at low speed


class Centreline:
    """One lane's centre line; its signed curvature (left positive) is sampled along it
    when first asked for, since a car reads only the few lanes it drives on."""

    def __init__(self, line: LineString):
        self.line = line
        self._curvatures: np.ndarray | None = None

    def curvature_at(self, along: float) -> float:
        if self._curvatures is None:
            self._curvatures = signed_curvatures(self.line, SAMPLE_STEP, CHORD)[1]
        index = int(np.clip(round(along / SAMPLE_STEP), 0, len(self._curvatures) - 1))
        return float(self._curvatures[index])


class LaneCentrelines:
    """Every lane centre line of a road network, indexed for queries near a point."""

    def __init__(self, network: Any):
        self.network = network
        lines = (
            LineString(lane.centerline.lineString.coords)
            for road in network.allRoads
            for lane in road.lanes
        )
        self.centrelines = [Centreline(line) for line in lines if line.length > 0]
        self.tree = STRtree([c.line for c in self.centrelines])

    @classmethod
    def of(cls, network: Any) -> LaneCentrelines:
        """The index of a network, built once per network; a worker keeps the last few,
        as it keeps the parsed maps themselves."""
        for index in _INDEXES:
            if index.network is network:
                return index
        index = cls(network)
        _INDEXES.insert(0, index)
        del _INDEXES[KEPT_INDEXES:]
        return index

    def near(self, point: Point) -> list[Centreline]:
        indices = self.tree.query(point, predicate="dwithin", distance=SEARCH_RADIUS)
        return [self.centrelines[int(i)] for i in indices]


_INDEXES: list[LaneCentrelines] = []  # most recently built first


@dataclass(frozen=True)
class PathPoint:
    """Where the car stands on the path it follows, in the car's direction of travel."""

    curvature: float  # 1/m just ahead, positive where the path bends left
    heading_error: float  # radians, positive when the car points left of the path


@dataclass(frozen=True)
class _Reading:
    centreline: Centreline
    error: float  # metres between the behavior's error and this centreline's distance
    point: PathPoint


class FollowedPath:
    """The lane path one car's behavior follows, found from the error it measured."""

    def __init__(self, network: Any, agent: Any):
        self.index = LaneCentrelines.of(network) if network is not None else None
        self.agent = agent
        self.kept: Centreline | None = None

    def read(self, cte: float) -> PathPoint | None:
        """The followed path at the car; None when no lane centreline matches the error
        (the car is off the road network, or its path is not a lane)."""
        if self.index is None:
            return None
        position = self.agent.position
        point = Point(position.x, position.y)
        heading = float(self.agent.heading) + math.pi / 2  # Scenic's heading as a math angle
        speed = float(getattr(self.agent, "speed", 0.0) or 0.0)
        preview = max(MIN_PREVIEW, speed * PREVIEW_TIME)
        readings = []
        candidates = self.index.near(point)
        for centreline in candidates:
            reading = _read(centreline, point, heading, cte, preview)
            if reading is not None and reading.error <= MATCH_TOLERANCE:
                readings.append(reading)
        if not readings:
            self.kept = None
            return None
        kept = [r for r in readings if r.centreline is self.kept]
        best = kept[0] if kept else min(readings, key=lambda r: (abs(r.point.curvature), r.error))
        self.kept = best.centreline
        return best.point


def _read(
    centreline: Centreline, point: Point, heading: float, cte: float, preview: float
) -> _Reading | None:
    line = centreline.line
    along = line.project(point)
    if along <= 0.0 or along >= line.length:
        return None  # beyond the centreline's ends: another lane carries on from here
    lane_heading = line_direction(line, along, 0.5)
    offset = wrap_angle(heading - lane_heading)
    if abs(offset) <= MAX_HEADING_ERROR:
        direction = 1.0
    elif abs(offset) >= math.pi - MAX_HEADING_ERROR:
        direction = -1.0
    else:
        return None
    nearest = line.interpolate(along)
    dx, dy = point.x - nearest.x, point.y - nearest.y
    left = -math.sin(lane_heading) * dx + math.cos(lane_heading) * dy  # left of the lane
    distance = direction * left
    ahead = along + direction * preview
    curvature = direction * centreline.curvature_at(ahead)
    heading_error = offset if direction > 0 else wrap_angle(offset - math.pi)
    return _Reading(centreline, abs(distance - cte), PathPoint(curvature, heading_error))


def feed_forward_steer(curvature: float, wheelbase: float) -> float:
    """The steering signal that holds a curve of this curvature in the offline physics,
    where yaw rate = -v sin(steer pi/2) / wheelbase (negative steer turns left)."""
    ratio = max(-1.0, min(1.0, curvature * wheelbase))
    return -(2 / math.pi) * math.asin(ratio)


def heading_damping(k_p: float, k_d: float, speed: float, wheelbase: float) -> float:
    """The gain on the heading error that tops the PID's damping up to DAMPING_RATIO.

    Near the path, steer s gives curvature about c*s with c = pi / (2 * wheelbase), and
    the PID's derivative term acts like a heading gain of K_D * v. With a heading gain k
    the loop is x'' + c v k x' + c v^2 K_P x = 0: damping ratio k sqrt(c) / (2 sqrt(K_P)),
    the same at every speed. The derivative term alone is weak at low speed: a 16 m
    junction turn at 2.6 m/s swung 0.9 m either side of its arc. Above the speed where
    K_D * v reaches the target nothing is added, so faster driving is as tuned before.
    """
    c = math.pi / (2 * wheelbase)
    wanted = 2 * DAMPING_RATIO * math.sqrt(k_p / c)
    return max(0.0, wanted - k_d * speed)
