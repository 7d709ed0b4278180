"""The metrics on real runs: a script simulated in the confined world model with an agent
at the wheel, measured by the parent from the trace and its own copy of the map.

The `blind` agent drives into the crossing pedestrian of examples/pedestrian_crossing.scenic;
`idm` stops for it. The metrics' box contacts must agree with the worker's own collision
facts, and the route the world model recorded must be the one the ego drove.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from arise.drive.metrics import DrivingMetrics, ScenicRoad, compute_metrics
from arise.validate import CheckOptions, WorkerPool
from arise.validate.api import check
from arise.validate.types import SimulationFacts
from tests.conftest import EXAMPLES

pytestmark = pytest.mark.slow


_runs: dict[str, tuple[SimulationFacts, DrivingMetrics]] = {}


def drive(pool: WorkerPool, agent: str) -> tuple[SimulationFacts, DrivingMetrics]:
    """The run of the example with a built-in agent (built-ins share one pool), measured."""
    if agent not in _runs:
        options = CheckOptions(seed=7, timeout=90, agent=agent)
        result = check(EXAMPLES / "pedestrian_crossing.scenic", options, pool=pool)
        assert result.ok, result.summary()
        assert result.simulation is not None and result.map is not None
        facts = result.simulation
        road = ScenicRoad.from_map(result.map.path)
        timeout_s = options.steps * facts.timestep
        _runs[agent] = (facts, compute_metrics(facts, road, timeout_s=timeout_s))
    return _runs[agent]


def test_blind_hits_the_pedestrian_and_the_metrics_agree_with_the_worker(
    validator_pool: WorkerPool,
) -> None:
    facts, got = drive(validator_pool, "blind")
    (contact,) = [c for c in facts.collisions if "ego" in (c.first, c.second)]
    assert got.collision == 1 and got.collision_count == 1
    assert got.time_spent_s == pytest.approx(contact.time)  # the episode ends there
    assert got.min_ttc_s == 0 and got.pet_s == 0
    # it kept its lane on the road, on its route, and covered part of it
    assert got.lane_invasions == 0 and got.out_of_road_m == 0
    assert got.distance_to_route_m < 0.5 and 0 < got.route_completion < 1
    assert got.overall_score < 0.6  # the collision alone costs 0.4


def test_idm_stops_short_and_scores_better(validator_pool: WorkerPool) -> None:
    facts, got = drive(validator_pool, "idm")
    assert not facts.collisions and got.collision == 0
    assert got.min_ttc_s is not None and got.min_ttc_s > 0
    assert got.pet_s is not None and got.pet_s > 0  # the pedestrian crossed its path first
    assert got.distance_to_route_m < 0.5 and got.route_completion > 0
    assert all(
        math.isfinite(value) for value in got.model_dump().values() if isinstance(value, float)
    )
    _, blind = drive(validator_pool, "blind")
    assert got.overall_score > blind.overall_score


def test_a_red_light_run_on_a_real_run_and_a_green_one(
    validator_pool: WorkerPool, tmp_path: Path
) -> None:
    # The example's ego sets its light green and waits while it is red; turned round, it
    # sets it red and drives on: its scripted behavior runs the red light.
    source = (EXAMPLES / "categories" / "red_light_running.scenic").read_text()
    wait = 'while withinDistanceToTrafficLight(self, 20) and getClosestTrafficLightStatus(self) == "Red":'
    assert wait in source and 'take SetTrafficLightAction("green")' in source
    reckless = tmp_path / "ego_runs_the_red.scenic"
    reckless.write_text(
        source.replace(wait, "while False:").replace(
            'take SetTrafficLightAction("green")', 'take SetTrafficLightAction("red")'
        )
    )
    for script, runs in ((EXAMPLES / "categories" / "red_light_running.scenic", 0), (reckless, 1)):
        options = CheckOptions(seed=7, timeout=90)
        result = check(script, options, pool=validator_pool)
        assert result.ok and result.simulation is not None and result.map is not None
        facts = result.simulation
        assert facts.signals  # the junction's lights were recorded
        got = compute_metrics(
            facts, ScenicRoad.from_map(result.map.path), timeout_s=options.steps * facts.timestep
        )
        assert got.red_lights_run == runs, script.name
        assert got.route_completion > 0.5


# The stem of our T-junction carries a stop sign: the ego turns right out of it.
STEM_RIGHT_TURN = """\
param map = localPath('maps/arise_tjunction.xodr')
param carla_map = 'arise_tjunction'
model scenic.simulators.carla.model
behavior EgoGo():
    do FollowTrajectoryBehavior(target_speed=7, trajectory=egoRoute)
    do FollowLaneBehavior(target_speed=7)
egoManeuver = Uniform(*[m for i in network.intersections for m in i.maneuvers if m.type is ManeuverType.RIGHT_TURN and m.startLane.road.uid == 'road3'])
egoRoute = [egoManeuver.startLane, egoManeuver.connectingLane, egoManeuver.endLane]
egoStart = new OrientedPoint at egoManeuver.startLane.centerline.pointAlongBy(-30), facing roadDirection
ego = new Car at egoStart, with behavior EgoGo()
terminate when (distance to egoStart) > 60
"""


def test_blind_runs_the_stop_sign_and_idm_stops_for_it(
    validator_pool: WorkerPool, tmp_path: Path
) -> None:
    script = tmp_path / "stem_right_turn.scenic"
    script.write_text(STEM_RIGHT_TURN)
    seen = {}
    for agent in ("blind", "idm"):
        options = CheckOptions(seed=7, timeout=90, agent=agent)
        result = check(script, options, pool=validator_pool)
        assert result.ok and result.simulation is not None and result.map is not None
        facts = result.simulation
        assert [s.kind.value for s in facts.signals] == ["stop_sign"]
        road = ScenicRoad.from_map(result.map.path)
        seen[agent] = compute_metrics(facts, road, timeout_s=options.steps * facts.timestep)
    assert seen["blind"].stop_signs_run == 1 and seen["idm"].stop_signs_run == 0
    # both complete the turn onto the main road; the stop costs idm time
    assert seen["blind"].route_completion == seen["idm"].route_completion == 1.0
    assert seen["idm"].time_spent_s > seen["blind"].time_spent_s
