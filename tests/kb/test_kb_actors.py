"""Copies of the adversary's spawn and behavior entries for the other actors of a scene."""

from __future__ import annotations

import pytest

from arise.kb.actors import actor_name, actor_param, for_actor, spawn_span
from arise.kb.compose import (
    actor_at_line,
    compose,
    composition_problems,
    entry_at_line,
    mark_at_line,
)
from arise.kb.loader import KnowledgeBase, load_kb
from arise.kb.schema import Entry


@pytest.fixture(scope="module")
def kb() -> KnowledgeBase:
    return load_kb()


def core(kb: KnowledgeBase) -> list[Entry]:
    return [
        kb.get("geometry.straight_road"),
        kb.get("spawn.behind_same_lane"),
        kb.get("behavior.tailgate"),
    ]


def trucks_ahead(kb: KnowledgeBase, count: int = 2) -> list[Entry]:
    spawn, behavior = kb.get("spawn.lead_same_lane"), kb.get("behavior.slow_to_block")
    entries = []
    for copy in range(count):
        name = f"actor{copy + 2}"
        entries += [
            for_actor(spawn, name, "Truck", copy=copy, spacing=22),
            for_actor(behavior, name, "Truck"),
        ]
    return entries


def test_names_of_the_adversary_become_the_actors() -> None:
    assert actor_name("adversary", "actor2") == "actor2"
    assert actor_name("advStart", "actor2") == "actor2Start"
    assert actor_name("advParkedLane", "actor3") == "actor3ParkedLane"
    assert actor_name("AdversaryBehavior", "actor2") == "Actor2Behavior"
    assert actor_name("Steer", "actor2") == "Actor2Steer"
    assert actor_name("advance", "actor2") == "Actor2advance"  # not an adv<Name> anchor
    assert actor_param("OPT_SPAWN_GAP", "actor2") == "OPT_ACTOR2_SPAWN_GAP"


def test_a_spawn_copy_places_the_actor_under_its_own_names(kb: KnowledgeBase) -> None:
    copy = for_actor(kb.get("spawn.lead_same_lane"), "actor2", "Bus")
    assert copy.id == "spawn.lead_same_lane" and copy.actor == "actor2"
    assert copy.label == "spawn.lead_same_lane as actor2"
    assert copy.defines == ["actor2Start", "actor2Lane", "actor2"]
    assert copy.needs == ["egoStart", "egoLane"]  # the scene's names stay
    assert copy.params == ["OPT_ACTOR2_SPAWN_GAP"]
    assert copy.placeholders == []
    assert "actor2 = new Bus at actor2Start, with behavior Actor2Behavior()" in copy.snippet
    assert "following roadDirection from egoStart" in copy.snippet
    for old in ("adversary", "advStart", "advLane", "OPT_SPAWN_GAP", "{{"):
        assert old not in copy.snippet.replace("OPT_ACTOR2_SPAWN_GAP", "")


def test_a_behavior_copy_renames_its_helpers_and_what_it_reads(kb: KnowledgeBase) -> None:
    copy = for_actor(kb.get("behavior.pull_out_from_curb"), "actor3", "Car")
    assert copy.defines == ["Actor3Steer", "Actor3Behavior"]
    assert copy.needs == ["actor3ParkedLane"]
    assert "behavior Actor3Steer(amount, throttle):" in copy.snippet
    assert "do Actor3Steer(-0.35, 0.5)" in copy.snippet
    assert "laneToFollow=actor3ParkedLane" in copy.snippet
    assert "globalParameters.OPT_ACTOR3_ADV_TRIGGER" in copy.snippet
    assert "distance from self to ego" in copy.snippet


def test_further_copies_stand_further_out(kb: KnowledgeBase) -> None:
    spawn = kb.get("spawn.roadside_right_near")  # AHEAD 14-22, OFFSET 1-2
    assert spawn_span(spawn) == 8
    second = for_actor(spawn, "actor3", "Pedestrian", copy=1, spacing=12)
    assert "param OPT_ACTOR3_SPAWN_AHEAD = Range(26, 34)" in second.snippet
    assert "param OPT_ACTOR3_SPAWN_OFFSET = Range(1.0, 2.0)" in second.snippet
    first = for_actor(spawn, "actor2", "Pedestrian", copy=0, spacing=12)
    assert "param OPT_ACTOR2_SPAWN_AHEAD = Range(14, 22)" in first.snippet


def test_only_spawns_and_behaviors_are_copied(kb: KnowledgeBase) -> None:
    with pytest.raises(ValueError, match="only spawn and behavior"):
        for_actor(kb.get("geometry.straight_road"), "actor2", "Car")
    with pytest.raises(ValueError, match="not an actor name"):
        for_actor(kb.get("spawn.lead_same_lane"), "adversary", "Car")


def test_several_actors_compose_and_each_mark_names_its_actor(kb: KnowledgeBase) -> None:
    entries = core(kb) + trucks_ahead(kb)
    assert composition_problems(entries, "Car") == []
    script = compose(entries, "Car", "arise_straight")
    lines = script.splitlines()
    assert "# kb: spawn.lead_same_lane as actor3" in lines
    line = next(n for n, text in enumerate(lines, 1) if text.startswith("actor3 = new Truck"))
    assert mark_at_line(script, line) == ("spawn.lead_same_lane", "actor3")
    assert entry_at_line(script, line) == "spawn.lead_same_lane"
    assert actor_at_line(script, line) == "actor3"
    adversary = next(n for n, text in enumerate(lines, 1) if text.startswith("adversary = "))
    assert actor_at_line(script, adversary) is None
    assert entry_at_line(script, adversary) == "spawn.behind_same_lane"
    assert "param OPT_ACTOR3_SPAWN_GAP = Range(37, 47)" in lines


def test_the_adversarys_spawn_may_also_place_an_actor(kb: KnowledgeBase) -> None:
    entries = [
        kb.get("geometry.straight_road"),
        kb.get("spawn.lead_same_lane"),
        kb.get("behavior.sudden_brake"),
        *trucks_ahead(kb, 1),
    ]
    assert composition_problems(entries, "Car") == []


def test_an_actor_needs_one_spawn_and_one_behavior_for_its_class(kb: KnowledgeBase) -> None:
    spawn, behavior = trucks_ahead(kb, 1)
    assert "actor2: needs one behavior entry, has none" in composition_problems(
        [*core(kb), spawn], "Car"
    )
    walker = for_actor(kb.get("spawn.roadside_right_near"), "actor2", "Truck")
    problems = composition_problems([*core(kb), walker, behavior], "Car")
    assert "spawn.roadside_right_near as actor2: written for Pedestrian, Bicycle, not Truck" in (
        problems
    )
    twice = composition_problems([*core(kb), spawn, spawn, behavior], "Car")
    assert "spawn.lead_same_lane as actor2: chosen twice" in twice
    # A van and a bus fit where a car and a truck do, as for the adversary.
    bus = [
        for_actor(kb.get("spawn.lead_same_lane"), "actor2", "Bus"),
        for_actor(kb.get("behavior.slow_to_block"), "actor2", "Bus"),
    ]
    assert composition_problems([*core(kb), *bus], "Car") == []


def test_a_fixed_distance_is_shifted_too(kb: KnowledgeBase) -> None:
    spawn = kb.get("spawn.lead_same_lane")
    fixed = spawn.model_copy(update={"snippet": spawn.snippet.replace("Range(15, 25)", "20")})
    assert spawn_span(fixed) == 0
    copy = for_actor(fixed, "actor3", "Car", copy=2, spacing=9)
    assert "param OPT_ACTOR3_SPAWN_GAP = 38" in copy.snippet
