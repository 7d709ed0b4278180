"""The road outline of a Scenic road network, cut to a window and simplified.

Works on the network object alone (duck-typed), so the confined worker can outline the
network it already holds, and the parent can outline a map file it knows (`load_network`);
a script's code is never needed for either.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from arise.render.model import Area, Line, LineKind, Outline, Point, RegionKind, Window

#: Simplification tolerance of outline polygons and lines, in metres (below a pixel).
TOLERANCE = 0.05
#: Two edges closer than this (Hausdorff, metres) are the same painted line.
SAME_EDGE = 0.2


def load_network(map_path: str | Path) -> Any:
    """Scenic's road network of a map file.

    Scenic's parsed cache (`.snet`) is a pickle, so it is loaded only for a map in our
    cache that `trusted_entry` vouches for (inside the cache, no symbolic link, content
    matching its folder's digest), whose `.snet` only the confined preparer writes
    (`arise.validate.map_cache`). Any other file is parsed as OpenDRIVE without reading
    or writing a cache: no file a script or a run folder could have named or written is
    ever unpickled here.
    """
    from scenic.domains.driving.roads import Network

    from arise.maps.cache import trusted_entry
    from arise.maps.errors import MapError

    path = Path(map_path)
    entry = trusted_entry(path)
    if entry is not None:
        return Network.fromFile(str(entry), useCache=True, writeCache=False)
    if path.suffix != ".xodr":
        raise MapError(f"{path} is not an OpenDRIVE map (.xodr)")
    return Network.fromFile(str(path), useCache=False, writeCache=False)


def _shape(region: Any) -> Any:
    return getattr(region, "polygons", None)


def _rings(geometry: Any) -> list[Any]:
    parts = getattr(geometry, "geoms", [geometry])
    return [part for part in parts if not part.is_empty and hasattr(part, "exterior")]


def _coords(ring: Any) -> list[Point]:
    return [(round(float(x), 2), round(float(y), 2)) for x, y, *_ in ring.coords]


def _areas(kind: RegionKind, geometry: Any) -> list[Area]:
    areas = []
    for polygon in _rings(geometry.simplify(TOLERANCE)):
        areas.append(
            Area(
                kind=kind,
                exterior=_coords(polygon.exterior),
                holes=[_coords(hole) for hole in polygon.interiors],
            )
        )
    return areas


def _lines(kind: LineKind, geometry: Any) -> list[Line]:
    parts = getattr(geometry, "geoms", [geometry])
    return [
        Line(kind, _coords(part))
        for part in parts
        if not part.is_empty and part.geom_type == "LineString" and len(part.coords) > 1
    ]


def outline_of(network: Any, window: Window) -> Outline:
    """The surfaces and painted lines of `network` inside `window` (None: empty outline)."""
    if network is None:
        return Outline()
    from shapely.geometry import box

    frame = box(window.xmin, window.ymin, window.xmax, window.ymax)
    junctions = _shape(getattr(network, "intersectionRegion", None))
    junction_area = junctions.intersection(frame) if junctions is not None else None
    areas: list[Area] = []
    for kind, attribute in (
        (RegionKind.SHOULDER, "shoulderRegion"),
        (RegionKind.SIDEWALK, "sidewalkRegion"),
        (RegionKind.DRIVABLE, "drivableRegion"),
        (RegionKind.JUNCTION, "intersectionRegion"),
        (RegionKind.CROSSING, "crossingRegion"),
    ):
        shape = _shape(getattr(network, attribute, None))
        if shape is None:
            continue
        clipped = shape.intersection(frame)
        if kind is RegionKind.DRIVABLE and junction_area is not None:
            clipped = clipped.difference(junction_area)
        if not clipped.is_empty:
            areas.extend(_areas(kind, clipped))
    return Outline(areas=areas, lines=_painted_lines(network, frame, junction_area))


def _painted_lines(network: Any, frame: Any, junction_area: Any) -> list[Line]:
    """Dashed lines between lanes of one direction, a solid one between directions;
    none inside junctions, where connecting lanes overlap."""
    lines: list[Line] = []
    for road in getattr(network, "roads", ()):
        groups = [g for g in (road.forwardLanes, road.backwardLanes) if g is not None]
        for group in groups:
            outer = [group.leftEdge.lineString, group.rightEdge.lineString]
            for lane in group.lanes:
                edge = lane.leftEdge.lineString
                if any(edge.hausdorff_distance(o) < SAME_EDGE for o in outer):
                    continue
                lines.extend(_clip(LineKind.LANE, edge, frame, junction_area))
        if road.forwardLanes is not None and road.backwardLanes is not None:
            median = road.forwardLanes.leftEdge.lineString
            lines.extend(_clip(LineKind.DIVIDER, median, frame, junction_area))
    return lines


def _clip(kind: LineKind, line: Any, frame: Any, junction_area: Any) -> list[Line]:
    if not line.intersects(frame):
        return []
    clipped = line.intersection(frame)
    if junction_area is not None and not junction_area.is_empty:
        clipped = clipped.difference(junction_area)
    clipped = clipped.simplify(TOLERANCE)
    if clipped.geom_type == "MultiLineString":
        return _lines(kind, clipped)
    if clipped.geom_type == "LineString":
        return _lines(kind, clipped)
    return []
