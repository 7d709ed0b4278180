"""Whether a text is about traffic at all, and what in it cannot all hold: read from the
cast and the rules, never from raw keyword lists of another stage."""

from __future__ import annotations

from arise.language.cast import read_cast
from arise.language.lexicon import class_pattern
from arise.language.readers import Reading, ego_turns
from arise.vocabulary import RoadType


def is_about_traffic(text: str) -> bool:
    """The text names the ego, a vehicle or an object of the road (the lexicon's nouns), or a
    place or act of driving (the lexicon class `traffic_words`). People alone do not count:
    "a cake for twelve people" is no scenario."""
    cast = read_cast(text)
    named = any(not m.cls.is_walker for m in cast.others)
    return bool(cast.ego) or named or bool(class_pattern("traffic_words").search(text))


def self_contradictions(reading: Reading) -> list[str]:
    """Statements of one description that cannot all hold: the ego turning both ways, a
    walker on a highway."""
    found = []
    cast = reading.cast
    if len(ego_turns(cast)) == 2:
        found.append("the description has the ego turn both left and right")
    road = reading.facts.get("road_type")
    walkers = [m for m in cast.others if m.cls.is_walker]
    if road is not None and road.value == RoadType.HIGHWAY.value and walkers:
        found.append("pedestrians and sidewalks do not belong on a highway")
    return found
