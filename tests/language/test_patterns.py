"""The phrase pattern language the reading rules are written in."""

from __future__ import annotations

import pytest

from arise.language.errors import RuleError
from arise.language.lexicon import lexicon
from arise.language.patterns import compile_pattern

CLASSES = {"side": ("left", "right"), "ego": ("ego", "ego vehicle", "av")}


@pytest.mark.parametrize(
    ("pattern", "text", "found"),
    [
        ("oncoming", "an oncoming van", "oncoming"),
        ("oncoming", "an oncomingvan", None),  # whole words only
        ("right front", "on the right-front", "right-front"),
        ("left-hand lane", "in the left hand lane", "left hand lane"),
        ("overtak*", "it overtakes the ego", "overtakes"),
        ("turns left|right", "then turns right", "turns right"),
        ("the? bus stop", "near bus stop", "bus stop"),
        ("in ~ lane", "in the lane", "in the lane"),
        ("ahead in", "ahead, in the lane", "ahead, in"),
        ("lane to the? @ego", "the lane to the ego vehicle", "lane to the ego vehicle"),
        (
            "stop|stops ... then go",
            "stops at the line and then go",
            "stops at the line and then go",
        ),
        ("stop|stops ... then go", "stops. Then go", None),  # not across sentences
        ("<side> turn !left|right", "a right turn left", None),
        ("<side> turn !left|right", "a right turn ahead", "right turn"),
        ("junction", "a non-junction stretch", None),  # a hyphenated word is one word
        ("# m|metres", "stops 20 m short", "20 m"),
        ("# m|metres", "stops 20m short", "20m"),
        ("# m|metres", "stops 2.5 metres short", "2.5 metres"),
        ("# m|metres", "stops 20 mph short", None),
        ("# m|metres", "stops m short", None),
        ("within #", "passes within 2m of it", "within 2m"),
    ],
)
def test_a_pattern_matches_whole_words(pattern: str, text: str, found: str | None) -> None:
    match = compile_pattern(pattern, CLASSES).search(text)
    if found is None:
        assert match is None
    else:
        assert match is not None and match.group(0).endswith(found)


def test_a_slot_gives_the_word_it_matched() -> None:
    match = compile_pattern("in the <side> lane", CLASSES).search("in the Left lane")
    assert match is not None and match.group("side") == "Left"


@pytest.mark.parametrize("pattern", ["", "<nowhere>", "@nowhere", "the? a?", "left;right"])
def test_a_malformed_pattern_is_a_rule_error(pattern: str) -> None:
    with pytest.raises(RuleError):
        compile_pattern(pattern, CLASSES)


def test_a_plain_the_before_a_possessive_is_refused() -> None:
    # alternatives are single words: "the ego's|its lane" would need "the its lane"
    with pytest.raises(RuleError, match="the\\?"):
        compile_pattern("into the ego's|its lane", lexicon().classes)
    assert compile_pattern("into the? ego's|its lane", lexicon().classes).search("into its lane")


def test_a_verb_with_a_plus_matches_every_form_of_it() -> None:
    from arise.language.patterns import compile_pattern, verb_forms

    assert verb_forms("cross") == ("cross", "crosses", "crossed", "crossing")
    assert verb_forms("move") == ("move", "moves", "moved", "moving")
    assert verb_forms("carry") == ("carry", "carries", "carried", "carrying")
    assert verb_forms("see") == ("see", "sees", "seed", "seeing")
    pattern = compile_pattern("ride+ toward us", {}, {"ride": ("rode", "ridden")})
    for text in ("rides toward us", "rode toward us", "riding toward us", "ride toward us"):
        assert pattern.search(text), text
    assert not pattern.search("rider toward us")
