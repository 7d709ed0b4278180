"""The ego's route, read from the scene: the lanes it means to drive and how fast.

Every geometry entry of the knowledge base picks the ego's lanes and maneuver; scripts
say it in one of three ways, tried in order:

1. the ego's behavior is given a list of lanes (`FollowTrajectoryBehavior(speed, route)`);
2. the script names the list `egoRoute` (a behavior of its own then follows it);
3. neither: the ego follows its lane (FollowLaneBehavior), straight on through junctions.

The route then goes on along the last lane's successors (straight on through junctions,
as the world model's lane follower does) until it is long enough for the whole run at the
target speed. The target speed is the behavior's first number (or its `target_speed`),
else the script's OPT_EGO_SPEED or EGO_SPEED parameter, else 8 m/s.
"""

from __future__ import annotations

import math
from typing import Any

from arise.agents.types import MAX_ROUTE_LANES, MAX_ROUTE_POINTS, MAX_TARGET_SPEED, EgoRoute

WAYPOINT_SPACING = 2.0  # metres between route points
DEFAULT_SPEED = 8.0  # m/s
SPEED_PARAMETERS = ("OPT_EGO_SPEED", "EGO_SPEED")
EXTRA_LENGTH = 40.0  # metres beyond what the run needs at the target speed


def read_route(scene: Any, ego: Any, network: Any, steps: int, timestep: float) -> EgoRoute | None:
    """The ego's route, or None (no road network, or the ego is on none of its lanes)."""
    if network is None or ego is None:
        return None
    speed = _target_speed(scene, ego)
    lanes = _given_lanes(scene, ego) or []
    start = network.laneAt(ego.position)
    if start is None and lanes:
        start = lanes[0]
    if start is None:
        return None
    if not lanes:
        lanes = [start]
    elif start in lanes:
        lanes = lanes[lanes.index(start) :]
    needed = speed * steps * timestep + EXTRA_LENGTH
    lanes = _extend(lanes, needed, ego)
    points = _points(lanes, (float(ego.position.x), float(ego.position.y)), needed)
    if not points:
        return None
    maneuver = _maneuver(lanes)
    return EgoRoute(
        waypoints=points[:MAX_ROUTE_POINTS],
        lanes=[str(lane.uid) for lane in lanes][:MAX_ROUTE_LANES],
        target_speed=min(MAX_TARGET_SPEED, max(0.0, speed)),
        maneuver=maneuver,
    )


def _is_lane(value: Any) -> bool:
    return hasattr(value, "centerline") and hasattr(value, "maneuvers") and hasattr(value, "uid")


def _lane_list(value: Any) -> list[Any] | None:
    if isinstance(value, list | tuple) and value and all(_is_lane(v) for v in value):
        return list(value)
    return None


def _given_lanes(scene: Any, ego: Any) -> list[Any] | None:
    behavior = getattr(ego, "behavior", None)
    for value in (*getattr(behavior, "_args", ()), *getattr(behavior, "_kwargs", {}).values()):
        lanes = _lane_list(value)
        if lanes:
            return lanes
    for namespaces in dict(getattr(scene, "behaviorNamespaces", {}) or {}).values():
        for namespace in namespaces if isinstance(namespaces, tuple) else (namespaces,):
            if isinstance(namespace, dict):
                lanes = _lane_list(namespace.get("egoRoute"))
                if lanes:
                    return lanes
    return None


def _number(value: Any) -> float | None:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    return float(value) if math.isfinite(value) and value >= 0 else None


def _target_speed(scene: Any, ego: Any) -> float:
    behavior = getattr(ego, "behavior", None)
    kwargs = getattr(behavior, "_kwargs", {}) or {}
    for value in (kwargs.get("target_speed"), *getattr(behavior, "_args", ())):
        number = _number(value)
        if number is not None:
            return number
    params = dict(getattr(scene, "params", {}) or {})
    for name in SPEED_PARAMETERS:
        number = _number(params.get(name))
        if number is not None:
            return number
    return DEFAULT_SPEED


def _next_lane(lane: Any) -> Any:
    """Straight on where there is a choice, as the world model's autopilot goes."""
    maneuvers = list(getattr(lane, "maneuvers", ()) or ())
    if not maneuvers:
        return getattr(lane, "_successor", None)
    straight = [m for m in maneuvers if m.type.name == "STRAIGHT"]
    chosen = (straight or maneuvers)[0]
    return chosen.connectingLane or chosen.endLane


def _extend(lanes: list[Any], needed: float, ego: Any) -> list[Any]:
    """Follow successors after the given lanes until the route is long enough."""
    out = list(lanes)
    total = sum(float(lane.centerline.length) for lane in out)
    while total < needed and len(out) < MAX_ROUTE_LANES:
        following = _next_lane(out[-1])
        if following is None or following in out:
            break
        out.append(following)
        total += float(following.centerline.length)
    return out


def _points(
    lanes: list[Any], start: tuple[float, float], needed: float
) -> list[tuple[float, float]]:
    """Points every WAYPOINT_SPACING metres along the lanes' centrelines, from the ego's
    projection on the first lane."""
    from shapely.geometry import LineString, Point

    coords: list[tuple[float, float]] = []
    for lane in lanes:
        for x, y, *_ in lane.centerline.lineString.coords:
            point = (float(x), float(y))
            if not coords or math.dist(coords[-1], point) > 1e-6:
                coords.append(point)
    if len(coords) < 2:
        return []
    line = LineString(coords)
    begin = line.project(Point(*start))
    end = min(line.length, begin + needed)
    count = max(1, int((end - begin) / WAYPOINT_SPACING))
    out = []
    for i in range(count + 1):
        p = line.interpolate(min(end, begin + i * WAYPOINT_SPACING))
        out.append((round(p.x, 3), round(p.y, 3)))
    return out


def _maneuver(lanes: list[Any]) -> str | None:
    """The first junction maneuver along the route (lower case: straight, left_turn...)."""
    for lane, following in zip(lanes, lanes[1:], strict=False):
        for maneuver in getattr(lane, "maneuvers", ()) or ():
            if maneuver.connectingLane is following or maneuver.endLane is following:
                return str(maneuver.type.name).lower()
    return None
