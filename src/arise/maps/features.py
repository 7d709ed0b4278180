"""Measure what a road network offers, from Scenic's own parse of the map.

Why: a script asks for a 4-way signalized junction, a sidewalk or a highway;
the map registry must pick a map that really has it. The features are read off
the network Scenic builds (not off the map's name or our intentions), so a map
is only advertised with what Scenic will actually give a scenario.

Run ``python -m arise.maps.features`` to re-measure the CARLA towns into
``data/carla_towns.json`` (or ``python -m arise.maps.features MAP.xodr``).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import sys
import tempfile
import time
import warnings
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from scenic.domains.driving.roads import Intersection, Maneuver, ManeuverType, Network, Road
from shapely.geometry import Point

from arise.vocabulary import MAP_FEATURES

#: Order of features in every list we write: the vocabulary's, plus what we detect but
#: no knowledge-base entry needs.
FEATURES = (*MAP_FEATURES, "roundabout")

#: Road ends whose directions differ by less than this form one junction arm
#: (two carriageways side by side, a ramp merging at a shallow angle).
ARM_TOLERANCE_DEG = 35.0
#: A road stretch counts as straight if its heading stays within this of its start...
STRAIGHT_TOLERANCE_DEG = 3.0
#: ...for at least this long: room for following, cut-in and overtaking.
STRAIGHT_MIN_LENGTH_M = 80.0
#: A road that turns by at least this much in total is a curve.
CURVE_MIN_TURN_DEG = 15.0
#: Highway: roads with at least this many lanes in a direction and no sidewalk...
HIGHWAY_MIN_LANES = 3
#: ...adding up to at least this length.
HIGHWAY_MIN_LENGTH_M = 400.0
#: An on-ramp meets the through lanes at most this steeply (a turn from a side road
#: into a multi-lane road meets them at about 90 degrees).
MERGE_MAX_ANGLE_DEG = 60.0

DATA_DIR = Path(__file__).with_name("data")
#: The CARLA towns: $ARISE_CARLA_MAPS, else ../shared/maps/CARLA beside the repo.
DEFAULT_CARLA_DIR = Path(
    os.environ.get(
        "ARISE_CARLA_MAPS",
        Path(__file__).resolve().parents[3].parent / "shared" / "maps" / "CARLA",
    )
)

#: Hand-written facts about the CARLA towns (public knowledge), and the two
#: towns that do not parse in Scenic 3.1.1 / are not on this machine.
CARLA_TOWNS: dict[str, dict[str, Any]] = {
    "Town01": {"description": "Small town: single-lane roads, T-junctions, a river and bridges."},
    "Town02": {"description": "Small town like Town01, smaller: single-lane roads, T-junctions."},
    "Town03": {
        "description": "Urban: multi-lane roads, signalized 4-way intersections, a roundabout, "
        "a tunnel (entry written by hand: not available here).",
        "available": False,
        "features": [
            "straight",
            "multilane",
            "sidewalk",
            "intersection4",
            "tjunction",
            "signalized",
            "curve",
            "roundabout",
        ],
        "lanes_per_direction": 2,
        "has_sidewalks": True,
        "signalized": True,
    },
    "Town04": {
        "description": "Small town in the mountains with a figure-8 multi-lane highway loop."
    },
    "Town05": {
        "description": "Urban grid: multi-lane roads, signalized 4-way intersections, "
        "highway-like multi-lane roads (entry written by hand: not available here).",
        "available": False,
        "features": [
            "straight",
            "multilane",
            "sidewalk",
            "intersection4",
            "tjunction",
            "signalized",
            "highway",
            "curve",
        ],
        "lanes_per_direction": 3,
        "has_sidewalks": True,
        "signalized": True,
    },
    "Town06": {
        "description": "Long multi-lane highways with entrance and exit ramps, few buildings."
    },
    "Town07": {
        "description": "Rural: mostly narrow single-lane roads, barns and fields, a few signalized junctions."
    },
    "Town10HD": {"description": "Downtown: 2-lane avenues, signalized intersections, sidewalks."},
}


def load_network(xodr_path: Path | str) -> Network:
    """Parse a map without reading or writing a ``.snet`` cache next to it.

    Why: the shipped maps live in the package and the CARLA towns on a
    read-only share; a stale cache must not hide a change to the map either.
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # OpenDriveWarning about odd CARLA lanes
        return Network.fromFile(str(xodr_path), useCache=False, writeCache=False)


def _angle_diff(a: float, b: float) -> float:
    """Smallest absolute difference between two angles (radians)."""
    return abs((a - b + math.pi) % (2 * math.pi) - math.pi)


def _polyline(element: Any) -> list[tuple[float, float]]:
    return [(float(p[0]), float(p[1])) for p in element.centerline.points]


def _segments(points: Sequence[tuple[float, float]]) -> list[tuple[float, float]]:
    """(heading, length) of each non-degenerate segment of a polyline."""
    result = []
    for (x0, y0), (x1, y1) in zip(points, points[1:], strict=False):
        length = math.hypot(x1 - x0, y1 - y0)
        if length > 1e-6:
            result.append((math.atan2(y1 - y0, x1 - x0), length))
    return result


def longest_straight(road: Road) -> float:
    """Length (m) of the longest stretch whose heading stays near its start."""
    best = run = 0.0
    ref = None
    tolerance = math.radians(STRAIGHT_TOLERANCE_DEG)
    for heading, length in _segments(_polyline(road)):
        if ref is None or _angle_diff(heading, ref) > tolerance:
            ref, run = heading, 0.0
        run += length
        best = max(best, run)
    return best


def total_turn(road: Road) -> float:
    """Sum of absolute heading changes (degrees) along the road's centre line."""
    segs = _segments(_polyline(road))
    turn = sum(_angle_diff(a[0], b[0]) for a, b in zip(segs, segs[1:], strict=False))
    return math.degrees(turn)


def road_length(road: Road) -> float:
    return sum(length for _, length in _segments(_polyline(road)))


def lanes_per_direction(road: Road) -> tuple[int, int]:
    """(fewest, most) driving lanes in one direction over the road's sections."""
    counts = [max(len(s.forwardLanes), len(s.backwardLanes)) for s in road.sections]
    return min(counts), max(counts)


def has_sidewalk(road: Road) -> bool:
    """Whether either side of the road has a sidewalk.

    Reads ``_sidewalk``: the public ``sidewalk`` property raises Scenic's
    RejectionException when there is none (it is meant for sampling).
    """
    groups = (road.forwardLanes, road.backwardLanes)
    return any(getattr(group, "_sidewalk", None) is not None for group in groups)


def junction_arms(intersection: Intersection) -> list[float]:
    """Directions (radians) in which the roads leave the intersection, one per arm.

    Why not ``len(intersection.roads)``: CARLA splits some roads, runs the two
    directions of an avenue as separate roads and joins ramps in junctions, so
    the number of roads over-counts the directions a driver can choose from.
    """
    directions = []
    for road in intersection.roads:
        points = _polyline(road)
        if len(points) < 2:
            continue
        start, end = points[0], points[-1]
        d_start = intersection.polygons.distance(Point(start))
        d_end = intersection.polygons.distance(Point(end))
        ordered = points if d_start <= d_end else points[::-1]
        # Direction away from the junction, over the first few metres of road.
        x0, y0 = ordered[0]
        for x1, y1 in ordered[1:]:
            if math.hypot(x1 - x0, y1 - y0) >= 5.0:
                break
        directions.append(math.atan2(y1 - y0, x1 - x0))
    return _cluster_angles(directions, math.radians(ARM_TOLERANCE_DEG))


def _cluster_angles(angles: Iterable[float], tolerance: float) -> list[float]:
    """Merge angles closer than ``tolerance`` (circularly); one representative each."""
    ordered = sorted(a % (2 * math.pi) for a in angles)
    if not ordered:
        return []
    clusters: list[list[float]] = [[ordered[0]]]
    for angle in ordered[1:]:
        if angle - clusters[-1][-1] < tolerance:
            clusters[-1].append(angle)
        else:
            clusters.append([angle])
    if len(clusters) > 1 and ordered[0] + 2 * math.pi - clusters[-1][-1] < tolerance:
        clusters[0] = clusters.pop() + clusters[0]
    return [cluster[0] for cluster in clusters]


def _start_heading(maneuver: Maneuver) -> float:
    """Heading (radians) at the start of the maneuver's connecting lane."""
    (x0, y0), (x1, y1) = _polyline(maneuver.connectingLane)[:2]
    return math.atan2(y1 - y0, x1 - x0)


def on_ramp_merges(intersection: Intersection) -> list[tuple[Maneuver, Maneuver]]:
    """(ramp, through) maneuvers of a junction where an on-ramp joins a multi-lane road.

    Read off the lanes, since OpenDRIVE has no notion of a ramp: the through maneuver goes
    straight on a road with several lanes that way; the ramp's comes from another road with
    fewer lanes, at a shallow angle, and ends in the same lane, which is the rightmost one.
    CARLA's towns and our arise_merge build their on-ramps like this.
    """
    found = []
    limit = math.radians(MERGE_MAX_ANGLE_DEG)
    for through in intersection.maneuvers:
        lanes = len(through.startLane.group.lanes)
        end = through.endLane.sections[0]
        if (
            through.type is not ManeuverType.STRAIGHT
            or through.connectingLane is None
            or lanes < 2
            or end._laneToRight is not None
        ):
            continue
        for ramp in intersection.maneuvers:
            if (
                ramp.endLane is through.endLane
                and ramp.connectingLane is not None
                and ramp.startLane.road is not through.startLane.road
                and len(ramp.startLane.group.lanes) < lanes
                and _angle_diff(_start_heading(ramp), _start_heading(through)) <= limit
            ):
                found.append((ramp, through))
    return found


def classify_intersection(intersection: Intersection) -> str:
    """'intersection4', 'tjunction' or 'other' (merges, splits, dead ends)."""
    turns = {m.type for m in intersection.maneuvers}
    if not turns & {ManeuverType.LEFT_TURN, ManeuverType.RIGHT_TURN}:
        return "other"
    arms = len(junction_arms(intersection))
    if arms >= 4:
        return "intersection4"
    if arms == 3:
        return "tjunction"
    return "other"


def describe_network(network: Network) -> dict[str, Any]:
    """Features and statistics of a parsed network (see the module constants)."""
    roads = list(network.roads)
    kinds = [classify_intersection(i) for i in network.intersections]
    traffic_lights = {
        s.openDriveID for i in network.intersections for s in i.signals if s.isTrafficLight
    }
    max_lanes = max((lanes_per_direction(r)[1] for r in roads), default=0)
    highway_length = math.fsum(
        road_length(r)
        for r in roads
        if lanes_per_direction(r)[0] >= HIGHWAY_MIN_LANES and not has_sidewalk(r)
    )
    straight = max((longest_straight(r) for r in roads), default=0.0)
    turn = max((total_turn(r) for r in roads), default=0.0)
    sidewalks = len(network.sidewalks) > 0
    merges = sum(len(on_ramp_merges(i)) for i in network.intersections)

    present = {
        "straight": straight >= STRAIGHT_MIN_LENGTH_M,
        "multilane": max_lanes >= 2,
        "sidewalk": sidewalks,
        "intersection4": "intersection4" in kinds,
        "tjunction": "tjunction" in kinds,
        "signalized": bool(traffic_lights),
        "highway": highway_length >= HIGHWAY_MIN_LENGTH_M,
        "curve": turn >= CURVE_MIN_TURN_DEG,
        "merge": merges > 0,
        "roundabout": False,  # Scenic's network has no notion of it: never measured
    }
    return {
        "features": [f for f in FEATURES if present[f]],
        "lanes_per_direction": max_lanes,
        "has_sidewalks": sidewalks,
        "signalized": bool(traffic_lights),
        "stats": {
            "roads": len(roads),
            "connecting_roads": len(network.connectingRoads),
            "intersections": len(kinds),
            "intersections4": kinds.count("intersection4"),
            "tjunctions": kinds.count("tjunction"),
            "other_junctions": kinds.count("other"),
            "traffic_lights": len(traffic_lights),
            "sidewalks": len(network.sidewalks),
            "longest_straight_m": round(straight, 1),
            "max_road_turn_deg": round(turn, 1),
            "highway_length_m": round(highway_length, 1),
            "on_ramp_merges": merges,
        },
    }


def measure_features(xodr_path: Path | str) -> dict[str, Any]:
    """Parse ``xodr_path`` with Scenic and describe it; adds the parse time."""
    started = time.perf_counter()
    network = load_network(xodr_path)
    parse_seconds = time.perf_counter() - started
    result = describe_network(network)
    result["stats"]["parse_seconds"] = round(parse_seconds, 2)
    return result


def measure_carla_towns(carla_dir: Path | str) -> list[dict[str, Any]]:
    """Catalogue entries for the CARLA towns: measured if present, else by hand.

    The maps are copied into a temporary folder first: Scenic may write a cache
    next to a map, and the share they come from is read-only.
    """
    source = Path(carla_dir)
    entries = []
    with tempfile.TemporaryDirectory(prefix="arise-towns-") as tmp:
        for name, facts in CARLA_TOWNS.items():
            entry: dict[str, Any] = {
                "name": name,
                "file": f"{name}.xodr",
                "description": facts["description"],
            }
            path = source / entry["file"]
            if facts.get("available", True) and path.exists():
                copy = Path(tmp) / entry["file"]
                shutil.copyfile(path, copy)
                entry.update(measure_features(copy))
                entry["available"] = True
            else:
                for key in ("features", "lanes_per_direction", "has_sidewalks", "signalized"):
                    entry[key] = facts[key]
                entry["available"] = False
            entries.append(entry)
    return entries


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m arise.maps.features",
        description="Measure map features with Scenic's parser.",
    )
    parser.add_argument("maps", nargs="*", type=Path, help="xodr files to measure and print")
    parser.add_argument("--carla", type=Path, default=DEFAULT_CARLA_DIR, help="CARLA towns folder")
    parser.add_argument(
        "--out", type=Path, default=DATA_DIR / "carla_towns.json", help="where to write the towns"
    )
    args = parser.parse_args(argv)
    if args.maps:
        for path in args.maps:
            print(json.dumps({"file": str(path), **measure_features(path)}, indent=2))
        return 0
    entries = measure_carla_towns(args.carla)
    args.out.write_text(json.dumps(entries, indent=2) + "\n")
    print(f"wrote {len(entries)} towns to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
