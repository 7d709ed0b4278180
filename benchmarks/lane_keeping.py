"""Intended versus observed ego lane changes, per geometry entry and speed.

Run:  .venv/bin/python benchmarks/lane_keeping.py [--carla-maps DIR] [--seeds N]
Each geometry entry of the knowledge base drives the ego alone at the top of its speed
range (highway entries also at 35 m/s) for 20 s; the trace is read lane by lane with
Scenic's road network (the validator's `lane_changes`, `weaving`, `opposite_lane_steps`).
Prints one markdown row per case: the lane changes the entry intends (from its tags) and
those observed per seed; then the ego's lateral deviation from the centre of the lane it
is in, max and RMS per speed band, over every trace point outside junctions (connecting
lanes overlap there), read with Scenic's road network in this process. To compare with
an older world model, run it from a copy of that commit's src (PYTHONPATH=<copy>/src);
facts that commit did not have print as "-".
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from arise.kb.compose import compose, pick_map
from arise.kb.loader import load_kb
from arise.kb.schema import Component
from arise.maps.registry import MapRegistry
from arise.validate import CheckOptions, WorkerPool, check_text

SPEED = re.compile(r"param OPT_EGO_SPEED = Range\(([\d.]+), ([\d.]+)\)")
# Entries whose ego leaves the lane centre on purpose: their points show the maneuver, not
# how well the ego keeps a lane, so the lane-keeping table leaves them out.
ON_PURPOSE = frozenset({"ego_lane_change", "ego_bypass", "ego_pulls_over"})
BANDS = ((0.0, 15.0, "<= 15 m/s"), (15.0, 25.0, "15-25 m/s"), (25.0, math.inf, "25-35 m/s"))


def _intended(tags: Sequence[str]) -> int:
    """Lane changes the entry makes on purpose (as tests/validate/test_lane_keeping.py)."""
    if "ego_lane_change" not in tags:
        return 0
    return 2 if "ego_returns" in tags else 1


def _said(value: object) -> str:
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    return str(value)


def _network(path: Path) -> Any:
    from scenic.domains.driving.roads import Network

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return Network.fromFile(str(path))


def _deviations(network: Any, trajectory: Sequence[Any]) -> list[tuple[float, float]]:
    """(speed, distance from the centre of the lane the ego is in) per point off junctions."""
    from scenic.core.vectors import Vector
    from shapely.geometry import Point

    found = []
    for point in trajectory:
        where = Vector(point.x, point.y)
        if network.intersectionAt(where) is not None:
            continue
        lane = network.laneAt(where)
        if lane is not None:
            distance = lane.centerline.lineString.distance(Point(point.x, point.y))
            found.append((float(point.speed), float(distance)))
    return found


def _band_rows(samples: list[tuple[float, float]]) -> list[str]:
    rows = []
    for low, high, name in BANDS:
        band = [d for v, d in samples if low < v <= high or (low == 0.0 and v <= high)]
        if not band:
            rows.append(f"| {name} | 0 | - | - |")
            continue
        rms = math.sqrt(sum(d * d for d in band) / len(band))
        rows.append(f"| {name} | {len(band)} | {max(band):.2f} | {rms:.2f} |")
    return rows


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--carla-maps", help="folder of CARLA town maps (else our maps)")
    parser.add_argument("--seeds", type=int, default=2)
    args = parser.parse_args(argv)
    registry = MapRegistry(args.carla_maps) if args.carla_maps else MapRegistry()
    maps = {
        name: entry.features
        for name, entry in registry.entries.items()
        if entry.features and (not args.carla_maps or entry.source == "map-dir")
    }
    print(
        "| geometry | map | speed (m/s) | intended | observed per seed | weaving "
        "| oncoming-lane steps |\n|---|---|---|---|---|---|---|"
    )
    samples: list[tuple[float, float]] = []
    keeping: list[tuple[float, float]] = []
    networks: dict[str, Any] = {}
    wanted_total = observed_total = exact = cases = 0
    with WorkerPool(size=1) as pool:
        for entry in load_kb().of(Component.GEOMETRY):
            found = SPEED.search(entry.snippet)
            map_name = pick_map([entry], maps)
            if found is None or map_name is None:
                continue
            speeds = [float(found.group(2))]
            if "highway" in entry.map_features:
                speeds.append(35.0)
            for speed in speeds:
                script = compose([entry], None, map_name).replace(
                    found.group(0), f"param OPT_EGO_SPEED = {speed:g}"
                )
                changes, weaving, opposite = [], [], []
                for seed in range(args.seeds):
                    options = CheckOptions(
                        seed=seed, steps=200, timeout=120, map_dir=args.carla_maps
                    )
                    result = check_text(script, options, pool=pool)
                    if not result.ok or result.simulation is None:
                        changes.append("failed")
                        continue
                    ego = next(a for a in result.simulation.agents if a.is_ego)
                    changes.append(str(ego.lane_changes))
                    cases += 1
                    wanted_total += _intended(entry.tags)
                    observed_total += ego.lane_changes
                    exact += ego.lane_changes == _intended(entry.tags)
                    path = registry.entries[map_name].path
                    if path is not None:
                        if map_name not in networks:
                            networks[map_name] = _network(path)
                        found_points = _deviations(networks[map_name], ego.trajectory)
                        samples.extend(found_points)
                        if not ON_PURPOSE & set(entry.tags):
                            keeping.extend(found_points)
                    weaving.append(_said(getattr(ego, "weaving", None)))
                    opposite.append(_said(getattr(ego, "opposite_lane_steps", None)))
                print(
                    f"| {entry.id} | {map_name} | {speed:g} | {_intended(entry.tags)} "
                    f"| {', '.join(changes)} | {', '.join(weaving)} | {', '.join(opposite)} |"
                )
    print(
        f"\nRuns: {cases}; lane changes intended {wanted_total}, observed {observed_total}; "
        f"runs with exactly the intended changes: {exact}\n"
    )
    for title, points in (("lane-keeping entries", keeping), ("all entries", samples)):
        print(f"\nLateral deviation from the lane centre, {title}:\n")
        print("| speed band | trace points | max deviation (m) | RMS (m) |\n|---|---|---|---|")
        for row in _band_rows(points):
            print(row)
    return 0


if __name__ == "__main__":
    sys.exit(main())
