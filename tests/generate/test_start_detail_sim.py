"""Finer starts the text gives, proven on the real Scenic compiler and simulator: the far
corner of the street a turning ego enters, a cyclist coming up from behind on the right,
and a box lying in the lane a turning ego enters (no adversary at all).

Each spec goes through retrieval and assembly unchanged; the trace says where the actor
started, read as the fidelity score reads it.
"""

from __future__ import annotations

import math

import pytest

from arise.evaluate.fidelity import Start, placement, start_matches
from arise.generate.conformity import find_adversary
from arise.generate.spec import Actor, ScenarioSpec
from arise.kb.loader import KnowledgeBase, load_kb
from arise.language.readers import read_description
from arise.maps.registry import MapRegistry
from arise.validate import WorkerPool
from arise.vocabulary import ActorRole, RelativePosition, StartDetail
from tests.generate.test_retrieve_sides_sim import simulated


@pytest.fixture(scope="module")
def kb() -> KnowledgeBase:
    return load_kb(builtin=True)


@pytest.fixture(scope="module")
def maps() -> dict[str, frozenset[str]]:
    return {name: entry.features for name, entry in MapRegistry().entries.items()}


@pytest.mark.parametrize(
    ("text", "detail", "position"),
    [
        (
            "Turning right at a four-way junction, the ego finds a pedestrian crossing the "
            "side street from the far corner.",
            StartDetail.EXIT_FAR_CORNER,
            RelativePosition.ROADSIDE_RIGHT,
        ),
        (
            "The ego turns left and hits a pedestrian walking in the crosswalk of the street "
            "it enters.",
            StartDetail.EXIT_CROSSING,
            RelativePosition.ROADSIDE_LEFT,
        ),
        (
            "The AV was turning right from Vireo Avenue onto Marrow Lane when a pedestrian "
            "stepped into the crosswalk on Marrow Lane.",
            StartDetail.EXIT_CROSSING,
            RelativePosition.ROADSIDE_RIGHT,
        ),
        (
            "The AV turned right. A cyclist approaching from behind on the AV's right hit "
            "its rear quarter panel.",
            StartDetail.FROM_BEHIND,
            RelativePosition.ADJACENT_LANE_RIGHT,
        ),
        (
            "A fast car comes from behind in the left lane and passes the ego.",
            StartDetail.FROM_BEHIND,
            RelativePosition.ADJACENT_LANE_LEFT,
        ),
        (
            "On the freeway, a motorcycle entering from the on-ramp to its right merged into "
            "the AV's lane ahead of it.",
            StartDetail.AHEAD,
            RelativePosition.ADJACENT_LANE_RIGHT,
        ),
    ],
)
def test_the_reader_gives_the_start_detail_and_its_side(
    text: str, detail: StartDetail, position: RelativePosition
) -> None:
    facts = read_description(text).facts
    assert facts["start_detail"].value == detail.value
    assert facts["spawn_position"].value == position.value


@pytest.mark.parametrize(
    "text",
    [
        "A child runs out from behind a parked van on the right.",
        "Turning left at a T-junction, the ego meets a cyclist riding toward the junction on "
        "the road the ego turns into.",
        "The ego goes straight; a pedestrian crosses from the far side of the road.",
    ],
)
def test_no_start_detail_where_the_text_gives_none(text: str) -> None:
    assert "start_detail" not in read_description(text).facts


@pytest.mark.slow
@pytest.mark.parametrize("turn", ["turn_right", "turn_left"])
def test_a_walker_from_the_far_corner_crosses_the_street_the_ego_enters(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], validator_pool: WorkerPool, turn: str
) -> None:
    right = turn == "turn_right"
    spec = ScenarioSpec(
        adversary_type="pedestrian",
        behavior="crosses the side street",
        road_type="intersection",
        ego_maneuver=turn,
        geometry="a four-way junction",
        spawn_position=(
            RelativePosition.ROADSIDE_RIGHT if right else RelativePosition.ROADSIDE_LEFT
        ),
        start_detail=StartDetail.EXIT_FAR_CORNER,
        spawn="from the far corner",
    )
    chosen, runs = simulated(spec, "Pedestrian", kb, maps, validator_pool)
    assert "spawn.junction_exit_far_corner" in chosen
    for seed, simulation in runs:
        ego = next(a for a in simulation.agents if a.is_ego)
        adversary = find_adversary(simulation.agents)
        assert adversary is not None
        where = placement(ego, adversary)
        assert where is not None, chosen
        wanted = Start.RIGHT_FRONT if right else Start.LEFT_FRONT
        assert start_matches(wanted, where), (chosen, seed, where)
        # It walks back across the street, toward the ego's side of the junction.
        origin, first, last = ego.trajectory[0], adversary.trajectory[0], adversary.trajectory[-1]
        along = math.cos(origin.heading + math.pi / 2), math.sin(origin.heading + math.pi / 2)
        walked = (last.x - first.x) * along[0] + (last.y - first.y) * along[1]
        assert walked < -2, (chosen, seed, where, walked)


@pytest.mark.slow
def test_a_cyclist_from_behind_on_the_right_starts_behind(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], validator_pool: WorkerPool
) -> None:
    spec = ScenarioSpec(
        adversary_type="bicycle",
        behavior="goes straight through the intersection",
        road_type="intersection",
        ego_maneuver="turn_right",
        geometry="a right turn",
        spawn_position=RelativePosition.ADJACENT_LANE_RIGHT,
        start_detail=StartDetail.FROM_BEHIND,
        spawn="approaching from behind on the AV's right",
    )
    chosen, runs = simulated(spec, "Bicycle", kb, maps, validator_pool)
    for seed, simulation in runs:
        ego = next(a for a in simulation.agents if a.is_ego)
        adversary = find_adversary(simulation.agents)
        assert adversary is not None
        where = placement(ego, adversary)
        assert where is not None and start_matches(Start.RIGHT_REAR, where), (chosen, seed, where)


@pytest.mark.slow
def test_a_box_in_the_lane_a_turning_ego_enters_is_placed_there(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], validator_pool: WorkerPool
) -> None:
    spec = ScenarioSpec(
        adversary_type="pedestrian",
        behavior="",
        road_type="intersection",
        ego_maneuver="turn_left",
        geometry="turns left at a junction",
        spawn_position=RelativePosition.AHEAD_SAME_LANE,
        spawn="",
        no_adversary=True,
        participants=["a box lies in the lane it is turning into"],
        actors=[Actor(role=ActorRole.OBSTACLE, scenic_class="Box", stationary=True, quote="a box")],
    )
    chosen, runs = simulated(spec, None, kb, maps, validator_pool)
    assert "misc.box_in_exit_lane" in chosen
    for seed, simulation in runs:
        ego = next(a for a in simulation.agents if a.is_ego)
        box = next((a for a in simulation.agents if a.kind == "Box"), None)
        assert box is not None, (chosen, seed)
        where = placement(ego, box)
        assert where is not None and start_matches(Start.LEFT_FRONT, where), (chosen, seed, where)
