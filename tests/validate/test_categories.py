"""The paper's eight scenario categories, written ChatScene/ARISE-style, execute offline
on our own maps (fresh machine) and on the CARLA towns."""

from __future__ import annotations

from pathlib import Path

import pytest

from arise.validate import CheckOptions, WorkerPool, check
from tests.conftest import EXAMPLES

CATEGORIES = {
    "straight_obstacle": "Pedestrian",
    "turning_obstacle": "Bicycle",
    "lane_changing": "Car",
    "vehicle_passing": "Truck",
    "red_light_running": "Car",
    "unprotected_left_turn": "Motorcycle",
    "right_turn": "Car",
    "crossing_negotiation": "Car",
}


def _check_category(name: str, pool: WorkerPool, map_dir: Path | None):
    options = CheckOptions(seed=11, timeout=90, map_dir=str(map_dir) if map_dir else None)
    result = check(EXAMPLES / "categories" / f"{name}.scenic", options, pool=pool)
    assert result.ok, result.diagnostic
    simulation = result.simulation
    assert simulation is not None and simulation.steps > 10
    kinds = {agent.kind for agent in simulation.agents if not agent.is_ego}
    assert CATEGORIES[name] in kinds
    ego = next(agent for agent in simulation.agents if agent.is_ego)
    assert ego.trajectory[-1].speed > 0 or len(ego.trajectory) > 10
    assert [pair.other for pair in simulation.ego_pairs]
    return result


def test_there_are_eight_categories() -> None:
    assert len(CATEGORIES) == 8
    assert {p.stem for p in (EXAMPLES / "categories").glob("*.scenic")} == set(CATEGORIES)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(CATEGORIES))
def test_category_runs_on_our_maps(name: str, validator_pool: WorkerPool) -> None:
    result = _check_category(name, validator_pool, None)
    assert result.map is not None and result.map.name.startswith("arise_")
    # No CARLA town is available on a fresh machine: the substitution is reported.
    assert result.map.substituted and any("not available" in w for w in result.warnings)


@pytest.mark.slow
@pytest.mark.carla_towns
@pytest.mark.parametrize("name", sorted(CATEGORIES))
def test_category_runs_on_carla_towns(
    name: str, validator_pool: WorkerPool, carla_maps: Path
) -> None:
    result = _check_category(name, validator_pool, carla_maps)
    assert result.map is not None
    if result.map.requested in ("Town03", "Town05"):
        assert result.map.substituted and result.map.name.startswith("Town")
    else:
        assert not result.map.substituted and result.map.name == result.map.requested
