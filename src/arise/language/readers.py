"""Fixed readers of a description: who the adversary is, where it starts, which way it and
the ego go, whether it stays put, each fact with the words it rests on.

Every reader looks only at the words about one actor (`words_of`): a side said of a parked
truck is not the pedestrian's side, and "the other car turns left" is not the ego's turn.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from functools import lru_cache
from typing import NamedTuple

from arise.language.cast import (
    VEHICLE_CLASSES,
    Cast,
    Clause,
    Mention,
    heading_end,
    party_number,
    phrase_start,
    sentence_end,
    sentence_start,
)
from arise.language.clauses import ego_speaks_before
from arise.language.facts import FactSource, GroundedFact, StartFact, start_detail, text_fact
from arise.language.generic import lessons_of
from arise.language.quotes import find_quote
from arise.language.reading import parse
from arise.language.rules import Fact, Hit, Target, rulebook
from arise.language.weather import WeatherReading, read_weather
from arise.vocabulary import (
    CROSSING_STARTS,
    ActorClass,
    AdversaryManeuver,
    AdversaryType,
    EgoManeuver,
    EgoPlan,
    RelativePosition,
    RoadType,
    StartDetail,
    Unit,
)


def cue_before(fact: Fact, text: str, position: int, *, spaced: bool = True) -> Hit | None:
    """The cue of `fact` whose words end right before `position` (starting within 40
    characters, only spaces between): "following | a van", "out from behind | a parked
    truck", "made contact with the rear end of | a van"."""
    found = None
    for hit in rulebook().hits(fact, text, max(0, position - 40), position):
        between = text[hit.end : position]
        if not between.strip() and (between or not spaced):
            found = hit
    return found


@dataclass
class Reading:
    """What the fixed rules read from one description, each with its words."""

    cast: Cast
    adversary: Mention | None = None
    facts: dict[str, GroundedFact] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    weather: WeatherReading | None = None


#: Openers of clauses about the actor just named ("a truck parked on the right, which hides
#: the car"), whoever their subject was taken to be: they never end its words.
_ABOUT_THE_ONE_BEFORE = frozenset({"which", "that", "who", "~participle"})


def _opens_with_its_subject(cast: Cast, clause: Clause) -> bool:
    """Whether the clause starts with its subject named ("and the ego wants to overtake"), not
    with a verb whose object was taken for one ("hides a second car behind it"); or goes on
    with the subject before ("emerging between two parked cars, and crosses the path")."""
    if not clause.explicit:
        return clause.subject is not None and clause.opener in _GOES_ON
    if clause.subject == "ego":
        spans = list(cast.ego)
    elif isinstance(clause.subject, Mention):
        spans = list(clause.subject.spans)
    else:
        return False
    first = next((s for s in spans if clause.start <= s.start < clause.end), None)
    if first is None:
        return False
    before = cast.text[clause.start : phrase_start(cast.text, first.start)]
    return all(word.lower() in _LEAD_WORDS for word in re.findall(r"[\w'-]+", before))


#: Openers of a clause that goes on with the subject before it.
_GOES_ON = frozenset({"and", "and then", "then", "but"})
#: Words that may stand before a clause's subject ("and then the ego ...").
_LEAD_WORDS = frozenset({"and", "but", "then", "so", "suddenly", "also", "now", "later"})


@lru_cache(maxsize=16)
def _actor_starts(cast: Cast) -> tuple[int, ...]:
    """Where the phrase of each named road user begins, in order: the ends of other actors'
    words (the same for every actor of a cast, so found once)."""
    text = cast.text
    # A road user named as a place ("between SV and POV") does not end the words before it.
    places = _between_ends(text)
    named = [
        phrase_start(text, s.start) for m in cast.others if not m.cls.is_place for s in m.spans
    ]
    return tuple(sorted(at for at in named if not any(_just_after(at, end) for end in places)))


#: "... and crossed", "... then ran": a verb joined to the clause's own subject.
_PARTICIPLE_OPENS = re.compile(
    r"\s*(?:heading|walking|running|making|going|coming|moving|cutting|crossing|riding|"
    r"driving|travelling|traveling|aiming|darting|dashing|stepping)\b",
    re.I,
)
_CARRIES_ON = re.compile(r"\b(?:and|then|and then|before|but)\s+(?=[a-z])", re.I)


def words_of(cast: Cast, mention: Mention) -> list[tuple[int, int]]:
    """The stretches of text about `mention`: from a few words before each of its spans to
    the next named actor or the end of the sentence."""
    text = cast.text
    stretches = []
    starts = _actor_starts(cast)
    inverted = [c for c in cast.clauses if c.inverted and isinstance(c.subject, Mention)]
    for span in mention.spans:
        lead = _passive_verb_start(text, phrase_start(text, span.start))
        lead = _touched_part_start(cast, lead)
        opener = _fronted_participle(cast, lead)
        if opener is not None:
            stretches.append(opener)
        # A clause whose subject follows its verb opens with words about that subject
        # ("from the right side also comes a cyclist"): they end this actor's words.
        starts_after = [s for s in starts if s > span.end]
        starts_after += [
            c.start for c in inverted if c.start > span.end and c.subject is not mention
        ]
        # A later clause that names someone else as its subject ("... a slow bus, and the ego
        # wants to overtake it from the left") is that one's words.
        starts_after += [
            c.start
            for c in cast.clauses
            if c.start > span.end
            and c.subject is not mention
            and c.opener not in _ABOUT_THE_ONE_BEFORE
            and _opens_with_its_subject(cast, c)
        ]
        end = min(starts_after, default=len(text))
        stretches.append((lead, min(end, sentence_end(text, span.end))))
    for clause in inverted:
        if clause.subject is mention:
            stretches.append((clause.start, phrase_start(text, mention.spans[0].start)))
    stretches += _opening_clauses(cast, mention)
    stretches += _carried_past_semicolon(cast, mention, stretches)
    # "... when we pass, he starts suddenly and goes out": a clause opened by a pronoun that
    # stands for this actor is about it too.
    for clause in cast.clauses:
        if (
            clause.subject is mention
            and not clause.explicit
            and (
                _PRONOUN_OPENS.match(text, clause.start)
                # "darts out from the front of the bus, heading from your left": the
                # walker's words, though the bus was named last
                or _PARTICIPLE_OPENS.match(text, clause.start)
            )
        ):
            stretches.append((clause.start, clause.end))
    # "a pedestrian emerged between the parked cars and crossed southbound": the words after
    # another actor named inside this actor's own clause are this actor's again.
    for clause in cast.clauses:
        if clause.subject is not mention or clause.inverted:
            continue
        inside = [
            s.end
            for m in cast.others
            if m is not mention
            for s in m.spans
            if clause.start <= s.start and s.end < clause.end
        ]
        joined = _CARRIES_ON.search(text, max(inside), clause.end) if inside else None
        if joined is not None:
            stretches.append((joined.start(), clause.end))
    # "On the left a van pulls out", "Ahead on the kerb side a bus has pulled in": a place
    # said before the subject it opens the clause with is about that subject.
    for clause in cast.clauses:
        if clause.subject is not mention or not clause.explicit or clause.inverted:
            continue
        named = [s.start for s in mention.spans if clause.start <= s.start < clause.end]
        if not named:
            continue
        opened = phrase_start(text, named[0])
        fronted = text[clause.start : opened]
        if (
            (_FRONTED_PLACE.match(fronted) or _FRONTED_ORIGIN.match(fronted))
            and len(fronted.split()) <= 8
            and not any(clause.start <= s.start < opened for m in cast.others for s in m.spans)
            and not any(clause.start <= s.start < opened for s in cast.ego)
        ):
            stretches.append((clause.start, opened))
    return stretches


def _carried_past_semicolon(
    cast: Cast, mention: Mention, stretches: list[tuple[int, int]]
) -> list[tuple[int, int]]:
    """The clauses after a semicolon that go on about `mention` with no subject named
    ("a pickup came up behind; struck the AV's right rear"): each one that starts right
    where its words so far end."""
    found: list[tuple[int, int]] = []
    ends = [end for _, end in stretches]
    for clause in cast.clauses:
        if (
            clause.subject is mention
            and not clause.explicit
            and not clause.inverted
            and clause.opener == ";"
            and any(0 <= clause.start - end <= 3 for end in ends)
        ):
            found.append((clause.start, clause.end))
            ends.append(clause.end)
    return found


def _opening_clauses(cast: Cast, mention: Mention) -> list[tuple[int, int]]:
    """The phrases that open a sentence before `mention` is named in it, each a clause the
    clause model gave to it ("Ahead, in the same lane, a truck ..."): one at a time, back
    from its phrase, while no one else is named in them."""
    text = cast.text
    named = [s for m in cast.others if m is not mention for s in m.spans] + list(cast.ego)
    found = []
    for span in mention.spans:
        at = phrase_start(text, span.start)
        for clause in reversed(cast.clauses):
            if clause.end > at:
                continue
            if (
                clause.subject is not mention
                or clause.explicit
                or clause.inverted
                or sentence_end(text, clause.start) < at
                or any(clause.start <= s.start < clause.end for s in named)
            ):
                break
            found.append((clause.start, clause.end))
            at = clause.start
    return found


@lru_cache(maxsize=16)
def _between_ends(text: str) -> tuple[int, ...]:
    """Where each "between the ego and" of `text` ends: words_of asks for every actor."""
    return tuple(hit.end for hit in rulebook().hits(Fact.BETWEEN_ANOTHER, text))


def _just_after(at: int, end: int) -> bool:
    """Whether a phrase starting at `at` is the one right after words ending at `end`."""
    return 0 <= at - end <= 2


#: A place phrase that opens a clause before its subject: a preposition, no verb.
_FRONTED_PLACE = re.compile(
    r"\s*(?:and\s+)?(?:just\s+|right\s+|shortly\s+|further\s+|up\s+|then\s+)?(?:ahead\s+)?"
    r"(?:on|in|at|to|off|beside|alongside|along|down|across|after|past|round|around)\s"
    r"(?![^,]*\b\w+(?:ing|ed|s)\b)[^,]*$",
    re.I,
)


#: Where the subject comes from, said before it ("From the left a car ran the red",
#: "Crossing from the left was a van"): verbs may follow, since the origin opens the clause.
_FRONTED_ORIGIN = re.compile(
    r"\s*(?:and\s+)?(?:(?:coming|approaching|crossing|travell?ing|heading|driving|moving|"
    r"riding|emerging|appearing)\s+)?from\s[^,]*$",
    re.I,
)


_PRONOUN_OPENS = re.compile(r"\s*(?:then\s+|suddenly\s+)?(?:it|he|she|they)\b", re.I)


# "Merging from the on-ramp on the right, a truck ...", "Just ahead on the right, a bus
# ...": a sentence (or clause after a semicolon) that opens with a phrase and a comma tells
# about the actor named next, unless the phrase is a clause of its own ("While the ego
# turns, ...", "When the light changed, ...").
_OPENER = re.compile(
    r"(?:^|[.;!?]\s+)"
    r"((?!(?:while|whilst|when|as|after|before|if|because|since|although|though|once|until"
    r"|where|then|but|and|so|then)\b)[A-Z][\w'-]*\b[^.;!?,]{0,80}),\s*$",
    re.I,
)


def _fronted_participle(cast: Cast, lead: int) -> tuple[int, int] | None:
    """The opening phrase right before the phrase at `lead`, when no one else is named in
    it (in "Turning left, the ego ..." it is the ego's)."""
    found = _OPENER.search(cast.text, max(0, lead - 160), lead)
    if found is None:
        return None
    start, end = found.span(1)
    named = [s for m in cast.others for s in m.spans] + list(cast.ego)
    if any(start <= s.start < end for s in named):
        return None
    return start, end


# "(is) struck from behind by a car": the passive verb before "by" says what the agent did.
_PASSIVE_AGENT = re.compile(
    r"\b(?:is|was|are|were|gets?|got|being|been)\s+([\w'-]+(?:\s+[\w'-]+){0,4}?)\s+by\s+$"
    # notes drop the verb: "ego lane blocked by stalled SUV"
    r"|\b((?:lane|way|path|road)\s+(?:blocked|obstructed)\s+by\s+)$",
    re.I,
)


def _passive_verb_start(text: str, lead: int) -> int:
    """Where the words about a passive agent begin: at its verb when the phrase follows
    "is <verb> ... by" in the same clause, else at the phrase itself."""
    found = _PASSIVE_AGENT.search(text[max(0, lead - 60) : lead])
    if found is None:
        return lead
    return max(0, lead - 60) + found.start(1 if found.group(1) is not None else 2)


#: "<the ego's part> was <verb>": the part of the ego a passive clause is about, named at
#: most this many characters before the verb.
_PART_REACH = 60
_PART_BEFORE_PASSIVE = re.compile(
    r"^\s*(?:[\w-]+\s+){0,3}?(?:is|was|were|are|got|gets|has\s+been|had\s+been)\s+$", re.I
)


def _touched_part_start(cast: Cast, lead: int) -> int:
    """Where the words about a passive agent begin when the clause's subject is a part of
    the ego ("the AV's rear bumper was struck by a bus"): at that part, which tells where
    the agent touched the ego; else `lead`."""
    for span in cast.ego:
        owner = cast.text[span.start : span.end]
        if (
            0 <= lead - span.end <= _PART_REACH
            and owner.endswith(("'s", "\u2019s"))
            and _PART_BEFORE_PASSIVE.match(cast.text[span.end : lead])
        ):
            return phrase_start(cast.text, span.start)
    return lead


def _squeezed_beside(cast: Cast, mention: Mention) -> GroundedFact | None:
    """ "riding between the AV and a car parked on the right": squeezed in on that side,
    when those words follow the actor within 40 characters of its sentence."""
    text = cast.text
    for span in mention.spans:
        found = rulebook().first(Fact.BETWEEN, text, span.end)
        if found is None:
            beside = _between_the_ego_and_another(cast, mention, span.end)
            if beside is not None:
                return beside
            continue
        lead = text[span.end : found.start]
        if len(lead) <= 40 and not re.search(r"[.;]", lead):
            return GroundedFact(
                name="spawn_position",
                value=_SIDED[RelativePosition.ADJACENT_LANE_LEFT][found.value].value,
                source=FactSource.TEXT,
                quote=text[span.end : found.end].strip(),
            )
    return None


def _between_the_ego_and_another(cast: Cast, mention: Mention, after: int) -> GroundedFact | None:
    """ "filters up between SV and POV": on the side of the road user named right after,
    as the text places that one."""
    text = cast.text
    found = rulebook().first(Fact.BETWEEN_ANOTHER, text, after)
    if (
        found is None
        or len(text[after : found.start]) > 60
        or re.search(r"[.;]", text[after : found.start])
    ):
        return None
    other = next(
        (
            m
            for m in cast.others
            if m is not mention
            and any(_just_after(phrase_start(text, s.start), found.end) for s in m.spans)
        ),
        None,
    )
    # not squeezed in its turn: "A between SV and B ... B between SV and A" reads once
    where = (
        read_position(cast, other, by_another=False, squeezed=False) if other is not None else None
    )
    if where is None:
        return None
    side = _SIDE_OF.get(RelativePosition(where.value))
    if side is None:
        return None
    return GroundedFact(
        name="spawn_position",
        value=_SIDED[RelativePosition.ADJACENT_LANE_LEFT][side].value,
        source=FactSource.TEXT,
        quote=f"{found.quote} ... {where.quote}",
    )


def _ego_verb_before(cast: Cast, mention: Mention, cue: Fact) -> GroundedFact | None:
    """The ego's own verb right before the actor puts it ahead of the ego in its lane:
    following it (`EGO_BEHIND`: "the AV was following a van", "travelling ... behind a box
    truck") or passing it (`EGO_PASSES`: "the ego pulls out to pass a slow bicycle", a
    fallback for when the actor's words say nothing of where)."""
    for span in mention.spans:
        lead = phrase_start(cast.text, span.start)
        found = cue_before(cue, cast.text, lead)
        if found and subject_of(cast, found.start) == "ego":
            return GroundedFact(
                name="spawn_position",
                value=RelativePosition.AHEAD_SAME_LANE.value,
                source=FactSource.TEXT,
                quote=cast.text[found.start : span.end],
            )
    return None


_ALONG = (RelativePosition.AHEAD_SAME_LANE, RelativePosition.BEHIND_SAME_LANE)
_BEHIND = RelativePosition.BEHIND_SAME_LANE
#: The starts that have a side, in pairs: the same start on the left and on the right.
_PAIRS: tuple[dict[str, RelativePosition], ...] = (
    {"left": RelativePosition.ROADSIDE_LEFT, "right": RelativePosition.ROADSIDE_RIGHT},
    {"left": RelativePosition.ADJACENT_LANE_LEFT, "right": RelativePosition.ADJACENT_LANE_RIGHT},
    {"left": RelativePosition.CROSSING_FROM_LEFT, "right": RelativePosition.CROSSING_FROM_RIGHT},
)
_ROADSIDE, _ADJACENT, _CROSSING = _PAIRS
#: A start of a side -> its pair, by the side said.
_SIDED = {position: pair for pair in _PAIRS for position in pair.values()}
#: A start of a side -> that side.
_SIDE_OF = {position: side for pair in _PAIRS for side, position in pair.items()}


def _lane_number(cast: Cast, stretches: list[tuple[int, int]]) -> Hit | None:
    """The first numbered lane named in these stretches of text."""
    for start, end in stretches:
        found = rulebook().first(Fact.LANE_NUMBER, cast.text, start, end)
        if found is not None:
            return found
    return None


def _ego_words(cast: Cast) -> list[tuple[int, int]]:
    """The ego's own stretches: from each of its names to the next actor named or the end
    of the sentence."""
    others = sorted(phrase_start(cast.text, s.start) for m in cast.others for s in m.spans)
    return [
        (span.start, min([s for s in others if s > span.end] + [sentence_end(cast.text, span.end)]))
        for span in cast.ego
    ]


def _right_of(cast: Cast, lane: int, other: int) -> bool:
    """Whether numbered `lane` lies right of lane `other`: lanes count from the left, as
    police reports number them, unless the text counts them from the right."""
    from_right = rulebook().first(Fact.LANE_ORDER, cast.text) is not None
    return (lane > other) != from_right


def read_lane_number(cast: Cast, mention: Mention) -> GroundedFact | None:
    """The lane beside the ego from numbered lanes ("V1 in the #1 lane ... V2 in the #2
    lane"): lanes count from the left, so a higher number than the ego's is on its right,
    unless the text counts them from the right."""
    theirs = _lane_number(cast, words_of(cast, mention))
    ours = _lane_number(cast, _ego_words(cast)) if theirs is not None else None
    if theirs is None or ours is None or theirs.value == ours.value:
        return None
    right = _right_of(cast, int(theirs.value), int(ours.value))
    return GroundedFact(
        name="spawn_position",
        value=(
            RelativePosition.ADJACENT_LANE_RIGHT if right else RelativePosition.ADJACENT_LANE_LEFT
        ).value,
        source=FactSource.TEXT,
        quote=f"{ours.quote} ... {theirs.quote}",
    )


_THIRD_PERSON = r"(?:it|them|him|her)"
#: "out from in front of it", "close behind him": the pronoun is the one named last before it.
_PRONOUN = re.compile(rf"\s*{_THIRD_PERSON}\b", re.I)
#: A cue that ends in a third-person pronoun ("behind it"): whom it means decides whose
#: start the cue tells.
_ENDS_IN_PRONOUN = re.compile(rf"\b{_THIRD_PERSON}$", re.I)


_OWNED = re.compile(r"(?:'s|^(?:my|our|your|its))$", re.I)


def _ego_named_in(cast: Cast, clause: Clause) -> bool:
    """Whether the clause names the ego itself, not only as an owner ("the AV's lane")."""
    return any(
        clause.start <= span.start < clause.end
        and not _OWNED.search(cast.text[span.start : span.end])
        for span in cast.ego
    )


_HIDDEN_BY = re.compile(r"\b(?:hidden|hiding|concealed|obscured|masked|screened)\s+$", re.I)


def _pronoun_means_another(cast: Cast, mention: Mention, hit: Hit) -> bool:
    """Whether the pronoun ending a cue ("two cones behind it") stands for another road user
    or the actor itself rather than the ego: the subject of its clause when that is another
    than the actor, else of the clauses before it ("the ego follows a car while a motorbike
    comes up behind it": the ego); without clauses, the one named last before it."""
    if not _ENDS_IN_PRONOUN.search(hit.quote):
        return False
    if _HIDDEN_BY.search(cast.text, max(0, hit.start - 30), hit.start):
        return True  # "hidden behind it": nothing hides from the ego behind the ego
    if ego_speaks_before(cast.text, cast.ego, hit.start):
        return True  # "you see a van, and behind it you make out ...": "it" is not "you"
    before = [c for c in cast.clauses if c.start <= hit.start]
    for clause in reversed(before):
        if clause.subject is None or clause.subject is mention:
            continue
        if clause.subject == "ego" and not _ego_named_in(cast, clause):
            continue  # "swerved into the AV's lane": the AV only owns the lane
        return clause.subject != "ego"
    ego_last = max((s.end for s in cast.ego if s.end <= hit.start), default=-1)
    other_last = max(
        (s.end for m in cast.others if not m.cls.is_place for s in m.spans if s.end <= hit.start),
        default=-1,
    )
    return other_last > ego_last


_DEMONSTRATIVES = frozenset({"", "that", "this", "those", "these"})


def _named_after(cast: Cast, mention: Mention, at: int) -> Mention | None:
    """The other actor whose phrase starts right at `at` (spaces aside), or, for "it" or
    "them" there, the last other actor named before it."""
    text = cast.text
    for other in cast.others:
        if other is mention or other.cls.is_place:
            continue
        for span in other.spans:
            lead = phrase_start(text, span.start)
            if lead >= at and text[at:lead].strip().lower() in _DEMONSTRATIVES:
                return other  # "up the side of | that truck"
    if not _PRONOUN.match(text, at):
        return None
    before = [
        (span.end, other)
        for other in cast.others
        if other is not mention and not other.cls.is_place
        for span in other.spans
        if span.end <= at
    ]
    return max(before, key=lambda item: item[0])[1] if before else None


def _walks_or_rides(mention: Mention) -> bool:
    """A walker or a cyclist: one that comes out from between parked cars."""
    return mention.cls in (ActorClass.PEDESTRIAN, ActorClass.BICYCLE)


#: At most this many words open a sentence before the actor they place ("Out of the gap
#: between two parked cars on the left, a child comes running").
_FRONTED_WORDS = 14
_CLAUSE_LEAD = re.compile(r"[\s,;:]*(?:(?:and|then|when|suddenly)\s+)?", re.I)


def _fronted_by_another(cast: Cast, mention: Mention) -> list[tuple[int, int]]:
    """The words that open the sentence of `mention` before its phrase when they place it
    by another actor from the first word ("out of the gap between the vans comes a boy"):
    they name that actor, so they are not the actor's own words (`words_of`)."""
    text = cast.text
    found = []
    for span in mention.spans:
        opened = phrase_start(text, span.start)
        first = sentence_start(text, opened)
        # the sentence's start, or a clause's in it ("Two vans are parked, and out of ...")
        for start in sorted({first, *(c.start for c in cast.clauses if first < c.start < opened)}):
            lead = _CLAUSE_LEAD.match(text, start)
            start = lead.end() if lead else start
            hit = rulebook().first(Fact.BY_ANOTHER, text, start, opened)
            if (
                hit is not None
                # "out of the gap between the vans comes a boy", "Behind him a truck"
                and hit.value in ("emerges", "behind", "ahead")
                and hit.start == start
                and len(text[start:opened].split()) <= _FRONTED_WORDS
            ):
                found.append((start, opened))
                break
    return found


def _by_another(cast: Cast, mention: Mention) -> GroundedFact | None:
    """A start said by another actor whose start the text gives: a walker that steps out
    from behind (or in front of) a van parked on the left crosses from the left; a vehicle
    coming up behind a car in the lane to the left is in that lane too, and one behind an
    oncoming car is oncoming."""
    text = cast.text
    walker = _walks_or_rides(mention)
    for start, end in [*words_of(cast, mention), *_fronted_by_another(cast, mention)]:
        for hit in rulebook().hits(Fact.BY_ANOTHER, text, start, min(len(text), end + 1)):
            other = _named_after(cast, mention, hit.end)
            if other is None:
                continue
            told = read_compass(cast, other) or read_position(cast, other, by_another=False)
            if told is None:
                continue
            theirs = RelativePosition(told.value)
            position: RelativePosition | None = None
            if hit.value == "emerges" and walker and theirs in _SIDE_OF:
                position = _SIDED[RelativePosition.CROSSING_FROM_LEFT][_SIDE_OF[theirs]]
            elif hit.value in ("behind", "ahead") and not walker:
                position = theirs  # behind a car ahead is ahead, behind an oncoming one oncoming
            elif not mention.cls.is_walker and theirs is RelativePosition.ONCOMING:
                # out from behind, past, beside or hidden by an oncoming one (a rider too)
                position = theirs
            if position is not None:
                return GroundedFact(
                    name="spawn_position",
                    value=position.value,
                    source=FactSource.TEXT,
                    quote=f"{hit.quote} ... {told.quote}",
                )
    return None


class _Cue(NamedTuple):
    """A start some words give: where they are and the rule's order (the earliest wins),
    the position they say and the words themselves."""

    at: int
    order: int
    position: RelativePosition
    quote: str

    @property
    def rank(self) -> tuple[int, int]:
        return (self.at, self.order)


@dataclass
class _PositionCues:
    """What the words about one actor say of its start, gathered over all its stretches."""

    best: _Cue | None = None
    fallback: _Cue | None = None  # from a weak rule
    damage: set[tuple[int, int]] = field(default_factory=set)  # from where the ego was touched
    routed: set[tuple[int, int]] = field(default_factory=set)  # on the road a turning ego enters
    side_damage: list[_Cue] = field(default_factory=list)  # a side of the ego that was hit


def _from_there(cast: Cast, stretches: list[tuple[int, int]]) -> _Cue | None:
    """ "from there" in the actor's words (`stretches`): the place named last before it
    ("keep an eye on the far pavement: a child may dart out from there")."""
    for start, end in stretches:
        there = rulebook().first(Fact.THERE, cast.text, start, end)
        if there is None:
            continue
        since = max(0, there.start - 240)
        places = [
            hit
            for hit in rulebook().hits(Fact.START, cast.text, since, there.start)
            if hit.end <= there.start
        ]
        if places:
            place = max(places, key=lambda hit: hit.start)
            quote = f"{place.quote} ... {there.quote}"
            return _Cue(place.start, place.order, RelativePosition(place.value), quote)
    return None


def read_start(cast: Cast, mention: Mention) -> GroundedFact | None:
    """Where `mention` starts, seen from the ego: from compass headings when the text gives
    the ego's and its own, else from the words about it."""
    return read_compass(cast, mention) or read_position(cast, mention)


def read_position(
    cast: Cast, mention: Mention, *, by_another: bool = True, squeezed: bool = True
) -> GroundedFact | None:
    """Where `mention` starts, seen from the ego, from the words about it; when they say
    none, from the start of another actor they place it by (`_by_another`)."""
    told = (
        read_lane_number(cast, mention)
        or _ego_verb_before(cast, mention, Fact.EGO_BEHIND)
        or (_squeezed_beside(cast, mention) if squeezed else None)
    )
    if told is not None and told.value != RelativePosition.AHEAD_SAME_LANE.value:
        return told
    stretches = words_of(cast, mention)
    there = _from_there(cast, stretches)
    # the place a "where" clause about it opens on tells its start, not what it does
    cues = _position_cues(cast, mention, stretches + _place_it_is_in(cast, mention), there)
    if told is not None and not (cues.best is not None and cues.best.rank in cues.routed):
        # ... but a turning ego that waits behind it ("hold back behind the lorry") meets it
        # where its own words put it, just round the corner
        return told
    # "came up behind the AV ...; struck its passenger-side rear": the side it hit tells
    # the lane it came up in, from behind (not the road across, as side damage alone does);
    # "a little ahead of V1 ... struck V1's left front corner": that lane, ahead
    along_then_hit = bool(
        cues.best is not None
        and cues.best.position in _ALONG
        and cues.side_damage
        and cues.best.rank not in cues.routed
    )
    from_behind = along_then_hit and cues.best is not None and cues.best.position is _BEHIND
    ahead_beside = along_then_hit and not from_behind
    best = (min(cues.side_damage) if along_then_hit else cues.best) or cues.fallback
    best = best or there
    if best is None:
        return _start_unplaced(cast, mention, stretches, by_another=by_another)
    if by_another and (placed := _placed_by_another(cast, mention, best.position)) is not None:
        return placed
    position = best.position
    damaged = best.rank in cues.damage
    if (
        position in _ADJACENT.values()
        and (damaged or _side_alone(mention, " ".join(cast.text[a:b] for a, b in stretches)))
        and not along_then_hit
        and _crosses_there(cast, mention)
    ):
        # "struck the AV on its driver's side", "a car on the ego's left at the four-way
        # stop": at a junction, the crossing road from that side
        position = _CROSSING[_SIDE_OF[position]]
    elif (
        position in _ADJACENT.values()
        and damaged
        and (across := _straight_through_the_turn(cast, mention, stretches, position))
    ):
        # "V2 went straight through and struck V1's passenger side" as V1 turned left
        return across
    walker = mention.cls.is_walker or mention.is_prop
    if (
        position is RelativePosition.BEHIND_SAME_LANE
        and not walker
        and (changed_to := _ego_lane_change_side(cast)) is not None
        and any(rulebook().first(Fact.CLOSES_FROM_BEHIND, cast.text, a, b) for a, b in stretches)
    ):
        # "the ego moved over to the right ... a motorcycle came up from behind": coming up
        # fast behind an ego that changes lanes, it is in the lane the ego moves into
        position = _ADJACENT[changed_to]
        from_behind = True
    if mention.cls.is_walker and position in _ADJACENT.values():
        # A walker "from the passenger side", "in the lane on the right": no walker starts
        # in a traffic lane; it stands at that kerb, or comes off it across the road.
        pair = _ROADSIDE if read_stationary(cast, mention) else _CROSSING
        position = pair[_SIDE_OF[position]]
    # Waiting in the lane a turning ego enters; one that moves on that road may come the
    # other way ("riding toward the junction on the road the ego turns into").
    exit_lane = (
        best.rank in cues.routed
        and position is RelativePosition.AHEAD_SAME_LANE
        and not moves_in(cast.text, stretches)
    )
    return StartFact(
        name="spawn_position",
        value=position.value,
        source=FactSource.TEXT,
        quote=best.quote,
        detail=(
            StartDetail.EXIT_LANE
            if exit_lane
            else StartDetail.FROM_BEHIND
            if from_behind and position in _ADJACENT.values()
            else StartDetail.AHEAD
            if ahead_beside and position in _ADJACENT.values()
            else None
        ),
    )


_WHERE = re.compile(r"[\s,]+where\s+$", re.I)
#: At most this many words name the place a "where" clause opens on.
_PLACE_WORDS = 12


def _place_it_is_in(cast: Cast, mention: Mention) -> list[tuple[int, int]]:
    """The place a "where" clause about `mention` opens on: "the van hides the cross street
    on your right side, where a motorcyclist is trying to beat the red" (from the last
    actor named before it)."""
    text = cast.text
    found = []
    named = [s.end for m in cast.others for s in m.spans] + [s.end for s in cast.ego]
    for span in mention.spans:
        opened = phrase_start(text, span.start)
        where = _WHERE.search(text, sentence_start(text, opened), opened)
        if where is None or where.end() != opened:
            continue
        start = max([sentence_start(text, opened), *(e for e in named if e <= where.start())])
        if len(text[start : where.start()].split()) <= _PLACE_WORDS:
            found.append((start, where.start()))
    return found


def _position_cues(
    cast: Cast,
    mention: Mention,
    stretches: list[tuple[int, int]],
    there: _Cue | None,
) -> _PositionCues:
    """The start each stretch of words about `mention` gives, the earliest cue winning."""
    gathered = _PositionCues()
    side_said = next(
        (hit for a, b in stretches if (hit := rulebook().first(Fact.BARE_SIDE, cast.text, a, b))),
        None,
    )
    walker = mention.cls.is_walker or mention.is_prop
    on_exit_street = bool(ego_turns(cast)) and any(
        _exit_street_named(cast, cast.text[a:b], along=True) for a, b in stretches
    )
    for start, end in stretches:
        # "on the right"/"on its left" alone: a lane for a vehicle, the roadside for a walker.
        bare = rulebook().first(Fact.BARE_SIDE, cast.text, start, end)
        cues, weak = _start_cues(cast, mention, (start, end), bare or side_said, gathered)
        if on_exit_street:
            # "Along Abbeymoor Lane a cyclist is heading your way": on the street it enters
            toward = (cue for cue in cues if cue.position is RelativePosition.ONCOMING)
            gathered.routed.update(cue.rank for cue in toward)
        on_route = any(cue.rank in gathered.routed for cue in cues)
        cues, weak = _on_the_road_entered(cast, cues, weak, gathered.routed, on_route=on_route)
        gathered.side_damage += [
            cue
            for cue in cues
            if cue.rank in gathered.damage and cue.position in _ADJACENT.values()
        ]
        cues = _side_over_end(cues, side_said, there, on_route=on_route)
        for cue in cues:
            if gathered.best is None or cue.rank < gathered.best.rank:
                gathered.best = cue
        if weak and gathered.fallback is None:
            gathered.fallback = min(weak, key=lambda cue: cue.rank)
        if bare and gathered.best is None:
            kind = RelativePosition.ROADSIDE_LEFT if walker else RelativePosition.ADJACENT_LANE_LEFT
            gathered.best = _Cue(bare.start, 99, _SIDED[kind][bare.value], bare.quote)
        _read_target_lane(cast, (start, end), gathered)
    return gathered


def _start_cues(
    cast: Cast,
    mention: Mention,
    stretch: tuple[int, int],
    side: Hit | None,
    gathered: _PositionCues,
) -> tuple[list[_Cue], list[_Cue]]:
    """The start rules' hits in one stretch about `mention`, strong and weak, the first hit
    of each position counting; damage and on-route cues are noted in `gathered`."""
    start, end = stretch
    cues: list[_Cue] = []
    weak: list[_Cue] = []
    seen_values: set[tuple[str, bool]] = set()
    # A rule's `unless` may see a little past the stretch ("from behind | a parked van");
    # the cue itself must lie inside it.
    for hit in rulebook().hits(Fact.START, cast.text, start, end + 40):
        if (hit.value, hit.rule.weak) in seen_values:
            continue
        if hit.rule.about is Target.SUBJECT and subject_of(cast, hit.start) is not mention:
            continue  # the words tell what the clause's subject does, and it is another
        if _pronoun_means_another(cast, mention, hit):
            continue  # "behind it" of a car named before: placed by that car
        if hit.rule.after_turn and not ego_turns(cast):
            continue  # "in the side street" of an ego that does not turn into it
        seen_values.add((hit.value, hit.rule.weak))
        if hit.end > end:
            continue
        cue = _Cue(hit.start, hit.order, RelativePosition(hit.value), hit.quote)
        if hit.rule.side_assumed and side and cue.position in _SIDED:
            # "at the kerb ... on my left": the side said wins over the usual one.
            said = _SIDED[cue.position][side.value]
            cue = cue._replace(position=said, quote=f"{cue.quote} ... {side.quote}")
        (weak if hit.rule.weak else cues).append(cue)
        if hit.rule.damage:
            gathered.damage.add(cue.rank)
        if hit.rule.after_turn:
            gathered.routed.add(cue.rank)
    return cues, weak


def _on_the_road_entered(
    cast: Cast,
    cues: list[_Cue],
    weak: list[_Cue],
    routed: set[tuple[int, int]],
    *,
    on_route: bool,
) -> tuple[list[_Cue], list[_Cue]]:
    """Cues on the road a turning ego enters: one coming toward the junction along it comes
    from the side the ego turns to, or from the side told; else the side of that road, not
    a lane beside the ego."""
    toward = next(
        (cue for cue in [*cues, *weak] if cue.position is RelativePosition.ONCOMING), None
    )
    turned = sorted(ego_turns(cast)) if on_route and toward else []
    if toward is not None and len(turned) == 1:
        # "riding toward the junction on the road the ego turns into"
        from_side = _CROSSING["left" if turned[0] == "turn_left" else "right"]
        routed_quote = next(cue.quote for cue in cues if cue.rank in routed)
        routed.clear()
        return [toward._replace(position=from_side, quote=f"{toward.quote} ... {routed_quote}")], []
    crossing = [cue for cue in cues if cue.position in CROSSING_STARTS]
    if on_route and crossing:
        # "approaching from SV's left, in the lane SV is entering": coming along that road
        # from the side told, not standing in it
        routed.clear()
        return crossing, weak
    if on_route:
        # "double-parked just past the corner on the right": the side of the road the ego
        # turns into; a kerb said still holds ("parked at the kerb just round the corner").
        kerb = [cue for cue in cues if cue.position in _ROADSIDE.values()]
        return kerb or [cue for cue in cues if cue.rank in routed], weak
    return cues, weak


def _side_over_end(
    cues: list[_Cue],
    side_said: Hit | None,
    there: _Cue | None,
    *,
    on_route: bool,
) -> list[_Cue]:
    """A side said tells more than an end (ahead or behind) said with it."""
    if any(cue.position in _SIDED for cue in cues) and any(cue.position in _ALONG for cue in cues):
        # "comes from behind in the left lane", "just ahead of me in the right-hand lane",
        # "behind me, coming from my right"
        cues = [cue for cue in cues if cue.position not in _ALONG]
    if side_said and cues and all(cue.position in _ALONG for cue in cues) and not on_route:
        # "beside me at left, a little in front": the side's lane (or kerb), read apart
        return []
    if cues and there and there.position in _SIDED and all(cue.position in _ALONG for cue in cues):
        # "the lane on the right ... a motorbike comes there from behind": that lane.
        return [there]
    return cues


def _read_target_lane(cast: Cast, stretch: tuple[int, int], gathered: _PositionCues) -> None:
    """ "A car coming up in that lane": the lane the ego moves into, by its own lane change
    ("moves into the left lane"); with none said, the lane a turning ego enters."""
    start, end = stretch
    target = rulebook().first(Fact.TARGET_LANE, cast.text, start, end)
    if target is None:
        return
    lane_side = rulebook().first(Fact.LANE_SIDE, cast.text)
    if not lane_side and gathered.fallback is None:
        # Ahead on its route, unless the actor's words place it ("in that lane ... hit the
        # AV's rear").
        gathered.fallback = _Cue(target.start, -1, RelativePosition.AHEAD_SAME_LANE, target.quote)
        if ego_turns(cast):  # "stopped in the lane the ego enters" as it turns: on that road
            gathered.routed.add(gathered.fallback.rank)
    best = gathered.best
    behind_here = (
        best is not None and best.position is RelativePosition.BEHIND_SAME_LANE and best.at >= start
    )
    if lane_side and (best is None or target.start < best.at or behind_here):
        position = (
            RelativePosition.ADJACENT_LANE_LEFT
            if lane_side.value == "left"
            else RelativePosition.ADJACENT_LANE_RIGHT
        )
        gathered.best = _Cue(target.start, -1, position, f"{lane_side.quote} ... {target.quote}")


def _start_unplaced(
    cast: Cast, mention: Mention, stretches: list[tuple[int, int]], *, by_another: bool
) -> GroundedFact | None:
    """The start of an actor whose own words say none: waiting on the street a turning ego
    enters, placed by another actor, passed by the ego, or through the ego's turn."""
    if not _walks_or_rides(mention):
        waits_there = _waits_on_exit_street(cast, mention, stretches)
        if waits_there is not None:
            return waits_there
    if not by_another:
        return None
    return (
        _by_another(cast, mention)
        or _ego_verb_before(cast, mention, Fact.EGO_PASSES)
        or _straight_through_the_turn(cast, mention, stretches)
    )


def _placed_by_another(
    cast: Cast, mention: Mention, position: RelativePosition
) -> GroundedFact | None:
    """Where another actor places `mention` when that tells more than its own words."""
    if position in _ALONG and _walks_or_rides(mention):
        # "steps out from in front of it and walks across the ego's path": the side of the
        # car it comes out by tells more than the path it crosses.
        return _by_another(cast, mention)
    if position in _ADJACENT.values() and not (mention.cls.is_walker or mention.is_prop):
        # "behind it, on its right" of a truck coming the other way: on the truck's road
        beside = _by_another(cast, mention)
        if beside is not None and beside.value == RelativePosition.ONCOMING.value:
            return beside
    return None


#: Where a vehicle that goes straight on, its side unsaid, comes from while the ego turns:
#: a left turn crosses the traffic coming the other way, a right turn joins the traffic
#: from the left (the conflicts of right-hand traffic); and the side of the ego it hits.
_THROUGH_THE_TURN: dict[str, tuple[RelativePosition, RelativePosition]] = {
    "turn_left": (RelativePosition.ONCOMING, RelativePosition.ADJACENT_LANE_RIGHT),
    "turn_right": (RelativePosition.CROSSING_FROM_LEFT, RelativePosition.ADJACENT_LANE_LEFT),
}


def _straight_through_the_turn(
    cast: Cast,
    mention: Mention,
    stretches: list[tuple[int, int]],
    hit_side: RelativePosition | None = None,
) -> GroundedFact | None:
    """A vehicle that goes straight on, its side unsaid, while the ego turns ("V1 turned
    left; V2, a motorcycle, proceeded straight"): from where that turn meets traffic
    (`_THROUGH_THE_TURN`); with the side of the ego it hit (`hit_side`), only when that is
    the side such a vehicle hits."""
    turns = ego_turns(cast)
    if mention.cls.is_walker or mention.is_prop or len(turns) != 1:
        return None
    start, struck = _THROUGH_THE_TURN[next(iter(turns))]
    if hit_side is not None and hit_side is not struck:
        return None
    straight = next(
        (
            hit
            for a, b in stretches
            for hit in rulebook().hits(Fact.TURN, cast.text, a, b)
            if hit.value == "straight" and subject_of(cast, hit.start) is mention
        ),
        None,
    )
    if straight is None:
        return None
    return GroundedFact(
        name="spawn_position", value=start.value, source=FactSource.TEXT, quote=straight.quote
    )


@lru_cache(maxsize=16)
def _ego_lane_change_side(cast: Cast) -> str | None:
    """The side ("left", "right") of a lane change the text has the ego make, if any."""
    if not any(
        hit.value == "change_lane" and subject_of(cast, hit.start) == "ego"
        for hit in rulebook().hits(Fact.TURN, cast.text)
    ):
        return None
    side = _ego_lane_side_hit(cast)
    return side.value if side is not None else None


def _ego_lane_side_hit(cast: Cast) -> Hit | None:
    """The first words that give the side of a lane change whose subject is the ego."""
    return next(
        (
            hit
            for hit in rulebook().hits(Fact.LANE_SIDE, cast.text)
            if subject_of(cast, hit.start) == "ego"
        ),
        None,
    )


@lru_cache(maxsize=16)
def ego_turns(cast: Cast) -> frozenset[str]:
    """The turns ("turn_left", "turn_right") the text has the ego make; cached, as every
    actor's start asks for them."""
    return frozenset(
        hit.value
        for hit in rulebook().hits(Fact.TURN, cast.text)
        if hit.value in ("turn_left", "turn_right") and subject_of(cast, hit.start) == "ego"
    )


#: Words with a side that put a road user beside the ego, in a lane of its road.
_BESIDE_WORDS = re.compile(
    r"\b(?:lanes?|beside|alongside|next to|abreast|level with|passing|overtak\w*|filter\w*)\b",
    re.I,
)


def _side_alone(mention: Mention, words: str) -> bool:
    """Whether a car, van, truck or bus is placed by a side alone ("on the left", "to the
    ego's right"), with no lane or word of going along beside the ego; two-wheelers filter
    beside the ego at a junction as well."""
    return (
        mention.cls.is_vehicle
        and not mention.cls.is_two_wheeler
        and _BESIDE_WORDS.search(words) is None
    )


def _crosses_there(cast: Cast, mention: Mention) -> bool:
    """Whether a road user on the ego's side (hit it there, or said to be there) came along
    the crossing road: the scene is a junction (its road words, else traffic-control
    words), the ego does not turn (one going its way hits a turning ego's side too) and the
    road user's words say no lane change, which would put it beside the ego."""
    if ego_turns(cast):
        return False
    road = rulebook().by_order(Fact.ROAD, cast.text)
    if road is not None and road.value not in (RoadType.INTERSECTION, RoadType.T_JUNCTION):
        return False
    if road is None and rulebook().first(Fact.TRAFFIC_CONTROL, cast.text) is None:
        return False
    return not any(
        hit.value == "change_lane"
        for start, end in words_of(cast, mention)
        for hit in rulebook().hits(Fact.TURN, cast.text, start, end)
    )


_COMPASS = {"north": 0, "east": 90, "south": 180, "west": 270}
_CORNERS = {"northeast": 45, "southeast": 135, "southwest": 225, "northwest": 315}


def _heading(text: str, start: int, end: int) -> Hit | None:
    """The first compass heading in text[start:end] (rules of `heading`)."""
    return rulebook().first(Fact.HEADING, text, start, end)


# A street's name: one or two capitalised words or an ordinal ("5th"), and the kind of
# street, in full or as reports abbreviate it ("Oak Ave", "W 5th St").
_STREET = (
    r"(?:[A-Z][a-z]+ )?(?:[A-Z][a-z]+|\d+(?:st|nd|rd|th)) "
    r"(?:Avenue|Street|Road|Lane|Boulevard|Drive|Way|Place|Parkway|Highway"
    r"|Ave|St|Rd|Blvd|Dr|Ln|Pl|Pkwy|Hwy)\b"
)
_FROM_COMPASS = {"north": "south", "south": "north", "east": "west", "west": "east"}


def _side_road_bearing(text: str, words: str) -> tuple[int, str] | None:
    """An actor "on Larkmoor Avenue", where the text says that street "meets ... from the
    north", travels south: its bearing, and the words that say so."""
    named = re.search(rf"\b(?:on|from|out of) ({_STREET})", words)
    if not named:
        return None
    told = re.search(
        rf"{re.escape(named.group(1))},? (?:which |that )?(?:meets|joins|enters|comes in|"
        r"runs in|crosses)[^.;]{0,60}?\bfrom the (north|east|south|west)\b",
        text,
    )
    if not told:
        return None
    return (_COMPASS[told.group(1).lower()] + 180) % 360, told.group(0)


#: The ego's first names looked at for its bearing: a report gives it early, and a text
#: that names the ego hundreds of times must not cost a pass per name.
_BEARING_NAMES = 12


@lru_cache(maxsize=16)
def _ego_bearing(cast: Cast) -> int | None:
    """The ego's compass bearing before any turn, from its own words ("the AV was
    northbound"); None when they give none."""
    # up to the other's phrase: "the AV was hit by an eastbound sedan" is the sedan's bearing
    others = sorted(phrase_start(cast.text, s.start) for m in cast.others for s in m.spans)
    for span in cast.ego[:_BEARING_NAMES]:
        # In the ego's own words: up to the next actor named or the end of the sentence
        # ("V1 entered the intersection of A Street and 9th Avenue eastbound").
        until = min([s for s in others if s > span.end] + [sentence_end(cast.text, span.end)])
        found = next(
            (  # "she was driving the insured vehicle north": the ego inside the words
                hit
                for hit in rulebook().hits(
                    Fact.HEADING, cast.text, sentence_start(cast.text, span.start), until
                )
                if hit.start < span.start and hit.end >= span.end
            ),
            None,
        ) or _heading(cast.text, span.end, min(until, span.end + 120))
        opener = _fronted_participle(cast, phrase_start(cast.text, span.start))
        if opener is not None and found is None:  # "Heading south on Pike Road, the AV ..."
            found = _heading(cast.text, *opener)
            if found:
                return _COMPASS[found.value]
        # within the ego's sentence (`until`, which knows "Mr." ends none) and clause
        if found and ";" not in cast.text[span.end : found.start]:
            return _COMPASS[found.value]
    return None


def _own_heading(cast: Cast, start: int, end: int) -> Hit | None:
    """An actor's compass heading in its words, then with the few characters before ("an
    eastbound sedan")."""
    back = max(0, start - 15, sentence_start(cast.text, start))  # not the sentence before
    return _heading(cast.text, start, end) or _heading(cast.text, back, end)


def read_compass(cast: Cast, mention: Mention) -> GroundedFact | None:
    """A side from compass words ("the AV was northbound; an eastbound car"), as crash
    reports give them: the ego's bearing from its own words, the actor's from its words."""
    ego_bearing = _ego_bearing(cast)
    if ego_bearing is None:
        return None
    for start, end in words_of(cast, mention):
        corner = rulebook().first(Fact.CORNER, cast.text, start, end)
        if corner is not None:
            # a corner to the right of the ego's bearing (0-180 degrees round) is on its right
            right = 0 < (_CORNERS[corner.value] - ego_bearing) % 360 < 180
            kerb = RelativePosition.ROADSIDE_RIGHT if right else RelativePosition.ROADSIDE_LEFT
            return GroundedFact(
                name="spawn_position", value=kerb.value, source=FactSource.TEXT, quote=corner.quote
            )
        curb = rulebook().first(Fact.CURB, cast.text, start, end)
        side = {90: RelativePosition.ROADSIDE_RIGHT, 270: RelativePosition.ROADSIDE_LEFT}.get(
            (_COMPASS[curb.value] - ego_bearing) % 360 if curb else -1
        )
        if curb is not None and side is not None:
            return GroundedFact(
                name="spawn_position", value=side.value, source=FactSource.TEXT, quote=curb.quote
            )
        words = cast.text[max(0, start - 15, sentence_start(cast.text, start)) : end]
        bound = _own_heading(cast, start, end)
        heading = (
            (_COMPASS[bound.value], bound.quote) if bound else _side_road_bearing(cast.text, words)
        )
        if heading is None:
            continue
        relative = (heading[0] - ego_bearing) % 360
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
                quote=heading[1],
            )
    return None


def subject_of(cast: Cast, position: int) -> Mention | str | None:
    """Who a verb at `position` is about: the subject of its clause (`language.clauses`);
    without clauses, the actor named last before it in its sentence, or, for a leading
    participle ("Turning left at ..., the ego ..."), the one after it."""
    if cast.clauses:
        return cast.subject_at(position)
    head = cast.text[:position]
    sentence_start = max(head.rfind(c) for c in ".;!?") + 1
    if not head[sentence_start:].strip() or re.fullmatch(
        r"\s*(?:while |when |as |after |before )?", head[sentence_start:], re.I
    ):
        return cast.subject_after(position)
    if re.search(r",\s*$", head) and re.match(r"\w+ing\b", cast.text[position:]):
        # A trailing participle (", changing lanes twice") is about the clause's subject,
        # the first actor of the sentence, not the last one named before the comma.
        return cast.subject_after(sentence_start)
    return cast.subject_before(position)


def read_ego_overtaking(reading: Reading) -> None:
    """An ego that overtakes changes lanes to the left, and an adversary it overtakes starts
    ahead of it in its lane (right-hand traffic); only where no other words give the ego's
    maneuver or the adversary's start. Overtaking through the oncoming lane is a bypass."""
    adversary = reading.adversary
    if adversary is not None and adversary.cls not in VEHICLE_CLASSES:
        return  # going by a walker or a rider needs no lane change
    said = reading.facts.get("ego_maneuver")
    if said is not None and (
        said.value != EgoManeuver.CHANGE_LANE.value or "ego_lane_side" in reading.facts
    ):
        return  # a lane change with no side said: overtaking gives the side
    text = reading.cast.text
    book = rulebook()
    for match in book.hits(Fact.EGO_OVERTAKES, text):
        if subject_of(reading.cast, match.start) != "ego":
            continue
        quote = match.quote
        through = book.first(
            Fact.THROUGH_ONCOMING, text, match.start, sentence_end(text, match.start)
        )
        if through is not None:  # around it on the other side of the road: a bypass
            reading.facts.setdefault(
                "ego_plan",
                GroundedFact(
                    name="ego_plan",
                    value=EgoPlan.BYPASS.value,
                    source=FactSource.TEXT,
                    quote=f"{quote} ... {through.quote}",
                ),
            )
            return
        for name, value in (
            ("ego_maneuver", EgoManeuver.CHANGE_LANE.value),
            ("ego_lane_side", "left"),
        ):
            reading.facts[name] = GroundedFact(
                name=name, value=value, source=FactSource.TEXT, quote=quote
            )
        if adversary is not None and "spawn_position" not in reading.facts:
            reading.facts["spawn_position"] = GroundedFact(
                name="spawn_position",
                value=RelativePosition.AHEAD_SAME_LANE.value,
                source=FactSource.TEXT,
                quote=quote,
            )
        return


_LANE_NUMBERS = re.compile(r"\b(\d)\b\D+\b(\d)\b")


_ONE_LANE_NUMBER = re.compile(r"#\s*(\d)\b")


def _numbered_lane_change(cast: Cast, words: str) -> tuple[str, str] | None:
    """The side of a move between numbered lanes ("from the #2 lane to the #1 lane"), or
    into one ("a lane change into the #2 lane") from the lane the ego's words put it in."""
    numbers = _LANE_NUMBERS.search(words)
    if numbers is not None:
        if numbers.group(1) == numbers.group(2):
            return None
        right = _right_of(cast, int(numbers.group(2)), int(numbers.group(1)))
        return ("right" if right else "left", words)
    into = _ONE_LANE_NUMBER.search(words)
    ours = _lane_number(cast, _ego_words(cast)) if into is not None else None
    if into is None or ours is None or ours.value == into.group(1):
        return None
    right = _right_of(cast, int(into.group(1)), int(ours.value))
    return ("right" if right else "left", f"{ours.quote} ... {words}")


#: Words right before a heading that say the ego takes it by turning: "turned onto
#: northbound Elm Avenue", "to go south on Brannock", "turning west into Oak Street".
_TURNING_ONTO = re.compile(
    r"\b(?:turn\w*|onto|to\s+go|to\s+head|to\s+travel|swung|swing\w*|bore|bear\w*)"
    r"(?:\s+(?:on|onto|into|to|the|a))*\s+$",
    re.I,
)


def _compass_turn(cast: Cast) -> tuple[EgoManeuver, str] | None:
    """A turn told by compass headings alone: the ego's bearing, then a heading a quarter
    round that its words turn onto (to the right when clockwise)."""
    bearing = _ego_bearing(cast)
    if bearing is None:
        return None
    for found in _BEARING_WORD.finditer(cast.text):
        if not _TURNING_ONTO.search(cast.text, max(0, found.start() - 30), found.start()):
            continue
        if subject_of(cast, found.start()) != "ego":
            continue
        turn = {90: EgoManeuver.TURN_RIGHT, 270: EgoManeuver.TURN_LEFT}.get(
            (_COMPASS[found.group(1).lower()] - bearing) % 360
        )
        if turn is not None:
            return turn, found.group(0)
    return None


#: A compass bearing taken ("northbound", "north", "westward").
_BEARING_WORD = re.compile(r"\b(north|south|east|west)(?:bound|ward|wards)?\b", re.I)


def read_maneuvers(reading: Reading) -> None:
    """The ego's maneuver and the adversary's turn, each from verbs about that actor."""
    cast = reading.cast
    ego: tuple[EgoManeuver, str] | None = None
    adversary: tuple[AdversaryManeuver, str] | None = None
    found: list[tuple[int, str, str]] = []
    for hit in rulebook().hits(Fact.TURN, cast.text):
        found.append((hit.start, hit.value, hit.quote))
    # A typology heading ("Left-turn-across-path family: ...") names the crash, maybe by the
    # other's move: the body's words come first, the heading's only when the body says none.
    heading = heading_end(cast.text)
    found.sort(key=lambda item: (item[0] < heading, item[0]))
    for position, kind, words in found:
        subject = subject_of(cast, position)
        if subject is None and re.match(r"unprotected", words, re.I):
            subject = "ego"
        # Going straight is what the ego does until it does something else: a lane change
        # said after it in the body is the maneuver ("was travelling straight ... pulled
        # out to pass"); a heading's words come last and decide nothing here.
        if subject == "ego" and (
            ego is None
            or (ego[0] is EgoManeuver.GO_STRAIGHT and kind == "change_lane" and position >= heading)
        ):
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
    if ego is None:
        ego = _compass_turn(cast)  # "was eastbound ... turned onto northbound Elm Avenue"
    if ego is not None:
        reading.facts["ego_maneuver"] = GroundedFact(
            name="ego_maneuver", value=ego[0].value, source=FactSource.TEXT, quote=ego[1]
        )
    if ego is not None and ego[0] is EgoManeuver.CHANGE_LANE:
        said = _ego_lane_side_hit(cast)
        side = _numbered_lane_change(cast, ego[1]) or (
            (said.value, said.quote) if said is not None else None
        )
        if side is not None:
            reading.facts["ego_lane_side"] = GroundedFact(
                name="ego_lane_side", value=side[0], source=FactSource.TEXT, quote=side[1]
            )
    if adversary is not None:
        reading.facts["adversary_maneuver"] = GroundedFact(
            name="adversary_maneuver",
            value=adversary[0].value,
            source=FactSource.TEXT,
            quote=adversary[1],
        )


_ONTO_STREET = re.compile(
    rf"\b(?:onto|into|turn(?:s|ed|ing)? (?:left|right) on|to go (?:\w+ )?on) ({_STREET})"
)


def _exit_street_named(cast: Cast, words: str, *, along: bool = False) -> str | None:
    """ "the AV was turning right ... onto Tamsin Street when a pedestrian entered the
    crosswalk on Tamsin Street": the street the ego turns onto, named in the actor's words.
    Code, not a rule: a street's name is a capitalised word, and patterns ignore case."""
    for onto in _ONTO_STREET.finditer(cast.text):
        if subject_of(cast, onto.start()) == "ego":
            # "along"/"down" it: a way of moving on it, not a place to stand
            places = "on|across|of|along|down|up" if along else "on|across|of"
            named = re.search(rf"\b(?:{places}) {re.escape(onto.group(1))}", words, re.I)
            return named.group(0) if named else None
    return None


def _waits_on_exit_street(
    cast: Cast, mention: Mention, stretches: list[tuple[int, int]]
) -> StartFact | None:
    """A vehicle that stays put on the street the ego turns onto, named ("turning left
    onto Tenter Street ... a van double-parked on Tenter Street"): in that street's lane,
    ahead on the ego's route."""
    if moves_in(cast.text, stretches):
        return None
    for start, end in stretches:
        street = _exit_street_named(cast, cast.text[start:end])
        if street is not None:
            return StartFact(
                name="spawn_position",
                value=RelativePosition.AHEAD_SAME_LANE.value,
                source=FactSource.TEXT,
                quote=street,
                detail=StartDetail.EXIT_LANE,
            )
    return None


@dataclass(frozen=True)
class ExitStreetWalker:
    """A walker or cyclist on the street a turning ego enters: the side it starts on (the
    one the ego turns to), which corner, and the words that say so."""

    position: RelativePosition
    detail: StartDetail
    quote: str
    heading: Hit | None  # its compass heading, when that placed it


def exit_street_walker(
    cast: Cast, mention: Mention, ego_maneuver: str | None
) -> ExitStreetWalker | None:
    """Where a walker or cyclist crossing the street a turning ego enters starts: at the
    corner on the side the ego turns to; the far corner when it comes from there or toward
    the ego by compass ("walking south" of a northbound AV turning)."""
    turn = {
        EgoManeuver.TURN_RIGHT.value: RelativePosition.ROADSIDE_RIGHT,
        EgoManeuver.TURN_LEFT.value: RelativePosition.ROADSIDE_LEFT,
    }.get(ego_maneuver or "")
    if turn is None or mention.cls not in (ActorClass.PEDESTRIAN, ActorClass.BICYCLE):
        return None
    book = rulebook()
    text = cast.text
    ego_bearing = _ego_bearing(cast)
    stretches = words_of(cast, mention)
    # "crosses the street I turn into; she comes from the corner on the far side": the far
    # corner may be said in another of its clauses
    far_said = next(
        (hit for s, e in stretches if (hit := book.first(Fact.FAR_CORNER, text, s, e))), None
    )
    for start, end in stretches:
        far = book.first(Fact.FAR_CORNER, text, start, end) or far_said
        street = book.first(Fact.EXIT_STREET, text, start, end)
        quote = (
            far.quote
            if far
            else street.quote
            if street
            else _exit_street_named(cast, text[start:end])
        )
        # A walker crossing along the ego's first bearing crosses the street it turns
        # into; one coming toward the ego ("walking south" of a northbound AV) starts
        # from that crossing's far corner.
        heading = _own_heading(cast, start, end) if ego_bearing is not None else None
        along = (
            (_COMPASS[heading.value] - ego_bearing) % 360
            if heading is not None and ego_bearing is not None
            else None
        )
        if along not in (0, 180):
            heading = None
        elif quote is None:
            quote = heading.quote if heading else None
        if quote is not None and (far or book.first(Fact.CROSSES, text, start, end)):
            toward = along == 180 and heading is not None
            detail = StartDetail.EXIT_FAR_CORNER if far or toward else StartDetail.EXIT_CROSSING
            return ExitStreetWalker(turn, detail, quote, heading)
    return None


_KERBS = frozenset({RelativePosition.ROADSIDE_LEFT.value, RelativePosition.ROADSIDE_RIGHT.value})


def read_start_detail(reading: Reading) -> None:
    """Which end of the lane beside the ego the adversary starts at, or which corner of the
    street a turning ego enters; a walker on that street starts on the side the ego turns to."""
    adversary = reading.adversary
    if adversary is None:
        return
    cast = reading.cast
    ego = reading.facts.get("ego_maneuver")
    walker = exit_street_walker(cast, adversary, ego.value if ego else None)
    if walker is not None:
        reading.facts["start_detail"] = text_fact("start_detail", walker.detail.value, walker.quote)
        told = reading.facts.get("spawn_position")
        if (
            told is None
            or told.quote is None
            or told.quote.lower() in walker.quote.lower()
            or (walker.heading is not None and told.quote == walker.heading.quote)
            # "from the far side": a kerb of the street it crosses, the one the ego enters
            or told.value in _KERBS
        ):
            reading.facts["spawn_position"] = text_fact(
                "spawn_position", walker.position.value, walker.quote
            )
        return
    end_of_lane = lane_end(cast, adversary)
    if end_of_lane is not None:
        reading.facts["start_detail"] = end_of_lane


def lane_end(cast: Cast, mention: Mention) -> GroundedFact | None:
    """Which end of the lane beside the ego `mention` starts at, when its words say so."""
    book = rulebook()
    text = cast.text
    for start, end in words_of(cast, mention):
        # "merged into its lane ahead of it": it ends up in front of the ego, unless it came
        # from behind first; "approaching from behind on the AV's right", "overtakes": it
        # starts behind the ego ("from behind a parked van" is where it hides instead).
        ahead = book.first(Fact.AHEAD_OF_EGO, text, start, end)
        if ahead is not None and not book.first(Fact.FROM_BEHIND, text, start, ahead.start):
            return text_fact("start_detail", StartDetail.AHEAD.value, ahead.quote)
        behind = book.first(Fact.FROM_BEHIND, text, start, end + 40)
        if behind is not None and behind.end <= end:
            return text_fact("start_detail", StartDetail.FROM_BEHIND.value, behind.quote)
    return None


def moves(text: str, start: int, end: int) -> bool:
    """Whether text[start:end] has words that move an actor ("pulls out", "crosses")."""
    return rulebook().first(Fact.MOVING, text, start, end) is not None


def moves_in(text: str, stretches: list[tuple[int, int]]) -> bool:
    """Whether any of these stretches of text has words that move an actor."""
    return any(moves(text, start, end) for start, end in stretches)


def read_ego_on_ramp(reading: Reading) -> None:
    """Whether the ego is the one coming up the on-ramp, from words whose subject it is."""
    for hit in rulebook().hits(Fact.EGO_ON_RAMP, reading.cast.text):
        if subject_of(reading.cast, hit.start) == "ego":
            reading.facts["ego_on_ramp"] = GroundedFact(
                name="ego_on_ramp", value="true", source=FactSource.TEXT, quote=hit.quote
            )
            return


def _verb_subject(cast: Cast, position: int) -> Mention | str | None:
    """Like `_subject`, but a verb joined by "and (then)" ("changes lanes to pass a bus and
    then returns") belongs to the sentence's first actor, not the one named just before."""
    if cast.clauses:
        return cast.subject_at(position)
    head = cast.text[:position]
    if re.search(r"\b(?:and|then)\s+(?:then\s+)?$", head, re.I):
        sentence_start = max(head.rfind(c) for c in ".;!?") + 1
        return cast.subject_after(sentence_start)
    return subject_of(cast, position)


def read_ego_plan(reading: Reading) -> None:
    """What the ego does besides driving its route (pull over, bypass, change lanes and
    back, stop then go, yield then go), from words whose subject is the ego."""
    for rule in rulebook().of(Fact.EGO_PLAN):
        for hit in rule.hits(reading.cast.text):
            if _verb_subject(reading.cast, hit.start) == "ego":
                plan = EgoPlan(hit.value)
                reading.facts["ego_plan"] = GroundedFact(
                    name="ego_plan", value=plan.value, source=FactSource.TEXT, quote=hit.quote
                )
                if plan is EgoPlan.STOP_THEN_GO:
                    reading.facts.pop("ego_stopped", None)  # it stops, but not for good
                return


def read_bypassed_start(reading: Reading) -> None:
    """A standing adversary whose start no words give, that the ego goes round: it stands
    ahead in the ego's lane, in the lane a turning ego enters ("turned left ... had to go
    round a parked van through the oncoming lane")."""
    plan = reading.facts.get("ego_plan")
    if (
        reading.adversary is None
        or plan is None
        or plan.value != EgoPlan.BYPASS.value
        or "spawn_position" in reading.facts
        or "adversary_stationary" not in reading.facts
    ):
        return
    reading.facts["spawn_position"] = StartFact(
        name="spawn_position",
        value=RelativePosition.AHEAD_SAME_LANE.value,
        source=FactSource.TEXT,
        quote=plan.quote,
    )
    if ego_turns(reading.cast):
        reading.facts["start_detail"] = GroundedFact(
            name="start_detail",
            value=StartDetail.EXIT_LANE.value,
            source=FactSource.TEXT,
            quote=plan.quote,
        )


def read_overtake_past_oncoming(reading: Reading) -> None:
    """An ego that pulls out to the left while another road user comes the other way
    overtakes through that road user's lane, on a two-way road: a bypass, unless other words
    gave the ego a plan or the road is a highway (whose left lane runs the ego's way)."""
    facts = reading.facts
    maneuver, side = facts.get("ego_maneuver"), facts.get("ego_lane_side")
    if maneuver is None or maneuver.value != EgoManeuver.CHANGE_LANE.value:
        return
    if "ego_plan" in facts or (side is not None and side.value != "left"):
        return
    cast = reading.cast
    road = rulebook().by_order(Fact.ROAD, cast.text)
    if road is not None and road.value in (RoadType.HIGHWAY, RoadType.MERGE):
        return
    for mention in cast.others:
        if mention.cls.is_place or mention.is_prop:
            continue
        told = (
            facts.get("spawn_position")
            if mention is reading.adversary
            else read_start(cast, mention)
        )
        if told is not None and told.value == RelativePosition.ONCOMING.value:
            facts["ego_plan"] = GroundedFact(
                name="ego_plan",
                value=EgoPlan.BYPASS.value,
                source=FactSource.TEXT,
                quote=f"{maneuver.quote} ... {told.quote}",
            )
            return


def read_ego_stopped(reading: Reading) -> None:
    """Whether the ego stands still for the whole scene, from words whose subject it is; not
    when other words give it a maneuver ("stopped at the signal waiting to turn left"), nor
    when it sets off later ("as we pulled off")."""
    told = reading.facts.get("ego_maneuver")
    if told is not None and told.value != EgoManeuver.GO_STRAIGHT.value:
        return
    cast = reading.cast
    for hit in rulebook().hits(Fact.EGO_HELD, cast.text):
        if subject_of(cast, hit.start) == "ego":
            if any(
                off.start > hit.start
                and (off.rule.about is Target.SCENE or subject_of(cast, off.start) == "ego")
                for off in rulebook().hits(Fact.EGO_MOVES_OFF, cast.text)
            ):
                return  # "waiting at the light ... as we pulled off": it sets off
            reading.facts["ego_stopped"] = GroundedFact(
                name="ego_stopped", value="true", source=FactSource.TEXT, quote=hit.quote
            )
            return


def read_stationary(cast: Cast, mention: Mention) -> GroundedFact | None:
    """Whether the words about `mention` say it stays put for the whole scene ("a truck
    parked in its lane", "a stalled car"), and move it nowhere ("a parked car pulls out")."""
    stretches = words_of(cast, mention)
    if any(
        subject_of(cast, hit.start) is mention
        for start, end in stretches
        for hit in rulebook().hits(Fact.MOVING, cast.text, start, end)
    ):
        return None  # "parked at the side ... he starts suddenly": its own verbs move it
    for start, end in stretches:
        still = rulebook().first(Fact.STATIONARY, cast.text, start, end)
        # a verb of the ego's or another's in these words moves them, not this one ("a van
        # parked in its lane, so the ego swung out"); its own verbs were handled above
        moved = any(
            subject_of(cast, hit.start) is None
            for hit in rulebook().hits(Fact.MOVING, cast.text, start, end)
        )
        if still is not None and not moved:
            return GroundedFact(
                name="adversary_stationary", value="true", source=FactSource.TEXT, quote=still.quote
            )
    return None


def read_turns_back(cast: Cast, mention: Mention) -> GroundedFact | None:
    """Whether the words about a walker send it back the way it came ("steps back onto the
    kerb", "changes her mind"); a vehicle that "goes back" returns to a lane."""
    if mention.cls is not ActorClass.PEDESTRIAN:
        return None
    for start, end in words_of(cast, mention):
        back = rulebook().first(Fact.TURNS_BACK, cast.text, start, end)
        if back is not None:
            return GroundedFact(
                name="adversary_turns_back", value="true", source=FactSource.TEXT, quote=back.quote
            )
    return None


# -- who is the adversary -------------------------------------------------------------------


def adversary_type_of(cls: ActorClass) -> AdversaryType | None:
    """The adversary type a road user of this class plays (a van a car, a bus a truck);
    None for a prop."""
    refined = cls.as_adversary
    return next((kind for kind in AdversaryType if kind.scenic_class is refined), None)


def someone_comes_out_from(cast: Cast, mention: Mention, stretches: list[tuple[int, int]]) -> bool:
    """Whether the words right before `mention` (its words' start, or one of its names, as
    in "out from the front of the bus") put someone behind it or coming out from it."""
    starts = {a for a, _ in stretches} | {span.start for span in mention.spans}
    if any(cue_before(Fact.HIDES_BEHIND, cast.text, a, spaced=False) for a in starts):
        return True
    # "darts out round the bus's front", "emerged past V2's front bumper"
    return any(
        _ROUND_ITS.search(cast.text, max(0, span.start - 25), span.start)
        and _ITS_FRONT.match(cast.text, span.end)
        for span in mention.spans
        if cast.text[span.start : span.end].lower().endswith(("'s", "\u2019s"))
    )


_ROUND_ITS = re.compile(
    r"\b(?:round|around|past|from|out\s+of|in\s+front\s+of)\s+(?:the\s+)?$", re.I
)
_ITS_FRONT = re.compile(r"\s+(?:front|nose|bonnet|hood)\b", re.I)


#: Moving into the road or the ego's path: "darts into the road", "steps out", "pulls out
#: across", "cuts in".
_INTO_THE_ROAD = re.compile(
    r"\b(?:dart\w*|dash\w*|step\w*|ran|run\w*|walk\w*|pull\w*|cut\w*|swerv\w*|emerg\w*|"
    r"shot|shoot\w*|lurch\w*|veer\w*)\b(?:\s+(?!(?:is|was|are|be)\b)[\w'-]+){0,2}?"
    r"\s+(?:into|onto|out|across|in)\b"
    r"|\b(?:enter\w*|merg\w*|ran\s+the|runs\s+the|running\s+the|jump\w*\s+the)\b",
    re.I,
)


def choose_adversary(cast: Cast, quote: str | None) -> Mention | None:
    """The named road user the model points at (by a quote that is in the text); else, of
    the road users not described as parked or hiding something, nor one someone comes out
    from behind ("walks out from in front of the bus"), the first whose own clause touches
    the ego, else the first that nearly does, else the first; else the first one."""
    road_users = [m for m in cast.others if adversary_type_of(m.cls) is not None]
    playing: list[tuple[int, Mention]] = []
    occluders: list[Mention] = []
    for mention in road_users:
        stretches = words_of(cast, mention)
        if any(rulebook().first(Fact.BACKGROUND, cast.text, a, b) for a, b in stretches):
            continue
        if someone_comes_out_from(cast, mention, stretches):
            continue
        if any(
            hit.value == "occluder"
            for a, b in stretches
            for hit in rulebook().hits(Fact.ROLE_CUE, cast.text, a, b)
        ):
            occluders.append(mention)  # "a lorry waiting opposite blocked her view of ..."
            continue
        rank = _meeting_rank(cast, mention, stretches)
        # of those that meet no one, one that moves into the road comes first
        enters = any(_INTO_THE_ROAD.search(cast.text, a, b) for a, b in stretches)
        playing.append((2 * rank + (rank == 2 and not enters), mention))
    if quote:
        span = find_quote(cast.text, quote)
        if span is not None:
            at = cast.mention_at(*span)
            if at is not None and adversary_type_of(at.cls) is not None:
                named = [at]
            else:
                named = [
                    m for m in road_users if re.search(rf"\b{re.escape(m.quote)}\b", quote, re.I)
                ]
            # the model's pick, unless the words make it the view's blocker beside one
            # that plays
            if named and not (playing and any(named[0] is m for m in occluders)):
                return named[0]
    # A report's other party is its lowest-numbered one ("V2", "Party 2"), before a truck it
    # only mentions: among equal meetings, that one first.
    numbers = [n for _, m in playing if (n := party_number(cast, m)) is not None]
    first = min(numbers, default=None)
    if playing:
        return min(
            playing,
            key=lambda ranked: (
                ranked[0],
                first is not None and party_number(cast, ranked[1]) != first,
            ),
        )[1]
    return road_users[0] if road_users else None


def _meeting_rank(cast: Cast, mention: Mention, stretches: list[tuple[int, int]]) -> int:
    """0 for a road user that is the subject of words touching the ego ("the estate car ran
    into the back of mine"), 1 for one that nearly does, 2 for the rest: the one in the
    collision is the adversary, not the bus the ego waited behind."""
    meetings = [
        hit.value
        for a, b in stretches
        if (hit := rulebook().first(Fact.MEETING, cast.text, a, b))
        and subject_of(cast, hit.start) is mention
    ]
    meetings += _met_by_the_ego(cast, mention, stretches)
    if "contact" in meetings:
        return 0
    return 1 if meetings else 2


#: A part of the ego as the subject of a meeting: "my front bumper hit ...".
_EGO_PART = re.compile(r"\b(?:my|our|your)\s+(?:[\w-]+\s+)?[\w-]+\s+$", re.I)
_OBJECT_PRONOUN = re.compile(r"\s+(him|her|his|it|its|them|their)\b", re.I)
#: At most this many words between a meeting and its object ("hit the back of | a van").
_OBJECT_WORDS = 3


def _met_by_the_ego(cast: Cast, mention: Mention, stretches: list[tuple[int, int]]) -> list[str]:
    """The meetings whose subject is the ego and whose object is `mention` (its words are
    `stretches`): "my front bumper hit his front wheel" of a cyclist named last before it,
    "the ego clipped the van"."""
    text = cast.text
    found = []
    for hit in rulebook().hits(Fact.MEETING, text):
        own_part = _EGO_PART.search(text, max(0, hit.start - 40), hit.start)
        if subject_of(cast, hit.start) != "ego" and own_part is None:
            continue
        if pronoun := _OBJECT_PRONOUN.match(text, hit.end):
            before = [
                (span.end, other)
                for other in cast.others
                if not other.cls.is_place and not other.is_prop
                for span in other.spans
                if span.end <= hit.start
            ]
            if pronoun.group(1).lower() in ("him", "her", "his"):  # a person: walks or rides
                people = [m for m in before if m[1].cls.is_walker or m[1].cls.is_two_wheeler]
                before = people or before
            met = max(before, key=lambda item: item[0])[1] if before else None
        else:
            met = next(
                (
                    other
                    for other in cast.others
                    for span in other.spans
                    if (lead := phrase_start(text, span.start)) >= hit.end
                    and len(text[hit.end : lead].split()) <= _OBJECT_WORDS
                    and not re.search(r"[.;,]", text[hit.end : lead])
                ),
                None,
            )
        if met is None and any(a <= hit.start < b for a, b in stretches):
            met = mention  # "a motorbike arrives very quick and almost we touch"
        if met is mention:
            found.append(hit.value)
    return found


def is_vehicle(cls: str) -> bool:
    return cls in VEHICLE_CLASSES


def read_description(description: str, adversary_quote: str | None = None) -> Reading:
    """Everything the fixed rules read: the cast, the adversary, its side and turn, the
    ego's maneuver and the weather, each with its words."""
    cast = parse(description)
    reading = Reading(cast=cast)
    reading.adversary = choose_adversary(cast, adversary_quote)
    # "In wet weather give more room": a lesson's weather is no scene's
    reading.weather = read_weather(lessons_of(description).masked(description))
    reading.facts["weather"] = reading.weather.fact
    if reading.adversary is not None:
        adversary = reading.adversary
        reading.facts["adversary_class"] = GroundedFact(
            name="adversary_class",
            value=adversary.cls,
            source=FactSource.TEXT,
            quote=adversary.quote,
        )
        position = read_start(cast, adversary)
        if position is not None:
            reading.facts["spawn_position"] = position
            detail = start_detail(position)
            if detail is not None:  # a finer point read later (read_start_detail) wins
                reading.facts["start_detail"] = GroundedFact(
                    name="start_detail",
                    value=detail.value,
                    source=FactSource.TEXT,
                    quote=position.quote,
                )
        stationary = read_stationary(cast, adversary)
        if stationary is not None:
            reading.facts["adversary_stationary"] = stationary
        back = read_turns_back(cast, adversary)
        if back is not None:
            reading.facts["adversary_turns_back"] = back
    read_maneuvers(reading)
    read_ego_overtaking(reading)
    read_start_detail(reading)
    read_ego_stopped(reading)
    read_ego_plan(reading)
    read_bypassed_start(reading)
    read_overtake_past_oncoming(reading)
    read_ego_on_ramp(reading)
    read_road(reading)
    read_quantity(reading)
    read_measures(reading)
    read_meeting(reading)
    return reading


def read_meeting(reading: Reading) -> None:
    """What the text says of the meeting itself: that the two touched or nearly did
    (`contact_stated`), and when the other made its move (`timing`); the first such words."""
    text = reading.cast.text
    for fact, name in ((Fact.MEETING, "contact_stated"), (Fact.TIMING, "timing")):
        found = rulebook().first(fact, text)
        if found is not None:
            reading.facts[name] = GroundedFact(
                name=name, value=found.value, source=FactSource.TEXT, quote=found.quote
            )


_NUMBER = re.compile(r"\d+(?:\.\d+)?")


def read_measures(reading: Reading) -> None:
    """Numbers with their units, each in the clause of whom it is about: the first speed of
    the ego and of the adversary become facts `ego_speed` and `adversary_speed` (metres per
    second), which set their speeds in the script; the first other speed or time a fact
    `unread_measure`, left to the model's tuning. A distance is none of these: a narrative's
    "about 30 feet ahead" or "stopped 3 feet short" tells the moment of the conflict, which
    the behaviors already time to the ego, or its outcome."""
    cast = reading.cast
    hits = sorted(rulebook().hits(Fact.MEASURE, cast.text), key=lambda hit: hit.start)
    for hit in hits:
        number = _NUMBER.search(hit.quote)
        if number is None:
            continue
        unit = Unit(hit.value)
        if unit.is_distance:
            continue
        who = subject_of(cast, hit.start)
        name = "unread_measure"
        if unit.is_speed and who == "ego":
            name = "ego_speed"
        elif unit.is_speed and reading.adversary is not None and who is reading.adversary:
            name = "adversary_speed"
        value = f"{float(number.group()) * unit.in_si:.1f}" if unit.is_speed else "unread"
        if name not in reading.facts:
            reading.facts[name] = GroundedFact(
                name=name, value=value, source=FactSource.TEXT, quote=hit.quote
            )


def read_quantity(reading: Reading) -> None:
    """Whether the description says how fast, how far or when (the first such words)."""
    found = rulebook().by_order(Fact.QUANTITY, reading.cast.text)
    if found is not None:
        reading.facts["quantity"] = GroundedFact(
            name="quantity", value=found.value, source=FactSource.TEXT, quote=found.quote
        )


def read_road(reading: Reading) -> None:
    """The road type: a mid-block location is an ordinary road; else the road words in the
    rules' order, where a plain road or street gives way to a turn (a junction), a vehicle
    crossing from the side, or traffic-control words."""
    text = reading.cast.text
    facts = reading.facts
    found = rulebook().by_order(Fact.ROAD, text)

    def told(value: str, quote: str | None) -> None:
        facts["road_type"] = GroundedFact(
            name="road_type", value=value, source=FactSource.TEXT, quote=quote
        )

    if found is not None and found.value == "mid_block":
        return told(RoadType.STRAIGHT.value, found.quote)
    if found is not None and found.value != RoadType.STRAIGHT.value:
        return told(found.value, found.quote)
    for name, kinds in (
        ("ego_maneuver", (EgoManeuver.TURN_LEFT, EgoManeuver.TURN_RIGHT)),
        ("adversary_maneuver", (AdversaryManeuver.TURN_LEFT, AdversaryManeuver.TURN_RIGHT)),
    ):
        turn = facts.get(name)
        if turn is not None and turn.value in kinds:
            return told(RoadType.INTERSECTION.value, turn.quote)
    position = facts.get("spawn_position")
    adversary = reading.adversary
    if (
        position is not None
        and position.value in CROSSING_STARTS
        and adversary is not None
        and adversary.cls in VEHICLE_CLASSES
    ):  # a vehicle cannot come from the side on an open road
        return told(RoadType.INTERSECTION.value, position.quote)
    signal = rulebook().first(Fact.TRAFFIC_CONTROL, text)
    if signal is not None:
        return told(RoadType.INTERSECTION.value, signal.quote)
    if found is not None:
        return told(found.value, found.quote)
    return None
