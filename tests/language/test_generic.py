"""Lessons and orders in a description name kinds of road users, not actors of the scene."""

from __future__ import annotations

import pytest

from arise.language.cast import read_cast
from arise.language.generic import lessons_of
from arise.language.readers import read_description


def _named(text: str) -> list[str]:
    return [m.quote for m in read_cast(text).others]


@pytest.mark.parametrize(
    ("text", "actors"),
    [
        # a lesson ("whenever", "usually", "rule of thumb") names a kind
        (
            "You pass a row of three parked vans at 25 mph. A boy runs out between them. "
            "Slow right down whenever you drive past parked vans on a school run.",
            ["three parked vans", "A boy"],
        ),
        (
            "A cyclist ahead of you wobbles on the gravel. Where there is gravel there is "
            "usually a rider in trouble.",
            ["A cyclist"],
        ),
        (
            "As a rule of thumb, a lorry that waits at a green has seen something; here a "
            "bus on your left waits while you move off.",
            ["a bus"],
        ),
        # an order names plural kinds; a road user it points at is still in the scene
        (
            "You turn left into a narrow lane. Before any turn, check for pedestrians "
            "stepping off the kerb. A jogger is crossing the lane.",
            ["A jogger"],
        ),
        (
            "Check your mirror: a van is coming up fast on your right.",
            ["a van"],
        ),
        # drivers at large are no actor; "the drivers" of a scene are
        (
            "Roundabouts confuse experienced drivers. A taxi cuts across you from the left.",
            ["A taxi"],
        ),
        # what the junction is empty of is not in it
        ("The AV turns right; the junction was otherwise empty of cars.", []),
    ],
)
def test_lessons_and_orders_name_no_new_actor(text: str, actors: list[str]) -> None:
    assert _named(text) == actors


def test_a_subject_before_the_verb_makes_no_order() -> None:
    text = "When you turn left at the lights, you yield to cars coming the other way."
    assert lessons_of(text).orders == ()
    picture = "Picture yourself on a quiet road at dusk. Imagine cars parked on both sides."
    assert lessons_of(picture).orders == ()


def test_weather_of_a_lesson_is_no_scene_weather() -> None:
    lesson = "A cyclist rides ahead of you. In fog you should always leave him twice the room."
    assert read_description(lesson).weather.fact.value == "ClearNoon"
    scene = "At night, keep scanning the right kerb: a child may step out behind a bus."
    assert read_description(scene).weather.fact.value == "ClearNight"
