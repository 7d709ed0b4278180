"""Crash-report paragraphs are reduced to the scenario (texts written for these tests)."""

from __future__ import annotations

from arise.language.condense import condense

REPORT = (
    "On October 9, 2026 at 7:15 AM, the AV was travelling westbound on Brill Road at "
    "19 mph. A delivery van reversing out of a driveway on the right made contact with "
    "the AV's passenger door. The van's tail light was cracked and the AV's door was "
    "dented. The van driver was cited by police. No injuries were reported."
)


def test_the_date_and_the_aftermath_are_left_out_and_listed() -> None:
    condensed = condense(REPORT)
    assert condensed.text == (
        "The AV was travelling westbound on Brill Road at 19 mph. A delivery van reversing "
        "out of a driveway on the right made contact with the AV's passenger door."
    )
    assert condensed.ignored == [
        "On October 9, 2026 at 7:15 AM",
        "The van's tail light was cracked and the AV's door was dented.",
        "The van driver was cited by police.",
        "No injuries were reported.",
    ]


def test_a_sentence_that_tells_what_happened_is_kept_whatever_else_it_says() -> None:
    text = "A scooter hit the ego's mirror and the rider was taken to hospital."
    assert condense(text).text == text and condense(text).ignored == []


def test_a_short_description_is_left_as_it_is() -> None:
    text = "The ego turns left while an oncoming pickup goes straight."
    assert condense(text).text == text
    assert condense("No injuries were reported.").text == "No injuries were reported."


def test_a_sentence_of_someone_coming_towards_the_ego_is_kept() -> None:
    """ "towards" is no tow truck: the sentence tells where a road user comes from."""
    text = "The ego waits behind a van. A cyclist is heading towards you on the other side."
    assert condense(text).text == text
