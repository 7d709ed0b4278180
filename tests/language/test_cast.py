"""Who a description names: the ego under its names, each other road user once, with its
class and count. Every sentence here is written for these tests."""

from __future__ import annotations

import pytest

from arise.language.actors import read_actors
from arise.language.cast import read_cast
from arise.language.readers import read_description
from arise.language.reading import parse


def _named(text: str) -> list[tuple[str, int]]:
    return [(m.cls.value, m.count) for m in parse(text).others]


def _ego_words(text: str) -> list[str]:
    cast = parse(text)
    return [text[s.start : s.end] for s in cast.ego]


@pytest.mark.parametrize(
    ("text", "ego"),
    [
        ("The test vehicle slows as a bus pulls out.", ["test vehicle"]),
        ("The subject vehicle was stopped when a van rolled back.", ["subject vehicle"]),
        ("SV slowing for a queue; POV behind it fails to stop.", ["SV"]),
        ("I was driving my car down Elm Road when a bike appeared.", ["I", "my car"]),
        # NHTSA's typology names the ego "Vehicle", with no article.
        ("Vehicle turning right; a cyclist going straight on its right.", ["Vehicle"]),
        # ... and in the typology's style "the vehicle's" is the ego's too.
        (
            "Vehicle turning left; a moped on the vehicle's left goes straight.",
            ["Vehicle", "the vehicle's"],
        ),
        # The possessive of a name of the ego is the ego's, not another car's.
        ("The test vehicle's front wing was clipped by a scooter.", ["test vehicle's"]),
        # In a driver's own claim, the vehicle they drive is the ego, whatever its kind.
        ("Our lorry was sideswiped by a coach on the ring road.", ["Our lorry"]),
    ],
)
def test_the_ego_is_found_under_its_names(text: str, ego: list[str]) -> None:
    assert _ego_words(text) == ego


def test_nhtsa_phrasing_has_the_ego_and_one_other_vehicle() -> None:
    text = (
        "Vehicle going straight at a junction; another vehicle from the left crosses its "
        "path. The other vehicle strikes Vehicle's side."
    )
    cast = parse(text)
    assert [m.cls.value for m in cast.others] == ["Car"]
    assert len(cast.others[0].spans) == 2, "'the other vehicle' is the one named before"


def test_nhtsa_notes_name_the_ego_vehicle_in_lower_case_at_a_clause_start() -> None:
    text = "Vehicle turning right; stalled coach obstructs travel lane; vehicle steers around."
    cast = parse(text)
    assert [m.cls.value for m in cast.others] == ["Bus"]
    assert len(cast.ego) == 2


def test_numbered_parties_the_autonomous_one_is_the_ego() -> None:
    text = (
        "V1 was northbound. V2, a self-driving shuttle, was behind V1 and touched its "
        "rear bumper. V1 stopped."
    )
    cast = parse(text)
    # what it is, set off after its number, is the ego too
    assert [text[s.start : s.end] for s in cast.ego] == ["V2", "a self-driving shuttle"]
    assert [m.quote for m in cast.others] == ["V1"]


def test_the_first_numbered_vehicle_is_the_ego_when_none_is_called_autonomous() -> None:
    text = "V1 turned left. V2, a pickup, came the other way and struck V1."
    cast = parse(text)
    assert [text[s.start : s.end] for s in cast.ego] == ["V1", "V1"]
    assert [(m.cls.value, len(m.spans)) for m in cast.others] == [("Truck", 2)]


def test_a_sentence_that_opens_with_vehicle_2_names_a_party_not_the_ego() -> None:
    text = "Vehicle 2 was in the lane to the left and then moved over into Vehicle 1."
    cast = parse(text)
    assert [text[s.start : s.end] for s in cast.ego] == ["Vehicle 1"]
    assert [m.quote for m in cast.others] == ["Vehicle 2"]


@pytest.mark.parametrize(
    ("text", "named"),
    [
        # a year and a name we never heard of name a car
        ("A 2018 Velora Strand that was behind the ego rolled into it.", [("Car", 1)]),
        # a known make after a colour
        ("A silver Subaru Outback pulled out of a driveway.", [("Car", 1)]),
        # the make and the noun name one vehicle
        ("A 2015 Brask Hauler pickup cut in front of the ego.", [("Truck", 1)]),
        # the ego described is not one more actor
        ("The AV, a white hatchback in autonomous mode, slowed for a cyclist.", [("Bicycle", 1)]),
        # the ego's own driver and the driver of a named vehicle are no road users
        ("The AV's safety driver braked as the driver of a van opened a door.", [("Van", 1)]),
        ("A box truck stopped ahead; a box fell off it.", [("Truck", 1), ("Box", 1)]),
        # "stop" after a plural noun is its verb; the place is "the taxi stop"
        ("Two vans stop at the line as the ego waits at the taxi stop.", [("Van", 2)]),
        # a lane's number is no count, and a phrase does not reach back across "as"
        ("V1 moved from the #1 lane to the #3 lane as V2 came up on the right.", [("Car", 1)]),
    ],
)
def test_road_users_are_named_once_with_their_class(
    text: str, named: list[tuple[str, int]]
) -> None:
    assert _named(text) == named


@pytest.mark.parametrize(
    ("text", "counted"),
    [
        ("two parked vans", True),
        ("a parked van", True),
        ("parked vans along the street", False),
        ("several cyclists", False),
        ("a row of parked cars", False),
    ],
)
def test_a_count_is_stated_or_open(text: str, counted: bool) -> None:
    assert read_cast(text).others[0].counted is counted


def test_a_road_user_named_in_a_typology_heading_is_the_one_described_after_it() -> None:
    from arise.language.reading import parse

    cast = parse(
        "Motorcyclist turning: subject vehicle goes straight; a motorcyclist from the "
        "opposite direction turns left across its path."
    )
    assert len(cast.others) == 1
    assert cast.others[0].quote == "a motorcyclist"


@pytest.mark.parametrize(
    ("text", "named"),
    [
        # a rider and the bike are one road user, the bike
        ("A lad on a mountain bike shot across the zebra in front of us.", [("Bicycle", 1)]),
        ("A woman riding a moped filters past the queue.", [("Motorcycle", 1)]),
        # the car the writer drives is the ego's, not another road user
        ("I am drive the car to work and a dog runs out.", []),
        ("We were driving a hire van when a tractor pulled out.", [("Truck", 1)]),
        # the host is the ego in a crash typology
        ("The host car brakes for a van halted ahead.", [("Van", 1)]),
    ],
)
def test_riders_and_the_ego_own_vehicle_are_no_extra_actors(
    text: str, named: list[tuple[str, int]]
) -> None:
    assert _named(text) == named


def test_every_numbered_party_takes_its_apposition() -> None:
    # two parties each with an apposition: merging the first must not lose the second
    text = (
        "V1, the AV, was eastbound. V2, a 2015 Ardel Wren hatchback, turned left across it. "
        "V3, a flatbed, waited at the limit line."
    )
    cast = parse(text)
    assert [(m.quote, m.cls.value) for m in cast.others] == [("V2", "Car"), ("V3", "Truck")]


def test_the_insured_is_another_party_when_the_driver_writes() -> None:
    text = (
        "I had stopped at the zebra when the car behind, driven by the insured, "
        "shunted into my rear bumper."
    )
    cast = parse(text)
    assert not any("insured" in text[s.start : s.end] for s in cast.ego)
    assert [m.cls.value for m in cast.others] == ["Car"]


def test_a_generic_car_placed_by_the_ego_is_a_new_one() -> None:
    # "the car behind" is not the lorry named before it
    text = "A skip lorry was parked ahead on the left, and the car behind me hit my rear."
    assert [m.cls.value for m in parse(text).others] == ["Truck", "Car"]


def test_the_junction_box_is_no_box() -> None:
    text = "A van ran the red light and stopped in the junction box; a box junction followed."
    assert [m.cls.value for m in parse(text).others] == ["Van"]


def test_a_bare_noun_in_terse_notes_is_the_one_named_before() -> None:
    # no articles: the second "van" is the first; "car behind" is placed anew
    text = "van stalled in ego lane, ego waits; van restarts. lead car brakes, car behind honks."
    assert [(m.cls.value, len(m.spans)) for m in parse(text).others] == [
        ("Van", 2),
        ("Car", 1),
        ("Car", 1),
    ]


def test_a_vehicle_described_in_brackets_is_one_vehicle_of_that_class() -> None:
    assert _named("POV (grey estate car) from the left lane cuts in front of SV.") == [("Car", 1)]
    assert _named("The other vehicle (a flatbed truck) reversed into us.") == [("Truck", 1)]


def test_a_typology_heading_ended_by_a_full_stop_names_the_same_car() -> None:
    text = "Lead vehicle decelerating. SV follows a minicab on a wet bypass when it brakes hard."
    assert _named(text) == [("Car", 1)]
    # a short first sentence that names the ego is no heading
    assert _named("SV turns left. A van waits opposite.") == [("Van", 1)]


def test_a_road_users_possessive_names_it() -> None:
    text = "A horsebox waits at the lights. A jogger runs past the horsebox's tailgate."
    cast = parse(text)
    [horsebox] = [m for m in cast.others if m.cls.value == "Truck"]
    assert [text[s.start : s.end] for s in horsebox.spans] == ["horsebox", "horsebox's"]


def test_a_principal_other_vehicle_is_one_more_vehicle_in_terse_notes() -> None:
    assert _named("Box truck stopped in LT lane. POV pickup runs red from L.") == [
        ("Truck", 1),
        ("Truck", 1),
    ]


def test_a_distance_before_a_bare_noun_is_no_count() -> None:
    text = "Ped in xwalk crossing R->L. SV stopped ~2 m short of ped."
    assert _named(text) == [("Pedestrian", 1)]


@pytest.mark.parametrize(
    ("text", "named"),
    [
        # An apposition names a generic one: one road user, of the class it names.
        (
            "Vehicle slowing in traffic; following vehicle, a moped, does not brake.",
            [("Motorcycle", 1)],
        ),
        (
            "I had stopped when the third party, driving a grey minivan, rolled into me.",
            [("Van", 1)],
        ),
        # "the third party" said again, and "their" vehicle, are the one named before.
        (
            "A jogger ran out in front of my car. I think the third party never looked.",
            [("Pedestrian", 1)],
        ),
        ("The other party reversed into my door. Their pickup had no lights on.", [("Truck", 1)]),
    ],
)
def test_a_party_or_a_generic_vehicle_is_the_road_user_its_words_name(
    text: str, named: list[tuple[str, int]]
) -> None:
    assert _named(text) == named


@pytest.mark.parametrize(
    ("text", "classes"),
    [
        # the claimant is the other party of a claim: a road user, named properly by the
        # vehicle it rides or drives ...
        (
            "I pulled out to turn right, but the claimant was coming along the main road on "
            "a scooter and we touched.",
            ["Motorcycle"],
        ),
        ("My insured was waiting at the lights when the claimant drove into her.", ["Car"]),
        # ... but not by a vehicle further on in the clause
        ("The claimant was in a hurry and hit a parked van.", ["Car", "Van"]),
        # ... or by its own vehicle, which is the one road user
        ("The claimant's horsebox clipped our insured's mirror.", ["Truck"]),
        # ... also with its make and model, and named again with no article
        (
            "The claimant's 2016 Hollis Tern pickup clipped our mirror. Claimant says the "
            "lane was clear.",
            ["Truck"],
        ),
        # ... and the claimant's account is no road user
        ("Claimant's statement: she was parked when a taxi reversed into her.", ["Car"]),
        # one that runs into the back of the ego is no walker named before it
        (
            "Our insured braked for a boy on the zebra and the claimant hit her rear bumper.",
            ["Pedestrian", "Car"],
        ),
    ],
)
def test_the_claimant_is_one_road_user(text: str, classes: list[str]) -> None:
    assert [m.cls.value for m in parse(text).others] == classes


def test_a_noun_phrase_reaches_back_over_a_year_and_a_made_up_make() -> None:
    text = "The AV was westbound. A northbound 2019 Hollis Tern sedan ran the red light."
    [sedan] = parse(text).others
    assert sedan.quote == "A northbound 2019 Hollis Tern sedan"


@pytest.mark.parametrize(
    ("text", "classes"),
    [
        # a crossing, an island or a phase named by its walkers is a place
        ("The ego slows for the pedestrian crossing as a minicab pulls out.", ["Car"]),
        ("The AV waits by the pedestrian refuge while a tanker turns.", ["Truck"]),
        ("ped phase on, oncoming hatchback turns left across the AV", ["Car"]),
        # ... but a walker crossing is a walker
        ("The ego saw a pedestrian crossing the road.", ["Pedestrian"]),
        ("The van stopped for the pedestrian crossing in front of it.", ["Van", "Pedestrian"]),
    ],
)
def test_a_crossing_named_by_its_walkers_is_a_place(text: str, classes: list[str]) -> None:
    assert [m.cls.value for m in parse(text).others] == classes


def test_the_ego_is_named_by_what_it_is_and_what_is_said_of_it() -> None:
    text = (
        "Test car turns left as I wait in my tipper lorry. The AV, a 2031 Rellan Vesk, keeps going."
    )
    cast = parse(text)
    assert [text[s.start : s.end] for s in cast.ego] == [
        "Test car",
        "I",
        "my tipper lorry",
        "AV",
        "a 2031 Rellan Vesk",
    ]
    assert cast.others == ()


def test_with_no_name_for_the_ego_the_vehicle_is_the_ego() -> None:
    text = "Right-turning vehicle clips a cyclist riding beside it; the vehicle's mirror breaks."
    cast = parse(text)
    assert [text[s.start : s.end] for s in cast.ego] == ["Right-turning vehicle", "the vehicle's"]
    assert [m.cls.value for m in cast.others] == ["Bicycle"]
    introduced = "A vehicle pulls out of a drive and the vehicle stops across the lane."
    assert parse(introduced).ego == ()


def test_the_one_named_last_before_a_word_in_its_sentence() -> None:
    text = "The AV slows. A van ahead brakes hard while the ego waits."
    cast = parse(text)
    assert cast.subject_before(text.index("brakes")).quote == "A van"
    assert cast.subject_before(text.index("waits")) == "ego"
    assert cast.subject_before(text.index("slows")) == "ego"


def test_the_ego_pronoun_with_a_verb_joined_on() -> None:
    text = "You're waiting to turn left and I'm behind a bus."
    cast = parse(text)
    assert [text[s.start : s.end] for s in cast.ego] == ["You're", "I'm"]


def test_the_bike_after_a_motorcyclist_is_that_motorcycle() -> None:
    cast = parse("A motorcyclist runs the red; let the bike clear the junction.")
    assert [(m.cls.value, len(m.spans)) for m in cast.others] == [("Motorcycle", 2)]


def test_the_van_driver_is_the_van() -> None:
    cast = parse("A van waits at the stop line; catch the van driver's eye before you go.")
    assert [(m.cls.value, len(m.spans)) for m in cast.others] == [("Van", 2)]


def test_a_thing_someone_carries_is_no_object_of_the_scene() -> None:
    cast = parse("A man pushing two crates crosses; a crate lies in the lane.")
    assert [(m.cls.value, m.quote) for m in cast.others] == [
        ("Pedestrian", "A man"),
        ("Box", "a crate"),
    ]


def test_the_party_the_writer_says_it_is_is_the_ego() -> None:
    cast = parse("I am the claimant. The insured's van backed into the claimant's car.")
    assert [(m.cls.value, m.quote) for m in cast.others] == [("Van", "The insured's van")]


def test_a_vehicle_in_the_ego_s_lane_is_not_its_own_vehicle() -> None:
    cast = parse("In your lane a van stops suddenly, and I was in my lane a car length back.")
    assert [m.quote for m in cast.others] == ["a van"]


def test_a_list_after_the_ego_is_no_apposition() -> None:
    cast = parse("The scene has the ego, a cyclist, and a van parked on the right.")
    assert [m.quote for m in cast.others] == ["a cyclist", "a van"]


def test_the_writers_vehicle_named_again_is_the_ego() -> None:
    cast = parse("I was driving the van of my firm at the lights. I stopped the van just short.")
    assert cast.others == ()


def test_a_party_described_as_a_walker_is_that_walker() -> None:
    cast = parse("The claimant, an old man with a stick, was on foot in the crosswalk.")
    assert [(m.cls.value, m.quote) for m in cast.others] == [("Pedestrian", "The claimant")]


def test_a_rider_after_a_cyclist_or_pedalling_rides_a_bicycle() -> None:
    cast = parse("Passing a cyclist is hard here. You are behind a rider on the climb.")
    assert [(m.cls.value, len(m.spans)) for m in cast.others] == [("Bicycle", 2)]
    cast = parse("A rider pedalling hard comes up on the left.")
    assert [m.cls.value for m in cast.others] == ["Bicycle"]
    cast = parse("A motorcyclist waits; a rider on a scooter pulls out.")
    assert [m.cls.value for m in cast.others][0] == "Motorcycle"


def test_the_car_a_relative_clause_places_is_a_new_one() -> None:
    text = (
        "A motorbike came against me so I went back behind the lorry. "
        "The car which was following me had to brake hard."
    )
    cast = read_cast(text)
    assert [m.cls.value for m in cast.others] == ["Motorcycle", "Truck", "Car"]


def test_what_the_writer_or_reader_is_is_the_ego() -> None:
    text = "You're the lead car at the lights when a scooter jumps the red from the right."
    assert [m.quote for m in read_cast(text).others] == ["a scooter"]


def test_a_driver_out_of_the_vehicle_is_on_foot() -> None:
    text = "A lorry is broken down on the shoulder and its driver is standing behind it."
    assert [m.cls.value for m in read_cast(text).others] == ["Truck", "Pedestrian"]
    text = "A street sweeper worker stands by the cones; the van driver waves us on."
    assert "Pedestrian" in [m.cls.value for m in read_cast(text).others]


def test_pick_up_as_a_verb_and_a_wheeled_thing_are_read_as_meant() -> None:
    text = "A lorry ahead of the ego has stopped so that a man can pick up a box."
    assert [m.cls.value for m in read_cast(text).others] == ["Truck", "Pedestrian", "Box"]
    text = "The AV clipped a wheeled recycling bin left out in its lane."
    assert [m.cls.value for m in read_cast(text).others] == ["Trash"]


def test_the_turning_vehicle_of_a_typology_line_is_the_ego() -> None:
    text = "At dusk the turning vehicle, going left at the lights, meets a van from the opposite direction."
    cast = read_cast(text)
    assert [m.quote for m in cast.others] == ["a van"]
    # with another name for the ego, "the turning vehicle" is someone else
    text = "The AV went straight on and the turning vehicle cut across its path."
    assert [m.quote for m in read_cast(text).others] == ["the turning vehicle"]


def test_the_one_who_runs_out_from_the_front_of_a_bus_is_the_adversary() -> None:
    text = (
        "A bus stood at the stop with its doors open. As the ego passed, a girl ran out "
        "from the front of the bus."
    )
    reading = read_description(text)
    assert reading.adversary is not None and reading.adversary.quote == "a girl"
    roles = [a.role.value for a in read_actors(reading) if a.scenic_class.value == "Bus"]
    assert roles == ["occluder"]


def test_a_participle_after_another_named_is_the_subjects() -> None:
    text = (
        "A lorry stood in the far lane. A boy ran out from behind the lorry, heading from "
        "your right into your lane."
    )
    assert read_description(text).facts["spawn_position"].value == "crossing_road_from_right"


@pytest.mark.parametrize(
    ("text", "named"),
    [
        # a report's number for the thing just named: that thing, of its noun's class
        ("V1 was northbound. A tour coach (V2) was stopped at the kerb.", [("Bus", 2)]),
        ("V1 was northbound. A tipper truck, V2, was stopped at the kerb.", [("Truck", 2)]),
        # what a walker is, said again between commas: one walker
        ("V1 was northbound. A pedestrian (P1), an older woman, crossed.", [("Pedestrian", 3)]),
        # a list is not an apposition
        (
            "The ego passes a man, a woman, and a child.",
            [("Pedestrian", 1), ("Pedestrian", 1), ("Pedestrian", 1)],
        ),
    ],
)
def test_a_number_or_an_apposition_names_the_thing_just_named(
    text: str, named: list[tuple[str, int]]
) -> None:
    assert [(m.cls.value, len(m.spans)) for m in read_cast(text).others] == named


def test_ones_own_vehicle_or_driver_is_not_one_more() -> None:
    text = "P1, a courier, was riding north. The front wheel of P1's bicycle struck the AV's door."
    assert [(m.cls.value, m.count) for m in read_cast(text).others] == [("Bicycle", 1)]
    text = "The AV was rear-ended by a tipper truck whose driver failed to stop."
    assert [m.cls.value for m in read_cast(text).others] == ["Truck"]


@pytest.mark.parametrize(
    ("text", "count"),
    [
        ("Half a dozen cones stand in the ego's lane.", 6),
        ("2-lane rd, 3x cones in ego lane ahead.", 3),
        ("12 cones line the ego's lane ahead.", 12),
        ("At 25 mph a cyclist pulls out in front of the ego.", 1),
    ],
)
def test_counts_said_many_ways(text: str, count: int) -> None:
    assert read_cast(text).others[0].count == count


def test_of_those_that_meet_no_one_the_one_moving_into_the_road_is_the_adversary() -> None:
    text = (
        "A moped is tucked in close behind you, so braking hard is risky. A girl darts into "
        "the road from between two parked vans on the left."
    )
    reading = read_description(text)
    assert reading.adversary is not None and reading.adversary.quote == "A girl"


def test_behind_him_at_a_sentences_start_places_by_the_one_named_before() -> None:
    text = (
        "At the crossroad I wait to turn left. Against me is coming one taxi, so I let him "
        "go. Behind him a tipper truck is turning to his right side."
    )
    actors = read_actors(read_description(text))
    assert [(a.scenic_class.value, a.start and a.start.value) for a in actors] == [
        ("Truck", "oncoming")
    ]


def test_the_rest_of_a_negated_list_and_a_measure_are_no_actors() -> None:
    text = "A drum stood in my lane; there were no cones, signs or lorries about."
    assert [m.cls.value for m in read_cast(text).others] == ["Barrel"]
    text = "A builder's skip stood in the road, poking about a car's width into my lane."
    assert [m.cls.value for m in read_cast(text).others] == ["Container"]
