"""How far along its route the ego got, and how far from it it drove.

Progress is the arc length of the ego centre's projection on the route, searched only a
short way ahead of the progress already made, so a route that passes near itself (a
U-turn, a loop round a block) is not skipped ahead; it never goes back. As in CARLA's
route completion test, a point more than `PROGRESS_RADIUS_M` from the route makes no
progress (a car in the next lane still does).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from arise.agents.types import EgoRoute
from arise.drive.metrics_track import Floats

#: A point farther than this from the route makes no progress along it.
PROGRESS_RADIUS_M = 10.0
#: Progress is searched at most this far ahead of the progress made so far (plus the
#: distance the ego moved since the step before).
PROGRESS_WINDOW_M = 20.0
#: The route is complete once the ego is this close to its end, along it.
END_TOLERANCE_M = 1.0


@dataclass(frozen=True)
class RouteProgress:
    """Metres along the route reached by each point (never decreasing), and the index of
    the first point at which the route was complete (None: never, or a route too short to
    drive, which counts as complete but ends nothing)."""

    reached: Floats
    length: float
    completed_at: int | None

    def completion(self, index: int) -> float:
        """The share of the route covered by point `index`, 0..1."""
        if self.length <= END_TOLERANCE_M:
            return 1.0
        if self.completed_at is not None and index >= self.completed_at:
            return 1.0
        return float(min(1.0, self.reached[index] / self.length))


def _project(
    ax: Floats,
    ay: Floats,
    bx: Floats,
    by: Floats,
    px: float,
    py: float,
    starts: Floats,
    horizon: float,
) -> tuple[Floats, Floats]:
    """For each segment (a, b) starting `starts` metres along the route: the fraction
    along it of the point's projection, cut where the route passes `horizon` metres, and
    the point's distance to that projection."""
    dx, dy = bx - ax, by - ay
    squared = dx * dx + dy * dy
    with np.errstate(divide="ignore", invalid="ignore"):
        fraction = np.where(squared > 0, ((px - ax) * dx + (py - ay) * dy) / squared, 0.0)
        reach = np.where(squared > 0, (horizon - starts) / np.sqrt(squared), 1.0)
    fraction = np.clip(fraction, 0.0, np.clip(reach, 0.0, 1.0))
    return fraction, np.hypot(ax + fraction * dx - px, ay + fraction * dy - py)


def follow_route(route: EgoRoute, xs: Floats, ys: Floats) -> RouteProgress:
    """The ego's progress along `route` at each of its points (see the module doc)."""
    points = np.array(route.waypoints, dtype=np.float64).reshape(-1, 2)
    ax, ay, bx, by = points[:-1, 0], points[:-1, 1], points[1:, 0], points[1:, 1]
    seglen = np.hypot(bx - ax, by - ay)
    starts = np.concatenate(([0.0], np.cumsum(seglen)))
    length = float(starts[-1])
    reached = np.zeros(len(xs))
    completed_at: int | None = None
    progress = 0.0
    moves = np.hypot(np.diff(xs, prepend=xs[:1]), np.diff(ys, prepend=ys[:1]))
    for index, (px, py) in enumerate(zip(xs.tolist(), ys.tolist(), strict=True)):
        if len(seglen):
            horizon = progress + PROGRESS_WINDOW_M + float(moves[index])
            first = int(np.searchsorted(starts, progress, side="right")) - 1
            first = min(max(0, first), len(seglen) - 1)
            last = int(np.searchsorted(starts, horizon, side="right"))
            window = slice(first, max(first + 1, min(last, len(seglen))))
            fraction, distance = _project(
                ax[window], ay[window], bx[window], by[window], px, py, starts[window], horizon
            )
            best = int(np.argmin(distance))
            if distance[best] <= PROGRESS_RADIUS_M:
                arc = float(starts[first + best] + fraction[best] * seglen[first + best])
                progress = max(progress, arc)
        reached[index] = progress
        if completed_at is None and length > END_TOLERANCE_M >= length - progress:
            completed_at = index
    return RouteProgress(reached=reached, length=length, completed_at=completed_at)


def distances_to_route(route: EgoRoute, xs: Floats, ys: Floats) -> Floats:
    """Each point's distance to the route's polyline, metres."""
    if len(route.waypoints) == 1:
        line: shapely.Geometry = shapely.Point(route.waypoints[0])
    else:
        line = shapely.LineString(route.waypoints)
    shapely.prepare(line)
    return np.asarray(shapely.distance(line, shapely.points(xs, ys)), dtype=np.float64)
