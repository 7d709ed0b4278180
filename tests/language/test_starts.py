"""Where another road user starts, said in ways the first rules did not know (issue 28):
clock positions, British sides, a start said by another actor, an opening participle."""

from __future__ import annotations

import pytest

from arise.evaluate.fidelity import DEVSET_DIR, DevSet, load_devset
from arise.language.lexicon import slot_key, slot_word
from arise.language.readers import read_description


@pytest.mark.parametrize(
    ("word", "canonical"),
    [
        ("R", "right"),
        ("Left", "left"),
        ("2 o'clock", "right"),
        ("10  o'clock", "left"),
        ("Nearside", "left"),
        ("near-side", "left"),
        ("off side", "right"),
    ],
)
def test_a_slot_word_is_canonical_however_it_is_spaced(word: str, canonical: str) -> None:
    assert slot_word(word) == canonical
    assert slot_key("Near-Side") == slot_key("nearside") == slot_key("near side")


@pytest.mark.parametrize(
    ("text", "start"),
    [
        # clock positions seen from the driver's seat
        ("A lorry at our 4 o'clock keeps pace with us on the ring road.", "adjacent_lane_right"),
        ("Tractor at the AV's 11 o'clock, coming out of a farm track.", "adjacent_lane_left"),
        ("A cyclist waits at our 6 o'clock as the lights change.", "behind_same_lane"),
        # the walker is placed by the thing it steps out from; 'it' is the thing named last
        (
            "A skip lorry is parked on the left and a man walks out from in front of it.",
            "crossing_road_from_left",
        ),
        # the opener is the actor's own words, not the ego's
        (
            "Pulling out of a petrol station on the right, a taxi crosses in front of us.",
            "crossing_road_from_right",
        ),
        (
            "Some way ahead on the left, a removal van pulls out into our lane.",
            "adjacent_lane_left",
        ),
        # the ego's bearing in its opener; the sedan's own bearing is not the ego's
        (
            "Travelling north on Quarry Lane, the AV was hit by a westbound cab at the crossing.",
            "crossing_road_from_right",
        ),
        # "it" is a phrase of its own: "the AV's left as | it" does not open at "the"
        ("Jogger crosses from the AV's left as it pulls off.", "crossing_road_from_left"),
        # numbered lanes spelled out, after the word "lane"
        ("I was in lane two and a minibus in lane three drifted over.", "adjacent_lane_right"),
    ],
)
def test_new_ways_of_saying_a_start(text: str, start: str) -> None:
    assert read_description(text).facts["spawn_position"].value == start


def test_an_opener_that_names_the_ego_is_not_the_actors() -> None:
    reading = read_description("Turning left off the slip road, the ego meets a van.")
    assert "spawn_position" not in reading.facts


def test_the_variants_set_loads_and_each_actor_has_a_start() -> None:
    items = load_devset(DEVSET_DIR / "variants.jsonl")
    assert len(items) == 36 and {item.set for item in items} == {DevSet.VARIANTS}
    assert all(actor.start is not None for item in items for actor in item.truth.actors)
    assert sum(len(item.truth.actors) > 1 for item in items) >= 5  # scenes of several roles


@pytest.mark.parametrize(
    "text",
    [
        # the AV named in words and a numbered other party (no V1)
        "The AV waited at the light. Unit 2, a grey estate in the lane to its left, pulled across.",
        # "the AV" further on is the one struck, not what V2 is
        "V2, a flatbed truck in the right lane, drifted left and scraped the AV's right side.",
    ],
)
def test_a_numbered_party_that_meets_the_av_is_not_the_av(text: str) -> None:
    reading = read_description(text)
    assert reading.adversary is not None and reading.adversary.quote.startswith(("Unit 2", "V2"))
    assert reading.cast.ego


def test_the_adversary_is_the_road_user_that_touches_the_ego() -> None:
    """Not the bus the ego waited behind, but the car whose own clause runs into it."""
    from arise.language.readers import read_description

    text = (
        "We were sitting at the lights behind a coach. A hatchback then ran into the back "
        "of our car; the coach was not touched."
    )
    reading = read_description(text)
    assert reading.adversary is not None and reading.adversary.quote == "A hatchback"
    assert reading.facts["spawn_position"].value == "behind_same_lane"


def test_a_numbered_party_driving_a_vehicle_is_that_vehicle() -> None:
    from arise.language.readers import read_description

    text = (
        "Party 1 (the AV) was stopped at a red signal. Party 2, driving a 2011 Parlow "
        "estate, collided with the rear of Party 1."
    )
    reading = read_description(text)
    assert len(reading.cast.others) == 1
    assert reading.facts["spawn_position"].value == "behind_same_lane"


def test_a_person_who_owns_the_vehicle_is_no_road_user_of_their_own() -> None:
    from arise.language.readers import read_description

    reading = read_description("Van of one man is standing at left side of road and starts.")
    assert [m.cls.value for m in reading.cast.others] == ["Van"]
    assert reading.facts["spawn_position"].value == "roadside_left"


def test_a_reports_other_party_is_its_lowest_numbered_one() -> None:
    text = (
        "V1 (the AV) was eastbound behind V3, a tractor hauling hay at about 10 mph. V1 moved"
        " into the westbound lane to pass. V2, a westbound hatchback, came over the crest and"
        " V1 returned behind V3."
    )
    reading = read_description(text)
    assert reading.adversary is not None and reading.adversary.quote == "V2"


def test_a_lead_ahead_of_an_ego_held_at_a_red_waits_too() -> None:
    from arise.language.actors import read_actors
    from arise.vocabulary import ActorRole

    text = (
        "The ego sat at the red light behind a campervan when a taxi ran into the back of the ego."
    )
    [campervan] = [a for a in read_actors(read_description(text)) if a.scenic_class == "Van"]
    assert campervan.role is ActorRole.STOPPED and campervan.stationary
    moving = "The ego follows a campervan on the bypass when a taxi cuts in."
    [lead] = [a for a in read_actors(read_description(moving)) if a.scenic_class == "Van"]
    assert lead.role is not ActorRole.STOPPED


def test_two_road_users_each_between_the_ego_and_the_other_read_once() -> None:
    text = "A moped filters up between the ego and a van. The van creeps between the ego and the moped."
    assert read_description(text).adversary is not None


@pytest.mark.parametrize(
    ("text", "start"),
    [
        # at a junction, a car, van, truck or bus placed by a side alone is on the road
        # across the ego's
        (
            "At the all-way stop a minibus on the ego's right does not wait its turn.",
            "crossing_road_from_right",
        ),
        (
            "At the uncontrolled crossroads a tanker to our left keeps coming.",
            "crossing_road_from_left",
        ),
        # ... but not a lane said, a rider filtering, or an ego that turns
        ("At the lights a horsebox in the lane on our left pulls ahead.", "adjacent_lane_left"),
        ("At the lights a moped on the left filters past the ego.", "adjacent_lane_left"),
        (
            "The ego turns left at the crossroads; a tanker on its right keeps pace.",
            "adjacent_lane_right",
        ),
        # a road across the ego's, said by its side
        (
            "A pickup on the road to our right rolled out into the junction.",
            "crossing_road_from_right",
        ),
        ("Another vehicle crossing from the driver's side.", "crossing_road_from_left"),
    ],
)
def test_a_side_at_a_junction_is_the_crossing_road(text: str, start: str) -> None:
    assert read_description(text).facts["spawn_position"].value == start


def test_a_vehicle_that_waits_on_the_street_the_ego_turns_onto_is_in_its_lane() -> None:
    reading = read_description(
        "I was turning right onto Hatch Lane, where a skip lorry stood on Hatch Lane."
    )
    assert reading.facts["spawn_position"].value == "ahead_same_lane"
    assert reading.facts["start_detail"].value == "exit_lane"
    # one that drives on that street is not placed there by the street alone
    moving = read_description(
        "I was turning right onto Hatch Lane when a skip lorry drove along Hatch Lane."
    )
    assert "start_detail" not in moving.facts


@pytest.mark.parametrize(
    ("text", "start"),
    [
        # a vehicle going straight on, its side unsaid, as the ego turns left: it comes
        # the other way (the left turn across the path of oncoming traffic) ...
        ("Unit 1 turned left on the green. Unit 2, a tanker, continued straight.", "oncoming"),
        (
            "The AV was turning left when a hatchback going straight on hit its right side.",
            "oncoming",
        ),
        # ... as it turns right, from the left (the right turn into traffic from the left)
        (
            "Unit 1 turned right on the green. Unit 2, a tanker, continued straight.",
            "crossing_road_from_left",
        ),
        (
            "The AV was turning right when a hatchback going straight on hit its left side.",
            "crossing_road_from_left",
        ),
        # ... not one that hit the other side, and not with a side said
        (
            "The AV was turning right when a hatchback going straight on hit its right side.",
            "adjacent_lane_right",
        ),
        (
            "The AV was turning left when a hatchback from the right going straight on hit it.",
            "crossing_road_from_right",
        ),
    ],
)
def test_straight_on_through_the_egos_turn(text: str, start: str | None) -> None:
    fact = read_description(text).facts.get("spawn_position")
    assert (fact.value if fact else None) == start


def test_the_one_that_blocks_the_view_is_not_the_adversary_even_when_the_model_says_so() -> None:
    text = (
        "The AV turned left; a pickup waiting opposite screened its view of a quad bike "
        "that came straight on."
    )
    quoted = read_description(text, adversary_quote="a pickup")
    assert quoted.adversary is not None and quoted.adversary.quote == "a quad bike"
    # with no one else playing, the model's pick stands
    alone = read_description(
        "The AV turned left; a pickup waiting opposite screened its view.", "a pickup"
    )
    assert alone.adversary is not None and alone.adversary.quote == "a pickup"


@pytest.mark.parametrize(
    ("text", "start", "detail"),
    [
        # a walker crossing along the ego's first bearing crosses the street it turns into:
        # from the far corner when it comes toward the ego ...
        (
            "The AV was northbound on Pine Avenue and turned right to go eastbound on Elm "
            "Street. A pedestrian crossing the eastbound lanes of Elm Street in the marked "
            "crosswalk was walking south and was struck.",
            "roadside_right",
            "exit_far_corner",
        ),
        (
            "V1 was westbound on 5th St turning right onto Oak Ave. A pedestrian in the "
            "crosswalk walking east across Oak Ave was struck by V1.",
            "roadside_right",
            "exit_far_corner",
        ),
        (
            "The AV was southbound and turned left. A cyclist crossing northbound in the "
            "crosswalk was struck.",
            "roadside_left",
            "exit_far_corner",
        ),
        # ... from the near side when it goes the ego's way
        (
            "V1 was westbound on 5th St turning right onto Oak Ave. A pedestrian in the "
            "crosswalk walking west across Oak Ave was struck by V1.",
            "roadside_right",
            "exit_crossing",
        ),
    ],
)
def test_a_walker_crossing_the_street_a_turning_ego_enters_by_compass(
    text: str, start: str, detail: str
) -> None:
    facts = read_description(text).facts
    assert facts["spawn_position"].value == start
    assert facts["start_detail"].value == detail


@pytest.mark.parametrize(
    ("text", "start", "detail"),
    [
        # the side it hit, said after a semicolon, tells the lane it came up behind in
        (
            "At the crossroads the AV sat at the red light. A tipper lorry came up behind it; "
            "scraped the AV's driver side rear and drove on.",
            "adjacent_lane_left",
            "from_behind",
        ),
        # closing in from behind an ego that changes lanes: in the lane the ego moves into
        (
            "The AV moved over to the left lane to pass a slow milk float, and a motorbike "
            "came up fast from behind and clipped its rear.",
            "adjacent_lane_left",
            "from_behind",
        ),
    ],
)
def test_from_behind_in_the_lane_beside(text: str, start: str, detail: str) -> None:
    facts = read_description(
        text, adversary_quote="motorbike" if "motorbike" in text else None
    ).facts
    assert facts["spawn_position"].value == start
    assert facts["start_detail"].value == detail


def test_a_sentence_opening_phrase_is_the_words_of_the_subject_named_after_it() -> None:
    facts = read_description("Ego at 50 kph. Ahead, in the same lane, a tractor has stopped.").facts
    assert facts["spawn_position"].value == "ahead_same_lane"


def test_a_standing_adversary_the_ego_goes_round_stands_in_its_lane() -> None:
    turning = read_description(
        "The AV turns right at the T-junction and has to go round a parked skip lorry "
        "through the oncoming lane."
    ).facts
    assert turning["spawn_position"].value == "ahead_same_lane"
    assert turning["start_detail"].value == "exit_lane"
    straight = read_description(
        "On the high street the ego steers around a stationary horsebox by using the oncoming lane."
    ).facts
    assert straight["spawn_position"].value == "ahead_same_lane"
    assert "start_detail" not in straight


@pytest.mark.parametrize(
    "text",
    [
        "At the crossroads the AV kept straight on. From the right a pickup jumped the lights.",
        "At the crossroads the AV kept straight on. Crossing from the right was a pickup.",
        "At the crossroads the AV kept straight on. From the right came a pickup at speed.",
    ],
)
def test_where_the_subject_comes_from_said_before_it(text: str) -> None:
    assert read_description(text).facts["spawn_position"].value == "crossing_road_from_right"


def test_on_the_street_a_turning_ego_enters_named_by_its_name() -> None:
    """Coming toward the ego along the street it turns onto is coming from the side it
    turns to; a lorry just round the corner that the ego waits behind stands in its exit
    lane."""
    from arise.language.actors import read_actors

    text = (
        "You turn right from Mill Road into Gorse Street. A horsebox has broken down just "
        "round the corner. Down Gorse Street a jogger is running towards you. Wait behind "
        "the horsebox until the jogger is past."
    )
    reading = read_description(text)
    assert reading.facts["spawn_position"].value == "ahead_same_lane"
    assert reading.facts["start_detail"].value == "exit_lane"
    [jogger] = [a for a in read_actors(reading) if a.scenic_class == "Pedestrian"]
    assert jogger.start is not None and jogger.start.value == "crossing_road_from_right"


def test_ahead_in_the_same_lane_then_a_side_of_the_ego_hit_is_that_lane_ahead() -> None:
    facts = read_description(
        "The AV was on the motorway. V2, a van, was a little ahead of the AV when it swerved "
        "and struck the AV's right front corner."
    ).facts
    assert facts["spawn_position"].value == "adjacent_lane_right"
    assert facts["start_detail"].value == "ahead"


def test_the_place_a_where_clause_opens_on_is_where_its_subject_is() -> None:
    facts = read_description(
        "The AV waits at the lights. A lorry blocks its view of a cross street on the left, "
        "where a cyclist is about to jump the red."
    ).facts
    assert facts["adversary_class"].value == "Bicycle"
    assert facts["spawn_position"].value == "crossing_road_from_left"


def test_the_one_the_ego_runs_into_is_the_adversary() -> None:
    reading = read_description(
        "I was turning left. A lorry coming the other way stopped and flashed me across, "
        "and a moped rider overtaking that lorry came on. My front wing hit his back wheel."
    )
    assert reading.facts["adversary_class"].value == "Motorcycle"
    assert reading.facts["spawn_position"].value == "oncoming"


def test_a_walker_who_is_not_the_adversary_on_the_street_a_turning_ego_enters() -> None:
    from arise.language.actors import read_actors

    reading = read_description(
        "You turn left at the lights behind a bus coming the other way. A man is crossing "
        "from the far corner of the street you are turning into."
    )
    [man] = [a for a in read_actors(reading) if a.scenic_class == "Pedestrian"]
    assert man.start is not None and man.start.value == "roadside_left"
    assert man.start_detail is not None and man.start_detail.value == "exit_far_corner"


def test_a_pronoun_after_the_writer_means_the_last_other_subject() -> None:
    reading = read_description(
        "I was behind a slow tractor. A taxi that had been in the lane to my left swung "
        "into the gap between me and the tractor. I braked and it missed my bumper by inches."
    )
    assert reading.facts["adversary_class"].value == "Car"
    assert reading.facts["spawn_position"].value == "adjacent_lane_left"


def test_a_party_heading_a_first_person_statement_is_the_ego() -> None:
    reading = read_description(
        "Claimant's statement. I was driving my van on Stoke Road when a scooter "
        "pulled out from the right. The claimant's van was not damaged."
    )
    assert [m.quote for m in reading.cast.others] == ["a scooter"]


def test_sides_said_in_words_of_a_transit_report() -> None:
    bus = read_description(
        "The ego went through on green. A coach was loading at the near-side stop, "
        "occupying the right lane, which cut off the view to the south."
    )
    assert bus.facts["spawn_position"].value == "adjacent_lane_right"
    assert "meeting" not in bus.facts  # a view cut off is no near miss
    clock = read_description("You move off; a van coming from your nine o'clock runs its red.")
    assert clock.facts["spawn_position"].value == "crossing_road_from_left"


def test_an_actor_beside_the_ego_starts_at_the_end_its_words_say() -> None:
    from arise.language.actors import read_actors

    reading = read_description(
        "Ego in R lane; bin lorry stopped ahead. Ego moves L to pass; moped in L lane "
        "@ 7 o'clock. A cyclist in the R lane ahead of the ego keeps going."
    )
    details = {a.quote: (a.start, a.start_detail) for a in read_actors(reading)}
    assert details["moped"][1] is not None and details["moped"][1].value == "from_behind"
