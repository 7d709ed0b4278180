"""Grounded extraction: the fixed readers and how they overrule or keep the model's answer.

The sentences here are written for these tests (none is from a dev set or a prompt file).
"""

from __future__ import annotations

import pytest

from arise.generate.grounding import ground
from arise.generate.spec import ExtractionAnswer
from arise.language.cast import read_cast
from arise.language.facts import FactSource
from arise.language.quotes import find_quote, quote_in
from arise.language.readers import read_description
from arise.language.weather import read_weather
from arise.vocabulary import AdversaryManeuver, AdversaryType, EgoManeuver, RelativePosition


def answer(**overrides: object) -> ExtractionAnswer:
    """A model answer that is wrong in the usual ways unless a test says otherwise."""
    fields: dict[str, object] = {
        "adversary": "",
        "adversary_type": "car",
        "behavior": "",
        "road_type": "straight_road",
        "ego_maneuver": "go_straight",
        "geometry": "",
        "spawn_position": "ahead_same_lane",
        "spawn": "",
        "participants": [],
        "requirements": [],
    }
    fields.update(overrides)
    return ExtractionAnswer.model_validate(fields)


# -- quotes ---------------------------------------------------------------------------------


def test_a_quote_is_found_whatever_its_case_spacing_and_punctuation() -> None:
    text = "Near the school, a Boy  chases his ball into the road."
    assert quote_in(text, "a boy chases his ball")
    assert quote_in(text, "near the school")
    assert find_quote(text, "a boy chases") == (17, 30)


def test_a_quote_that_is_not_in_the_text_is_rejected() -> None:
    text = "A boy chases his ball into the road."
    assert not quote_in(text, "a girl chases")
    assert not quote_in(text, "boy chases his ball onto the pavement")
    assert not quote_in(text, "")
    assert not quote_in(text, "oy chas")  # words, not fragments of words


# -- who is named ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("A courier van waits at the kerb; the van then pulls out.", [("Van", 1)]),
        (
            "Two joggers and a dog walker cross near the ego vehicle.",
            [("Pedestrian", 2), ("Pedestrian", 1)],
        ),
        ("The ego car passes four traffic cones and a recycling bin.", [("Cone", 4), ("Trash", 1)]),
        ("A tour bus is parked at the bus stop.", [("Bus", 1), ("BusStop", 1)]),
        ("The AV's bumper touched a pickup truck; both vehicles were scratched.", [("Truck", 1)]),
        ("The ego skids on ice; no other vehicle is involved.", []),
        ("A box truck brakes hard in front of the ego.", [("Truck", 1)]),
        ("A scooter weaves through the bike lane.", [("Motorcycle", 1)]),
    ],
)
def test_the_things_a_text_names_are_read_once_each(
    text: str, expected: list[tuple[str, int]]
) -> None:
    assert [(m.cls, m.count) for m in read_cast(text).others] == expected


def test_the_ego_is_never_one_of_the_others() -> None:
    cast = read_cast("The ego vehicle follows a taxi; the autonomous vehicle brakes.")
    assert [m.cls for m in cast.others] == ["Car"]
    assert len(cast.ego) == 2


# -- weather --------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "preset", "source"),
    [
        ("A cyclist swerves around a pothole.", "ClearNoon", FactSource.DEFAULT),
        ("In a light drizzle a car brakes ahead.", "SoftRainNoon", FactSource.TEXT),
        ("During a downpour at night a truck skids.", "HardRainNight", FactSource.TEXT),
        ("At dusk a runner crosses.", "ClearSunset", FactSource.TEXT),
        ("On a wet street under an overcast sky a van stops.", "WetCloudyNoon", FactSource.TEXT),
        ("A dark blue sedan cuts in.", "ClearNoon", FactSource.DEFAULT),
        ("The car waits at the red light.", "ClearNoon", FactSource.DEFAULT),
    ],
)
def test_weather_comes_from_weather_words_only(text: str, preset: str, source: FactSource) -> None:
    fact = read_weather(text).fact
    assert (fact.value, fact.source) == (preset, source)


# -- sides and turns, attributed to the right actor -----------------------------------------


@pytest.mark.parametrize(
    ("text", "position"),
    [
        ("A moped rider on the right front cuts across the ego.", "adjacent_lane_right"),
        ("A sedan on the left front drifts toward the ego.", "adjacent_lane_left"),
        (
            "A pickup truck approaches the crossing from the right and keeps going.",
            "crossing_road_from_right",
        ),
        ("An oncoming bus swings wide into the ego's lane.", "oncoming"),
        ("A hatchback closes in from behind and taps the ego.", "behind_same_lane"),
        ("A woman on the opposite sidewalk starts to cross.", "roadside_left"),
        ("The ego follows a lead truck that stops suddenly.", "ahead_same_lane"),
        (
            "Ego vehicle stopped at an intersection is struck from behind by a following car.",
            "behind_same_lane",
        ),
        ("The ego waits at a light when a following van fails to stop.", "behind_same_lane"),
        ("The ego is cut off from the right by a taxi.", "crossing_road_from_right"),
        (
            "In heavy rain, the AV was following a white van northbound. The van stopped "
            "suddenly to let a pedestrian cross.",
            "ahead_same_lane",
        ),
        ("The AV was travelling east at 18 mph behind a box truck.", "ahead_same_lane"),
        (
            "The ego turns right at a crossroads; just after the turn a motorcycle is stopped "
            "in the lane the ego enters.",
            "ahead_same_lane",
        ),
        (
            "The ego moves into the right lane where a scooter is riding in that lane.",
            "adjacent_lane_right",
        ),
    ],
)
def test_the_adversary_side_is_read_from_its_own_words(text: str, position: str) -> None:
    reading = read_description(text)
    assert reading.facts["spawn_position"].value == position


def test_a_side_said_of_another_actor_is_not_the_adversary_side() -> None:
    text = "A lorry is parked on the right; a child runs out from the left."
    reading = read_description(text, adversary_quote="a child")
    assert reading.adversary is not None and reading.adversary.cls == "Pedestrian"
    assert reading.facts["spawn_position"].value == "crossing_road_from_left"


def test_compass_bearings_turn_into_the_ego_frame() -> None:
    text = (
        "The AV was travelling southbound on Elm Row. A westbound motorcycle crossed in "
        "front of it."
    )
    assert read_description(text).facts["spawn_position"].value == "crossing_road_from_left"


@pytest.mark.parametrize(
    ("text", "ego", "adversary"),
    [
        (
            "The ego goes straight while the other car makes a left turn.",
            "go_straight",
            "turn_left",
        ),
        (
            "The ego turns left; a courier van coming the other way goes straight.",
            "turn_left",
            "straight",
        ),
        ("Turning right at the lights, the ego meets a jogger.", "turn_right", None),
        ("A taxi turns right in front of the ego.", None, "turn_right"),
        ("An unprotected left at a crossroads with a fast oncoming sedan.", "turn_left", None),
    ],
)
def test_turns_belong_to_whoever_makes_them(
    text: str, ego: str | None, adversary: str | None
) -> None:
    facts = read_description(text).facts
    assert (facts["ego_maneuver"].value if "ego_maneuver" in facts else None) == ego
    assert (
        facts["adversary_maneuver"].value if "adversary_maneuver" in facts else None
    ) == adversary


# -- the grounded spec ----------------------------------------------------------------------


def test_the_text_overrules_the_model_and_says_so() -> None:
    text = "The ego goes straight over a junction while a minibus from the right turns left."
    grounded = ground(
        text,
        answer(
            adversary="a minibus",
            adversary_type="car",
            ego_maneuver="turn_left",
            spawn_position="oncoming",
            participants=["a minibus from the right", "a parked car"],
        ),
    )
    spec = grounded.spec
    assert spec.adversary_type is AdversaryType.TRUCK and spec.scenic_class == "Bus"
    assert spec.ego_maneuver is EgoManeuver.GO_STRAIGHT
    assert spec.adversary_maneuver is AdversaryManeuver.TURN_LEFT
    assert spec.spawn_position is RelativePosition.CROSSING_FROM_RIGHT
    assert spec.participants == []  # the adversary echoed back and a car nobody named
    assert spec.weather == "ClearNoon"
    assert any("ego_maneuver: turn_left -> go_straight" in note for note in grounded.notes)
    assert any("a parked car" in note for note in grounded.notes)


def test_every_fact_says_where_it_came_from() -> None:
    text = "At night a man steps out from behind a parked van on the right."
    spec = ground(text, answer(adversary="a man", behavior="walks across the road")).spec
    by_name = {fact.name: fact for fact in spec.grounding}
    assert by_name["weather"].value == "ClearNight" and by_name["weather"].quote == "night"
    assert by_name["adversary_type"].source is FactSource.TEXT
    assert by_name["ego_maneuver"].source is FactSource.DEFAULT
    assert spec.participants == ["a parked van on the right"]
    assert spec.behavior == ""  # the model's words are not the text's
    for fact in spec.grounding:
        if fact.source in (FactSource.TEXT, FactSource.MODEL):
            for piece in (fact.quote or "").split(" ... "):
                assert quote_in(text, piece), fact


def test_a_requirement_the_text_does_not_state_is_dropped() -> None:
    text = "A van pulls out of a driveway ahead of the ego."
    grounded = ground(
        text,
        answer(
            adversary="a van",
            requirements=[{"kind": "not_visible_at_start", "text": "hidden by a hedge"}],
        ),
    )
    assert grounded.spec.requirements == []
    assert any("not_visible_at_start" in note for note in grounded.notes)


def test_without_a_named_road_user_the_model_type_is_marked_a_guess() -> None:
    text = "Three cones block the ego's lane on a straight road."
    spec = ground(text, answer(adversary="something", adversary_type="car")).spec
    fact = next(f for f in spec.grounding if f.name == "adversary_type")
    assert fact.source is FactSource.GUESS
    assert [p.split()[:2] for p in spec.participants] == [["Three", "cones"]]


def test_only_facts_resting_on_words_are_held_against_a_script() -> None:
    # ("on the road it turns into" would say where: ahead on its route, start.exit_lane)
    text = "Turning left at the lights, the ego meets a cyclist."
    spec = ground(text, answer(adversary="a cyclist", spawn_position="adjacent_lane_left")).spec
    assert spec.rests_on_words("ego_maneuver")  # "Turning left"
    assert spec.rests_on_words("adversary_type")  # "a cyclist"
    assert not spec.rests_on_words("spawn_position")  # the model's guess: no words say it


def test_an_unstated_road_is_an_ordinary_road_not_the_model_guess() -> None:
    text = "A stalled hatchback sits in the ego's lane."
    spec = ground(text, answer(adversary="A stalled hatchback", road_type="highway")).spec
    assert spec.road_type.value == "straight_road"
    fact = next(f for f in spec.grounding if f.name == "road_type")
    assert fact.source is FactSource.DEFAULT


def test_a_vehicle_from_a_side_road_comes_from_that_side_at_a_junction() -> None:
    text = "A pickup from the side street to the ego's left pulls out in front of it."
    spec = ground(text, answer(adversary="A pickup", spawn_position="adjacent_lane_left")).spec
    assert spec.spawn_position is RelativePosition.CROSSING_FROM_LEFT
    assert spec.road_type.value == "intersection"


def test_a_walker_never_starts_in_a_traffic_lane_on_a_guess() -> None:
    text = "Near a school a boy steps out between two parked cars."
    spec = ground(text, answer(adversary="a boy", spawn_position="oncoming")).spec
    assert spec.spawn_position is RelativePosition.ROADSIDE_RIGHT
    assert [p.split()[:3] for p in spec.participants] == [["two", "parked", "cars"]]


@pytest.mark.parametrize(
    ("text", "stationary"),
    [
        ("A removal van is parked in the ego's lane ahead.", True),
        ("A stalled hatchback sits across the lane.", True),
        ("The ego reaches a taxi stopped in its lane.", True),
        ("A parked taxi pulls out in front of the ego.", False),
        ("The taxi ahead stopped suddenly.", False),
        ("A taxi ahead brakes to a stop.", False),
    ],
)
def test_an_adversary_that_stays_put_is_read_from_its_own_words(
    text: str, stationary: bool
) -> None:
    spec = ground(text, answer(adversary="taxi" if "taxi" in text else "")).spec
    assert spec.adversary_stationary is stationary


def test_an_object_of_a_class_the_text_never_names_is_extra() -> None:
    from arise.generate.conformity import check_conformity
    from arise.validate.types import AgentTrace, SimulationFacts, TracePoint

    def agent(name: str, kind: str, x: float, ego: bool = False) -> AgentTrace:
        point = TracePoint(step=0, x=x, y=0.0, heading=0.0, speed=0.0)
        return AgentTrace(
            name=name, kind=kind, width=2.0, length=4.5, is_ego=ego, trajectory=[point]
        )

    text = "The ego turns left at a junction and a box lies in the lane it turns into."
    spec = ground(text, answer()).spec
    facts = SimulationFacts(
        steps=0,
        timestep=0.1,
        termination_type="time_limit",
        termination_reason="test",
        agents=[agent("ego", "Car", 0.0, ego=True), agent("c", "Car", 9)],
    )
    checks = {c.name: c for c in check_conformity(spec, facts).checks}
    assert checks["participants"].ok is False and "no Box" in checks["participants"].observed
    assert checks["extra_actors"].ok is False


@pytest.mark.parametrize(
    ("text", "stopped"),
    [
        ("The ego waits at a red light; a bus runs its red light and turns left.", True),
        ("Ego vehicle stopped at an intersection is struck from behind by a following car.", True),
        ("The AV was stopped in traffic behind a bus when a sedan hit its rear.", True),
        ("While the ego waits to turn left, an oncoming motorcycle goes straight.", False),
        ("The ego turns left and stops a metre short of a pedestrian.", False),
        ("A motorcycle is stopped in the lane the ego enters.", False),
        ("The AV stopped, but its bumper touched the pedestrian.", False),
    ],
)
def test_an_ego_held_still_is_read_from_words_about_the_ego(text: str, stopped: bool) -> None:
    reading = read_description(text)
    assert ("ego_stopped" in reading.facts) is stopped


@pytest.mark.parametrize(
    ("text", "position"),
    [
        (
            "On June 11, 2026, the AV was travelling westbound on Marrow Lane at 20 mph through "
            "its T-intersection with Larkmoor Avenue, which meets Marrow Lane from the north. "
            "A car waiting at the stop sign on Larkmoor Avenue pulled out to turn left.",
            "crossing_road_from_right",
        ),
        (
            "The AV was stopped at a red light on Tamsin Street when a cyclist riding forward "
            "between the AV and a car parked on the right hit the AV's right mirror.",
            "adjacent_lane_right",
        ),
        (
            "The AV was travelling in the rightmost northbound lane of the freeway at 50 mph "
            "when a motorcycle entering from the on-ramp to its right merged into its lane "
            "ahead of it and braked.",
            "adjacent_lane_right",
        ),
    ],
)
def test_crash_report_sides_from_streets_squeezes_and_ramps(text: str, position: str) -> None:
    reading = read_description(text)
    fact = reading.facts["spawn_position"]
    assert fact.value == position
    assert fact.quote is not None and fact.quote in text


@pytest.mark.parametrize(
    ("text", "side"),
    [
        (
            "A barrier blocks the ego's lane on a highway and the ego changes lanes to the left "
            "to get around it.",
            "left",
        ),
        ("The ego moves into the right lane while a scooter rides in that lane.", "right"),
        ("The ego changes lanes while a car ahead brakes.", None),
        ("A truck on the left changes into the right lane in front of the ego.", None),
    ],
)
def test_the_side_of_the_egos_lane_change_is_its_own(text: str, side: str | None) -> None:
    fact = read_description(text).facts.get("ego_lane_side")
    assert (fact.value if fact else None) == side


def test_a_trailing_participle_belongs_to_the_clause_subject() -> None:
    text = (
        "On a four-lane road a car weaves between lanes in front of the ego, changing lanes "
        "twice in quick succession."
    )
    assert "ego_maneuver" not in read_description(text).facts


def test_signalling_is_no_traffic_signal_and_behind_a_van_is_no_rear() -> None:
    text = (
        "A truck in the adjacent right lane drifts into the ego's lane without signalling "
        "while both travel side by side."
    )
    answer = ExtractionAnswer.model_validate(
        {
            "adversary": "A truck",
            "adversary_type": "truck",
            "behavior": "",
            "road_type": "straight_road",
            "ego_maneuver": "go_straight",
            "geometry": "",
            "spawn_position": "adjacent_lane_right",
            "spawn": "",
        }
    )
    assert ground(text, answer).spec.road_type == "straight_road"
    child = "On a straight street, a child runs out from behind a parked van on the right."
    position = read_description(child, "a child").facts.get("spawn_position")
    assert position is None or position.value != "behind_same_lane"


@pytest.mark.parametrize(
    ("text", "ego_on_ramp"),
    [
        (
            "On the freeway, a motorcycle entering from the on-ramp to its right merged into "
            "the AV's lane ahead of it.",
            False,
        ),
        ("The ego merges from the on-ramp onto the motorway in front of a fast truck.", True),
        ("The AV entered the freeway from the ramp; a car in the right lane sped up.", True),
    ],
)
def test_an_on_ramp_makes_a_merge_and_the_reader_says_who_is_on_it(
    text: str, ego_on_ramp: bool
) -> None:
    spec = ground(text, answer(road_type="highway")).spec
    assert spec.road_type.value == "merge"
    assert spec.ego_on_ramp is ego_on_ramp


@pytest.mark.parametrize(
    ("text", "contact", "timing"),
    [
        (
            "A van pulls out of a driveway on the right just as the ego passes and hits it.",
            True,
            "late",
        ),
        ("A cyclist crosses from the left far ahead of the ego.", False, "early"),
        ("A jogger crosses from the left and the ego slows down for him.", False, None),
        ("A pickup nearly clips the ego while cutting across from the left.", True, None),
    ],
)
def test_what_the_text_says_of_the_meeting_is_read_with_its_words(
    text: str, contact: bool, timing: str | None
) -> None:
    spec = ground(text, answer()).spec
    assert spec.contact_stated is contact
    assert (spec.timing.value if spec.timing else None) == timing
    by_name = {fact.name: fact for fact in spec.grounding}
    if contact:
        assert by_name["contact_stated"].source is FactSource.TEXT
        assert quote_in(text, by_name["contact_stated"].quote or "")
