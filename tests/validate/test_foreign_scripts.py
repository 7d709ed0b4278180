"""Scripts written for CARLA in other people's styles (Scenic's example idioms: map paths
into Scenic's assets folder, autopilot, modular scenarios, traffic-light helpers, props)
pass offline; one that needs CARLA's own API gets a diagnostic that says so."""

from __future__ import annotations

from pathlib import Path

import pytest

from arise.validate import CheckOptions, Stage, WorkerPool, check
from tests.conftest import DATA

FOREIGN = DATA / "foreign"
RUNNABLE = ["autopilot_traffic", "modular_lead_brake", "traffic_lights", "props_and_walkers"]


@pytest.mark.slow
@pytest.mark.parametrize("name", RUNNABLE)
def test_foreign_script_runs_offline(name: str, validator_pool: WorkerPool) -> None:
    result = check(FOREIGN / f"{name}.scenic", CheckOptions(seed=5), pool=validator_pool)
    assert result.ok, result.diagnostic
    assert result.simulation is not None and result.simulation.steps > 0


@pytest.mark.slow
def test_traffic_light_and_autopilot_actions_are_recorded(validator_pool: WorkerPool) -> None:
    lights = check(FOREIGN / "traffic_lights.scenic", CheckOptions(seed=5), pool=validator_pool)
    assert lights.simulation is not None
    assert any(e["kind"] == "traffic_light" for e in lights.simulation.events)
    auto = check(FOREIGN / "autopilot_traffic.scenic", CheckOptions(seed=5), pool=validator_pool)
    assert auto.simulation is not None
    assert any(e["kind"] == "autopilot" for e in auto.simulation.events)
    ego = next(a for a in auto.simulation.agents if a.is_ego)
    travelled = abs(ego.trajectory[-1].x - ego.trajectory[0].x) + abs(
        ego.trajectory[-1].y - ego.trajectory[0].y
    )
    assert travelled > 10, "autopilot should drive the ego along its lane"


@pytest.mark.slow
def test_script_needing_the_carla_api_says_what_it_needs(validator_pool: WorkerPool) -> None:
    result = check(FOREIGN / "needs_carla_api.scenic", CheckOptions(seed=5), pool=validator_pool)
    assert result.diagnostic is not None
    assert result.diagnostic.stage is Stage.SIMULATE
    assert result.diagnostic.line == 7
    assert "--simulator carla" in (result.diagnostic.hint or "")


@pytest.mark.slow
@pytest.mark.carla_towns
@pytest.mark.parametrize("name", RUNNABLE)
def test_foreign_script_runs_on_carla_towns(
    name: str, validator_pool: WorkerPool, carla_maps: Path
) -> None:
    result = check(
        FOREIGN / f"{name}.scenic",
        CheckOptions(seed=5, map_dir=str(carla_maps)),
        pool=validator_pool,
    )
    assert result.ok, result.diagnostic
    assert result.map is not None and result.map.name.startswith("Town")
