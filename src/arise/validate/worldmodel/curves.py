"""Slow for curves: a speed cap read from the lane ahead, for the offline controllers.

Scenic's driving behaviors hold one target speed whatever the road does, and CARLA's
own agents (their local planner and BehaviorAgent) slow for turns and curves. Offline,
a car at 24-35 m/s on Town06's highway curves (radius about 50 m) and at 18 m/s on
Town01's bends ran wide out of its lane. The governor looks ahead along the lane's
centreline, estimates the curvature from the circle through three points, and caps the
target speed so that the car can brake in time to reach every curve ahead at
sqrt(a_lat * R).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scenic.core.vectors import Vector
from scenic.domains.driving.controllers import PIDLongitudinalController
from shapely.geometry import LineString, Point

from arise.validate.worldmodel.linegeometry import line_direction, signed_curvatures, wrap_angle

# Lateral acceleration a curve may ask for: 2-4 m/s^2 is comfortable in a passenger car;
# 3.5 lets a 50 m curve be taken at 13 m/s, a 10 m junction turn at 6 m/s.
LATERAL_ACCELERATION = 3.5  # m/s^2
# Deceleration planned towards a curve, below the 3.4 m/s^2 that the behaviors' regulated
# control action can give (max_brake 0.5 of MAX_BRAKING), so the cap can be met.
CURVE_BRAKING = 2.5  # m/s^2
SAMPLE_STEP = 2.0  # metres between samples of the path ahead
CHORD = 6.0  # metres either side of a sample for the circle through three points
MIN_LOOKAHEAD = 30.0  # metres
LOOKAHEAD_MARGIN = 20.0  # metres beyond the braking distance from the current speed
OFF_PATH = 1.5  # metres from the path at which it is read again from the road network
MAX_HEADING_ERROR = math.radians(60)  # beyond it the car is not following this lane
MAX_LANES = 30  # lanes chained into one path (a guard against loops)


@dataclass(frozen=True)
class CurvePath:
    """The centreline the car follows and the curve speed at samples along it."""

    line: LineString
    distances: np.ndarray
    curve_speeds: np.ndarray
    ends: bool  # the road network gave no more lanes: reading it again would not help

    def limit(self, along: float, lookahead: float) -> float | None:
        """The highest speed now from which every curve ahead can be reached in time."""
        ahead = (self.distances >= along) & (self.distances <= along + lookahead)
        if not ahead.any():
            return None
        gaps = self.distances[ahead] - along
        allowed = np.sqrt(self.curve_speeds[ahead] ** 2 + 2 * CURVE_BRAKING * gaps)
        return float(allowed.min())


def curve_speeds(line: LineString) -> tuple[np.ndarray, np.ndarray]:
    """Samples along the line and sqrt(a_lat * R) at each (inf where it is straight)."""
    distances, signed = signed_curvatures(line, SAMPLE_STEP, CHORD)
    curvature = np.abs(signed)
    with np.errstate(divide="ignore", invalid="ignore"):
        speeds = np.where(
            curvature > 1e-6, np.sqrt(LATERAL_ACCELERATION / np.maximum(curvature, 1e-6)), np.inf
        )
    return distances, speeds


def _next_lanes(lane: Any) -> list[Any]:
    """The lanes after this one on the way a lane follower takes: straight on, or the only
    way; none where it must choose among turns (the turn's own speed applies there)."""
    maneuvers = list(lane.maneuvers)
    if not maneuvers:
        successor = getattr(lane, "_successor", None)  # `successor` rejects at a dead end
        return [successor] if successor is not None else []
    straight = [m for m in maneuvers if m.type.name == "STRAIGHT"]
    if straight:
        chosen = straight[0]
    elif len(maneuvers) == 1:
        chosen = maneuvers[0]
    else:
        return []
    return [x for x in (chosen.connectingLane, chosen.endLane) if x is not None]


class CurveSpeedGovernor:
    """Caps one car's target speed by the curves on the lane ahead of it."""

    def __init__(self, network: Any, agent: Any):
        self.network = network
        self.agent = agent
        self.path: CurvePath | None = None

    def limit(self) -> float | None:
        """The speed cap now, or None when no lane ahead is known."""
        if self.network is None:
            return None
        position = self.agent.position
        point = Point(position.x, position.y)
        speed = float(getattr(self.agent, "speed", 0.0) or 0.0)
        lookahead = max(MIN_LOOKAHEAD, speed**2 / (2 * CURVE_BRAKING) + LOOKAHEAD_MARGIN)
        path = self.path
        if path is not None:
            along = path.line.project(point)
            short = not path.ends and along + lookahead > path.line.length
            if short or path.line.distance(point) > OFF_PATH:
                path = None
        if path is None:
            path = self.path = self._read_path(position, lookahead)
            if path is None:
                return None
            along = path.line.project(point)
        return path.limit(along, lookahead)

    def _read_path(self, position: Vector, lookahead: float) -> CurvePath | None:
        lane = self._lane_followed(position)
        if lane is None:
            return None
        coords = list(lane.centerline.lineString.coords)
        start = LineString(coords).project(Point(position.x, position.y))
        ends = False
        for _ in range(MAX_LANES):
            if LineString(coords).length >= start + 2 * lookahead + CHORD:
                break
            following = _next_lanes(lane)
            if not following:
                ends = True
                break
            for lane in following:
                coords.extend(lane.centerline.lineString.coords[1:])
        line = LineString(coords)
        distances, speeds = curve_speeds(line)
        return CurvePath(line, distances, speeds, ends)

    def _lane_followed(self, position: Vector) -> Any:
        """The lane under the car that runs its way (in a junction, of the overlapping
        connecting lanes the one nearest and best aligned)."""
        candidates = []
        found = self.network.laneAt(position)
        if found is not None:
            candidates.append(found)
        junction = self.network.intersectionAt(position)
        if junction is not None:
            for maneuver in junction.maneuvers:
                connecting = maneuver.connectingLane
                if connecting is not None and connecting.containsPoint(position):
                    candidates.append(connecting)
        best, best_score = None, math.inf
        point = Point(position.x, position.y)
        for lane in candidates:
            line = lane.centerline.lineString
            along = line.project(point)
            heading = line_direction(line, along, 1.0) - math.pi / 2  # as Scenic's heading
            error = abs(wrap_angle(heading - float(self.agent.heading)))
            if error > MAX_HEADING_ERROR:
                continue
            score = line.distance(point) + 4.0 * error
            if score < best_score:
                best, best_score = lane, score
        return best


class GovernedLongitudinalController(PIDLongitudinalController):
    """Scenic's longitudinal PID, with the behavior's target speed capped for curves."""

    def __init__(self, governor: CurveSpeedGovernor, K_P: float, K_D: float, K_I: float, dt: float):
        super().__init__(K_P=K_P, K_D=K_D, K_I=K_I, dt=dt)
        self.governor = governor

    def run_step(self, speed_error: float) -> float:
        cap = self.governor.limit()
        if cap is not None:
            speed = float(getattr(self.governor.agent, "speed", 0.0) or 0.0)
            speed_error = min(speed_error, cap - speed)
        return float(super().run_step(speed_error))
