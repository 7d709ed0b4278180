"""The ego's route, read from the scene: the lanes it means to drive and how fast.

Every geometry entry of the knowledge base picks the ego's lanes and maneuver; scripts
say it in one of three ways, tried in order:

1. the ego's behavior is given a list of lanes (`FollowTrajectoryBehavior(speed, route)`);
2. the script names the list `egoRoute` (a behavior of its own then follows it);
3. neither: the ego follows its lane (FollowLaneBehavior), straight on through junctions.

Where the route ends says when the ego has done its task (route completion, as in
SafeBench, whose routes end just past the scenario's conflict):

- a script that names the lanes: `PAST_LAST_LANE` (40 m) into the last lane it names,
  i.e. just past the junction or merge its maneuver crosses;
- else a script that ends when the ego is `OPT_REQ_END_DISTANCE` from its start (the
  knowledge base's ending): that far along;
- else as far as the ego would go in the whole run at its target speed, plus 40 m,

never further than the road goes (the route follows the last lane's successors, straight
on through junctions, as the world model's lane follower does). The target speed is the
behavior's first number (or its `target_speed`), else the script's OPT_EGO_SPEED or
EGO_SPEED parameter, else 8 m/s.
"""

from __future__ import annotations

import math
from typing import Any

from arise.agents.types import MAX_ROUTE_LANES, MAX_ROUTE_POINTS, MAX_TARGET_SPEED, EgoRoute

WAYPOINT_SPACING = 2.0  # metres between route points
DEFAULT_SPEED = 8.0  # m/s
SPEED_PARAMETERS = ("OPT_EGO_SPEED", "EGO_SPEED")
EXTRA_LENGTH = 40.0  # metres beyond what the run needs at the target speed
PAST_LAST_LANE = 40.0  # metres into the last lane a script names
END_PARAMETER = "OPT_REQ_END_DISTANCE"


def read_route(scene: Any, ego: Any, network: Any, steps: int, timestep: float) -> EgoRoute | None:
    """The ego's route, or None (no road network, or the ego is on none of its lanes)."""
    if network is None or ego is None:
        return None
    speed = _target_speed(scene, ego)
    given = _given_lanes(scene, ego) or []
    lanes = list(given)
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
    origin = (float(ego.position.x), float(ego.position.y))
    length = needed
    if given and given[-1] in lanes:
        last = lanes.index(given[-1])
        length = min(needed, _station_of_lane(lanes, last, origin) + PAST_LAST_LANE)
    else:
        end = _number(dict(getattr(scene, "params", {}) or {}).get(END_PARAMETER))
        if end is not None and end > 0:
            length = min(needed, end)
    lanes = _lanes_within(lanes, origin, length)
    points = _points(lanes, origin, length)
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


def _centreline(lanes: list[Any]) -> list[tuple[float, float]]:
    coords: list[tuple[float, float]] = []
    for lane in lanes:
        for x, y, *_ in lane.centerline.lineString.coords:
            point = (float(x), float(y))
            if not coords or math.dist(coords[-1], point) > 1e-6:
                coords.append(point)
    return coords


def _station_of_lane(lanes: list[Any], index: int, origin: tuple[float, float]) -> float:
    """Metres from the ego's projection on the route to the start of lanes[index]."""
    from shapely.geometry import LineString, Point

    coords = _centreline(lanes)
    if len(coords) < 2:
        return 0.0
    before = sum(float(lane.centerline.length) for lane in lanes[:index])
    return max(0.0, before - LineString(coords).project(Point(*origin)))


def _lanes_within(lanes: list[Any], origin: tuple[float, float], length: float) -> list[Any]:
    """The lanes the first `length` metres of the route touch."""
    kept = []
    for index, lane in enumerate(lanes):
        if index and _station_of_lane(lanes, index, origin) > length:
            break
        kept.append(lane)
    return kept


def _points(
    lanes: list[Any], start: tuple[float, float], needed: float
) -> list[tuple[float, float]]:
    """Points every WAYPOINT_SPACING metres along the lanes' centrelines, from the ego's
    projection on the first lane."""
    from shapely.geometry import LineString, Point

    coords = _centreline(lanes)
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
