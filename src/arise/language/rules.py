"""Reading rules as data: each rule is phrase patterns, the fact they give, and examples.

A rule file (data/rules/*.yaml) is a list of rules:

    - id: start.oncoming
      fact: start              # what it tells (see Fact)
      value: oncoming          # the value; "{side}" takes the word a <side> slot matched
      about: actor             # whose fact: the actor whose words hold the match (actor),
                               # the subject of its clause (subject), or the scene
      when: [oncoming, coming the other way]      # patterns (arise.language.patterns)
      unless: [oncoming lane]  # optional: a match inside one of these does not count
      examples:                # at least one; tests/language runs every one
        - text: An oncoming bus swings wide into the ego's lane.
          actor: bus           # a word of the actor's quote, or "ego"
          gives: {start: oncoming}

Rules of one fact are tried in file order; where two match, the earlier match in the text
wins and, on a tie, the earlier rule. Adding coverage means adding a rule with its example,
not editing code.
"""

from __future__ import annotations

import re
import string
from collections.abc import Iterator
from dataclasses import dataclass
from enum import StrEnum
from functools import cache
from importlib import resources

import yaml
from pydantic import BaseModel, ConfigDict, Field, ValidationError

from arise.language.errors import RuleError
from arise.language.lexicon import SAFE_LOADER, lexicon, slot_word
from arise.language.numbered import ego_number_view
from arise.language.patterns import compile_pattern
from arise.vocabulary import (
    EgoPlan,
    RelativePosition,
    RequirementKind,
    RoadType,
    StartDetail,
    Timing,
    Unit,
)


class Fact(StrEnum):
    """What a rule tells."""

    START = "start"  # where an actor starts, seen from the ego (a RelativePosition)
    START_DETAIL = "start_detail"  # which end of the lane beside the ego (a StartDetail)
    STATIONARY = "stationary"  # the actor stays put ("parked", "stalled")
    MOVING = "moving"  # words that move it ("pulls out", "crosses")
    TURNS_BACK = "turns_back"  # it goes back the way it came ("steps back onto the kerb")
    TURN = "turn"  # which way an actor goes: turn_left, turn_right, straight, change_lane
    LANE_SIDE = "lane_side"  # the side an actor's lane change goes to
    EGO_PLAN = "ego_plan"  # what the ego does besides its route (an EgoPlan)
    EGO_HELD = "ego_held"  # the ego stands still for the scene
    EGO_MOVES_OFF = "ego_moves_off"  # the ego sets off after standing ("as we pulled off")
    EGO_ON_RAMP = "ego_on_ramp"  # the ego comes up an on-ramp
    ROAD = "road"  # the road type (a RoadType), or "mid_block"
    SKY = "sky"  # a weather word: HardRain, SoftRain, MidRain, Wet, Cloudy, Clear
    LIGHT = "light"  # a light word: Night, Sunset, Noon
    VISIBILITY = "visibility"  # fog, mist, haze, smoke, dense_fog
    GLARE = "glare"  # the sun low in the driver's eyes
    CONTACT = "contact"  # where the ego was touched: front, rear, left, right, ...
    IMPLIED = "implied"  # an actor the words imply without naming it (an ActorRole)
    SIGNAL = "signal"  # which side a road user signalled to
    TARGET_LANE = "target_lane"  # the lane the ego moves into ("a van coming up in that lane")
    BARE_SIDE = "bare_side"  # "on the right" alone: a lane for a vehicle, the roadside for a walker
    EGO_BEHIND = (
        "ego_behind"  # the ego's verb right before an actor puts it ahead ("following a van")
    )
    # the ego's verb of passing right before an actor: ahead, when nothing else says where
    EGO_PASSES = "ego_passes"
    BETWEEN = "between"  # squeezed between the ego and something on a side
    BETWEEN_ANOTHER = "between_another"  # squeezed between the ego and a road user named next
    EGO_OVERTAKES = "ego_overtakes"  # the ego overtakes (a lane change to the left)
    THROUGH_ONCOMING = "through_oncoming"  # around it through the oncoming lane (a bypass)
    FROM_BEHIND = "from_behind"  # the actor comes up from behind (StartDetail.FROM_BEHIND)
    # the actor closes in from behind (not "following", "tailgating"): beside an ego that
    # changes lanes, it is in the lane the ego moves into
    CLOSES_FROM_BEHIND = "closes_from_behind"
    AHEAD_OF_EGO = "ahead_of_ego"  # the actor ends up ahead of the ego (StartDetail.AHEAD)
    EXIT_STREET = "exit_street"  # the street (or its crossing) a turning ego enters
    FAR_CORNER = "far_corner"  # the far corner of that street's crossing
    CROSSES = "crosses"  # words of crossing a street ("crosses", "on the crosswalk")
    BACKGROUND = "background"  # the actor is scenery (parked, hiding something), not the adversary
    TRAFFIC_CONTROL = "traffic_control"  # lights or signs: a junction, when nothing else says
    ROLE_CUE = "role_cue"  # what an actor besides the adversary is for: occluder, waits, ...
    HIDES_BEHIND = "hides_behind"  # words right before a thing that put someone behind it
    REQUIREMENT = "requirement"  # a constraint the text states (a RequirementKind)
    HEADING = "heading"  # a compass heading ("northbound", "from south to north")
    LANE_NUMBER = "lane_number"  # the numbered lane an actor is in ("#2 lane", "lane 3")
    LANE_ORDER = "lane_order"  # lanes numbered from the right: "from_right"
    CURB = "curb"  # the compass side of the street an actor stands at ("the north curb")
    MEASURE = "measure"  # a number with its unit ("17 mph", "30 feet"): the unit
    THERE = "there"  # "from there": the place named just before
    CORNER = "corner"  # the compass corner of a junction an actor stands at ("the NE corner")
    QUANTITY = "quantity"  # words about a speed, a distance or a moment ("at 30 mph", "suddenly")
    MEETING = (
        "meeting"  # the two touched or nearly did: contact, near_miss ("struck", "nearly hits")
    )
    TIMING = "timing"  # when the other moved, seen from the ego: late, early ("just as it passes")
    # words right before another actor that place this one by it: "emerges" ("steps out
    # from behind a van"), "behind" ("coming up behind the coupe"), "past" ("comes past it")
    BY_ANOTHER = "by_another"


class Target(StrEnum):
    ACTOR = "actor"  # the actor whose words hold the match
    SUBJECT = "subject"  # the subject of the clause holding the match
    SCENE = "scene"  # the description as a whole


class Example(BaseModel):
    model_config = ConfigDict(extra="forbid")

    text: str
    actor: str | None = None
    gives: dict[str, str | None]  # None: the fact must not be given


class Rule(BaseModel):
    model_config = ConfigDict(extra="forbid")

    id: str = Field(pattern=r"^[a-z_]+(?:\.[a-z0-9_]+)+$")
    fact: Fact
    value: str
    about: Target
    when: list[str] = Field(min_length=1)
    unless: list[str] = Field(default_factory=list)
    #: The value fills in an end the words leave open (the ego's lane with no end is the
    #: lane ahead): another cue of the same fact in the actor's words wins over it.
    weak: bool = False
    #: The value's side is the usual one, not said (a kerb, a bike lane or a slip road with
    #: no side is on the right): a side said in the actor's words turns it to that side.
    side_assumed: bool = False
    #: The value is read from where the ego was touched ("scraped its left door"), which
    #: places a road user beside the ego on an open road but on the crossing road at a
    #: junction (`readers.read_position`).
    damage: bool = False
    #: The place is on the road a turning ego enters, ahead on its route: a side said with
    #: it is that road's kerb, not a lane beside the ego (`readers.read_position`).
    after_turn: bool = False
    examples: list[Example] = Field(min_length=1)


@dataclass(frozen=True)
class Hit:
    """One match of a rule: the value it gives and the words it rests on."""

    rule: Rule
    value: str
    start: int
    end: int
    quote: str
    order: int  # the rule's place among the rules of its fact


#: Facts of a move that a negation right before cancels.
NEGATABLE = frozenset(
    {Fact.TURN, Fact.LANE_SIDE, Fact.EGO_PLAN, Fact.EGO_OVERTAKES, Fact.THROUGH_ONCOMING}
)
_NEGATED = re.compile(
    r"\b(?:not|never|without|can't|cannot|couldn't|don't|didn't|won't|mustn't|shouldn't|"
    r"unable\s+to|no\s+room\s+to)\s+(?:[\w'-]+\s+){0,2}$",
    re.I,
)


@dataclass(frozen=True)
class CompiledRule:
    rule: Rule
    when: tuple[re.Pattern[str], ...]
    unless: tuple[re.Pattern[str], ...]
    order: int

    def hits(self, text: str, start: int = 0, end: int | None = None) -> Iterator[Hit]:
        """Matches that lie inside text[start:end] and inside no `unless` match; a move
        said not to happen ("without crossing the centre line", "you can't pull out") is
        none."""
        stop = len(text) if end is None else end
        seen = ego_number_view(text)  # "Vehicle 2's right rear" of an ego numbered 2
        vetoes = [m.span() for p in self.unless for m in p.finditer(seen)]
        negatable = self.rule.fact in NEGATABLE
        for pattern in self.when:
            for match in pattern.finditer(seen, start):
                if match.end() > stop:
                    break
                if any(a <= match.start() and match.end() <= b for a, b in vetoes):
                    continue
                if negatable and _NEGATED.search(seen, max(0, match.start() - 40), match.start()):
                    continue
                slots = {k: slot_word(v) for k, v in match.groupdict().items() if v}
                yield Hit(
                    rule=self.rule,
                    value=self.rule.value.format(**slots) if slots else self.rule.value,
                    start=match.start(),
                    end=match.end(),
                    quote=text[match.start() : match.end()],
                    order=self.order,
                )


@dataclass(frozen=True)
class RuleBook:
    rules: tuple[CompiledRule, ...]

    def of(self, fact: Fact) -> tuple[CompiledRule, ...]:
        return tuple(rule for rule in self.rules if rule.rule.fact is fact)

    def hits(self, fact: Fact, text: str, start: int = 0, end: int | None = None) -> list[Hit]:
        """Every hit of the rules of `fact` in text[start:end], earliest first, then by rule
        order."""
        found = [hit for rule in self.of(fact) for hit in rule.hits(text, start, end)]
        return sorted(found, key=lambda hit: (hit.start, hit.order))

    def first(self, fact: Fact, text: str, start: int = 0, end: int | None = None) -> Hit | None:
        found = self.hits(fact, text, start, end)
        return found[0] if found else None

    def by_order(self, fact: Fact, text: str, start: int = 0, end: int | None = None) -> Hit | None:
        """The hit of the first rule (in file order) that matches at all."""
        for rule in self.of(fact):
            hit = next(rule.hits(text, start, end), None)
            if hit is not None:
                return hit
        return None


RULE_FILES = (
    "start.yaml",
    "motion.yaml",
    "ego.yaml",
    "scene.yaml",
    "weather.yaml",
    "contact.yaml",
    "cues.yaml",
    "roles.yaml",
    "requirements.yaml",
    "quantities.yaml",
    "conflict.yaml",
)


def load_rules(text: str, where: str) -> list[Rule]:
    """The rules of one file's text; a malformed rule is a RuleError naming it."""
    data = yaml.load(text, Loader=SAFE_LOADER)
    if not isinstance(data, list):
        raise RuleError(f"{where}: a rule file is a list of rules")
    rules = []
    for index, item in enumerate(data):
        try:
            rules.append(Rule.model_validate(item))
        except ValidationError as error:
            name = item.get("id", f"#{index + 1}") if isinstance(item, dict) else f"#{index + 1}"
            problem = error.errors()[0]
            raise RuleError(
                f"{where}: rule {name}: {'.'.join(map(str, problem['loc']))}: {problem['msg']}"
            ) from error
    return rules


def _values(fact: Fact) -> frozenset[str] | None:
    """The values a fact may take (None: free)."""
    allowed: dict[Fact, frozenset[str]] = {
        Fact.START: frozenset(RelativePosition),
        Fact.START_DETAIL: frozenset(StartDetail),
        Fact.TURN: frozenset({"turn_left", "turn_right", "straight", "change_lane"}),
        Fact.LANE_SIDE: frozenset({"left", "right"}),
        Fact.EGO_PLAN: frozenset(EgoPlan),
        Fact.STATIONARY: frozenset({"true"}),
        Fact.MOVING: frozenset({"true"}),
        Fact.TURNS_BACK: frozenset({"true"}),
        Fact.EGO_HELD: frozenset({"true"}),
        Fact.EGO_MOVES_OFF: frozenset({"true"}),
        Fact.EGO_ON_RAMP: frozenset({"true"}),
        Fact.ROAD: frozenset({*RoadType, "mid_block"}),
        Fact.CONTACT: frozenset({"rear", "front", "left", "right"}),
        Fact.SIGNAL: frozenset({"left", "right"}),
        Fact.IMPLIED: frozenset({"oncoming", "crossing", "obstacle"}),
        Fact.BARE_SIDE: frozenset({"left", "right"}),
        Fact.BETWEEN: frozenset({"left", "right"}),
        Fact.ROLE_CUE: frozenset({"occluder", "waits", "parked", "follows", "slow"}),
        Fact.REQUIREMENT: frozenset(RequirementKind),
        Fact.HEADING: frozenset({"north", "east", "south", "west"}),
        Fact.CURB: frozenset({"north", "east", "south", "west"}),
        Fact.CORNER: frozenset({"northeast", "southeast", "southwest", "northwest"}),
        Fact.MEASURE: frozenset(Unit),
        Fact.QUANTITY: frozenset({"speed", "distance", "timing"}),
        Fact.MEETING: frozenset({"contact", "near_miss"}),
        Fact.TIMING: frozenset(Timing),
        Fact.BY_ANOTHER: frozenset({"emerges", "behind", "ahead", "past"}),
        **{
            fact: frozenset({"true"})
            for fact in (
                Fact.TARGET_LANE,
                Fact.EGO_BEHIND,
                Fact.EGO_PASSES,
                Fact.EGO_OVERTAKES,
                Fact.THROUGH_ONCOMING,
                Fact.FROM_BEHIND,
                Fact.CLOSES_FROM_BEHIND,
                Fact.AHEAD_OF_EGO,
                Fact.EXIT_STREET,
                Fact.FAR_CORNER,
                Fact.THERE,
                Fact.CROSSES,
                Fact.BACKGROUND,
                Fact.TRAFFIC_CONTROL,
                Fact.HIDES_BEHIND,
                Fact.BETWEEN_ANOTHER,
            )
        },
    }
    return allowed.get(fact)


def _check_value(rule: Rule, where: str) -> None:
    allowed = _values(rule.fact)
    if allowed is None:
        return
    # A value that takes a slot's word ("adjacent_lane_{side}") is checked for every word of
    # the slot's lexicon class.
    slots = [name for _, name, _, _ in string.Formatter().parse(rule.value) if name]
    classes = lexicon().classes
    if any(slot not in classes for slot in slots):
        raise RuleError(f"{where}: rule {rule.id}: its value names no lexicon class")
    for pattern in rule.when:
        missing = [slot for slot in slots if f"<{slot}>" not in pattern]
        if missing:
            # the value could not be filled when this pattern matches
            raise RuleError(
                f"{where}: rule {rule.id}: pattern {pattern!r} has no <{missing[0]}> for its value"
            )
    values = {rule.value}
    for slot in slots:
        values = {
            value.replace(f"{{{slot}}}", slot_word(word))
            for value in values
            for word in classes[slot]
        }
    unknown = sorted(values - allowed)
    if unknown:
        raise RuleError(f"{where}: rule {rule.id}: {rule.fact} cannot be {unknown[0]!r}")


@cache
def rulebook() -> RuleBook:
    """Every shipped rule, compiled; rule ids are unique."""
    folder = resources.files("arise.language").joinpath("data/rules")
    compiled: list[CompiledRule] = []
    seen: set[str] = set()
    counts: dict[Fact, int] = {}
    for name in RULE_FILES:
        for rule in load_rules(folder.joinpath(name).read_text("utf-8"), name):
            if rule.id in seen:
                raise RuleError(f"{name}: rule id {rule.id} is used twice")
            seen.add(rule.id)
            _check_value(rule, name)
            classes, verbs = lexicon().classes, lexicon().verbs
            order = counts.get(rule.fact, 0)
            counts[rule.fact] = order + 1
            try:
                when = tuple(compile_pattern(p, classes, verbs) for p in rule.when)
                unless = tuple(compile_pattern(p, classes, verbs) for p in rule.unless)
            except RuleError as error:
                raise RuleError(f"{name}: rule {rule.id}: {error}") from error
            compiled.append(CompiledRule(rule=rule, when=when, unless=unless, order=order))
    return RuleBook(tuple(compiled))
