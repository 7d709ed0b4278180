"""How a lane's centre line runs: its direction and curvature along it, and angle arithmetic.

Shared by the simulator's autopilot, the curve-speed governor (`curves`) and the steering
feed-forward (`feedforward`), which all compare headings and read how a lane bends from
its polyline. A polyline has no curvature of its own: it is taken from the circle through
three points a chord apart, which smooths over the polyline's short segments.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from shapely.geometry import LineString


def wrap_angle(angle: float) -> float:
    """The same angle in [-pi, pi)."""
    return (angle + math.pi) % (2 * math.pi) - math.pi


def line_direction(line: LineString, along: float, half_span: float) -> float:
    """The line's direction at a distance along it, as a math angle (0 is +x): the chord
    from `half_span` metres before to `half_span` after (clamped at the ends)."""
    start = line.interpolate(max(0.0, along - half_span))
    end = line.interpolate(min(line.length, along + half_span))
    return math.atan2(end.y - start.y, end.x - start.x)


def signed_curvatures(line: LineString, step: float, chord: float) -> tuple[np.ndarray, np.ndarray]:
    """Samples every `step` metres along the line, and the signed curvature (1/m) of the
    circle through the points `chord` metres before and after each: positive where the
    line bends left, 0 where it runs straight."""
    distances = np.arange(0.0, max(line.length, step), step)
    points = _coords(line, distances)
    before = _coords(line, np.maximum(0.0, distances - chord))
    after = _coords(line, np.minimum(line.length, distances + chord))
    a = np.linalg.norm(points - before, axis=1)
    b = np.linalg.norm(after - points, axis=1)
    c = np.linalg.norm(after - before, axis=1)
    u, v = points - before, after - before
    cross = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]  # twice the signed area: left positive
    with np.errstate(divide="ignore", invalid="ignore"):
        curvature = np.where(a * b * c > 1e-9, 2 * cross / (a * b * c), 0.0)
    return distances, curvature


def _coords(line: LineString, distances: np.ndarray) -> np.ndarray:
    return shapely.get_coordinates(shapely.line_interpolate_point(line, distances))[:, :2]
