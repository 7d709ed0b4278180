"""Grounded extraction: every fact of the spec rests on words of the description.

The model proposes; the description decides. Each fact the spec carries comes from one of
three places, and says which (`FactSource`):

- TEXT: a fixed rule read it from the description's words (weather, sides, turns, who
  is named), attributed to the actor the words are about;
- MODEL: the model's answer, kept only with a quote that is really in the description;
- DEFAULT: the description does not say, so a neutral value (clear noon, going
  straight, no other participants).

A quote that is not in the description is rejected mechanically, whatever the model says.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass, field

from arise.generate.facts import FactSource, GroundedFact
from arise.generate.mentions import VEHICLE_CLASSES, Cast, Mention, phrase_start, read_cast
from arise.generate.spec import ExtractionAnswer, Requirement, RequirementKind, ScenarioSpec
from arise.vocabulary import (
    DEFAULT_WEATHER,
    WEATHER_PRESETS,
    AdversaryManeuver,
    AdversaryType,
    EgoManeuver,
    RelativePosition,
    RoadType,
)

# -- quotes ---------------------------------------------------------------------------------


def _normal(text: str) -> str:
    text = text.lower().replace("’", "'").replace("`", "'")
    text = re.sub(r"[^a-z0-9' ]+", " ", text)
    return re.sub(r"\s+", " ", text).strip()


def quote_in(description: str, quote: str | None) -> bool:
    """True when `quote` is words of `description` (case, spacing and punctuation aside)."""
    if not quote or not _normal(quote):
        return False
    return f" {_normal(quote)} " in f" {_normal(description)} "


def find_quote(description: str, quote: str) -> tuple[int, int] | None:
    """Where the quote is in the description (character span), or None."""
    words = _normal(quote).split()
    if not words:
        return None
    pattern = r"\W+".join(re.escape(word) for word in words)
    match = re.search(rf"(?<![\w']){pattern}(?![\w'])", description, re.I)
    return match.span() if match else None


# -- weather --------------------------------------------------------------------------------

_SKY = (
    (
        "HardRain",
        r"heavy rain\w*|hard rain|downpour|pouring rain|torrential rain|"
        r"thunderstorms?|rainstorms?|storm",
    ),
    ("SoftRain", r"light rain|drizzl\w*|soft rain|light showers?|sprinkl\w+|misty rain"),
    ("MidRain", r"rain\w*|showers"),
    (
        "Wet",
        r"slippery|icy|wet (?:\w+ )?(?:road|roads|street|streets|asphalt|pavement|surface)|puddles?|"
        r"slick (?:road|street|surface)|road (?:is|was) wet|damp (?:road|street)",
    ),
    ("Cloudy", r"cloud\w*|overcast|grey skies?|gray skies?"),
    (
        "Clear",
        r"clear (?:sky|skies|weather|day|conditions)|sunny|sunshine|dry weather|"
        r"weather (?:is|was) clear|clear and dry",
    ),
)
_TIME = (
    (
        "Night",
        r"night\w*|darkness|after dark|in the dark|midnight|dark(?![\s-]+(?:red|blue|"
        r"green|grey|gray|colou?red|sedan|suv|car|van|truck|jacket|cloth\w*|coat))",
    ),
    ("Sunset", r"sunset|dusk|twilight|sundown|setting sun|low sun|dawn|sunrise|daybreak"),
    ("Noon", r"daylight|daytime|midday|noon|broad day"),
)
_RAIN_NAMES = {
    "HardRain": "HardRain",
    "SoftRain": "SoftRain",
    "MidRain": "MidRainy",
}


def _search(table: Sequence[tuple[str, str]], text: str) -> tuple[str, str] | None:
    for value, pattern in table:
        match = re.search(rf"\b(?:{pattern})\b", text, re.I)
        if match:
            return value, match.group(0)
    return None


def read_weather(description: str) -> GroundedFact:
    """The CARLA preset the description's weather and light words name; ClearNoon if none."""
    sky = _search(_SKY, description)
    time = _search(_TIME, description)
    if sky is None and time is None:
        return GroundedFact(name="weather", value=DEFAULT_WEATHER, source=FactSource.DEFAULT)
    sky_name = sky[0] if sky else "Clear"
    time_name = time[0] if time else "Noon"
    if sky_name == "Wet" and re.search(r"\b(?:cloud\w*|overcast)\b", description, re.I):
        sky_name = "WetCloudy"
    candidates = [f"{_RAIN_NAMES.get(sky_name, sky_name)}{time_name}"]
    if sky_name == "MidRain":
        candidates += [f"MidRain{time_name}", f"MidRainy{time_name}"]
    candidates.append(f"HardRain{time_name}" if "Rain" in sky_name else f"Clear{time_name}")
    preset = next((c for c in candidates if c in WEATHER_PRESETS), DEFAULT_WEATHER)
    words = [found[1] for found in (sky, time) if found]
    return GroundedFact(
        name="weather", value=preset, source=FactSource.TEXT, quote=" ... ".join(words)
    )


# -- sides and turns, attributed to an actor ------------------------------------------------

_SIDE = r"(?:the |its |his |her |their |the ego's |the av's )?"
# "from the side road on its right": a road user coming out of a road from that side.
_SIDE_ROAD = (
    r"(?:from|out of) (?:the |a )?(?:side road|side street|cross street|driveway|"
    r"minor road|junction)(?: on| to)? "
)
# (position, pattern); the earliest cue in an actor's words wins, ties in this order.
_POSITION_CUES: tuple[tuple[RelativePosition, str], ...] = (
    (
        RelativePosition.ONCOMING,
        r"oncoming|coming the other way|from the opposite direction|"
        r"in the opposite direction|opposite direction|head[- ]on|coming towards?|"
        r"approaching from the front|travell?ing towards? the (?:ego|av)",
    ),
    (
        RelativePosition.ADJACENT_LANE_LEFT,
        rf"(?:from |coming up )?behind on {_SIDE}left|"
        rf"in {_SIDE}left lane|lane to {_SIDE}left|left[- ]hand lane|left adjacent lane|"
        r"adjacent left lane|overtak\w+ (?:the ego |the av |it )?on (?:its|the) left|"
        rf"(?:on|in|from) {_SIDE}left[- ]front|alongside on {_SIDE}left|on {_SIDE}left side of "
        r"the (?:ego|av)",
    ),
    (
        RelativePosition.ADJACENT_LANE_RIGHT,
        rf"(?:from |coming up )?behind on {_SIDE}right|"
        rf"in {_SIDE}right lane|lane to {_SIDE}right|right[- ]hand lane|right adjacent lane|"
        r"adjacent right lane|bike lane|overtak\w+ (?:the ego |the av |it )?on (?:its|the) right|"
        rf"(?:on|in|from) {_SIDE}right[- ]front|alongside on {_SIDE}right|on {_SIDE}right side "
        r"of the (?:ego|av)",
    ),
    (
        RelativePosition.ROADSIDE_LEFT,
        r"left (?:sidewalk|pavement|kerb|curb|corner|roadside|"
        r"shoulder)|opposite (?:sidewalk|pavement|side of the (?:road|street))|far side|"
        r"parked (?:\w+ )?on the left|left side of the (?:road|street)",
    ),
    (
        RelativePosition.ROADSIDE_RIGHT,
        r"right (?:sidewalk|pavement|kerb|curb|corner|roadside|"
        r"shoulder)|(?:parked|standing|stopped) (?:\w+ )?on the right|"
        r"right side of the (?:road|street)|at the curb|by the curb|at a bus stop",
    ),
    (RelativePosition.CROSSING_FROM_LEFT, rf"from {_SIDE}left|from left|{_SIDE_ROAD}{_SIDE}left"),
    (
        RelativePosition.CROSSING_FROM_RIGHT,
        rf"from {_SIDE}right|from right|{_SIDE_ROAD}{_SIDE}right",
    ),
    (
        RelativePosition.BEHIND_SAME_LANE,
        r"from behind|behind the (?:ego|av)|behind it\b|"
        r"following the (?:ego|av)|approaching from the rear|rear[- ]end\w*",
    ),
    (
        RelativePosition.AHEAD_SAME_LANE,
        r"ahead in (?:the same|its|the ego's|the av's) lane|"
        r"in (?:its|the ego's|the av's|the same) lane|in front of the (?:ego|av)|ahead of "
        r"(?:the ego|the av|it|them)|lead(?:ing)? \w+|riding ahead|driving ahead|"
        r"stopped ahead|ahead,? in|edge of (?:its|the ego's|the av's) lane|"
        r"following (?:a|an)|following the (?!ego|av)",
    ),
)
# The lane the ego moves into ("a car coming up in that lane"): resolved by the ego's own
# lane change ("moves into the left lane").
_TARGET_LANE = re.compile(
    r"\b(?:in|into) (?:that|the target) lane\b|\bthe lane (?:the ego|the av|it) "
    r"(?:enters|is entering|moves into|changes into|merges into)\b",
    re.I,
)
_EGO_LANE_SIDE = re.compile(
    r"\b(?:chang\w*|mov\w*|merg\w*|pull\w*|steer\w*|swerv\w*)(?: \w+){0,2} "
    r"(?:in)?to (?:the )?(left|right)(?: lane|\b)",
    re.I,
)
# "on the right"/"on its left" alone: a lane for a vehicle, the roadside for a walker.
_BARE_SIDE = re.compile(rf"\b(?:on|to) {_SIDE}(left|right)\b(?![- ]turn)", re.I)

_TURN = re.compile(
    r"\b(?:turns?|turning|turned|to turn|makes? an? (?:unprotected )?|making an? "
    r"(?:unprotected )?|takes? an? |performs? an? (?:unprotected )?)\s*(left|right)\b|"
    r"(?<!from the )(?<!from its )\b(?:unprotected )?(left|right)[- ]turn(?:ing|s)?\b"
    r"(?!\s+(?:left|right))|\bunprotected (left)\b",
    re.I,
)
_STRAIGHT = re.compile(
    r"\b(?:go(?:es|ing)?|continu\w*|driv\w*|head\w*|proceed\w*|keep\w*(?: going)?|"
    r"went|carr\w+ on|travel\w*) straight\b|\bstraight (?:through|across|ahead|on)\b|"
    r"\bdoes not turn\b|\b(?:cross\w*|pass\w*|go\w* through|driv\w* through) (?:an?|the) "
    r"(?:\w+ )?(?:intersection|junction|crossroads)\b|\bkeeps? (?:to )?(?:its|the) lane\b",
    re.I,
)
_LANE_CHANGE = re.compile(
    r"\bchang\w* (?:in)?to (?:the )?(?:left|right|adjacent|next|other|oncoming) lane|"
    r"\bchang\w* lanes?\b|\bmoves? (?:over )?into (?:the )?(?:left|right|oncoming|adjacent|"
    r"next) lane|\bpulls? (?:out )?into (?:the )?(?:left|right|oncoming|opposite) lane|"
    r"\bswerves? into (?:the )?(?:left|right|adjacent|next) lane",
    re.I,
)
_PARTICIPLE_START = re.compile(r"(?:^|[.;!?]\s+)$")


@dataclass
class Reading:
    """What the fixed rules read from one description, each with its words."""

    cast: Cast
    adversary: Mention | None = None
    facts: dict[str, GroundedFact] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)


def _words_of(cast: Cast, mention: Mention) -> list[tuple[int, int]]:
    """The stretches of text about `mention`: from a few words before each of its spans to
    the next named actor or the end of the sentence."""
    text = cast.text
    stretches = []
    starts = sorted(phrase_start(text, s.start) for m in cast.others for s in m.spans)
    for span in mention.spans:
        lead = phrase_start(text, span.start)
        end = next((s for s in starts if s > span.end), len(text))
        found = re.search(r"[.;!?](?:\s|$)", text[span.end :])
        sentence_end = span.end + found.start() if found else len(text)
        stretches.append((lead, min(end, sentence_end)))
    return stretches


def read_position(cast: Cast, mention: Mention) -> GroundedFact | None:
    """Where `mention` starts, seen from the ego, from the words about it."""
    best: tuple[int, int, RelativePosition, str] | None = None
    for start, end in _words_of(cast, mention):
        words = cast.text[start:end]
        for order, (position, pattern) in enumerate(_POSITION_CUES):
            match = re.search(rf"\b(?:{pattern})\b", words, re.I)
            if match and (best is None or (start + match.start(), order) < best[:2]):
                best = (start + match.start(), order, position, match.group(0))
        bare = _BARE_SIDE.search(words)
        if bare and best is None:
            side = bare.group(1).lower()
            walker = mention.cls in ("Pedestrian",) or mention.is_prop
            position = (
                (
                    RelativePosition.ROADSIDE_LEFT
                    if side == "left"
                    else RelativePosition.ROADSIDE_RIGHT
                )
                if walker
                else (
                    RelativePosition.ADJACENT_LANE_LEFT
                    if side == "left"
                    else RelativePosition.ADJACENT_LANE_RIGHT
                )
            )
            best = (start + bare.start(), 99, position, bare.group(0))
        target = _TARGET_LANE.search(words)
        lane_side = _EGO_LANE_SIDE.search(cast.text)
        if target and lane_side and (best is None or start + target.start() < best[0]):
            position = (
                RelativePosition.ADJACENT_LANE_LEFT
                if lane_side.group(1).lower() == "left"
                else RelativePosition.ADJACENT_LANE_RIGHT
            )
            best = (
                start + target.start(),
                -1,
                position,
                f"{lane_side.group(0)} ... {target.group(0)}",
            )
    if best is None:
        return None
    return GroundedFact(
        name="spawn_position", value=best[2].value, source=FactSource.TEXT, quote=best[3]
    )


_COMPASS = {"north": 0, "east": 90, "south": 180, "west": 270}
_BOUND = re.compile(
    r"\b(north|east|south|west)(?:bound|ward)\b|\bfrom (?:north|east|south|west) to "
    r"(north|east|south|west)\b",
    re.I,
)


def _bearing(found: re.Match[str]) -> int:
    word = found.group(1) or found.group(2)
    return _COMPASS[word.lower()]


def read_compass(cast: Cast, mention: Mention) -> GroundedFact | None:
    """A side from compass words ("the AV was northbound; an eastbound car"), as crash
    reports give them: the ego's bearing from its own words, the actor's from its words."""
    ego_bearing = None
    for span in cast.ego:
        after = cast.text[span.end : span.end + 60]
        found = _BOUND.search(after)
        if found and not re.search(r"[.;]", after[: found.start()]):
            ego_bearing = _bearing(found)
            break
    if ego_bearing is None:
        return None
    for start, end in _words_of(cast, mention):
        words = cast.text[max(0, start - 15) : end]
        found = _BOUND.search(words)
        if not found:
            continue
        relative = (_bearing(found) - ego_bearing) % 360
        position = {
            90: RelativePosition.CROSSING_FROM_LEFT,
            180: RelativePosition.ONCOMING,
            270: RelativePosition.CROSSING_FROM_RIGHT,
        }.get(relative)
        if position is not None:
            return GroundedFact(
                name="spawn_position",
                value=position.value,
                source=FactSource.TEXT,
                quote=found.group(0),
            )
    return None


def _subject(cast: Cast, position: int) -> Mention | str | None:
    """Who a verb at `position` is about: the actor named last before it in its sentence,
    or, for a leading participle ("Turning left at ..., the ego ..."), the one after it."""
    head = cast.text[:position]
    sentence_start = max(head.rfind(c) for c in ".;!?") + 1
    if not head[sentence_start:].strip() or re.fullmatch(
        r"\s*(?:while |when |as |after |before )?", head[sentence_start:], re.I
    ):
        return cast.subject_after(position)
    return cast.subject_before(position)


def read_maneuvers(reading: Reading) -> None:
    """The ego's maneuver and the adversary's turn, each from verbs about that actor."""
    cast = reading.cast
    ego: tuple[EgoManeuver, str] | None = None
    adversary: tuple[AdversaryManeuver, str] | None = None
    found: list[tuple[int, str, str]] = []
    for match in _TURN.finditer(cast.text):
        side = next(g for g in match.groups() if g).lower()
        found.append((match.start(), f"turn_{side}", match.group(0)))
    for match in _STRAIGHT.finditer(cast.text):
        found.append((match.start(), "straight", match.group(0)))
    for match in _LANE_CHANGE.finditer(cast.text):
        found.append((match.start(), "change_lane", match.group(0)))
    for position, kind, words in sorted(found):
        subject = _subject(cast, position)
        if subject is None and re.match(r"unprotected", words, re.I):
            subject = "ego"
        if subject == "ego" and ego is None:
            maneuver = {
                "turn_left": EgoManeuver.TURN_LEFT,
                "turn_right": EgoManeuver.TURN_RIGHT,
                "straight": EgoManeuver.GO_STRAIGHT,
                "change_lane": EgoManeuver.CHANGE_LANE,
            }[kind]
            ego = (maneuver, words)
        elif (
            isinstance(subject, Mention)
            and subject is reading.adversary
            and adversary is None
            and kind != "change_lane"
        ):
            adversary = (AdversaryManeuver(kind), words)
    if ego is not None:
        reading.facts["ego_maneuver"] = GroundedFact(
            name="ego_maneuver", value=ego[0].value, source=FactSource.TEXT, quote=ego[1]
        )
    if adversary is not None:
        reading.facts["adversary_maneuver"] = GroundedFact(
            name="adversary_maneuver",
            value=adversary[0].value,
            source=FactSource.TEXT,
            quote=adversary[1],
        )


_STATIONARY = re.compile(
    r"\b(?:parked|double[- ]parked|stalled|broken[- ]down|stationary|abandoned|"
    r"(?:is |was |sits |stands |standing )?stopped|sits|lies|lying|standing still|"
    r"at a standstill|not moving)\b",
    re.I,
)
_MOVING = re.compile(
    r"\b(?:pulls?|pulled|start\w*|accelerat\w*|moves?|moving|drives?|driving|turns?|"
    r"turning|cross\w*|runs?|running|rides?|riding|walks?|walking|steps?|swerv\w*|"
    r"merg\w*|cuts?|reverses?|backs?|rolls?|speeds?|brakes?|braking|slows?|suddenly|"
    r"abruptly|sharply|hard)\b",
    re.I,
)


def read_stationary(cast: Cast, mention: Mention) -> GroundedFact | None:
    """Whether the words about `mention` say it stays put for the whole scene ("a truck
    parked in its lane", "a stalled car"), and move it nowhere ("a parked car pulls out")."""
    for start, end in _words_of(cast, mention):
        words = cast.text[start:end]
        still = _STATIONARY.search(words)
        if still and not _MOVING.search(words):
            return GroundedFact(
                name="adversary_stationary",
                value="true",
                source=FactSource.TEXT,
                quote=still.group(0),
            )
    return None


# -- who is the adversary -------------------------------------------------------------------

_CLASS_TYPE = {
    "Car": AdversaryType.CAR,
    "Van": AdversaryType.CAR,
    "Truck": AdversaryType.TRUCK,
    "Bus": AdversaryType.TRUCK,
    "Motorcycle": AdversaryType.MOTORCYCLE,
    "Bicycle": AdversaryType.BICYCLE,
    "Pedestrian": AdversaryType.PEDESTRIAN,
}
_BACKGROUND = re.compile(
    r"\b(?:parked|hides?|hidden|blocking the view|occlud\w*|standing at a bus stop)\b", re.I
)


def adversary_type_of(cls: str) -> AdversaryType | None:
    return _CLASS_TYPE.get(cls)


def choose_adversary(cast: Cast, quote: str | None) -> Mention | None:
    """The named road user the model points at (by a quote that is in the text); else the
    first road user not described as parked or hiding something; else the first one."""
    if quote:
        span = find_quote(cast.text, quote)
        if span is not None:
            mention = cast.mention_at(*span)
            if mention is not None and mention.cls in _CLASS_TYPE:
                return mention
            mentions = [m for m in cast.others if m.cls in _CLASS_TYPE]
            named = [m for m in mentions if re.search(rf"\b{re.escape(m.quote)}\b", quote, re.I)]
            if named:
                return named[0]
    road_users = [m for m in cast.others if m.cls in _CLASS_TYPE]
    for mention in road_users:
        words = " ".join(cast.text[a:b] for a, b in _words_of(cast, mention))
        if not _BACKGROUND.search(words):
            return mention
    return road_users[0] if road_users else None


def is_vehicle(cls: str) -> bool:
    return cls in VEHICLE_CLASSES


def read_description(description: str, adversary_quote: str | None = None) -> Reading:
    """Everything the fixed rules read: the cast, the adversary, its side and turn, the
    ego's maneuver and the weather, each with its words."""
    cast = read_cast(description)
    reading = Reading(cast=cast)
    reading.adversary = choose_adversary(cast, adversary_quote)
    reading.facts["weather"] = read_weather(description)
    if reading.adversary is not None:
        adversary = reading.adversary
        reading.facts["adversary_class"] = GroundedFact(
            name="adversary_class",
            value=adversary.cls,
            source=FactSource.TEXT,
            quote=adversary.quote,
        )
        position = read_compass(cast, adversary) or read_position(cast, adversary)
        if position is not None:
            reading.facts["spawn_position"] = position
        stationary = read_stationary(cast, adversary)
        if stationary is not None:
            reading.facts["adversary_stationary"] = stationary
    read_maneuvers(reading)
    return reading


# -- the grounded spec ----------------------------------------------------------------------

_ROAD_WORDS: tuple[tuple[RoadType, str], ...] = (
    (RoadType.HIGHWAY, r"highway|motorway|freeway|expressway|interstate"),
    (RoadType.T_JUNCTION, r"t-junction|t junction|t-intersection|t intersection|side road"),
    (
        RoadType.INTERSECTION,
        r"intersection|junction|crossroads|all-way stop|four-way stop|roundabout",
    ),
    (RoadType.STRAIGHT, r"straight (?:road|street|stretch)|road|street"),
)
# The evidence a requirement of each kind needs in the text; the match is its quote.
_REQUIREMENT_WORDS: dict[RequirementKind, str] = {
    RequirementKind.VISIBLE_AT_START: r"visible|in (?:plain |clear )?(?:view|sight)|"
    r"can see|sees|spots",
    RequirementKind.NOT_VISIBLE_AT_START: r"hidden|hides|occlud\w*|out of (?:view|sight)|"
    r"obscured|not visible|invisible|unseen|blind spot|"
    r"(?:from )?behind (?:a|an|the) (?:parked|stopped|bus|van|truck|wall|hedge|car)",
    RequirementKind.DISTANCE_AT_START: r"\d+(?:\.\d+)?\s*(?:m|meters?|metres?)\b|"
    r"(?:meters?|metres?) (?:ahead|away|behind)",
    RequirementKind.EVENTUALLY_CLOSE: r"comes? (?:very )?close|gets? (?:very )?close|"
    r"near miss|close call|within \d|nearly (?:collide|hit|clip)\w*",
    RequirementKind.IN_INTERSECTION: r"(?:in|inside|in the middle of) the (?:intersection|"
    r"junction|crossroads)",
    RequirementKind.SAME_DIRECTION: r"same direction|same way|side by side|alongside",
    RequirementKind.OPPOSITE_DIRECTION: r"oncoming|opposite direction|the other way|"
    r"head-on|towards? the ego",
}
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
_CROSSING_SIDES = (RelativePosition.CROSSING_FROM_LEFT, RelativePosition.CROSSING_FROM_RIGHT)


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


def _road(
    description: str, answer: ExtractionAnswer, facts: dict[str, GroundedFact]
) -> GroundedFact:
    found = _search([(road.value, pattern) for road, pattern in _ROAD_WORDS], description)
    if found is not None and found[0] != RoadType.STRAIGHT.value:
        return _fact("road_type", found[0], FactSource.TEXT, found[1])
    ego = facts.get("ego_maneuver")
    if ego is not None and ego.value in (EgoManeuver.TURN_LEFT, EgoManeuver.TURN_RIGHT):
        return _fact("road_type", RoadType.INTERSECTION.value, FactSource.TEXT, ego.quote)
    turn = facts.get("adversary_maneuver")
    if turn is not None and turn.value in (
        AdversaryManeuver.TURN_LEFT,
        AdversaryManeuver.TURN_RIGHT,
    ):
        return _fact("road_type", RoadType.INTERSECTION.value, FactSource.TEXT, turn.quote)
    position = facts.get("spawn_position")
    adversary = facts.get("adversary_class")
    if (
        position is not None
        and position.source is FactSource.TEXT
        and position.value in _CROSSING_SIDES
        and adversary is not None
        and is_vehicle(adversary.value)
    ):  # a vehicle cannot come from the side on an open road
        return _fact("road_type", RoadType.INTERSECTION.value, FactSource.TEXT, position.quote)
    signal = re.search(
        r"\b(?:red light|traffic lights?|signal\w*|stop sign|green light)\b", description, re.I
    )
    if signal is not None:
        return _fact("road_type", RoadType.INTERSECTION.value, FactSource.TEXT, signal.group(0))
    if found is not None:
        return _fact("road_type", found[0], FactSource.TEXT, found[1])
    # Unstated: an ordinary road, never the model's guess of a highway or a junction.
    return _fact("road_type", RoadType.STRAIGHT.value, FactSource.DEFAULT)


def _requirements(
    description: str, answer: ExtractionAnswer, position: RelativePosition
) -> tuple[list[Requirement], list[str]]:
    """The model's requirements that the text states in words (one per kind)."""
    kept: list[Requirement] = []
    notes: list[str] = []
    for requirement in answer.requirements:
        if requirement.kind in {r.kind for r in kept}:
            continue
        evidence = re.search(rf"\b(?:{_REQUIREMENT_WORDS[requirement.kind]})", description, re.I)
        if evidence is None:
            notes.append(
                f"requirements: dropped {requirement.kind} (not stated in the description)"
            )
        elif position in _REQUIREMENT_CONFLICTS.get(requirement.kind, set()):
            notes.append(f"requirements: dropped {requirement.kind} (contradicts {position})")
        else:
            kept.append(Requirement(kind=requirement.kind, text=evidence.group(0)))
    return kept, notes


def _participants(reading: Reading) -> list[str]:
    """The words about each other thing the description names (never the adversary)."""
    cast = reading.cast
    found = []
    for mention in cast.others:
        if mention is reading.adversary:
            continue
        start, end = _words_of(cast, mention)[0]
        words = re.sub(r"\s+", " ", cast.text[start:end]).strip(" ,;.")
        found.append(words or mention.quote)
    return found


def ground(description: str, answer: ExtractionAnswer) -> Grounded:
    """The spec of `description`: the fixed rules' readings first, the model's answers
    where they rest on words of the text, neutral defaults for what the text leaves open."""
    notes: list[str] = []
    adversary_quote = answer.adversary if quote_in(description, answer.adversary) else None
    if answer.adversary and adversary_quote is None:
        notes.append(
            f"adversary: the model's words {answer.adversary!r} are not in the description"
        )
    reading = read_description(description, adversary_quote)
    facts = dict(reading.facts)
    adversary_class: str | None = None
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
        if adversary_class == "Pedestrian" and answer.spawn_position not in _WALKER_STARTS:
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
    facts["road_type"] = _road(description, answer, facts)
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
        no_adversary=no_adversary,
        participants=participants,
        weather=facts["weather"].value,
        requirements=requirements,
        grounding=list(facts.values()),
    )
    return Grounded(spec=spec, notes=notes)
