"""Whether a text is about traffic, and what in it cannot all hold, from the language layer."""

from __future__ import annotations

import pytest

from arise.language.readers import read_description
from arise.language.sense import is_about_traffic, self_contradictions


@pytest.mark.parametrize(
    ("text", "about"),
    [
        ("Bake a chocolate cake for twelve people.", False),
        ("Write me a poem about the sea.", False),
        ("ego LT at 4-way", True),  # terse notes have no article and no verb form of "drive"
        ("Vehicle going straight; other vehicle drifts over.", True),
        ("Turn left at the lights.", True),
    ],
)
def test_a_text_is_about_traffic_when_it_names_someone_or_a_road(text: str, about: bool) -> None:
    assert is_about_traffic(text) is about


def test_a_turn_of_another_road_user_is_not_the_egos() -> None:
    reading = read_description("The ego turns right while an oncoming taxi turns left.")
    assert self_contradictions(reading) == []


def test_the_ego_turning_both_ways_cannot_hold() -> None:
    reading = read_description("The ego turns left at the corner and then the ego turns right.")
    assert self_contradictions(reading) == ["the description has the ego turn both left and right"]


def test_a_walker_on_a_highway_is_flagged() -> None:
    reading = read_description("On the highway a pedestrian walks across the ego's lane.")
    assert "pedestrians and sidewalks do not belong on a highway" in self_contradictions(reading)
