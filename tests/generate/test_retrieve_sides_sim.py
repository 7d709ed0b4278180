"""Side-aware retrieval, proven on the real Scenic compiler and simulator.

For each side and turn the knowledge base has at junctions, the spec goes through
retrieval and assembly unchanged (no tuned parameters), the validator runs the script, and
the trace says where the adversary started and which way it went.
"""

from __future__ import annotations

import math

import pytest

from arise.evaluate.fidelity import Direction, Maneuver, observed_maneuver, placement
from arise.generate.assemble import assemble
from arise.generate.conformity import (
    StartRelation,
    at_junction,
    find_adversary,
    start_relation,
    travel_heading,
    wrap,
)
from arise.generate.retrieve import retrieve
from arise.generate.spec import ScenarioSpec
from arise.kb.loader import KnowledgeBase, load_kb
from arise.kb.retrieval import BM25Retriever
from arise.maps.registry import MapRegistry
from arise.validate import CheckOptions, WorkerPool, check_text
from arise.validate.types import AgentTrace, SimulationFacts
from arise.vocabulary import AdversaryManeuver, RelativePosition, StartDetail

TURN_DEGREES = 45.0
SEEDS = (1, 2)
# (road, ego maneuver, where the adversary starts, which way it goes)
CASES = [
    ("intersection", "go_straight", RelativePosition.CROSSING_FROM_LEFT, "straight"),
    ("intersection", "go_straight", RelativePosition.CROSSING_FROM_RIGHT, "straight"),
    ("intersection", "go_straight", RelativePosition.CROSSING_FROM_RIGHT, "turn_left"),
    ("intersection", "go_straight", RelativePosition.CROSSING_FROM_RIGHT, "turn_right"),
    ("intersection", "go_straight", RelativePosition.ONCOMING, "turn_left"),
    ("intersection", "turn_left", RelativePosition.ONCOMING, "straight"),
    ("intersection", "turn_left", RelativePosition.CROSSING_FROM_LEFT, "straight"),
    ("intersection", "turn_left", RelativePosition.CROSSING_FROM_RIGHT, "straight"),
    ("intersection", "turn_right", RelativePosition.CROSSING_FROM_LEFT, "straight"),
    ("intersection", "turn_right", RelativePosition.ONCOMING, "turn_left"),
    ("t_junction", "go_straight", RelativePosition.CROSSING_FROM_RIGHT, "turn_left"),
    ("t_junction", "go_straight", RelativePosition.ONCOMING, "turn_left"),
    ("t_junction", "turn_left", RelativePosition.ONCOMING, "straight"),
    ("t_junction", "turn_left", RelativePosition.CROSSING_FROM_LEFT, "straight"),
]
WANTED_SIDE = {
    RelativePosition.CROSSING_FROM_LEFT: ("left", "crossing"),
    RelativePosition.CROSSING_FROM_RIGHT: ("right", "crossing"),
    RelativePosition.ONCOMING: (None, "opposite"),
}


@pytest.fixture(scope="module")
def kb() -> KnowledgeBase:
    return load_kb(builtin=True)


@pytest.fixture(scope="module")
def maps() -> dict[str, frozenset[str]]:
    return {name: entry.features for name, entry in MapRegistry().entries.items()}


def adversary_turn(adversary: AgentTrace) -> AdversaryManeuver | None:
    """Straight or a turn, from the first heading moved and the heading at the end."""
    start = travel_heading(adversary)
    if start is None or not adversary.trajectory:
        return None
    turn = math.degrees(wrap(adversary.trajectory[-1].heading - start))
    if turn > TURN_DEGREES:
        return AdversaryManeuver.TURN_LEFT
    if turn < -TURN_DEGREES:
        return AdversaryManeuver.TURN_RIGHT
    return AdversaryManeuver.STRAIGHT


def ego_and_adversary(
    simulation: SimulationFacts, chosen: list[str]
) -> tuple[AgentTrace, AgentTrace, StartRelation]:
    """The ego, the adversary and where the adversary started seen from the ego (each must
    be in the trace)."""
    ego_trace = next(a for a in simulation.agents if a.is_ego)
    adversary = find_adversary(simulation.agents)
    assert adversary is not None, chosen
    relation = start_relation(ego_trace, adversary)
    assert relation is not None, chosen
    return ego_trace, adversary, relation


def simulated(
    spec: ScenarioSpec,
    cls: str | None,
    kb: KnowledgeBase,
    maps: dict[str, frozenset[str]],
    pool: WorkerPool,
) -> tuple[list[str], list[tuple[int, SimulationFacts]]]:
    """The chosen entries for `spec`, and the simulation of the assembled script per seed
    (each must run)."""
    retrieval = retrieve(spec, kb, BM25Retriever(kb), maps)
    chosen = [e.id for e in retrieval.chosen_entries()]
    draft = assemble(retrieval, cls, spec.behavior, params={})
    runs = []
    for seed in SEEDS:
        result = check_text(draft.script, CheckOptions(seed=seed, timeout=60), pool=pool)
        assert result.ok and result.simulation is not None, (chosen, result.diagnostic)
        runs.append((seed, result.simulation))
    return chosen, runs


@pytest.mark.slow
@pytest.mark.parametrize(("road", "ego", "position", "turn"), CASES)
def test_the_adversary_starts_on_the_stated_side_and_goes_the_stated_way(
    kb: KnowledgeBase,
    maps: dict[str, frozenset[str]],
    validator_pool: WorkerPool,
    road: str,
    ego: str,
    position: RelativePosition,
    turn: str,
) -> None:
    spec = ScenarioSpec(
        adversary_type="car",
        behavior="drives on through the junction",
        road_type=road,
        ego_maneuver=ego,
        geometry="a junction",
        spawn_position=position,
        spawn="another car approaches the junction",
        adversary_maneuver=turn,
    )
    chosen, runs = simulated(spec, "Car", kb, maps, validator_pool)
    side, direction = WANTED_SIDE[position]
    for seed, simulation in runs:
        _, adversary, relation = ego_and_adversary(simulation, chosen)
        where = (chosen, seed, relation.describe())
        assert relation.direction == direction, where
        if side is not None:
            assert relation.side == side, where
        else:
            assert relation.ahead > 0, where
        assert adversary_turn(adversary) is AdversaryManeuver(turn), where


STOPPED_CASES = [
    ("intersection", RelativePosition.BEHIND_SAME_LANE, "unstated", "Car"),
    ("intersection", RelativePosition.ONCOMING, "turn_left", "Bus"),
    ("straight_road", RelativePosition.BEHIND_SAME_LANE, "unstated", "Car"),
]


@pytest.mark.slow
@pytest.mark.parametrize(("road", "position", "turn", "cls"), STOPPED_CASES)
def test_a_stopped_ego_never_moves_and_is_still_met(
    kb: KnowledgeBase,
    maps: dict[str, frozenset[str]],
    validator_pool: WorkerPool,
    road: str,
    position: RelativePosition,
    turn: str,
    cls: str,
) -> None:
    spec = ScenarioSpec(
        adversary_type="truck" if cls == "Bus" else "car",
        adversary_class=cls,
        behavior="comes at the waiting ego",
        road_type=road,
        ego_maneuver="go_straight",
        ego_stopped=True,
        geometry="the ego waits",
        spawn_position=position,
        spawn="another vehicle approaches",
        adversary_maneuver=turn,
    )
    chosen, runs = simulated(spec, cls, kb, maps, validator_pool)
    for seed, simulation in runs:
        agents = simulation.agents
        ego_trace = next(a for a in agents if a.is_ego)
        assert travel_heading(ego_trace) is None, (chosen, seed, "the ego moved")
        assert at_junction(ego_trace) is (road == "intersection"), (chosen, ego_trace.junction_gap)
        adversary = find_adversary(agents)
        assert adversary is not None and travel_heading(adversary) is not None, chosen
        relation = start_relation(ego_trace, adversary)
        assert relation is not None, chosen
        where = (chosen, seed, relation.describe())
        if position is RelativePosition.BEHIND_SAME_LANE:
            assert relation.ahead < 0 and relation.direction == "same", where
        else:
            assert relation.ahead > 0 and relation.direction == "opposite", where
            assert adversary_turn(adversary) is AdversaryManeuver.TURN_LEFT, where
        closest = min(
            math.hypot(a.x - b.x, a.y - b.y)
            for a, b in zip(ego_trace.trajectory, adversary.trajectory, strict=False)
        )
        # Met: within 12 m, less the half-lengths (a bus's centre is 6 m from its bumper).
        gap = closest - (ego_trace.length + adversary.length) / 2
        assert gap < 12, (where, closest, gap)


@pytest.mark.slow
def test_an_oncoming_drifter_stays_oncoming_until_the_scene_ends(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], validator_pool: WorkerPool
) -> None:
    spec = ScenarioSpec(
        adversary_type="car",
        behavior="drifting over the centre line into its lane",
        road_type="straight_road",
        ego_maneuver="go_straight",
        geometry="a two-way road",
        spawn_position=RelativePosition.ONCOMING,
        spawn="an oncoming car",
    )
    chosen, runs = simulated(spec, "Car", kb, maps, validator_pool)
    assert "behavior.oncoming_drift_into_lane" in chosen
    for seed, simulation in runs:
        agents = simulation.agents
        ego_trace = next(a for a in agents if a.is_ego)
        adversary = find_adversary(agents)
        assert adversary is not None
        where = placement(ego_trace, adversary)
        assert where is not None and where.direction is Direction.OPPOSITE, (seed, where)
        assert simulation.steps < 200, "the scene ends once the car is well past"


@pytest.mark.slow
@pytest.mark.parametrize("side", ["left", "right"])
def test_the_ego_changes_lanes_to_the_stated_side(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], validator_pool: WorkerPool, side: str
) -> None:
    spec = ScenarioSpec(
        adversary_type="car",
        behavior="brakes",
        road_type="straight_road",
        ego_maneuver="change_lane",
        ego_lane_side=side,
        geometry="a multi-lane road",
        spawn_position=RelativePosition.AHEAD_SAME_LANE,
        spawn="a car ahead",
    )
    chosen, runs = simulated(spec, "Car", kb, maps, validator_pool)
    for seed, simulation in runs:
        ego_trace = next(a for a in simulation.agents if a.is_ego)
        assert observed_maneuver(ego_trace) is Maneuver(f"lane_change_{side}"), (chosen, seed)
        assert ego_trace.lane_changes == 1, (chosen, seed)


@pytest.mark.slow
@pytest.mark.parametrize("cls", ["Bicycle", "Pedestrian"])
def test_a_walker_or_cyclist_from_the_left_at_a_junction_crosses_the_egos_road(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], validator_pool: WorkerPool, cls: str
) -> None:
    """Its anchor may fall inside the junction, whose direction field points along a
    crossing lane: the spawn faces it across the ego's road all the same (it rode along the
    kerb, away from the ego)."""
    spec = ScenarioSpec(
        adversary_type="bicycle" if cls == "Bicycle" else "pedestrian",
        adversary_class=cls,
        behavior="crosses the road in front of the ego",
        road_type="intersection",
        ego_maneuver="go_straight",
        geometry="a junction",
        spawn_position=RelativePosition.CROSSING_FROM_LEFT,
        spawn="from the left",
    )
    chosen, runs = simulated(spec, cls, kb, maps, validator_pool)
    for seed, simulation in runs:
        ego_trace, adversary, relation = ego_and_adversary(simulation, chosen)
        where = (chosen, seed, relation.describe())
        assert relation.side == "left" and relation.direction == "crossing", where
        where_placed = placement(ego_trace, adversary)
        assert where_placed is not None
        assert where_placed.direction is Direction.CROSSING_LEFT_TO_RIGHT, where


# (road, ego maneuver, stopped?, the lane beside the ego the adversary starts in, geometry)
NEIGHBOR_CASES = [
    (
        "intersection",
        "go_straight",
        True,
        RelativePosition.ADJACENT_LANE_RIGHT,
        "stopped_at_red_light_right",
    ),
    (
        "intersection",
        "go_straight",
        True,
        RelativePosition.ADJACENT_LANE_LEFT,
        "stopped_at_red_light_left",
    ),
    (
        "intersection",
        "go_straight",
        False,
        RelativePosition.ADJACENT_LANE_RIGHT,
        "junction_straight_right",
    ),
    (
        "intersection",
        "go_straight",
        False,
        RelativePosition.ADJACENT_LANE_LEFT,
        "junction_straight_left",
    ),
    (
        "intersection",
        "turn_left",
        False,
        RelativePosition.ADJACENT_LANE_RIGHT,
        "junction_left_turn_right",
    ),
    (
        "intersection",
        "turn_right",
        False,
        RelativePosition.ADJACENT_LANE_LEFT,
        "junction_right_turn_left",
    ),
    (
        "straight_road",
        "go_straight",
        True,
        RelativePosition.ADJACENT_LANE_RIGHT,
        "stopped_in_traffic_right",
    ),
    (
        "straight_road",
        "go_straight",
        True,
        RelativePosition.ADJACENT_LANE_LEFT,
        "stopped_in_traffic_left",
    ),
]


@pytest.mark.slow
@pytest.mark.parametrize(("road", "ego", "stopped", "position", "geometry"), NEIGHBOR_CASES)
def test_a_vehicle_in_the_lane_beside_the_ego_starts_there(
    kb: KnowledgeBase,
    maps: dict[str, frozenset[str]],
    validator_pool: WorkerPool,
    road: str,
    ego: str,
    stopped: bool,
    position: RelativePosition,
    geometry: str,
) -> None:
    """A motorbike filtering up beside an ego held at the lights or in a queue, a car in the
    next lane as the ego turns: a geometry with a same-direction lane beside the ego, and
    the road user in that lane, level with the ego or behind it, going its way."""
    spec = ScenarioSpec(
        adversary_type="car",
        adversary_class="Car",
        behavior="drives along in its lane",
        road_type=road,
        ego_maneuver=ego,
        ego_stopped=stopped,
        geometry="a crossroads" if road == "intersection" else "a multi-lane road",
        spawn_position=position,
        spawn="in the lane beside the ego",
    )
    chosen, runs = simulated(spec, "Car", kb, maps, validator_pool)
    assert f"geometry.{geometry}_neighbor" in chosen
    side = "left" if position is RelativePosition.ADJACENT_LANE_LEFT else "right"
    for seed, simulation in runs:
        _, _, relation = ego_and_adversary(simulation, chosen)
        where = (chosen, seed, relation.describe())
        assert relation.side == side and relation.direction == "same", where
        assert 2.0 < abs(relation.left) < 5.6, where


# (class, its type, where the text puts it, the spawn that must place it, the side seen)
STANDING_CASES = [
    ("Car", "car", RelativePosition.ROADSIDE_LEFT, "spawn.parked_left_curb_ahead", "left"),
    (
        "Pedestrian",
        "pedestrian",
        RelativePosition.AHEAD_SAME_LANE,
        "spawn.walker_in_lane_ahead",
        "centre",
    ),
]


@pytest.mark.slow
@pytest.mark.parametrize(("cls", "kind", "position", "spawn", "side"), STANDING_CASES)
def test_a_road_user_said_to_stand_still_stands_where_the_text_puts_it(
    kb: KnowledgeBase,
    maps: dict[str, frozenset[str]],
    validator_pool: WorkerPool,
    cls: str,
    kind: str,
    position: RelativePosition,
    spawn: str,
    side: str,
) -> None:
    """A car parked at the left kerb; a walker standing in the ego's lane ahead."""
    spec = ScenarioSpec(
        adversary_type=kind,
        adversary_class=cls,
        behavior="stays where it is",
        road_type="straight_road",
        ego_maneuver="go_straight",
        geometry="a two-way street",
        spawn_position=position,
        spawn="where it stands",
        adversary_stationary=True,
    )
    chosen, runs = simulated(spec, cls, kb, maps, validator_pool)
    assert spawn in chosen
    for seed, simulation in runs:
        _, adversary, relation = ego_and_adversary(simulation, chosen)
        where = (chosen, seed, relation.describe())
        assert relation.ahead > 0 and relation.side == side, where
        assert travel_heading(adversary) is None, where


@pytest.mark.slow
@pytest.mark.parametrize(
    "behavior", ["slows down in front of the ego and blocks it", "brakes hard"]
)
def test_a_lead_in_the_egos_lane_goes_straight_over_the_crossroads_with_the_ego(
    kb: KnowledgeBase,
    maps: dict[str, frozenset[str]],
    validator_pool: WorkerPool,
    behavior: str,
) -> None:
    """A truck ahead in the ego's lane as both go straight over a crossroads: inside the
    junction its lane follower restarts, and must keep the lane it was given, not one of
    the overlapping turning lanes there."""
    spec = ScenarioSpec(
        adversary_type="truck",
        adversary_class="Truck",
        behavior=behavior,
        road_type="intersection",
        ego_maneuver="go_straight",
        geometry="a crossroads with traffic lights",
        spawn_position=RelativePosition.AHEAD_SAME_LANE,
        spawn="ahead of the ego in its lane",
    )
    chosen, runs = simulated(spec, "Truck", kb, maps, validator_pool)
    for seed, simulation in runs:
        _, adversary, relation = ego_and_adversary(simulation, chosen)
        where = (chosen, seed, relation.describe())
        assert relation.ahead > 0 and relation.side == "centre", where
        assert adversary_turn(adversary) is AdversaryManeuver.STRAIGHT, where


@pytest.mark.slow
def test_a_fast_rider_that_rides_on_past_the_junction_stops_at_the_roads_end(
    kb: KnowledgeBase,
    maps: dict[str, frozenset[str]],
    validator_pool: WorkerPool,
) -> None:
    """A bicycle in the bike lane keeps going straight as the ego turns right: at 13-17 m/s
    it reaches the end of the map's road within the scene, where it must stop, not turn
    round into the other lane (which the trace reads as a turn)."""
    spec = ScenarioSpec(
        adversary_type="bicycle",
        adversary_class="Bicycle",
        behavior="comes up behind in the bike lane and keeps going straight past the ego",
        road_type="intersection",
        ego_maneuver="turn_right",
        geometry="a junction",
        spawn_position=RelativePosition.ADJACENT_LANE_RIGHT,
        spawn="behind the ego in the bike lane on its right",
        adversary_maneuver="straight",
        start_detail=StartDetail.FROM_BEHIND,
    )
    chosen, runs = simulated(spec, "Bicycle", kb, maps, validator_pool)
    for seed, simulation in runs:
        _, adversary, relation = ego_and_adversary(simulation, chosen)
        where = (chosen, seed, relation.describe())
        print(
            "DBG",
            where,
            [
                (p.step, round(p.x, 1), round(p.y, 1), round(p.heading, 2), round(p.speed, 1))
                for p in adversary.trajectory[::10]
            ],
        )
        assert adversary_turn(adversary) is AdversaryManeuver.STRAIGHT, where
