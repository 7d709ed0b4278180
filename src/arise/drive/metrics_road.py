"""What the metrics ask of the road network, and the answer from Scenic's network.

The parent computes a run's metrics from the validated trace and a network it loads
itself, from the map its own request named (`ScenicRoad.from_map`): nothing a run folder
or a worker holds is read here, and Scenic's `.snet` pickle is loaded only from a map
the cache vouches for (`arise.render.outline.load_network`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any, NamedTuple, Protocol

from arise.drive.metrics_types import MetricsError
from arise.errors import AriseError


class LaneRef(NamedTuple):
    """A lane and the road it belongs to (the map's own ids)."""

    road: str
    lane: str


class RoadQueries(Protocol):
    """Point queries on a road network (x east, y north, metres)."""

    def on_drivable(self, x: float, y: float) -> bool:
        """The point is on a road's driving lanes or in a junction."""
        ...

    def lane_at(self, x: float, y: float) -> LaneRef | None:
        """The driving lane at the point (None: no lane there)."""
        ...

    def in_junction(self, x: float, y: float) -> bool:
        """The point is inside a junction (where connecting lanes overlap by design)."""
        ...


class ScenicRoad:
    """`RoadQueries` over a Scenic road network (`scenic.domains.driving.roads.Network`).

    Answers as the network's own `laneAt` and `intersectionAt` do (the first element in
    the network's order that holds the point, else one within its tolerance), from spatial
    indexes of its own: a few microseconds a point instead of a few hundred.
    """

    def __init__(self, network: Any) -> None:
        import shapely

        self._lanes = list(network.lanes)
        self._lane_tree = shapely.STRtree([lane.polygons for lane in self._lanes])
        self._junction_tree = shapely.STRtree([j.polygons for j in network.intersections])
        self._tolerance = float(getattr(network, "tolerance", 0.0) or 0.0)
        self._drivable = network.drivableRegion.polygons
        shapely.prepare(self._drivable)

    @classmethod
    def from_map(cls, path: str | Path) -> ScenicRoad:
        """The network of a map file the parent chose (its cached `.xodr`)."""
        from arise.render.outline import load_network

        try:
            return cls(load_network(path))
        except AriseError:  # a map file refused (MapError): its own message
            raise
        except Exception as error:  # Scenic's parser raises whatever it meets
            raise MetricsError(f"cannot read the road network of {path}: {error}") from error

    def _first(self, tree: Any, x: float, y: float) -> int | None:
        import shapely

        point = shapely.Point(x, y)
        found = tree.query(point, predicate="intersects")
        if not len(found) and self._tolerance > 0:
            found = tree.query(point, predicate="dwithin", distance=self._tolerance)
        return int(found.min()) if len(found) else None

    def on_drivable(self, x: float, y: float) -> bool:
        import shapely

        return bool(shapely.intersects_xy(self._drivable, x, y))

    def lane_at(self, x: float, y: float) -> LaneRef | None:
        index = self._first(self._lane_tree, x, y)
        if index is None:
            return None
        lane = self._lanes[index]
        return LaneRef(road=str(lane.road.uid), lane=str(lane.uid))

    def in_junction(self, x: float, y: float) -> bool:
        return self._first(self._junction_tree, x, y) is not None


#: The ego's centre must stay in a new lane this long before the move counts, so a centre
#: that rides on a lane marking is one crossing, not one per step.
HOLD_SECONDS = 0.3


def lane_invasions(
    road: RoadQueries, xs: Sequence[float], ys: Sequence[float], timestep: float
) -> int:
    """Lane boundaries the ego's centre crossed outside junctions: moves into another
    lane of the same road (a neighbour, or the oncoming lanes), held for HOLD_SECONDS.
    Moving on into the next road is no crossing; a junction ends the lane it was in, and
    a point on no lane changes nothing."""
    hold = max(1, math.ceil(HOLD_SECONDS / timestep - 1e-9))
    crossings = 0
    current: LaneRef | None = None
    candidate: LaneRef | None = None
    held = 0
    for x, y in zip(xs, ys, strict=True):
        if road.in_junction(x, y):
            current, candidate, held = None, None, 0
            continue
        lane = road.lane_at(x, y)
        if lane is None or lane == current:
            candidate, held = None, 0
            continue
        held = held + 1 if lane == candidate else 1
        candidate = lane
        if held >= hold:
            if current is not None and current.road == lane.road:
                crossings += 1
            current, candidate, held = lane, None, 0
    return crossings


def out_of_road_length(road: RoadQueries, xs: Sequence[float], ys: Sequence[float]) -> float:
    """Metres driven with the ego's centre off the drivable area: every move between two
    steps whose midpoint is off it counts whole."""
    total = 0.0
    for x0, y0, x1, y1 in zip(xs, ys, xs[1:], ys[1:], strict=False):
        if not road.on_drivable((x0 + x1) / 2, (y0 + y1) / 2):
            total += math.hypot(x1 - x0, y1 - y0)
    return total
