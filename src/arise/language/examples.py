"""What the fixed rules read from a description, by whom, as plain strings: what every
reading rule's examples are checked against (tests/language/test_rule_examples.py)."""

from __future__ import annotations

from arise.language.actors import read_actor
from arise.language.readers import read_description, read_start, read_stationary
from arise.language.rules import Fact, rulebook


def read_facts(description: str) -> dict[str, dict[str, str]]:
    """Every fact the rules read from `description`, by whom: "ego", "scene" (with
    "requirement.KIND" for each requirement its words state), and each other actor by its
    quote (with its role unless it is the adversary). What a rule's examples are checked against
    (tests/language/test_rule_examples.py)."""
    reading = read_description(description)
    cast = reading.cast
    found: dict[str, dict[str, str]] = {"ego": {}, "scene": {}}
    for hit in rulebook().hits(Fact.REQUIREMENT, description):
        found["scene"][f"requirement.{hit.value}"] = "true"
    for mention in cast.others:
        facts: dict[str, str] = {"class": mention.cls.value, "count": str(mention.count)}
        if mention is not reading.adversary:
            facts["role"] = read_actor(cast, mention).role.value
        position = read_start(cast, mention)
        if position is not None:
            facts[Fact.START.value] = position.value
        if read_stationary(cast, mention) is not None:
            facts[Fact.STATIONARY.value] = "true"
        found[mention.quote] = facts
    names = {
        "ego_maneuver": ("ego", "maneuver"),
        "ego_lane_side": ("ego", Fact.LANE_SIDE.value),
        "ego_plan": ("ego", Fact.EGO_PLAN.value),
        "ego_stopped": ("ego", Fact.EGO_HELD.value),
        "ego_on_ramp": ("ego", Fact.EGO_ON_RAMP.value),
        "weather": ("scene", "weather"),
        "road_type": ("scene", Fact.ROAD.value),
        "quantity": ("scene", Fact.QUANTITY.value),
        "contact_stated": ("scene", Fact.MEETING.value),
        "timing": ("scene", Fact.TIMING.value),
        "ego_speed": ("ego", "speed"),
        "unread_measure": ("scene", Fact.MEASURE.value),
    }
    for name, fact in reading.facts.items():
        if name in names:
            who, key = names[name]
            found[who][key] = fact.value
    if reading.weather is not None:
        if reading.weather.light is not None:
            found["scene"][Fact.LIGHT.value] = reading.weather.light.value
        if reading.weather.parameters is not None:
            found["scene"][Fact.VISIBILITY.value] = reading.weather.visibility.value
    if reading.adversary is not None:
        adversary = found[reading.adversary.quote]
        adversary["adversary"] = "true"
        for name in ("adversary_maneuver", "start_detail"):
            if name in reading.facts:
                adversary[name] = reading.facts[name].value
        if "adversary_turns_back" in reading.facts:
            adversary[Fact.TURNS_BACK.value] = reading.facts["adversary_turns_back"].value
        if "adversary_speed" in reading.facts:
            adversary["speed"] = reading.facts["adversary_speed"].value
        if "spawn_position" in reading.facts:  # after the readers of the whole scene
            adversary[Fact.START.value] = reading.facts["spawn_position"].value
    return found
