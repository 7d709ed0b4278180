"""The offline ego keeps its lane at every speed the knowledge base uses (issue 13).

Every geometry entry drives the ego alone (no adversary) at the top of its speed range,
and highway entries also at 35 m/s, on our maps and on CARLA's towns; the trace, read lane
by lane with Scenic's road network, must show exactly the lane changes the entry intends
(none; one for an `ego_lane_change` entry; two when it also `ego_returns`), no weaving and
no time in the oncoming lanes. Before the lateral gains were scheduled with speed, the ego
wove across lane boundaries 7 to 19 times in 20 s at 21 m/s and above; before it braked
for curves, it left its lane on Town06's 50 m highway curves at 24-35 m/s.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from arise.kb.compose import compose, pick_map
from arise.kb.loader import load_kb
from arise.kb.schema import Component, Entry
from arise.maps.registry import MapRegistry
from arise.validate import CheckOptions, WorkerPool, check_text
from arise.validate.worldmodel.simulator import SpeedScheduledLateralController

SPEED = re.compile(r"param OPT_EGO_SPEED = Range\(([\d.]+), ([\d.]+)\)")
HIGHWAY_TOP_SPEED = 35.0


def intended_lane_changes(entry: Entry) -> int:
    """How many lane changes the entry's ego makes on purpose, from its tags."""
    if "ego_lane_change" not in entry.tags:
        return 0
    return 2 if "ego_returns" in entry.tags else 1


def _cases(geometries: list[Entry]) -> list[tuple[Entry, float]]:
    cases = []
    for entry in geometries:
        found = SPEED.search(entry.snippet)
        if found is None:
            continue  # no speed to set (the ego stands still)
        cases.append((entry, float(found.group(2))))
        if "highway" in entry.map_features:
            cases.append((entry, HIGHWAY_TOP_SPEED))
    return cases


def _unintended(
    entry: Entry, speed: float, maps: dict[str, frozenset[str]], pool: WorkerPool, **check: object
) -> list[str]:
    """What the ego did beyond its intended lane changes, per seed (empty: nothing)."""
    map_name = pick_map([entry], maps)
    assert map_name is not None, entry.id
    found = SPEED.search(entry.snippet)
    assert found is not None
    script = compose([entry], None, map_name).replace(
        found.group(0), f"param OPT_EGO_SPEED = {speed:g}"
    )
    wanted = intended_lane_changes(entry)
    wrong = []
    for seed in (0, 1):
        result = check_text(
            script, CheckOptions(seed=seed, steps=200, timeout=120, **check), pool=pool
        )
        assert result.ok and result.simulation is not None, (entry.id, result.diagnostic)
        ego = next(agent for agent in result.simulation.agents if agent.is_ego)
        if ego.lane_changes != wanted or ego.weaving or ego.opposite_lane_steps:
            wrong.append(
                f"seed {seed} on {map_name}: {ego.lane_changes} lane changes (wanted {wanted}), "
                f"weaving {ego.weaving}, {ego.opposite_lane_steps} steps in oncoming lanes"
            )
    return wrong


def test_the_gains_shrink_with_the_square_of_speed_above_the_reference() -> None:
    class Agent:
        speed = 5.0

    agent = Agent()
    controller = SpeedScheduledLateralController(agent, K_P=0.1, K_D=0.0, K_I=0.0, dt=0.1)
    slow = controller.run_step(1.0)
    agent.speed = 30.0
    assert controller.run_step(1.0) == pytest.approx(slow / 4)  # (15 / 30)^2


def test_a_controller_handed_back_after_a_pause_starts_afresh() -> None:
    """After a junction's turn controller had the car, no derivative kick from before."""

    class Agent:
        speed = 5.0

    steps = iter([0, 1, 9])
    controller = SpeedScheduledLateralController(
        Agent(), K_P=0.1, K_D=0.1, K_I=0.0, dt=0.1, clock=lambda: next(steps)
    )
    controller.run_step(0.0)
    controller.run_step(0.0)
    assert controller.run_step(1.0) == pytest.approx(0.1)  # P alone; the kick would be 1.0


@pytest.mark.slow
def test_no_geometry_entry_changes_lanes_unintentionally(validator_pool: WorkerPool) -> None:
    maps = {name: entry.features for name, entry in MapRegistry().entries.items()}
    wrong = {}
    for entry, speed in _cases(load_kb().of(Component.GEOMETRY)):
        found = _unintended(entry, speed, maps, validator_pool)
        if found:
            wrong[f"{entry.id} at {speed:g} m/s"] = found
    assert not wrong, wrong


@pytest.mark.slow
@pytest.mark.carla_towns
def test_highway_entries_keep_their_lane_on_carla_towns(
    validator_pool: WorkerPool, carla_maps: Path
) -> None:
    registry = MapRegistry(carla_maps)
    towns = {
        name: entry.features
        for name, entry in registry.entries.items()
        if entry.source == "map-dir" and entry.features
    }
    highways = [e for e in load_kb().of(Component.GEOMETRY) if "highway" in e.map_features]
    wrong = {}
    for entry, speed in _cases(highways):
        if pick_map([entry], towns) is None:
            continue
        found = _unintended(entry, speed, towns, validator_pool, map_dir=str(carla_maps))
        if found:
            wrong[f"{entry.id} at {speed:g} m/s"] = found
    assert not wrong, wrong


def test_the_curve_speed_is_that_of_the_lateral_acceleration_on_the_radius() -> None:
    """A 50 m radius (Town06's highway curves) allows sqrt(3.5 * 50), about 13 m/s."""
    from shapely.geometry import LineString

    from arise.validate.worldmodel.curves import LATERAL_ACCELERATION, curve_speeds

    arc = LineString([(50 * math.cos(a / 100), 50 * math.sin(a / 100)) for a in range(0, 158)])
    _, speeds = curve_speeds(arc)
    middle = speeds[len(speeds) // 4 : 3 * len(speeds) // 4]
    assert middle == pytest.approx(math.sqrt(LATERAL_ACCELERATION * 50), rel=0.01)
    _, straight = curve_speeds(LineString([(0, 0), (0, 100)]))
    assert all(math.isinf(s) for s in straight)
