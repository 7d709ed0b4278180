"""Facts read from a simulation trace: collisions, minimum distance, time-to-collision.

The Newtonian-style simulators have no collision detection (cars drive through
pedestrians), so contact is detected here from the footprints along the trajectories.
The same code serves CARLA traces.
"""

from __future__ import annotations

import math
from itertools import combinations

from shapely.geometry import Polygon

from arise.validate.types import AgentTrace, Collision, EgoPairFacts, TracePoint


def footprint(point: TracePoint, width: float, length: float) -> Polygon:
    """Rectangle of an agent at one step (Scenic headings: 0 = +y, counter-clockwise)."""
    forward = (-math.sin(point.heading), math.cos(point.heading))
    side = (forward[1], -forward[0])
    hl, hw = length / 2, width / 2
    corners = [
        (
            point.x + sx * hw * side[0] + fx * hl * forward[0],
            point.y + sx * hw * side[1] + fx * hl * forward[1],
        )
        for sx, fx in ((1, 1), (-1, 1), (-1, -1), (1, -1))
    ]
    return Polygon(corners)


def _velocity(point: TracePoint) -> tuple[float, float]:
    return (-math.sin(point.heading) * point.speed, math.cos(point.heading) * point.speed)


def find_collisions(agents: list[AgentTrace], timestep: float) -> list[Collision]:
    """First step at which each pair of agents overlaps."""
    found = []
    for first, second in combinations(agents, 2):
        for a, b in zip(first.trajectory, second.trajectory, strict=False):
            if footprint(a, first.width, first.length).intersects(
                footprint(b, second.width, second.length)
            ):
                found.append(
                    Collision(
                        first=first.name,
                        second=second.name,
                        step=a.step,
                        time=round(a.step * timestep, 3),
                    )
                )
                break
    return found


def ego_pair_facts(agents: list[AgentTrace]) -> list[EgoPairFacts]:
    """Closest approach and smallest time-to-collision between the ego and each other agent."""
    ego = next((a for a in agents if a.is_ego), None)
    if ego is None:
        return []
    facts = []
    for other in agents:
        if other is ego:
            continue
        best_distance, best_step = math.inf, 0
        best_ttc: float | None = None
        collided = False
        for a, b in zip(ego.trajectory, other.trajectory, strict=False):
            gap = footprint(a, ego.width, ego.length).distance(
                footprint(b, other.width, other.length)
            )
            if gap <= 0:
                collided = True
            if gap < best_distance:
                best_distance, best_step = gap, a.step
            dx, dy = b.x - a.x, b.y - a.y
            centre = math.hypot(dx, dy)
            if centre < 1e-6:
                continue
            va, vb = _velocity(a), _velocity(b)
            closing = -((vb[0] - va[0]) * dx + (vb[1] - va[1]) * dy) / centre
            if closing > 1e-3:
                ttc = gap / closing
                if best_ttc is None or ttc < best_ttc:
                    best_ttc = ttc
        facts.append(
            EgoPairFacts(
                other=other.name,
                min_distance=round(best_distance, 3) if best_distance != math.inf else -1.0,
                min_distance_step=best_step,
                min_ttc=round(best_ttc, 3) if best_ttc is not None else None,
                collided=collided,
            )
        )
    return facts
