"""Criticality of a run from its trace: the offline counterpart of SafeBench's numbers.

Collision, closest approach and smallest time-to-collision between the ego and the
adversary come from the validator's footprint facts. Route completion has no route to
measure against offline, so it is the distance the ego covered over the distance it would
have covered at its target speed (`OPT_EGO_SPEED`, else its top speed) for the whole run,
capped at 1: an ego that is blocked or stops for the adversary completes less.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

from arise.generate.conformity import find_adversary
from arise.validate.types import SimulationFacts


@dataclass(frozen=True)
class Criticality:
    collision: bool
    min_distance: float | None
    min_ttc: float | None
    route_completion: float | None

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)


def _float(text: str | None) -> float | None:
    try:
        return float(text) if text is not None else None
    except ValueError:
        return None


def criticality(facts: SimulationFacts | None) -> Criticality | None:
    if facts is None:
        return None
    ego = next((a for a in facts.agents if a.is_ego), None)
    adversary = find_adversary(facts.agents)
    pair = next((p for p in facts.ego_pairs if adversary and p.other == adversary.name), None)
    completion = None
    if ego is not None and len(ego.trajectory) > 1:
        points = ego.trajectory
        covered = sum(
            math.hypot(b.x - a.x, b.y - a.y) for a, b in zip(points, points[1:], strict=False)
        )
        speed = _float(facts.params.get("OPT_EGO_SPEED")) or max(p.speed for p in points)
        planned = speed * facts.timestep * (len(points) - 1)
        completion = round(min(1.0, covered / planned), 3) if planned > 0 else None
    return Criticality(
        collision=bool(pair and pair.collided),
        min_distance=pair.min_distance if pair else None,
        min_ttc=pair.min_ttc if pair else None,
        route_completion=completion,
    )
