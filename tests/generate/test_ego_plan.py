"""What the ego does besides driving its route: read from words whose subject is the ego,
and retrieval gives a geometry that acts it out only then (fast: no simulator)."""

from __future__ import annotations

import pytest

from arise.generate.retrieve import PLAN_TAGS, retrieve
from arise.generate.spec import ScenarioSpec
from arise.kb.loader import KnowledgeBase, load_kb
from arise.kb.retrieval import BM25Retriever
from arise.kb.schema import Component
from arise.language.readers import read_description
from arise.maps.registry import MapRegistry
from arise.vocabulary import EgoPlan


@pytest.fixture(scope="module")
def kb() -> KnowledgeBase:
    return load_kb(builtin=True)


@pytest.fixture(scope="module")
def maps() -> dict[str, frozenset[str]]:
    return {name: entry.features for name, entry in MapRegistry().entries.items()}


@pytest.mark.parametrize(
    ("text", "plan"),
    [
        ("The ego pulls over to the kerb as an ambulance approaches from behind.", "pull_over"),
        (
            "A truck is stalled in the ego's lane; the ego goes around it through the oncoming "
            "lane while an oncoming car approaches.",
            "bypass",
        ),
        (
            "The ego changes into the left lane to pass a slow bus and then returns to its own "
            "lane.",
            "change_and_return",
        ),
        (
            "The ego pulls into the oncoming lane to pass a slow bicycle while an oncoming car "
            "approaches.",
            "bypass",
        ),
        ("The ego stops at the stop line, then goes when a cyclist has crossed.", "stop_then_go"),
        ("The ego waits for the oncoming motorcycle to pass, then turns left.", "yield_then_go"),
    ],
)
def test_the_ego_plan_is_read_from_the_egos_own_words(text: str, plan: str) -> None:
    fact = read_description(text).facts["ego_plan"]
    assert fact.value == EgoPlan[plan.upper()].value
    assert fact.quote and fact.quote in text


@pytest.mark.parametrize(
    "text",
    [
        "An oncoming truck keeps going straight and does not yield.",
        "A car overtakes the ego and then returns to its lane.",
        "The ego stops at a red light when a car rear-ends it.",
        "The ego drifts into the oncoming lane on a curve and meets a truck head-on.",
    ],
)
def test_no_plan_from_what_others_do(text: str) -> None:
    assert "ego_plan" not in read_description(text).facts


def _spec(**changes: object) -> ScenarioSpec:
    base: dict[str, object] = {
        "adversary_type": "car",
        "behavior": "drives on",
        "road_type": "straight_road",
        "ego_maneuver": "go_straight",
        "geometry": "a road",
        "spawn_position": "oncoming",
        "spawn": "another car",
    }
    return ScenarioSpec.model_validate({**base, **changes})


def _geometry(spec: ScenarioSpec, kb: KnowledgeBase, maps: dict[str, frozenset[str]]) -> str:
    retrieval = retrieve(spec, kb, BM25Retriever(kb), maps)
    return retrieval.chosen[Component.GEOMETRY][0].id


@pytest.mark.parametrize(
    ("plan", "changes"),
    [
        (EgoPlan.PULL_OVER, {}),
        (EgoPlan.BYPASS, {"spawn_position": "ahead_same_lane"}),
        (EgoPlan.CHANGE_AND_RETURN, {"ego_maneuver": "change_lane"}),
        (
            EgoPlan.STOP_THEN_GO,
            {"road_type": "intersection", "spawn_position": "crossing_road_from_right"},
        ),
        (EgoPlan.YIELD_THEN_GO, {"road_type": "intersection", "ego_maneuver": "turn_left"}),
    ],
)
def test_a_stated_plan_gets_a_geometry_that_acts_it_out(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], plan: EgoPlan, changes: dict[str, object]
) -> None:
    geometry = kb.get(_geometry(_spec(ego_plan=plan, **changes), kb, maps))
    assert plan.value in geometry.tags, geometry.id


@pytest.mark.parametrize(
    ("turn", "tag"), [("turn_left", "left_turn"), ("turn_right", "right_turn")]
)
def test_a_turning_ego_that_goes_round_something_keeps_its_turn(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], turn: str, tag: str
) -> None:
    # no junction geometry acts out a bypass: the turn the text states still decides
    spec = _spec(
        ego_plan=EgoPlan.BYPASS,
        road_type="intersection",
        ego_maneuver=turn,
        spawn_position="adjacent_lane_left",
    )
    geometry = kb.get(_geometry(spec, kb, maps))
    assert tag in geometry.tags or tag in geometry.id, geometry.id


@pytest.mark.parametrize(
    "changes",
    [
        {},
        {"road_type": "intersection", "spawn_position": "crossing_road_from_right"},
        {"road_type": "intersection", "ego_maneuver": "turn_left"},
        {"ego_maneuver": "change_lane"},
    ],
)
def test_no_plan_no_geometry_that_stops_yields_or_pulls_over(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], changes: dict[str, object]
) -> None:
    geometry = kb.get(_geometry(_spec(**changes), kb, maps))
    assert not set(geometry.tags) & PLAN_TAGS, geometry.id


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (
            "The ego overtakes a slow truck on a straight road; while the ego is beside it, the "
            "truck swerves toward the ego.",
            ("change_lane", "left", "ahead_same_lane"),
        ),
        # someone else overtakes: the ego keeps its lane, the overtaker starts behind or beside
        (
            "A motorcycle overtakes the ego on its left and then cuts back in close in front of it.",
            (None, None, "adjacent_lane_left"),
        ),
        # on the other side of the road: a bypass, not a lane change
        (
            "The ego overtakes a slow truck through the oncoming lane while an oncoming car "
            "approaches.",
            (None, None, None),
        ),
        # the ego's own words for the change win over the verb "overtake"
        (
            "The ego moves into the right lane to overtake a slow van.",
            ("change_lane", "right", None),
        ),
    ],
)
def test_an_ego_that_overtakes_pulls_out_to_the_left(
    text: str, expected: tuple[str | None, str | None, str | None]
) -> None:
    facts = read_description(text).facts
    got = tuple(
        facts[name].value if name in facts else None
        for name in ("ego_maneuver", "ego_lane_side", "spawn_position")
    )
    assert got[:2] == expected[:2]
    if expected[2] is not None:
        assert got[2] == expected[2]
    bypass = "oncoming lane" in text
    assert ("ego_plan" in facts and facts["ego_plan"].value == "ego_bypass") == bypass
