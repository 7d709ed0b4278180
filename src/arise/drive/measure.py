"""One driven run's metrics as a flat row: `compute_metrics` (arise.drive.metrics) on the
run's facts and the road network of the map it ran on, as plain numbers.

The road network is loaded once per map per process (a Town takes seconds), and shared
by the runner's threads.
"""

from __future__ import annotations

import dataclasses
import threading
from pathlib import Path
from typing import Any

from pydantic import BaseModel

from arise.validate.types import CheckResult, SimulationFacts

MetricValue = float | int | None
MetricRow = dict[str, MetricValue]

_ROADS: dict[str, Any] = {}
_ROADS_LOCK = threading.Lock()


def road_of(map_path: str) -> Any:
    """The road queries of a map file the parent chose (a check's `result.map.path`)."""
    from arise.drive.metrics import ScenicRoad

    with _ROADS_LOCK:
        found = _ROADS.get(map_path)
        if found is None:
            found = _ROADS[map_path] = ScenicRoad.from_map(Path(map_path))
        return found


def flat(metrics: object) -> MetricRow:
    """A metrics object as name -> number (a bool becomes 0/1, nested values are left out)."""
    if isinstance(metrics, BaseModel):
        values = metrics.model_dump()
    elif dataclasses.is_dataclass(metrics) and not isinstance(metrics, type):
        values = dataclasses.asdict(metrics)
    else:
        values = dict(vars(metrics))
    row: MetricRow = {}
    for name, value in values.items():
        if isinstance(value, bool):
            row[name] = int(value)
        elif isinstance(value, int | float) or value is None:
            row[name] = value
    return row


def measure(result: CheckResult, timeout_s: float) -> MetricRow:
    """The metrics of a run that drove (`result.simulation` is set)."""
    facts = result.simulation
    assert facts is not None
    try:
        from arise.drive.metrics import compute_metrics
    except ImportError:  # the metrics module is not there yet: what the facts alone say
        return _from_facts(facts, timeout_s)
    road = road_of(result.map.path) if result.map is not None else None
    return flat(compute_metrics(facts, road, timeout_s=timeout_s))


def _from_facts(facts: SimulationFacts, timeout_s: float) -> MetricRow:
    del timeout_s  # the overall score needs the metrics module
    ego = next((a.name for a in facts.agents if a.is_ego), None)
    collided = any(ego in (c.first, c.second) for c in facts.collisions)
    ttcs = [p.min_ttc for p in facts.ego_pairs if p.min_ttc is not None]
    seconds = facts.steps * facts.timestep
    return {
        "collision": int(collided),
        "time_spent_s": round(seconds, 3),
        "min_ttc_s": min(ttcs) if ttcs else None,
    }
