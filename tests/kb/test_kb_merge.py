"""On-ramp merge scenes, proven on the real compiler and simulator, read from the trace.

The trace's positions are looked up in the road network of the map that ran, so "started
on the ramp" and "ended in the ego's lane" are the network's lanes, not our intentions.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from scenic.core.vectors import Vector
from scenic.domains.driving.roads import Lane, Maneuver, Network

from arise.generate.assemble import assemble
from arise.generate.conformity import check_conformity, find_adversary
from arise.generate.retrieve import retrieve
from arise.generate.spec import ExtractionAnswer, ScenarioSpec
from arise.kb.compose import compose, pick_map
from arise.kb.loader import KnowledgeBase, load_kb
from arise.kb.retrieval import BM25Retriever
from arise.language.readers import read_description
from arise.maps.features import on_ramp_merges
from arise.maps.registry import MapRegistry
from arise.validate import CheckOptions, CheckResult, WorkerPool, check_text
from arise.validate.types import AgentTrace
from arise.vocabulary import RelativePosition, RoadType

#: Long enough to merge, short enough that no one reaches the end of arise_merge's road.
STEPS = 150
SEEDS = (1, 2)
MERGE_ENTRIES = {
    "geometry.highway_merge_through_lane",
    "geometry.highway_ego_merges_from_ramp",
    "spawn.on_ramp_beside_right",
    "spawn.on_ramp_behind_right",
    "spawn.merge_target_lane_beside_left",
    "behavior.merge_from_ramp",
    "behavior.merge_from_ramp_and_brake",
    "behavior.close_gap_on_merging_ego",
}


@pytest.fixture(scope="module")
def kb() -> KnowledgeBase:
    return load_kb(builtin=True)


@pytest.fixture(scope="module")
def maps() -> dict[str, frozenset[str]]:
    return {name: entry.features for name, entry in MapRegistry().entries.items()}


@pytest.fixture(scope="module")
def merge_pool() -> Iterator[WorkerPool]:
    with WorkerPool(size=1) as pool:
        yield pool


def _network(result: CheckResult) -> Network:
    assert result.map is not None
    # The worker cached the parsed map next to its copy: reading it back is fast.
    return Network.fromFile(result.map.path, useCache=True, writeCache=False)


def _lanes(network: Network, trace: AgentTrace) -> list[Lane | None]:
    return [network.laneAt(Vector(p.x, p.y)) for p in trace.trajectory]


def _merges(network: Network) -> list[tuple[Maneuver, Maneuver]]:
    return [pair for zone in network.intersections for pair in on_ramp_merges(zone)]


def _check(script: str, pool: WorkerPool, seed: int, **options: object) -> CheckResult:
    result = check_text(
        script, CheckOptions(seed=seed, steps=STEPS, timeout=180, **options), pool=pool
    )
    assert result.ok and result.simulation is not None, result.diagnostic
    return result


def _assert_merges_into_ego_lane(result: CheckResult) -> None:
    """The adversary starts on an on-ramp and drives into the lane the ego drives in."""
    assert result.simulation is not None
    network = _network(result)
    agents = result.simulation.agents
    ego = next(a for a in agents if a.is_ego)
    adversary = find_adversary(agents)
    assert adversary is not None
    merges = _merges(network)
    ego_lanes, adversary_lanes = _lanes(network, ego), _lanes(network, adversary)
    (ramp, through) = next(pair for pair in merges if pair[0].startLane is adversary_lanes[0])
    assert ego_lanes[0] is through.startLane, "the ego starts in the lane the ramp joins"
    # At some moment both are in the lane after the merge zone. (Not "stays there": Town04's
    # highway crosses over other roads, and laneAt, in 2D, sees those for a few steps.)
    together = [
        step
        for step, (mine, theirs) in enumerate(zip(ego_lanes, adversary_lanes, strict=False))
        if mine is theirs is ramp.endLane
    ]
    assert together, "the adversary never drives in the ego's lane"
    pair = next(p for p in result.simulation.ego_pairs if p.other == adversary.name)
    assert pair.min_distance < 15, "the merge happens next to the ego"


@pytest.mark.slow
@pytest.mark.parametrize("cls", ["Car", "Motorcycle"])
def test_a_vehicle_from_the_on_ramp_merges_into_the_ego_lane(
    kb: KnowledgeBase, merge_pool: WorkerPool, cls: str
) -> None:
    script = compose(
        [
            kb.get("geometry.highway_merge_through_lane"),
            kb.get("spawn.on_ramp_beside_right"),
            kb.get("behavior.merge_from_ramp"),
        ],
        cls,
        "arise_merge",
    )
    for seed in SEEDS:
        _assert_merges_into_ego_lane(_check(script, merge_pool, seed))


@pytest.mark.slow
def test_the_ego_merges_from_the_on_ramp_onto_the_highway(
    kb: KnowledgeBase, merge_pool: WorkerPool
) -> None:
    script = compose(
        [
            kb.get("geometry.highway_ego_merges_from_ramp"),
            kb.get("spawn.merge_target_lane_beside_left"),
            kb.get("behavior.close_gap_on_merging_ego"),
        ],
        "Car",
        "arise_merge",
    )
    for seed in SEEDS:
        result = _check(script, merge_pool, seed)
        assert result.simulation is not None
        network = _network(result)
        ego = next(a for a in result.simulation.agents if a.is_ego)
        adversary = find_adversary(result.simulation.agents)
        assert adversary is not None
        ego_lanes, adversary_lanes = _lanes(network, ego), _lanes(network, adversary)
        ((ramp, through),) = _merges(network)
        assert ego_lanes[0] is ramp.startLane
        assert adversary_lanes[0] is through.startLane
        # The ego ends on the highway, in its rightmost lane, and stays there.
        assert ego_lanes[-1] is through.endLane
        assert len(through.endLane.group.lanes) > 1


@pytest.mark.slow
@pytest.mark.carla_towns
def test_the_merge_entries_run_on_town04(
    kb: KnowledgeBase, merge_pool: WorkerPool, carla_maps: Path
) -> None:
    """The same scene on CARLA's Town04, whose on-ramps are built like ours."""
    towns = {name: e.features for name, e in MapRegistry(carla_maps).entries.items()}
    assert "merge" in towns["Town04"] and "merge" in towns["Town06"]
    geometry = kb.get("geometry.highway_merge_through_lane")
    assert pick_map([geometry], {"Town04": towns["Town04"]}) == "Town04"
    script = compose(
        [
            kb.get("geometry.highway_merge_through_lane"),
            kb.get("spawn.on_ramp_behind_right"),
            kb.get("behavior.merge_from_ramp"),
        ],
        "Car",
        "Town04",
    )
    result = _check(script, merge_pool, 1, map_dir=str(carla_maps))
    assert result.map is not None and result.map.name == "Town04"
    _assert_merges_into_ego_lane(result)
    ego_merging = compose(
        [
            kb.get("geometry.highway_ego_merges_from_ramp"),
            kb.get("spawn.merge_target_lane_beside_left"),
            kb.get("behavior.close_gap_on_merging_ego"),
        ],
        "Car",
        "Town04",
    )
    _check(ego_merging, merge_pool, 1, map_dir=str(carla_maps))


def _spec(
    road: RoadType, maneuver: str, position: RelativePosition, words: str, adversary: str = "car"
) -> ScenarioSpec:
    return ScenarioSpec(
        adversary_type=adversary,
        behavior=words,
        road_type=road,
        ego_maneuver=maneuver,
        geometry=words,
        spawn_position=position,
        spawn=words,
    )


def test_a_merge_spec_retrieves_the_merge_entries(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    words = "a car merging from the on-ramp changed into the AV's lane from the acceleration lane"
    spec = _spec(RoadType.MERGE, "go_straight", RelativePosition.ADJACENT_LANE_RIGHT, words)
    chosen = {e.id for e in retrieve(spec, kb, BM25Retriever(kb), maps, words).chosen_entries()}
    assert "geometry.highway_merge_through_lane" in chosen
    assert chosen & {
        "spawn.on_ramp_beside_right",
        "spawn.on_ramp_ahead_right",
        "spawn.on_ramp_behind_right",
    }
    assert chosen & {"behavior.merge_from_ramp", "behavior.merge_from_ramp_and_brake"}

    words = "the AV entered the freeway from the ramp; a car in the right lane did not let it in"
    for maneuver in ("go_straight", "change_lane"):
        spec = _spec(RoadType.MERGE, maneuver, RelativePosition.ADJACENT_LANE_LEFT, words)
        # The reader puts the ego on the ramp ("the AV entered the freeway from the ramp").
        assert (
            read_description(words).facts["ego_on_ramp"].quote
            == "entered the freeway from the ramp"
        )
        spec = spec.model_copy(update={"ego_on_ramp": True})
        retrieval = retrieve(spec, kb, BM25Retriever(kb), maps, words)
        chosen = {e.id for e in retrieval.chosen_entries()}
        assert "geometry.highway_ego_merges_from_ramp" in chosen, maneuver
        assert "spawn.merge_target_lane_beside_left" in chosen, maneuver


@pytest.mark.slow
def test_a_merge_spec_runs_end_to_end_and_conforms(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], merge_pool: WorkerPool
) -> None:
    """Retrieved, assembled and run: the trace shows the merge, and the semantic gate's
    road check accepts it on arise_merge (not on a map without an on-ramp)."""
    words = "a motorcycle merging from the on-ramp cut into the AV's lane"
    spec = _spec(
        RoadType.MERGE, "go_straight", RelativePosition.ADJACENT_LANE_RIGHT, words, "motorcycle"
    )
    retrieval = retrieve(spec, kb, BM25Retriever(kb), maps, words)
    draft = assemble(retrieval, "Motorcycle", spec.behavior, params={})
    result = _check(draft.script, merge_pool, 3)
    assert result.map is not None and result.map.name == "arise_merge"
    _assert_merges_into_ego_lane(result)
    road = {
        c.name: c for c in check_conformity(spec, result.simulation, maps["arise_merge"]).checks
    }
    assert road["road_type"].ok, road["road_type"]
    highway = check_conformity(spec, result.simulation, maps["arise_highway"]).checks
    assert not next(c for c in highway if c.name == "road_type").ok


def test_a_plain_highway_spec_never_gets_a_merge_entry(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    words = "a car in the right lane of the freeway merges into the ego's lane"
    spec = _spec(RoadType.HIGHWAY, "go_straight", RelativePosition.ADJACENT_LANE_RIGHT, words)
    retrieval = retrieve(spec, kb, BM25Retriever(kb), maps, words)
    assert not {e.id for e in retrieval.chosen_entries()} & MERGE_ENTRIES


def test_the_model_is_not_offered_the_merge_road_type() -> None:
    """`merge` is read from words; the extraction schema (and its cassettes) stay as before."""
    roads = ExtractionAnswer.model_json_schema()["$defs"]["RoadType"]["enum"]
    assert roads == ["straight_road", "intersection", "t_junction", "highway"]
    assert RoadType("merge") is RoadType.MERGE
