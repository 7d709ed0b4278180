"""Whose is each verb: clauses and their subjects, and the classes of language the issue
names (a side said while the ego turns, two roles in one scene, the subject carried over).
Every sentence here is written for these tests."""

from __future__ import annotations

import pytest

from arise.language.examples import read_facts
from arise.language.reading import parse


def _subject_of(text: str, words: str) -> str | None:
    cast = parse(text)
    subject = cast.subject_at(text.index(words))
    if subject is None or isinstance(subject, str):
        return subject
    return subject.quote


@pytest.mark.parametrize(
    ("text", "words", "subject"),
    [
        # the subject carries over past a relative clause about someone else
        ("The ego trails a van that slows, then pulls out to pass it.", "pulls out", "ego"),
        ("A van that the ego trails slows down.", "slows", "A van"),
        # a participle right after an actor is that actor's
        ("The ego follows a tractor turning left.", "turning left", "a tractor"),
        # a sentence that opens with a participle takes the subject after it
        ("Turning right at the lights, the ego meets a runner.", "Turning right", "ego"),
        # a leading prepositional phrase is no subject
        ("At the roundabout the ego turns left.", "turns left", "ego"),
        # an actor after a preposition is not the clause's subject
        ("In front of the ego a scooter brakes.", "brakes", "a scooter"),
        # "it" opening a clause continues the subject that agrees in number
        ("A cab stops, and it then reverses.", "reverses", "A cab"),
        ("Two joggers cross while it waits at the line.", "waits", "ego"),
        # a place opening the clause puts the subject after its verb
        ("The ego waits. Out of the side road is coming a tractor.", "is coming", "a tractor"),
        ("The ego brakes, then from behind a moped is coming fast.", "fast", "a moped"),
        (
            "I pull out, but along the outside lane from far behind arrive very fast two bikes.",
            "arrive",
            "two bikes",
        ),
        ("The ego slowed. Out of the fog came a tractor.", "came", "a tractor"),
        # "It" opening a sentence means one named before, not a later sentence's subject
        (
            "My car was in the left lane. A van was parked on my right. It pulled out. "
            "I braked hard.",
            "pulled out",
            "A van",
        ),
        # "between X and Y" joins two places, not two clauses
        (
            "The ego waits at the lights. A scooter squeezes between the ego and a bus,"
            " clips the ego's mirror.",
            "clips",
            "A scooter",
        ),
        # an ego named right after a verb of contact is its object
        ("A moped filters up, clips the ego's mirror.", "clips", "A moped"),
        ("SV waits at red. Moto filters up, clips SV R mirror.", "clips", "Moto"),
        # a pronoun after a fronted phrase is still the subject
        ("On the ring road you change lanes to the right.", "change lanes", "ego"),
        # an instruction to the driver is the ego's, and so is the clause opening its
        # sentence; a road user after the instruction's verb is its object
        (
            "Before pulling into the right lane to pass a horsebox, glance over your shoulder.",
            "pulling into",
            "ego",
        ),
        ("When the road is clear, ease out and overtake the milk float.", "overtake", "ego"),
        ("Stop sign at the crossroads, a coach waits.", "waits", "a coach"),
        # a base verb after two road users is theirs (no instruction)
        ("Two joggers stop at the kerb and cross.", "cross", "Two joggers"),
        # spoken to "you", an instruction is the ego's even after a clause about another
        (
            "You sit behind the skip lorry. Wait until the cyclist has gone by, then pull out.",
            "pull out",
            "ego",
        ),
        ("You wait as two joggers stop and cross.", "cross", "two joggers"),
        # a past form after a place is the verb of the subject before the place, and a
        # state there describes the one in the place
        (
            "A moped in the bus lane to the right of the AV veered into its path.",
            "veered",
            "A moped",
        ),
        (
            "A jogger running on the verge beside the SV darted out.",
            "darted",
            "A jogger",
        ),
        ("A child steps out from behind a horsebox parked at the kerb.", "parked", "a horsebox"),
        ("We pass a coach halted in the far lane.", "halted", "a coach"),
        # a participle opening the sentence is the next clause's subject's, and the actor
        # after it is its object; a word that opens an actor's name is no participle
        ("Overtaking a milk float on the hill, the AV meets a van.", "Overtaking", "ego"),
        ("oncoming hatchback goes straight, the ego waits.", "goes straight", "oncoming hatchback"),
        # "which then": still the one before the relative word
        (
            "The AV is tailed by a horsebox, which then swings into the right lane.",
            "swings",
            "a horsebox",
        ),
        # a sentence's opening phrases are the subject's named after them
        ("Ahead, on the bridge, a tractor has stopped.", "on the bridge", "a tractor"),
    ],
)
def test_each_verb_has_the_subject_of_its_clause(text: str, words: str, subject: str) -> None:
    if text.startswith("Two joggers"):
        text = "The ego stops. " + text
    assert _subject_of(text, words) == subject


def test_a_side_said_while_the_ego_turns_is_the_actors_own() -> None:
    text = "While the ego turns left at the lights, a courier bike on the right front carries on."
    facts = read_facts(text)
    assert facts["ego"]["maneuver"] == "turn_left"
    assert facts["a courier bike"]["start"] == "adjacent_lane_right"


def test_two_roles_in_one_scene_stay_two_actors() -> None:
    text = (
        "The ego is stuck behind a slow tractor and moves into the left lane, where a "
        "motorbike is coming up from behind in the left lane."
    )
    facts = read_facts(text)
    assert facts["ego"]["maneuver"] == "change_lane"
    assert facts["ego"]["lane_side"] == "left"
    assert facts["a slow tractor"]["start"] == "ahead_same_lane"
    assert facts["a motorbike"]["start"] == "adjacent_lane_left"


def test_a_parked_car_and_a_walker_each_keep_their_own_words() -> None:
    text = "A van is parked on the right; a man steps out from the left in front of the ego."
    facts = read_facts(text)
    assert facts["A van"]["start"] == "roadside_right"
    assert facts["A van"]["stationary"] == "true"
    assert facts["a man"]["start"] == "crossing_road_from_left"
    assert "stationary" not in facts["a man"]


def test_a_subject_after_its_verb_keeps_the_place_before_it() -> None:
    text = (
        "Our car is waiting to turn. From right side is coming a lorry, and from the "
        "left also comes a scooter."
    )
    facts = read_facts(text)
    assert facts["a lorry"]["start"] == "crossing_road_from_right"
    assert facts["a scooter"]["start"] == "crossing_road_from_left"


def test_a_clause_that_names_another_subject_ends_an_actors_words() -> None:
    """ "from the left" is the ego's here, not the lorry's."""
    text = "Ahead of us goes a slow lorry, and the ego wants to pass it from the left side."
    facts = read_facts(text)
    assert facts["a slow lorry"].get("start") != "crossing_road_from_left"


def test_he_after_we_is_the_other_driver() -> None:
    text = (
        "A van is parked at left side of road, and when we come near, he starts suddenly "
        "and goes out into our lane."
    )
    cast = parse(text)
    assert cast.subject_at(text.index("starts suddenly")) is cast.others[0]
    assert cast.subject_at(text.index("goes out")) is cast.others[0]
    facts = read_facts(text)
    assert "stationary" not in facts["A van"]


def test_a_noun_phrase_does_not_reach_back_across_a_preposition() -> None:
    """ "was in the next lane a little ahead of V1 when ...": V1 is no subject of that
    clause; the words before "ahead" are not its phrase."""
    from arise.language.cast import phrase_start

    text = "V2, a lorry, was in the next lane a little ahead of V1 when its driver braked."
    assert phrase_start(text, text.index("V1")) == text.index("V1")
    assert phrase_start(text, text.index("lorry")) == text.index("a lorry")
    cast = parse(text)
    was = next(c for c in cast.clauses if cast.text[c.start : c.end].strip().startswith("was"))
    assert was.subject is not None and was.subject != "ego"
