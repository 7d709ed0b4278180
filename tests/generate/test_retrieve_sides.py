"""Side-aware retrieval: the spec's side and the adversary's turn filter candidates.

Fast: the real knowledge base and BM25, no Scenic. The simulated proof that the chosen
entries really start the adversary on that side is in test_retrieve_sides_sim.py.
"""

from __future__ import annotations

from collections.abc import Mapping

import pytest

from arise.generate.retrieve import (
    STATIONARY_TAGS,
    Fit,
    approach_fit,
    maneuver_fit,
    pair_approach,
    pair_fit,
    pair_maneuver,
    retrieve,
    turn_agrees,
)
from arise.generate.spec import ScenarioSpec
from arise.kb.loader import KnowledgeBase, load_kb
from arise.kb.retrieval import BM25Retriever
from arise.kb.schema import Component, Entry
from arise.vocabulary import AdversaryManeuver, Approach, RelativePosition

MAPS: dict[str, frozenset[str]] = {
    "arise_straight": frozenset({"straight", "multilane", "sidewalk"}),
    "arise_intersection4": frozenset(
        {"straight", "multilane", "sidewalk", "intersection4", "signalized"}
    ),
    "arise_tjunction": frozenset({"straight", "sidewalk", "tjunction"}),
    "arise_highway": frozenset({"straight", "multilane", "highway", "curve"}),
}
SIDE_OF: dict[RelativePosition, set[Approach]] = {
    RelativePosition.CROSSING_FROM_LEFT: {Approach.LEFT},
    RelativePosition.CROSSING_FROM_RIGHT: {Approach.RIGHT},
    RelativePosition.ONCOMING: {Approach.OPPOSITE},
}
# (road, ego maneuver, where the adversary starts, which way it goes) at junctions.
JUNCTION_CASES = [
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
    ("t_junction", "turn_right", RelativePosition.CROSSING_FROM_LEFT, "straight"),
]


@pytest.fixture(scope="module")
def kb() -> KnowledgeBase:
    return load_kb(builtin=True)


@pytest.fixture(scope="module")
def bm25(kb: KnowledgeBase) -> BM25Retriever:
    return BM25Retriever(kb)


def make_spec(
    position: RelativePosition,
    turn: str = "unstated",
    road: str = "intersection",
    ego: str = "go_straight",
    adversary: str = "car",
) -> ScenarioSpec:
    return ScenarioSpec(
        adversary_type=adversary,
        behavior="drives on through the junction",
        road_type=road,
        ego_maneuver=ego,
        geometry="a junction",
        spawn_position=position,
        spawn="another road user approaches",
        adversary_maneuver=turn,
    )


def entry(entry_id: str, component: Component, **fields: object) -> Entry:
    return Entry.model_validate(
        {"id": entry_id, "component": component, "descriptions": ["x"], "snippet": "x", **fields}
    )


# -- grades --------------------------------------------------------------------------------


def test_a_spawn_on_the_conflict_route_takes_the_geometrys_side_and_turn(kb) -> None:
    geometry = kb.get("geometry.junction_straight_left_turner_from_right")
    on_route = kb.get("spawn.junction_conflict_route")
    own_side = kb.get("spawn.junction_lead_on_ego_route")
    assert pair_approach(geometry, on_route) is Approach.RIGHT
    assert pair_maneuver(geometry, on_route) is AdversaryManeuver.TURN_LEFT
    assert pair_approach(geometry, own_side) is Approach.AHEAD
    assert pair_maneuver(geometry, own_side) is None


def test_grades_order_exact_near_unspecific_contradicts() -> None:
    right = RelativePosition.CROSSING_FROM_RIGHT
    assert approach_fit(right, Approach.RIGHT) is Fit.EXACT
    assert approach_fit(right, Approach.ROADSIDE_RIGHT) is Fit.NEAR
    assert approach_fit(right, None) is Fit.UNSPECIFIC
    assert approach_fit(right, Approach.LEFT) is Fit.CONTRADICTS
    assert approach_fit(right, Approach.OPPOSITE) is Fit.CONTRADICTS
    # A turn the text does not mention is the next best: a road user goes straight unless
    # the text says it turns.
    assert maneuver_fit(AdversaryManeuver.UNSTATED, AdversaryManeuver.TURN_LEFT) is Fit.NEAR
    assert maneuver_fit(AdversaryManeuver.UNSTATED, AdversaryManeuver.STRAIGHT) is Fit.EXACT
    assert maneuver_fit(AdversaryManeuver.UNSTATED, None) is Fit.EXACT
    assert maneuver_fit(AdversaryManeuver.TURN_LEFT, None) is Fit.UNSPECIFIC
    assert maneuver_fit(AdversaryManeuver.TURN_LEFT, AdversaryManeuver.STRAIGHT) is Fit.CONTRADICTS


def test_the_pair_grade_is_the_worse_of_side_and_turn(kb) -> None:
    geometry = kb.get("geometry.junction_straight_cross_from_right")
    spawn = kb.get("spawn.junction_conflict_route")
    assert pair_fit(make_spec(RelativePosition.CROSSING_FROM_RIGHT), geometry, spawn) is Fit.EXACT
    spec = make_spec(RelativePosition.CROSSING_FROM_RIGHT, "turn_left")
    assert pair_fit(spec, geometry, spawn) is Fit.CONTRADICTS
    assert pair_fit(make_spec(RelativePosition.ONCOMING), geometry, spawn) is Fit.CONTRADICTS


def test_a_turning_behavior_needs_a_route_that_turns_its_way(kb) -> None:
    left = kb.get("behavior.turn_left_across_path")
    steady = kb.get("behavior.drive_route")
    spec = make_spec(RelativePosition.ONCOMING)
    assert turn_agrees(spec, left, AdversaryManeuver.TURN_LEFT)
    assert not turn_agrees(spec, left, AdversaryManeuver.STRAIGHT)
    assert not turn_agrees(spec, left, None)
    assert turn_agrees(spec, steady, None)
    assert not turn_agrees(
        make_spec(RelativePosition.ONCOMING, "turn_right"), left, AdversaryManeuver.TURN_LEFT
    )


# -- the knowledge base states sides -------------------------------------------------------


def test_every_specific_junction_geometry_states_side_and_turn(kb) -> None:
    unstated = {
        e.id
        for e in kb.of(Component.GEOMETRY)
        if "conflictManeuver" in e.defines and e.adversary_maneuver is None
    }
    assert unstated == {"geometry.junction_any_maneuver"}
    ambiguous = {
        e.id
        for e in kb.of(Component.GEOMETRY)
        if "conflictManeuver" in e.defines and e.approach is None
    }
    # Kept for descriptions that do not say the side; each has one-sided variants.
    assert ambiguous == {
        "geometry.junction_any_maneuver",
        "geometry.junction_straight_cross_traffic",
        "geometry.signalized_straight_on_green",
        "geometry.tjunction_main_straight_pullout",
        "geometry.junction_straight_exit_crossing",
        # A stopped ego is met from behind or by a turner; crossing traffic of either side
        # has no one-sided variant yet.
        "geometry.stopped_at_red_light",
    }


def test_every_spawn_says_its_side_or_takes_the_geometrys(kb) -> None:
    silent = {
        e.id
        for e in kb.of(Component.SPAWN)
        if e.approach is None and "conflictManeuver" not in e.needs
    }
    assert silent == set()
    # The kerbs and crossing of the exit road: left or right of the ego is the ego's turn.
    turn_side = {e.id for e in kb.of(Component.SPAWN) if e.approach is Approach.TURN_SIDE}
    assert turn_side == {"spawn.junction_exit_roadside", "spawn.junction_exit_far_corner"}


def test_side_fields_are_refused_where_they_mean_nothing() -> None:
    with pytest.raises(ValueError, match="cannot state approach"):
        entry("weather.sided", Component.WEATHER, approach="left")
    with pytest.raises(ValueError, match="conflictManeuver"):
        entry("geometry.sided", Component.GEOMETRY, approach="left", defines=["ego"])
    with pytest.raises(ValueError, match="leave adversary_maneuver out"):
        entry("behavior.unstated", Component.BEHAVIOR, adversary_maneuver="unstated")


# -- retrieval filters ---------------------------------------------------------------------


@pytest.mark.parametrize(("road", "ego", "position", "turn"), JUNCTION_CASES)
def test_junction_candidates_keep_only_the_stated_side_and_turn(
    kb, bm25, road: str, ego: str, position: RelativePosition, turn: str
) -> None:
    spec = make_spec(position, turn, road, ego)
    result = retrieve(spec, kb, bm25, MAPS)
    geometry = result.chosen[Component.GEOMETRY][0]
    spawn = result.chosen[Component.SPAWN][0]
    assert pair_approach(geometry, spawn) in SIDE_OF[position], (geometry.id, spawn.id)
    assert pair_maneuver(geometry, spawn) is AdversaryManeuver(turn), (geometry.id, spawn.id)
    assert result.notes == []
    # Whatever the repair loop swaps in keeps the side and the turn.
    for other in result.candidates[Component.GEOMETRY]:
        assert pair_fit(spec, other, spawn) is Fit.EXACT, other.id
    for other in result.candidates[Component.SPAWN]:
        assert pair_fit(spec, geometry, other) is Fit.EXACT, other.id
    for behavior in result.candidates[Component.BEHAVIOR]:
        assert turn_agrees(spec, behavior, pair_maneuver(geometry, spawn)), behavior.id


def test_from_the_right_never_offers_the_left_or_an_oncoming_turner(kb, bm25) -> None:
    spec = make_spec(RelativePosition.CROSSING_FROM_RIGHT)
    ids = retrieve(spec, kb, bm25, MAPS).ids()
    assert "geometry.junction_straight_cross_from_right" in ids["geometry"]
    for wrong in (
        "geometry.junction_straight_cross_from_left",
        "geometry.junction_straight_oncoming_left_turner",
        "geometry.junction_straight_cross_traffic",  # either side: not when one side fits
        "geometry.junction_any_maneuver",
    ):
        assert wrong not in ids["geometry"]


def test_a_turn_the_text_does_not_mention_is_not_taken(kb, bm25) -> None:
    """ "A truck from the right enters the junction against the light": it goes straight,
    and a route that turns is kept out while a straight one composes."""
    result = retrieve(make_spec(RelativePosition.CROSSING_FROM_RIGHT), kb, bm25, MAPS)
    spawn = result.chosen[Component.SPAWN][0]
    for geometry in result.candidates[Component.GEOMETRY]:
        assert pair_maneuver(geometry, spawn) in (None, AdversaryManeuver.STRAIGHT), geometry.id


def test_a_pedestrian_from_the_right_starts_on_the_right_kerb(kb, bm25) -> None:
    spec = make_spec(RelativePosition.CROSSING_FROM_RIGHT, adversary="pedestrian")
    result = retrieve(spec, kb, bm25, MAPS)
    for spawn in result.candidates[Component.SPAWN]:
        assert spawn.approach is Approach.RIGHT, spawn.id


def test_a_position_read_only_by_rank_before_is_now_a_filter(kb, bm25) -> None:
    spec = make_spec(RelativePosition.ADJACENT_LANE_LEFT, road="straight_road")
    result = retrieve(spec, kb, bm25, MAPS)
    assert result.chosen[Component.SPAWN][0].approach is Approach.ADJACENT_LEFT
    assert all(s.approach is Approach.ADJACENT_LEFT for s in result.candidates[Component.SPAWN])


def _tiny_kb(geometries: list[Entry]) -> KnowledgeBase:
    spawn = entry(
        "spawn.on_route",
        Component.SPAWN,
        needs=["conflictManeuver"],
        defines=["adversary", "advRoute"],
    )
    behavior = entry("behavior.go", Component.BEHAVIOR, needs=["advRoute"])
    return KnowledgeBase({e.id: e for e in [*geometries, spawn, behavior]})


def _junction(entry_id: str, **fields: object) -> Entry:
    return entry(
        entry_id,
        Component.GEOMETRY,
        defines=["ego", "conflictManeuver"],
        map_features=["intersection4"],
        tags=["straight"],
        **fields,
    )


def _only_map(entries: list[Entry], maps: Mapping[str, frozenset[str]]) -> str | None:
    return "arise_intersection4"


def test_an_unspecific_entry_is_used_only_when_no_specific_one_fits() -> None:
    left = _junction("geometry.from_left", approach="left", adversary_maneuver="straight")
    either = _junction("geometry.either_side", adversary_maneuver="straight")
    kb = _tiny_kb([either, left])
    bm25 = BM25Retriever(kb)

    from_left = retrieve(
        make_spec(RelativePosition.CROSSING_FROM_LEFT), kb, bm25, MAPS, "", _only_map
    )
    assert from_left.ids()["geometry"] == ["geometry.from_left"]
    assert from_left.notes == []

    from_right = retrieve(
        make_spec(RelativePosition.CROSSING_FROM_RIGHT), kb, bm25, MAPS, "", _only_map
    )
    assert from_right.ids()["geometry"] == ["geometry.either_side"]
    assert any(
        "not specific" in note or "no entry is specific" in note for note in from_right.notes
    )


def test_a_contradicting_entry_is_the_last_resort_and_says_so() -> None:
    kb = _tiny_kb([_junction("geometry.from_left", approach="left")])
    result = retrieve(
        make_spec(RelativePosition.CROSSING_FROM_RIGHT), kb, BM25Retriever(kb), MAPS, "", _only_map
    )
    assert result.ids()["geometry"] == ["geometry.from_left"]
    assert any("not honoured" in note for note in result.notes)


@pytest.mark.parametrize("road", ["straight_road", "intersection"])
def test_an_adversary_the_text_says_is_stalled_gets_a_behavior_that_stays_put(
    kb: KnowledgeBase, bm25: BM25Retriever, road: str
) -> None:
    spec = make_spec(RelativePosition.AHEAD_SAME_LANE, road=road).model_copy(
        update={"adversary_stationary": True, "behavior": "drives on and accelerates"}
    )
    result = retrieve(spec, kb, bm25, MAPS)
    [behavior] = result.chosen[Component.BEHAVIOR]
    assert set(behavior.tags) & STATIONARY_TAGS, behavior.id


@pytest.mark.parametrize(
    ("road", "position", "turn", "geometry_id"),
    [
        (
            "intersection",
            RelativePosition.BEHIND_SAME_LANE,
            "unstated",
            "geometry.stopped_at_red_light",
        ),
        (
            "intersection",
            RelativePosition.ONCOMING,
            "turn_left",
            "geometry.stopped_at_red_light_oncoming_left_turner",
        ),
        (
            "straight_road",
            RelativePosition.BEHIND_SAME_LANE,
            "unstated",
            "geometry.stopped_in_traffic",
        ),
    ],
)
def test_a_stopped_ego_gets_a_geometry_that_holds_it_still(
    kb, bm25, road: str, position: RelativePosition, turn: str, geometry_id: str
) -> None:
    spec = make_spec(position, turn, road).model_copy(update={"ego_stopped": True})
    result = retrieve(spec, kb, bm25, MAPS)
    assert result.chosen[Component.GEOMETRY][0].id == geometry_id
    for other in result.candidates[Component.GEOMETRY]:
        assert "ego_stopped" in other.tags, other.id


@pytest.mark.parametrize("road", ["intersection", "straight_road", "t_junction", "highway"])
def test_a_moving_ego_never_gets_a_stopped_geometry(kb, bm25, road: str) -> None:
    for position in (RelativePosition.BEHIND_SAME_LANE, RelativePosition.ONCOMING):
        result = retrieve(make_spec(position, road=road), kb, bm25, MAPS)
        for other in result.candidates[Component.GEOMETRY]:
            assert "ego_stopped" not in other.tags, other.id


@pytest.mark.parametrize("road", ["straight_road", "highway"])
@pytest.mark.parametrize("side", ["left", "right", None])
def test_an_ego_lane_change_gets_a_geometry_where_the_ego_changes_lanes(
    kb, bm25, road: str, side: str | None
) -> None:
    spec = make_spec(RelativePosition.AHEAD_SAME_LANE, road=road, ego="change_lane")
    spec = spec.model_copy(update={"ego_lane_side": side})
    result = retrieve(spec, kb, bm25, MAPS)
    for geometry in result.candidates[Component.GEOMETRY]:
        assert "ego_lane_change" in geometry.tags, geometry.id
        if side is not None:
            assert f"ego_changes_{side}" in geometry.tags, geometry.id
    straight = retrieve(make_spec(RelativePosition.AHEAD_SAME_LANE, road=road), kb, bm25, MAPS)
    for geometry in straight.candidates[Component.GEOMETRY]:
        assert "ego_lane_change" not in geometry.tags, geometry.id


def test_a_stopped_ego_on_a_road_no_stopped_geometry_has_keeps_the_road_and_drives(
    kb, bm25
) -> None:
    from arise.generate.pipeline import _holdable

    spec = make_spec(RelativePosition.CROSSING_FROM_RIGHT, road="t_junction")
    spec = spec.model_copy(update={"ego_stopped": True})
    result = retrieve(spec, kb, bm25, MAPS)
    assert "tjunction" in result.chosen[Component.GEOMETRY][0].map_features
    assert "no geometry entry keeps the ego stopped on t_junction; it drives" in result.notes
    assert _holdable(spec, result).ego_stopped is False  # the gate does not chase it
    at_lights = ScenarioSpec.model_validate(spec.model_dump() | {"road_type": "intersection"})
    held = retrieve(at_lights, kb, bm25, MAPS)
    assert _holdable(spec, held).ego_stopped is True


def test_a_spawn_on_the_exit_street_takes_the_side_the_ego_turns_to(kb) -> None:
    spawn = kb.get("spawn.junction_exit_far_corner")
    right = kb.get("geometry.junction_right_turn_exit_crossing")
    left = kb.get("geometry.junction_left_turn_oncoming")
    straight = kb.get("geometry.junction_straight_cross_traffic")
    assert pair_approach(right, spawn) is Approach.ROADSIDE_RIGHT
    assert pair_approach(left, spawn) is Approach.ROADSIDE_LEFT
    assert pair_approach(straight, spawn) is None


def test_an_ego_said_to_go_straight_gets_no_geometry_of_any_route(kb, bm25) -> None:
    """ "the ego, going straight, reaches the crossroads": a geometry whose ego may take any
    route is kept out; with the maneuver left unsaid it may still be one."""
    from arise.language.facts import FactSource, GroundedFact

    stated = make_spec(RelativePosition.CROSSING_FROM_LEFT, turn="turn_right").model_copy(
        update={
            "grounding": [
                GroundedFact(
                    name="ego_maneuver",
                    value="go_straight",
                    source=FactSource.TEXT,
                    quote="going straight",
                )
            ]
        }
    )
    result = retrieve(stated, kb, bm25, MAPS)
    assert all("any_route" not in g.tags for g in result.candidates[Component.GEOMETRY])
    assert any(
        "any_route" in e.tags for e in kb.entries.values() if e.component is Component.GEOMETRY
    )


@pytest.mark.parametrize("back", [False, True])
def test_a_walker_goes_back_the_way_it_came_only_where_the_text_says_so(
    kb, bm25, back: bool
) -> None:
    """ "A pedestrian steps out in front of the ego" carries on across; only a walker read
    as stepping back gets a behavior that returns to the kerb (in the trace, one that
    returns looks like one that turned round)."""
    spec = ScenarioSpec(
        adversary_type="pedestrian",
        adversary_class="Pedestrian",
        behavior="steps out into the road in front of the ego",
        road_type="straight_road",
        ego_maneuver="go_straight",
        geometry="a two-way street",
        spawn_position=RelativePosition.CROSSING_FROM_RIGHT,
        spawn="from the right-hand pavement",
        adversary_turns_back=back,
    )
    result = retrieve(spec, kb, bm25, MAPS)
    chosen = result.chosen[Component.BEHAVIOR][0]
    assert ("turns_back" in chosen.tags) is back, chosen.id
