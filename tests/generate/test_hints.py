"""Plain words in a description overrule the small model's enums and requirements."""

from __future__ import annotations

from arise.generate.hints import apply_hints, keep_stated_requirements
from arise.generate.retrieve import retrieve
from arise.generate.spec import (
    EgoManeuver,
    RelativePosition,
    Requirement,
    RequirementKind,
    RoadType,
    ScenarioSpec,
)
from arise.kb.loader import load_kb
from arise.kb.retrieval import make_retriever
from arise.kb.schema import Component
from arise.maps.registry import MapRegistry


def _spec(**fields: object) -> ScenarioSpec:
    values: dict[str, object] = dict(
        adversary_type="car",
        behavior="goes straight",
        road_type="intersection",
        ego_maneuver="turn_right",
        geometry="four-way junction",
        spawn_position="crossing_road_from_left",
        spawn="on the road from the left",
        participants=[],
        weather="ClearNoon",
        requirements=[],
    )
    values.update(fields)
    return ScenarioSpec.model_validate(values)


def test_requirements_the_description_never_states_are_dropped() -> None:
    copied = [
        Requirement(kind=RequirementKind.NOT_VISIBLE_AT_START, text="hidden by a bus"),
        Requirement(kind=RequirementKind.OPPOSITE_DIRECTION, text="the other way"),
    ]
    spec, notes = keep_stated_requirements(
        "The ego turns right while a car from the left goes straight.", _spec(requirements=copied)
    )
    assert spec.requirements == []
    assert len(notes) == 2 and "not stated" in notes[0]


def test_stated_requirements_stay_unless_the_spawn_rules_them_out() -> None:
    hidden = Requirement(kind=RequirementKind.NOT_VISIBLE_AT_START, text="behind a van")
    spec, notes = keep_stated_requirements(
        "A child runs out from behind a parked van on the right.",
        _spec(spawn_position="roadside_right", requirements=[hidden]),
    )
    assert spec.requirements == [hidden] and notes == []
    opposite = Requirement(kind=RequirementKind.OPPOSITE_DIRECTION, text="oncoming")
    spec, notes = keep_stated_requirements(
        "A car from the left crosses while oncoming traffic waits.", _spec(requirements=[opposite])
    )
    assert spec.requirements == [] and "contradicts" in notes[0]


def test_stated_enums_win_over_the_model() -> None:
    spec, notes = apply_hints(
        "The ego turns right while a truck from the left crosses.",
        _spec(
            adversary_type="car",
            ego_maneuver="turn_left",
            road_type="straight_road",
            spawn_position="oncoming",
        ),
    )
    assert spec.adversary_type.value == "truck"
    assert spec.ego_maneuver is EgoManeuver.TURN_RIGHT
    assert spec.road_type is RoadType.INTERSECTION
    assert spec.spawn_position is RelativePosition.CROSSING_FROM_LEFT
    assert len(notes) == 4


def test_a_turning_behavior_only_comes_with_a_geometry_that_gives_it_the_turn() -> None:
    kb = load_kb([])
    registry = MapRegistry(None)
    maps = {name: entry.features for name, entry in registry.entries.items()}
    spec = _spec(behavior="turns left across the ego's path and goes straight")
    result = retrieve(
        spec,
        kb,
        make_retriever(kb, "bm25"),
        maps,
        "The ego turns right; a car from the left turns left across its path.",
    )
    geometry = result.chosen[Component.GEOMETRY][0]
    assert geometry.id == "geometry.junction_right_turn_cross_from_left"
    behaviors = result.candidates[Component.BEHAVIOR]
    assert behaviors and all("turning_across" not in entry.tags for entry in behaviors)
