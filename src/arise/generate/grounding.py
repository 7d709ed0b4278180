"""Grounded extraction: every fact of the spec rests on words of the description.

The model proposes; the description decides. Each fact the spec carries says where it came
from (`FactSource`):

- TEXT: a fixed rule read it from the description's words (`arise.language`: its readers, weather words and rules),
  attributed to the actor the words are about;
- MODEL: the model's answer, kept with a quote that is really in the description;
- GUESS: the model's answer with no words behind it (kept where something is needed,
  marked, and never held against a script by the semantic gate);
- DEFAULT: the description does not say, so a neutral value (clear noon, going
  straight, an ordinary road, no other participants).

A quote that is not in the description is rejected mechanically, whatever the model says.
"""

from __future__ import annotations

import re
from dataclasses import asdict, dataclass

from arise.generate.spec import (
    Actor,
    ExtractionAnswer,
    Requirement,
    RequirementKind,
    ScenarioSpec,
)
from arise.language.actors import read_actors
from arise.language.facts import FactSource, GroundedFact
from arise.language.quotes import quote_in
from arise.language.readers import (
    Reading,
    adversary_type_of,
    choose_adversary,
    read_description,
    words_of,
)
from arise.language.rules import Fact, rulebook
from arise.vocabulary import (
    ActorClass,
    AdversaryManeuver,
    AdversaryType,
    EgoManeuver,
    EgoPlan,
    RelativePosition,
    RoadType,
    Side,
    StartDetail,
    Timing,
)

# -- the grounded spec ----------------------------------------------------------------------

# Kinds that cannot hold for an adversary that starts at this position.
_REQUIREMENT_CONFLICTS: dict[RequirementKind, set[RelativePosition]] = {
    RequirementKind.SAME_DIRECTION: {
        RelativePosition.ONCOMING,
        RelativePosition.CROSSING_FROM_LEFT,
        RelativePosition.CROSSING_FROM_RIGHT,
    },
    RequirementKind.OPPOSITE_DIRECTION: {
        RelativePosition.AHEAD_SAME_LANE,
        RelativePosition.BEHIND_SAME_LANE,
        RelativePosition.ADJACENT_LANE_LEFT,
        RelativePosition.ADJACENT_LANE_RIGHT,
        RelativePosition.CROSSING_FROM_LEFT,
        RelativePosition.CROSSING_FROM_RIGHT,
    },
}
_WALKER_STARTS = frozenset(
    {
        RelativePosition.ROADSIDE_LEFT,
        RelativePosition.ROADSIDE_RIGHT,
        RelativePosition.CROSSING_FROM_LEFT,
        RelativePosition.CROSSING_FROM_RIGHT,
        RelativePosition.AHEAD_SAME_LANE,
    }
)


@dataclass
class Grounded:
    """The grounded spec and a note for each model answer that was overruled or dropped."""

    spec: ScenarioSpec
    notes: list[str]


def _fact(name: str, value: str, source: FactSource, quote: str | None = None) -> GroundedFact:
    return GroundedFact(name=name, value=value, source=source, quote=quote)


def _model_fact(name: str, value: str, description: str, quote: str) -> GroundedFact:
    """The model's value, MODEL with its quote when the quote is in the text, else GUESS."""
    if quote_in(description, quote):
        return _fact(name, value, FactSource.MODEL, quote.strip())
    return _fact(name, value, FactSource.GUESS)


def _requirements(
    description: str, answer: ExtractionAnswer, position: RelativePosition
) -> tuple[list[Requirement], list[str]]:
    """The model's requirements that the text states in words (one per kind)."""
    kept: list[Requirement] = []
    notes: list[str] = []
    for requirement in answer.requirements:
        if requirement.kind in {r.kind for r in kept}:
            continue
        # The evidence a requirement of each kind needs in the text (rules of `requirement`);
        # the words are its quote.
        evidence = next(
            (
                hit
                for hit in rulebook().hits(Fact.REQUIREMENT, description)
                if hit.value == requirement.kind
            ),
            None,
        )
        if evidence is None:
            notes.append(
                f"requirements: dropped {requirement.kind} (not stated in the description)"
            )
        elif position in _REQUIREMENT_CONFLICTS.get(requirement.kind, set()):
            notes.append(f"requirements: dropped {requirement.kind} (contradicts {position})")
        else:
            kept.append(Requirement(kind=requirement.kind, text=evidence.quote))
    return kept, notes


def _participants(reading: Reading) -> list[str]:
    """The words about each other thing the description names (never the adversary)."""
    cast = reading.cast
    found = []
    for mention in cast.others:
        if mention is reading.adversary:
            continue
        start, end = words_of(cast, mention)[0]
        words = re.sub(r"\s+", " ", cast.text[start:end]).strip(" ,;.")
        found.append(words or mention.quote)
    return found


def answer_from_reading(reading: Reading, *, partial: bool = False) -> ExtractionAnswer | None:
    """The answer the model would be asked for, from the fixed rules alone: when they read
    the adversary and where it starts, or that no road user is named; else None (the model
    must be asked), unless `partial` (no model answer to be had): then neutral defaults
    fill what they leave open. Free text is the description's own words about each part."""
    cast = reading.cast
    facts = reading.facts
    road_users = [m for m in cast.others if adversary_type_of(m.cls) is not None]
    adversary = reading.adversary
    if not partial and road_users and (adversary is None or "spawn_position" not in facts):
        return None

    def value(name: str, default: str) -> str:
        return facts[name].value if name in facts else default

    def words(stretches: list[tuple[int, int]]) -> str:
        """The longest stretch of words about it: one piece of the text, so a quote."""
        start, end = max(stretches, key=lambda s: s[1] - s[0])
        return re.sub(r"\s+", " ", cast.text[start:end]).strip(" ,;.")

    def quoted(name: str) -> str:
        quote = facts[name].quote if name in facts else None
        return quote if quote and quote_in(cast.text, quote) else ""

    kind = adversary_type_of(adversary.cls) if adversary is not None else None
    position = facts.get("spawn_position")
    requirements = {
        hit.value: Requirement(kind=RequirementKind(hit.value), text=hit.quote)
        for hit in rulebook().hits(Fact.REQUIREMENT, cast.text)
    }
    return ExtractionAnswer(
        adversary=adversary.quote if adversary is not None else "",
        adversary_type=kind or AdversaryType.CAR,
        behavior=words(words_of(cast, adversary)) if adversary is not None else "",
        road_type=RoadType(value("road_type", RoadType.STRAIGHT.value)),
        ego_maneuver=EgoManeuver(value("ego_maneuver", EgoManeuver.GO_STRAIGHT.value)),
        geometry=quoted("ego_maneuver") or quoted("road_type"),
        spawn_position=RelativePosition(
            position.value if position else RelativePosition.AHEAD_SAME_LANE.value
        ),
        spawn=quoted("spawn_position"),
        participants=[],
        requirements=list(requirements.values()),
    )


def ground(description: str, answer: ExtractionAnswer, read: Reading | None = None) -> Grounded:
    """The spec of `description`: the fixed rules' readings first, the model's answers
    where they rest on words of the text, neutral defaults for what the text leaves open.
    `read`, the description's reading already made, is used again when the answer's
    adversary is the one it chose (the reading would be the same)."""
    notes: list[str] = []
    adversary_quote = answer.adversary if quote_in(description, answer.adversary) else None
    if answer.adversary and adversary_quote is None:
        notes.append(
            f"adversary: the model's words {answer.adversary!r} are not in the description"
        )
    if read is not None and choose_adversary(read.cast, adversary_quote) is read.adversary:
        reading = read
    else:
        reading = read_description(description, adversary_quote)
    facts = dict(reading.facts)
    adversary_class: ActorClass | None = None
    if reading.adversary is not None and (kind := adversary_type_of(reading.adversary.cls)):
        adversary_class = reading.adversary.cls
        facts["adversary_type"] = _fact(
            "adversary_type", kind.value, FactSource.TEXT, reading.adversary.quote
        )
    else:
        facts["adversary_type"] = _model_fact(
            "adversary_type", answer.adversary_type.value, description, answer.adversary
        )
    no_adversary = not any(adversary_type_of(m.cls) for m in reading.cast.others)
    if no_adversary:
        facts["adversary"] = _fact(
            "adversary", "none (the description names no other road user)", FactSource.DEFAULT
        )
    if "spawn_position" not in facts:
        if adversary_class is ActorClass.PEDESTRIAN and answer.spawn_position not in _WALKER_STARTS:
            # A walker does not start in a traffic lane: the near kerb, unless the text says.
            facts["spawn_position"] = _fact(
                "spawn_position", RelativePosition.ROADSIDE_RIGHT.value, FactSource.DEFAULT
            )
        else:
            facts["spawn_position"] = _model_fact(
                "spawn_position", answer.spawn_position.value, description, answer.spawn
            )
    if "ego_maneuver" not in facts:
        facts["ego_maneuver"] = _fact(
            "ego_maneuver", EgoManeuver.GO_STRAIGHT.value, FactSource.DEFAULT
        )
    if "adversary_maneuver" not in facts:
        facts["adversary_maneuver"] = _fact(
            "adversary_maneuver", AdversaryManeuver.UNSTATED.value, FactSource.DEFAULT
        )
    if "road_type" not in facts:
        # Unstated: an ordinary road, never the model's guess of a highway or a junction.
        facts["road_type"] = _fact("road_type", RoadType.STRAIGHT.value, FactSource.DEFAULT)
    participants = _participants(reading)
    dropped = [
        p
        for p in answer.participants
        if not any(quote_in(p, q) or quote_in(q, p) for q in participants)
    ]
    if dropped:
        notes.append(
            "participants: dropped "
            + ", ".join(repr(p) for p in dropped)
            + " (not named in the description, or the adversary itself)"
        )
    for index, words in enumerate(participants):
        facts[f"participant {index + 1}"] = _fact("participant", words, FactSource.TEXT, words)
    position = RelativePosition(facts["spawn_position"].value)
    requirements, requirement_notes = _requirements(description, answer, position)
    notes += requirement_notes
    for requirement in requirements:
        facts[f"requirement {requirement.kind}"] = _fact(
            "requirement", requirement.kind.value, FactSource.TEXT, requirement.text
        )
    free_text = {}
    for name in ("behavior", "geometry", "spawn"):
        words = getattr(answer, name)
        if quote_in(description, words):
            free_text[name] = words.strip()
        else:
            free_text[name] = ""
            if words.strip():
                notes.append(f"{name}: the model's words {words!r} are not in the description")
    for name, fact in facts.items():
        model_value = getattr(answer, name, None)
        if (
            fact.source is FactSource.TEXT
            and model_value is not None
            and str(model_value) != fact.value
        ):
            notes.append(f"{name}: {model_value} -> {fact.value} (stated in the description)")
    spec = ScenarioSpec(
        adversary_type=AdversaryType(facts["adversary_type"].value),
        adversary_class=adversary_class,
        behavior=free_text["behavior"],
        road_type=RoadType(facts["road_type"].value),
        ego_maneuver=EgoManeuver(facts["ego_maneuver"].value),
        geometry=free_text["geometry"],
        spawn_position=position,
        spawn=free_text["spawn"],
        adversary_maneuver=AdversaryManeuver(facts["adversary_maneuver"].value),
        adversary_stationary="adversary_stationary" in facts,
        adversary_turns_back="adversary_turns_back" in facts,
        ego_stopped="ego_stopped" in facts,
        ego_on_ramp="ego_on_ramp" in facts,
        quantities_stated="unread_measure" in facts,
        ego_speed=float(facts["ego_speed"].value) if "ego_speed" in facts else None,
        adversary_speed=(
            float(facts["adversary_speed"].value) if "adversary_speed" in facts else None
        ),
        contact_stated="contact_stated" in facts,
        timing=Timing(facts["timing"].value) if "timing" in facts else None,
        ego_plan=EgoPlan(facts["ego_plan"].value) if "ego_plan" in facts else None,
        start_detail=(
            StartDetail(facts["start_detail"].value) if "start_detail" in facts else None
        ),
        ego_lane_side=Side(facts["ego_lane_side"].value) if "ego_lane_side" in facts else None,
        no_adversary=no_adversary,
        participants=participants,
        actors=[Actor(**asdict(actor)) for actor in read_actors(reading)],
        weather=facts["weather"].value,
        weather_parameters=reading.weather.parameters if reading.weather else None,
        requirements=requirements,
        grounding=list(facts.values()),
    )
    return Grounded(spec=spec, notes=notes)
