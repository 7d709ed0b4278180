"""The curvature of a lane's centre line, from the circle through three points on it.

Shared by the curve-speed governor (`curves`) and the steering feed-forward
(`feedforward`): both read how a lane bends from its polyline, which has no curvature of
its own. Points a chord apart either side smooth over the polyline's short segments.
"""

from __future__ import annotations

import numpy as np
import shapely
from shapely.geometry import LineString


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
