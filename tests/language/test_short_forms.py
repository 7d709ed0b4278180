"""Terse notes: the stop of a short form ends no sentence; a year opens an apposition."""

from __future__ import annotations

import pytest

from arise.language.cast import read_cast, sentence_end
from arise.language.readers import read_description


def test_the_stop_of_a_short_form_ends_no_sentence() -> None:
    text = "AV SB, approx. 20 mph, unprot. LT at lights. Moped opp. lane runs red."
    assert text[: sentence_end(text, 0)] == "AV SB, approx. 20 mph, unprot. LT at lights"
    assert read_description(text).facts["ego_maneuver"].value == "turn_left"


def test_a_model_year_after_the_egos_name_is_the_ego() -> None:
    text = (
        "V1 (2025 Pellor Ardent, driving itself) was northbound. V2, a 2014 Orsk van, "
        "came south and turned across V1."
    )
    cast = read_cast(text)
    assert [text[s.start : s.end] for s in cast.ego] == ["V1", "2025 Pellor Ardent", "V1"]
    assert [m.quote for m in cast.others] == ["V2"]


def test_what_the_ego_is_may_follow_under_test_and_end_its_sentence() -> None:
    text = (
        "Unit 1, the autonomous vehicle under test, a 2025 Ostry Vale, followed Unit 2. "
        "V1 is the self-driving prototype under evaluation, a 2026 Lumo Brisk with a driver."
    )
    cast = read_cast(text)
    assert [m.quote for m in cast.others] == ["Unit 2"]


def test_the_ego_numbered_2_is_read_as_the_rules_read_v1() -> None:
    from arise.language.numbered import ego_number_view

    text = "At the crossroads V2 (the AV) went straight; V1's nose hit V2's left rear door."
    assert ego_number_view(text) == (
        "At the crossroads V1 (the AV) went straight; V2's nose hit V1's left rear door."
    )
    reading = read_description(text)
    assert reading.facts["spawn_position"].value == "crossing_road_from_left"
    assert "V2's left rear" in reading.facts["spawn_position"].quote  # quoted as written
    assert ego_number_view("V1 turned left; V2 came on.") == "V1 turned left; V2 came on."


def test_a_title_ends_no_sentence_so_the_egos_heading_after_a_name_is_read() -> None:
    text = (
        "Our insured, Dr. Ines Walde, was eastbound on Harlow Street when a westbound van "
        "drifted over the centre line."
    )
    assert sentence_end(text, 0) == len(text) - 1
    assert read_description(text).facts["spawn_position"].value == "oncoming"


def test_a_heading_at_the_end_of_a_sentence_is_not_the_next_ones() -> None:
    text = (
        "Unit 1 was westbound and stopped at the four-way stop. A bus stood on the opposite "
        "approach, facing east. Unit 2, a sedan on the cross street, struck Unit 1's right "
        "rear door."
    )
    assert read_description(text).facts["spawn_position"].value == "crossing_road_from_right"


@pytest.mark.parametrize(
    ("text", "turn"),
    [
        ("V1 was eastbound on Hale Street and turned onto northbound Pike Avenue.", "turn_left"),
        ("Unit 1 was southbound and entered the junction to go west on Mill Road.", "turn_right"),
        ("V1 was northbound and kept northbound through the junction.", None),
    ],
)
def test_a_turn_told_by_compass_headings_alone(text: str, turn: str | None) -> None:
    found = read_description(text + " A van came the other way.").facts.get("ego_maneuver")
    assert (found.value if found else None) in ((turn,) if turn else (None, "go_straight"))
