"""Who and what a description names: the ego, and each road user or object with its words.

Read once, without a model. The cast finds:

- the ego under its names: "the ego", "the AV", "the test vehicle", "the subject vehicle",
  "I"/"my car" in a claim, NHTSA's leading "Vehicle ..." (its typology names the ego so),
  and the numbered vehicle of a report that is the autonomous one ("V1", "Vehicle 2");
- each other road user or prop by its noun (data/lexicon.yaml), or by a make, model and
  year ("a 2017 Hollis Tern") when no noun names it; numbered parties ("V2", "P1");
- references back to one of them: "the van", "the other car", "the other driver", "the
  pickup" after "a 2017 ... pickup" (pronouns are resolved with the clauses, `reading`).

Each mention keeps its spans, so every later fact (a side, a turn) is tied to the words it
rests on and to the actor those words are about.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace
from functools import cache

from arise.language.generic import lessons_of
from arise.language.lexicon import class_pattern, lexicon, noun_class
from arise.language.numbered import NUMBERED as _NUMBERED
from arise.language.numbered import numbered_ego, sentence_end, sentence_start
from arise.vocabulary import ActorClass

PROP_NOUN_CLASSES = frozenset(cls for cls in ActorClass if cls.is_prop)
VEHICLE_CLASSES = frozenset(cls for cls in ActorClass if cls.is_vehicle)

_COUNT_WORDS = {
    "two": 2,
    "three": 3,
    "four": 4,
    "five": 5,
    "six": 6,
    "seven": 7,
    "eight": 8,
    "nine": 9,
    "ten": 10,
    "half a dozen": 6,
    "a dozen": 12,
    "dozen": 12,
    "pair of": 2,
    "couple of": 2,
}
# A count a few modifiers before the noun ("half a dozen orange cones", "10 cones"); not a
# lane's number ("#3 lane as V2"), not a quantity, and not across a joining word.
_COUNT = re.compile(
    r"(?<!#)\b(two|three|four|five|six|seven|eight|nine|ten|half a dozen|a dozen|dozen|"
    r"\d{1,2}\s?x|\d{1,2}|"
    r"pair of|couple of)\s+"
    # a number of units is a quantity, not a count ("at 25 mph a cyclist")
    r"(?!(?:mph|km|kph|kmh|km/h|m|ft|feet|foot|metres|meters|miles|mi|yards|yd|s|sec|secs|"
    r"seconds|min|mins|minutes|hrs|hours|percent|o'clock)\b)"
    r"(?:(?!(?:as|and|when|while|then|to|from|in|into|on|at|lane|lanes)\b)\w+[- ]){0,2}$",
    re.I,
)
_NEW = re.compile(r"\b(?:a|an|another|second|third|one|some|other)\s+(?:[\w'-]+[- ]){0,3}$", re.I)
_DEFINITE = re.compile(r"\b(?:the|that|this|its|their|his|her)\s+(?:[\w'-]+[- ]){0,3}$", re.I)
# "both vehicles", "no other vehicle": a summary or a negation, not one more thing.
_NOT_NEW_THING = re.compile(
    r"\b(?:both|all|neither|either|no|any|none of the|no one|nobody|each|(?:empty|free|devoid) of)\s+"
    r"(?:other\s+)?(?:\w+\s+)?$"
    # ... and the rest of a list it opens: "no lorry or van", "no other vehicles or
    # pedestrians", "no cones, signs or lights"
    r"|\b(?:no|neither|without|nor)\s+(?:[\w'-]+,?\s+){1,5}(?:or|nor)\s+(?:[\w'-]+\s+)?$",
    re.I,
)
# A group with no number: "several cyclists", "a row of parked cars".
_GROUP = re.compile(
    r"\b(?:several|some|many|few|multiple|groups? of|crowd of|row of|line of|queue of|"
    r"platoon of|convoy of|stream of)\s+(?:[\w'-]+\s+){0,2}$",
    re.I,
)
_PLURAL = re.compile(r"(?:s|ren|men|ple|ies)$", re.I)
# "the other car", "the other driver": the road user named before that is not the ego.
_THE_OTHER = re.compile(r"\bthe other\s+$", re.I)
# "pick up" as a verb: what is picked up follows.
_PICK_UP = re.compile(r"^pick[- ]up$", re.I)
_PICKED = re.compile(
    r"^\s+(?:the|a|an|any|some|anything|something|it|them|him|her|his|their|my|your|"
    r"passengers?|speed|pace|debris|litter)\b",
    re.I,
)
# A driver out of the vehicle: "its driver is standing well up the verge", "the driver
# was walking round it".
_ON_FOOT = re.compile(
    r"^\s+(?:(?:is|was|were|had|has|then|now)\s+)?(?:\w+\s+)?"
    r"(?:standing|stood|stands|walking|walked|walks|pacing|on\s+foot|"
    r"got\s+out|gets\s+out|getting\s+out|stepped\s+out|steps\s+out|climbed\s+out)\b"
    # a driver who waves from the cab or stands on the brakes stays in it
    r"(?!\s+on\s+(?:the|his|her|their)\s+(?:brakes?|pedal|gas|throttle))",
    re.I,
)
# The person a vehicle belongs to ("car of other person"): between the two words.
_OWNER = re.compile(r"^\s+of\s+(?:the\s+|a\s+|an\s+|one\s+)?(?:other\s+|another\s+)?$", re.I)
# A driver, rider or operator of something already named is that thing.
_DRIVER = re.compile(r"^(?:driver|drivers|motorist|motorists)$", re.I)
# "a following SUV whose driver failed to stop": the driver of the one just named.
_WHOSE = re.compile(r"\bwhose\s+$", re.I)
_DRIVER_OF = re.compile(r"^\s+(?:of|in|driving)\s+(?:a|an|the)\b", re.I)
# The ego's own driver ("the AV's safety driver", "its driver", "my driver") is no road user.
_EGO_DRIVER = re.compile(
    r"\b(?:safety|test|backup|vehicle|av's|ego's|its|my|our)\s+(?:\w+\s+)?$", re.I
)
# The vehicle the writer drives ("I am drive the car", "we were driving a hire van") is the ego.
_EGO_DRIVES = re.compile(
    r"\b(?:i|we)\s+(?:am\s+|was\s+|were\s+|'m\s+)?(?:drive|drives|driving|drove)\s+"
    r"(?:the|a|an|my|our)\s+(?:[\w'-]+\s+){0,2}$"
    # what the writer or reader is: "I was the first car waiting", "you're the lead car"
    r"|\b(?:i\s+was|i\s+am|i'm|we\s+were|we\s+are|we're|you\s+are|you're|you\s+were)\s+"
    r"(?:the|a|an)\s+(?:[\w'-]+\s+){0,2}$",
    re.I,
)
# The writer's own vehicle named again: "I was driving the car ... I stopped the car".
_THE_OWN = re.compile(r"\b(?:the|my|our)\s+$", re.I)
# The one at the wheel of a vehicle named right before ("the van driver"): that vehicle.
_DRIVER = re.compile(r"(?:driver|rider|motorist)s?(?:['\u2019]s)?$", re.I)
# A person on a bike is its rider, one road user with the bike: "a man on a pushbike".
_RIDING = re.compile(
    r"^\s+(?:on|riding)\s+(?:(?:a|an|his|her|their|the)\s+)?(?:[\w'-]+\s+){0,2}$", re.I
)
_RIDDEN = (ActorClass.BICYCLE, ActorClass.MOTORCYCLE)
_NUMBERED_WALKER = re.compile(r"\bP([1-9])\b(?:'s)?")
# NHTSA's typology names the ego "Vehicle" with no article, at a sentence's start; a
# numbered "Vehicle 2" is a party like "V2" (`_NUMBERED`), never the bare name.
_NOT_NUMBERED = r"(?!\s?#?\s?[1-9]\b)"
_NHTSA_EGO = re.compile(r"(?:^|(?<=[.;:]\s))Vehicle(?:'s)?\b" + _NOT_NUMBERED)
_NHTSA_EGO_ANYWHERE = re.compile(
    r"(?<![\w'])(?<!\bthe )(?<!\ba )(?<!\ban )Vehicle(?:'s)?\b" + _NOT_NUMBERED
)
# In that style also a lower-case "vehicle" right after a preposition ("drifts into
# vehicle's lane"): group 1.
_NHTSA_EGO_AFTER_PREPOSITION = re.compile(
    r"\b(?:into|onto|of|to|with|by|behind|toward|towards|past|from|beside) (vehicle(?:'s)?)\b"
    # ... or opening a clause of a note in lower case ("...; vehicle steers around")
    r"|(?:(?<=[;:]\s)|(?<=\s[-=]>\s))(vehicle(?:'s)?)\b"
)
# ... and "the vehicle's" (its path, its right side): the typology names the other one "other
# vehicle" or by its kind.
_NHTSA_EGO_OWNS = re.compile(r"\bthe vehicle['\u2019]s\b", re.I)
# With no other name for the ego, the typology's other wording: "the vehicle" (and a
# sentence's leading "Left-turning vehicle") is the one the scenario is about, where the
# others are named by their kind ("a pickup", "an oncoming vehicle"). Not "the vehicle
# ahead" or "the vehicle that ran the red", which place or pick out another one.
_THE_VEHICLE = re.compile(
    # "the turning vehicle": the typology's word for the one the scenario is about
    r"\bthe (?:(?:left-|right-)?turning |lane-changing |subject )?vehicle(?:['\u2019]s)?\b"
    r"(?!\s+(?:ahead|in front|behind|beside|alongside|"
    r"next|opposite|that|which|who|to (?:the|its|his|her)|on (?:the|its)|in (?:the|its)))",
    re.I,
)
_LEADING_VEHICLE = re.compile(r"(?:^|(?<=[.;:]\s))[A-Z][\w-]*(?:ing|bound) vehicle\b")
# A vehicle brought in with an article before "the vehicle": that one is what it refers to.
_A_VEHICLE = re.compile(r"\b(?:a|an|another|one)\s+(?:[\w-]+\s+){0,3}?vehicle\b", re.I)
# The writer's own vehicle by any vehicle noun ("my hatchback", "our tipper lorry"), and the
# one under test by what it is ("the automated car", "Automated shuttle van", "the test car").
_OWN_OR_UNDER_TEST = re.compile(
    r"(?:\b(?:my|our|your)|\b(?:her|his|their|the)\s+insured|(?:\b(?:the|an?)\s+)?\b(?:automated|autonomous|self-driving|"
    r"driverless|test))\s+(?:(?!(?:a|an|the|one|some|lane|road|street|way|side)\b)[\w'-]+\s+){0,2}?$",
    re.I,
)
_EGO_BODIES = frozenset({ActorClass.CAR, ActorClass.TRUCK, ActorClass.VAN, ActorClass.BUS})
# Car nouns that name a person or a party, never the writer's own vehicle.
_PARTY_NOUNS = frozenset(
    {
        "driver",
        "drivers",
        "motorist",
        "motorists",
        "claimant",
        "claimants",
        "third party",
        "other party",
        "pov",
        "veh",
        "vehs",
    }
)
# What the ego is, set off after its name: "The AV, a 2026 Corvane Lumen, was travelling",
# "V1 (a white SUV)", "V1 (2026 Ambrel Tek, operating autonomously)", "the autonomous vehicle
# under test, a 2026 Caddow Fenn".
# Not one of a list: "the ego, a cyclist, and a van" (another item follows the comma).
_NOT_A_LIST = r"(?:,(?!\s*(?:and|or|a|an|the)\b)|\(|\))"
_EGO_APPOSITION = re.compile(
    r"(?:\s+(?:under\s+(?:test|evaluation|trial|assessment)|being\s+tested|involved|in\s+question))?"
    r"(?:\s*\([^()]{1,30}\))?\s*[,(]\s*"
    # a make and model year may end its sentence ("..., a 2026 Vantrell Osk with a driver.")
    r"((?:an?\s+)?(?:19|20)\d\d\s+[^,.;()]{1,60}?(?=\s*(?:" + _NOT_A_LIST + r"|[.;]))"
    r"|an?\s+[^,.;()]{1,60}?(?=\s*" + _NOT_A_LIST + r"))"
)
_EGO_BRACKET = re.compile(r"\s*\(([^()]{1,60})\)")
# A year and a capitalised name ("a 2017 Hollis Tern"), or a known make ("a white Subaru").
_YEAR_NAME = re.compile(
    r"\b(?:19[5-9]\d|20[0-4]\d)\s+(?:[A-Z][\w-]*)(?:\s+(?:[A-Z0-9][\w-]*))?(?:\s+(?:[A-Z0-9][\w-]*))?"
)


@dataclass(frozen=True)
class Span:
    start: int
    end: int


@dataclass(frozen=True)
class Mention:
    """One thing the text names: its class, how many, and its first words in the text."""

    cls: ActorClass
    count: int
    start: int
    end: int
    quote: str
    spans: tuple[Span, ...]
    #: The count is stated ("two vans", "a van"); False for a plural or a group with no
    #: number ("parked cars", "several cyclists"), which stands for any number of them.
    counted: bool = True

    @property
    def is_prop(self) -> bool:
        return self.cls in PROP_NOUN_CLASSES

    def with_span(self, span: Span) -> Mention:
        spans = tuple(sorted({*self.spans, span}, key=lambda s: s.start))
        return replace(self, spans=spans)


@dataclass(frozen=True)
class Clause:
    """A stretch of a sentence with one verb's worth of words, and whose they are."""

    start: int
    end: int
    opener: str  # the word or mark before it ("" at the start of the text)
    subject: Mention | str | None  # a Mention, "ego", or nobody named
    explicit: bool  # the subject is named in the clause (not carried over)
    # The subject comes after its verb, a place opening the clause ("from the left is
    # coming a bus"): the words before it are about it.
    inverted: bool = False
    # It opens with a bare verb of instruction ("then pull out around it"), and no subject
    # of its own: in a text that speaks to "you", the ego's.
    imperative: bool = False


@dataclass(frozen=True)
class Cast:
    """The ego's spans and the other things a description names, in order of first mention."""

    text: str
    ego: tuple[Span, ...]
    others: tuple[Mention, ...]
    #: Words read as naming someone that are not a road user of the scene (kept for reports).
    skipped: tuple[str, ...] = field(default=())
    #: The clauses and their subjects (`arise.language.reading.parse` fills them in).
    clauses: tuple[Clause, ...] = field(default=())

    def subject_at(self, position: int) -> Mention | str | None:
        """Whose is the verb at `position`: the subject of the clause holding it."""
        for clause in self.clauses:
            if clause.start <= position < clause.end:
                return clause.subject
        return None

    def subject_before(self, position: int) -> Mention | str | None:
        """The actor ("ego" or a Mention) named last before `position` in its sentence."""
        begins = sentence_start(self.text, position)
        best: tuple[int, Mention | str] | None = None
        for span in self.ego:
            possessive = self.text[span.start : span.end].lower().endswith("'s")
            if (
                begins <= span.start < position
                and not possessive
                and (best is None or span.start > best[0])
            ):
                best = (span.start, "ego")
        for mention in self.others:
            for span in mention.spans:
                if begins <= span.start < position and (best is None or span.start > best[0]):
                    best = (span.start, mention)
        return best[1] if best else None

    def subject_after(self, position: int) -> Mention | str | None:
        """The actor named first after `position` in its sentence (for a leading participle:
        "Turning left, the ego ...")."""
        end = sentence_end(self.text, position)
        best: tuple[int, Mention | str] | None = None
        for span in self.ego:
            if position <= span.start < end and (best is None or span.start < best[0]):
                best = (span.start, "ego")
        for mention in self.others:
            for span in mention.spans:
                if position <= span.start < end and (best is None or span.start < best[0]):
                    best = (span.start, mention)
        return best[1] if best else None

    def mention_at(self, start: int, end: int) -> Mention | None:
        """The mention one of whose spans overlaps [start, end)."""
        for mention in self.others:
            if any(span.start < end and start < span.end for span in mention.spans):
                return mention
        return None

    def actor_at(self, position: int) -> Mention | str | None:
        """The actor whose span holds `position`."""
        if any(span.start <= position < span.end for span in self.ego):
            return "ego"
        return self.mention_at(position, position + 1)


def _overlaps(spans: list[tuple[int, int]], start: int, end: int) -> bool:
    return any(a < end and start < b for a, b in spans)


#: The insurer's client, the ego of a claim the insurer writes; in one the driver writes
#: ("I was ... the car behind, driven by the insured"), another party.
_INSURED = re.compile(
    r"^(?:the insured(?:'s)?|insured vehicle|(?:the )?policyholder(?:'s)?)$", re.I
)
_FIRST_PERSON = re.compile(r"^(?:i|we|my car|my vehicle|our car|our vehicle)$", re.I)


#: The writer says which party it is: "I am the claimant", "I'm the insured".
_SELF_PARTY = re.compile(
    r"\b(?:i am|i'm|i was|we are|we were)\s+the\s+(claimant|insured|policyholder)\b", re.I
)
# A first-person statement headed by its party: "Statement of claimant (Mr. ...). I was ..."
_PARTY_STATEMENT = re.compile(
    r"^\W*(?:(?:statement|account|version|declaration)\s+(?:of|by)\s+(?:the\s+)?"
    r"(claimant|insured|policyholder)\b|(claimant|insured|policyholder)['\u2019]s\s+"
    r"(?:statement|account|version|declaration)\b)",
    re.I,
)


#: A party's own vehicle after its name: "the claimant's van" of a claimant who writes.
_PARTY_OWN = (
    r"(?:\s+(?:vehicle|car|van|truck|lorry|pickup|suv|hatchback|sedan|saloon|motorcycle|"
    r"motorbike|bike|bicycle))"
)


def _party_word(found: re.Match[str]) -> str:
    """The party a statement's writer says it is ("claimant")."""
    return next(group for group in found.groups() if group)


_POSSESSIVE = re.compile(r"['\u2019]s\b")
_OWN_VEHICLE = re.compile(r"(?<=['\u2019]s)\s+(?:vehicle|car)\b(?![\s-]+park)", re.I)


def _ego_spans(text: str) -> list[Span]:
    # "the test vehicle's front bumper": the possessive is the ego's too (its "vehicle's" is
    # no other car). The ego's phrases are matched with every "'s" blanked (same length).
    plain = _POSSESSIVE.sub("  ", text)
    spans = [
        Span(m.start(), m.end() + (2 if _POSSESSIVE.match(text, m.end()) else 0))
        for m in class_pattern("ego").finditer(plain)
    ]
    spans += [
        own
        for own in _own_vehicles(text)
        if not any(s.start < own.end and own.start < s.end for s in spans)
    ]
    # "our insured's vehicle", "the AV's car": the ego's own vehicle is the ego.
    spans = [
        Span(s.start, owned.end()) if (owned := _OWN_VEHICLE.match(text, s.end)) else s
        for s in spans
    ]
    # "I" only as a capital letter; "we"/"i" in lower case mid-word cannot occur (whole words)
    spans = [s for s in spans if text[s.start : s.end] != "i"]
    first_person = any(_FIRST_PERSON.match(text[s.start : s.end]) for s in spans)
    self_party = _SELF_PARTY.search(text) or (
        _PARTY_STATEMENT.match(text) if first_person else None
    )
    if first_person and not (self_party and _party_word(self_party).lower() != "claimant"):
        spans = [s for s in spans if not _INSURED.match(text[s.start : s.end])]
    if self_party is not None:
        # "I am the claimant": the writer's party is the ego wherever it is named
        word = re.escape(_party_word(self_party))
        spans += [
            Span(*m.span())
            for m in re.finditer(rf"\b(?:the\s+)?{word}(?:['\u2019]s{_PARTY_OWN}?)?\b", text, re.I)
            if not _overlaps([(s.start, s.end) for s in spans], *m.span())
        ]
    nhtsa = list(_NHTSA_EGO.finditer(text))
    if nhtsa:  # the typology's style: every bare "Vehicle" is the ego
        spans += [Span(*m.span()) for m in _NHTSA_EGO_ANYWHERE.finditer(text)]
        spans += [
            Span(*m.span(1 if m.group(1) else 2))
            for m in _NHTSA_EGO_AFTER_PREPOSITION.finditer(text)
        ]
        spans += [Span(*m.span()) for m in _NHTSA_EGO_OWNS.finditer(text)]
    ego_number = numbered_ego(text)
    if ego_number is not None:
        spans += [Span(*m.span()) for m in _NUMBERED.finditer(text) if m.group(1) == ego_number]
    if not spans:
        spans = _unnamed_ego(text)
    spans += [
        Span(*found.span(1))
        for span in spans
        if (found := _EGO_APPOSITION.match(text, span.end)) and " and " not in found.group(1)
    ]
    # "an automated-driving prototype (2025 Pellham Aster)": the make in brackets too
    brackets = [found for span in spans if (found := _EGO_BRACKET.match(text, span.end))]
    spans += [
        Span(*found.span(1))
        for found in brackets
        if not any(found.start(1) <= span.start < found.end(1) for span in spans)
    ]
    return sorted(set(spans), key=lambda s: s.start)


def _own_vehicles(text: str) -> list[Span]:
    """ "I was waiting in my hatchback", "Automated car is making the right turn": the
    vehicle the writer drives, or the one said to be under test, by any car-like noun."""
    found = []
    for match in lexicon().noun_pattern.finditer(text):
        cls = ActorClass(noun_class(match))
        if cls not in _EGO_BODIES or match.group(0).lower() in _PARTY_NOUNS:
            continue
        before = text[max(0, match.start() - 40) : match.start()]
        owner = _OWN_OR_UNDER_TEST.search(before)
        if owner is not None:
            end = match.end() + (2 if _POSSESSIVE.match(text, match.end()) else 0)
            found.append(Span(match.start() - len(before) + owner.start(), end))
    return found


def _unnamed_ego(text: str) -> list[Span]:
    """The ego of a text that gives it no name of its own: "Left-turning vehicle at a
    signal strikes a pedestrian ... the vehicle"; the vehicles named before with an article
    are others ("a van stops; the vehicle reverses" is the van)."""
    introduced = next((m.start() for m in _A_VEHICLE.finditer(text)), len(text))
    return [
        Span(*m.span())
        for pattern in (_LEADING_VEHICLE, _THE_VEHICLE)
        for m in pattern.finditer(text)
        if m.start() < introduced
    ]


def read_cast(text: str) -> Cast:
    """The ego and the things `text` names (each thing once, with a count)."""
    lex = lexicon()
    ego = _ego_spans(text)
    taken = [(s.start, s.end) for s in ego]
    found: list[Mention] = []
    skipped: list[str] = []
    ego_number = numbered_ego(text)
    numbered: dict[str, int] = {}  # "V2" -> index in found
    candidates: list[tuple[int, int, ActorClass, str]] = []  # start, end, class, kind
    for match in _NUMBERED.finditer(text):
        if match.group(1) != ego_number:
            candidates.append((match.start(), match.end(), ActorClass.CAR, f"V{match.group(1)}"))
    for match in _NUMBERED_WALKER.finditer(text):
        candidates.append((match.start(), match.end(), ActorClass.PEDESTRIAN, f"P{match.group(1)}"))
    for match in lex.noun_pattern.finditer(text):
        candidates.append((match.start(), match.end(), ActorClass(noun_class(match)), "noun"))
    for match in _YEAR_NAME.finditer(text):
        candidates.append((match.start(), match.end(), ActorClass.CAR, "make"))
    candidates += _named_makes(text)
    candidates.sort(key=lambda c: (c[0], -c[1]))
    # A noun right before another one modifies it ("a flatbed truck", "a taxi cab"): the
    # phrase is one thing, named by its head, the last noun.
    noun_starts = {start for start, _, _, kind in candidates if kind == "noun"}
    rider: Span | None = None  # a rider just named, whose bike follows ("a man on a bike")
    driven: set[str] = set()  # the nouns the writer's own vehicle was named by
    for at, (start, end, cls, kind) in enumerate(candidates):
        if _overlaps(taken, start, end):
            continue
        ridden = next((c for c in candidates[at + 1 :] if c[0] >= end), None)
        if (
            (cls is ActorClass.PEDESTRIAN or cls in _RIDDEN)  # "a delivery rider on a moped"
            and ridden is not None
            and ridden[2] in _RIDDEN
            and _RIDING.match(text[end : ridden[0]])
        ):
            skipped.append(text[start:end])  # the rider: the bike that follows is the actor
            taken.append((start, end))
            rider = Span(start, end)
            continue
        following = re.match(r"[ -]+", text[end:])
        if kind == "noun" and following and end + following.end() in noun_starts:
            head = next(c for c in candidates if c[0] == end + following.end() and c[3] == "noun")
            if not (cls.is_vehicle and _DRIVER.match(text[head[0] : head[1]])):
                continue
            taken.append((head[0], head[1]))  # "the van driver's eye": the van
        after = text[end:]
        if (
            kind in ("noun", "make")
            and _not_an_actor(after, lex.not_an_actor_before)
            and not (_is_plural(text[start:end], cls) and _VERB_AFTER_PLURAL.match(after))
        ):
            continue
        if kind == "noun" and _qualified(text[:start], lex.not_an_actor_after):
            continue  # "the junction box" is no box
        if kind == "noun" and cls.is_prop and _carried(text[max(0, start - 40) : start]):
            continue  # "a man carrying boxes": his load, not a thing on the road
        word = text[start:end]
        before = text[max(0, start - 40) : start]
        if kind == "noun" and cls is ActorClass.PEDESTRIAN and _crossing_as_a_place(before, after):
            continue
        if kind.startswith(("V", "P")) and kind != "noun" and kind in numbered:
            index = numbered[kind]
            found[index] = found[index].with_span(Span(start, end))
            taken.append((start, end))
            continue
        if kind in ("noun", "make") and cls in VEHICLE_CLASSES and _EGO_DRIVES.search(before):
            skipped.append(word)
            taken.append((start, end))
            driven.add(word.lower())
            continue
        if kind == "noun" and word.lower() in driven and _THE_OWN.search(before):
            skipped.append(word)  # "I was driving the car ... I stop the car": the same one
            taken.append((start, end))
            continue
        if kind == "make" and _noun_follows(text, end):
            continue  # "a 2017 Hollis Tern pickup": the noun names it, with these words
        if (
            kind == "noun"
            and word.lower().endswith("'s")
            and _is_party_word(word)
            and _noun_follows(text, end, words=4)
        ):
            continue  # "the claimant's 2018 Hollis pickup": the pickup is the party's
        if kind == "noun" and _PICK_UP.match(word) and _PICKED.match(after):
            continue  # "stop to pick up anything that has fallen": a verb, no pickup
        if kind == "noun" and _DRIVER.match(word) and _ON_FOOT.match(after):
            cls = ActorClass.PEDESTRIAN  # "its driver is standing on the verge": on foot
        elif _DRIVER.match(word) and (
            _EGO_DRIVER.search(before) or _DRIVER_OF.match(after) or _WHOSE.search(before)
        ):
            skipped.append(word)
            taken.append((start, end))
            continue
        if kind == "noun" and _NOT_NEW_THING.search(before) and not _THE_OTHER.search(before):
            continue
        if cls is ActorClass.PEDESTRIAN and found and _owner_of(text, found[-1], start):
            skipped.append(word)
            taken.append((start, end))
            continue
        count_match = _COUNT.search(before)
        count = 1
        if count_match:
            token = count_match.group(1).lower()
            digits = token.rstrip("x ")  # "3x cones"
            count = int(digits) if digits.isdigit() else _COUNT_WORDS.get(token, 1)
        span = Span(start, end)
        if kind == "noun" and _RIDER.match(word):
            cls, pedalled = _rider_class(found, cls, after)
            if pedalled is not None:  # "a cyclist ... behind a rider pedalling uphill"
                index = found.index(pedalled)
                found[index] = pedalled.with_span(span)
                taken.append((start, end))
                continue
        earlier = _same_thing(found, cls, before, word, ego_number, after) or _its_own(
            text, found, cls, start
        )
        if earlier is None and kind == "noun" and _bare_repeat(text, start, word, after, cls):
            # terse notes drop articles: "bus in bay ... ped emerges ahead of bus nose"
            earlier = next((m for m in reversed(found) if m.cls == cls), None)
        taken.append((start, end))
        if earlier is not None:
            index = found.index(earlier)
            found[index] = earlier.with_span(span)
            if earlier.cls.is_walker and cls in _RIDDEN:
                found[index] = replace(found[index], cls=cls)  # "P2's bicycle": P2 rides it
            if _is_party(earlier) and cls.is_vehicle and earlier.cls is not cls:
                found[index] = replace(found[index], cls=cls)  # "their van": a van
            continue
        plural = _is_plural(word, cls)
        if kind == "noun" and _a_kind(text, start, plural and not count_match):
            continue  # "whenever you pass parked cars", "experienced drivers": no actor
        counted = bool(count_match) or not (plural or _GROUP.search(before))
        if count == 1 and plural and cls is not ActorClass.PEDESTRIAN:
            count = 2 if not count_match else count
        spans: tuple[Span, ...] = (span,)
        if rider is not None and cls in _RIDDEN and _RIDING.match(text[rider.end : start]):
            spans = (rider, span)  # the rider's words open the clause: "a man on a bike rode"
        quote_start = phrase_start(text, spans[0].start)
        found.append(Mention(cls, count, start, end, text[quote_start:end], spans, counted=counted))
        rider = None
        if kind.startswith(("V", "P")) and kind != "noun":
            numbered[kind] = len(found) - 1
    found = _numbered_descriptions(text, found, numbered)
    found = _tagged_names(text, found)
    found = _generic_descriptions(text, found)
    found = _party_vehicles(text, found)
    found = _bracketed_descriptions(text, found)
    found = _heading_mentions(text, found)
    return Cast(text, tuple(ego), tuple(found), tuple(skipped))


_RIDER = re.compile(r"^rider$", re.I)
_PEDALS = re.compile(r"^\W*(?:\w+\s+)?(?:pedal|pedals|pedalled|pedaled|pedalling|pedaling)\b", re.I)


def _rider_class(
    found: list[Mention], cls: ActorClass, after: str
) -> tuple[ActorClass, Mention | None]:
    """A "rider" is a motorcyclist unless it pedals or the scene's only two-wheeler so far
    is a bicycle; then a bicycle, and that bicycle when one was named."""
    bicycles = [m for m in found if m.cls is ActorClass.BICYCLE]
    motorcycles = [m for m in found if m.cls is ActorClass.MOTORCYCLE]
    if motorcycles:
        return cls, None
    if len(bicycles) == 1:
        return ActorClass.BICYCLE, bicycles[0]
    return (ActorClass.BICYCLE if _PEDALS.match(after) else cls), None


def _a_kind(text: str, start: int, bare_plural: bool) -> bool:
    """Whether the phrase at `start`, naming a road user for the first time, names a kind
    rather than one in the scene: in a lesson, or as a plural with no number in an order
    to the reader, or as drivers at large (`language.generic`)."""
    lessons = lessons_of(text)
    if lessons.in_lesson(start):
        return True
    if not bare_plural:
        return False
    if lessons.in_order(start):
        return True
    kind = class_pattern("road_user_kind").match(text, start)
    return kind is not None and not _DEFINITE.search(text[max(0, start - 40) : start])


def _owner_of(text: str, vehicle: Mention, start: int) -> bool:
    """ "Car of other person", "the van of a man": the person owns the vehicle just named,
    no road user of their own."""
    return vehicle.cls in VEHICLE_CLASSES and bool(_OWNER.match(text[vehicle.end : start]))


#: After a plural noun these words are its verb, not a place it names ("two cars stop",
#: but "the taxi stop").
_VERB_AFTER_PLURAL = re.compile(r"[\s-]+(?:stop|park|signal)\b", re.I)


def _not_an_actor(after: str, words: tuple[str, ...]) -> bool:
    """ "bike lane", "car park", "the driver's door": the noun qualifies another word."""
    found = re.match(r"^(?:'s)?[\s-]+([\w-]+)", after)
    return bool(found and found.group(1).lower() in words)


#: "at the pedestrian crossing", "for the ped crossing": a crossing as a place (not "a
#: pedestrian crossing the road"), said after a place word and an article.
_CROSSING_PLACE_BEFORE = re.compile(
    r"\b(?:at|to|for|near|on|onto|over|past|before|approaching|toward|towards|into|by|"
    r"from|beyond|after)\s+(?:the|a|an)\s+$",
    re.I,
)
_CROSSING_PLACE_AFTER = re.compile(
    r"^\s+crossing\b(?!\s+(?:the|a|an|from|in front|towards?)\b)", re.I
)


def _crossing_as_a_place(before: str, after: str) -> bool:
    """Whether a walker's noun names a crossing, a place ("stopped at the pedestrian
    crossing"), not a walker crossing ("a pedestrian crossing the road")."""
    return bool(_CROSSING_PLACE_BEFORE.search(before) and _CROSSING_PLACE_AFTER.match(after))


def _is_plural(word: str, cls: ActorClass) -> bool:
    """ "cars", "children"; not "bus" or "debris", whose ending only looks plural."""
    return bool(_PLURAL.search(word)) and cls not in (ActorClass.BUS, ActorClass.DEBRIS)


#: Words right before a bare noun that make it one more of its class ("2x cone", "another van").
_ONE_MORE = re.compile(r"\d\s*x?\s*$|\b(?:another|other|second|2nd|new)\s+$", re.I)


def _bare_repeat(text: str, start: int, word: str, after: str, cls: ActorClass) -> bool:
    """A singular noun with nothing before it (no article, count or modifier) that is not
    placed anew ("car behind"): in terse notes, the one of that class named before."""
    return (
        phrase_start(text, start) == start
        and not _is_plural(word, cls)
        and not _PLACED_BY_THE_EGO.match(after)
        and not _ONE_MORE.search(text[:start])
    )


def _qualified(before: str, words: tuple[str, ...]) -> bool:
    """ "junction box": a word before the noun makes it a thing of the road, no actor."""
    found = re.search(r"([\w-]+)[\s-]+$", before)
    return bool(found and found.group(1).lower() in words)


def _carried(before: str) -> bool:
    """Whether a verb of carrying ends `before`, at most two words back ("carrying two
    boxes", "pushing a pram")."""
    return any(
        re.fullmatch(r"(?:\s+[\w'-]+){0,2}\s+", before[found.end() :])
        # "a wheeled trash can": a word of carrying after an article describes the thing
        and not re.search(r"\b(?:a|an|the|its|one)\s+$", before[: found.start()], re.I)
        for found in class_pattern("carrying").finditer(before)
    )


def _named_makes(text: str) -> list[tuple[int, int, ActorClass, str]]:
    """A known make after an article, a colour or a year ("a white Subaru Outback")."""
    lex = lexicon()
    found = []
    for match in re.finditer(r"\b[A-Z][\w-]+", text):
        if match.group(0).lower() not in lex.makes:
            continue
        before = text[max(0, match.start() - 30) : match.start()].lower().split()
        if before and (before[-1] in ("a", "an", "the", "another") or before[-1] in lex.colours):
            end = match.end()
            model = re.match(r"\s+([A-Z0-9][\w-]*)", text[end:])
            if model and model.group(1).lower() not in ("and", "on", "at", "in"):
                end += model.end()
            found.append((match.start(), end, ActorClass.CAR, "make"))
    return found


def _noun_follows(text: str, end: int, words: int = 2) -> bool:
    """A class noun within `words` words after `end`."""
    rest = text[end : end + 15 * words]
    head = re.match(rf"^(?:\s+[\w-]+){{0,{words}}}", rest)
    window = rest[: head.end()] if head else ""
    return bool(lexicon().noun_pattern.search(window))


# What a numbered party is, said right after it: "V2, a pickup", "V2 (a Toyota pickup)",
# "Party 2, driving a 2019 sedan", "Unit 2, riding a moped".
_APPOSITION = re.compile(
    r"^,?\s*\(?\s*(?:(?:driving|driven|operating|riding|in|on)\s+)?(?:a|an|the)\s+([^,;.()]{1,60})",
    re.I,
)


def _numbered_descriptions(
    text: str, found: list[Mention], numbered: dict[str, int]
) -> list[Mention]:
    """ "V2, a pickup, ..." or "Party 2, driving a sedan": the class the apposition names, and
    the apposition folded into V2 instead of standing as one more actor."""
    for mention in [found[index] for index in numbered.values()]:
        first = mention.spans[0]
        after = _APPOSITION.match(text[first.end :])
        if not after:
            continue
        found = _fold_described(
            found, mention, first.end + after.start(1), first.end + after.end(1)
        )
    return found


#: A generic name ("the other vehicle", "following vehicle", "the third party") and what it
#: is, said right after it between commas: "other vehicle, a sedan, ...".
_GENERIC_HEAD = re.compile(r"(?:vehicle|party)$", re.I)
_GENERIC_APPOSITION = re.compile(
    r"^,\s*(?:(?:driving|driven|riding|in|on)\s+)?(?:a|an)\s+([^,;.()]{1,60})", re.I
)


def _generic_descriptions(text: str, found: list[Mention]) -> list[Mention]:
    """ "Following vehicle, a motorcycle, fails to stop", "the third party, driving a blue
    estate car": the apposition names the generic one, folded into it (a vehicle first:
    "the third party, a man on a pushbike" is the pushbike)."""
    for mention in list(found):
        first = mention.spans[0]
        generic = _GENERIC_HEAD.search(text[first.start : first.end]) or _is_party(mention)
        if mention not in found or not generic:
            continue  # "the claimant, a man carrying bags": a party too
        after = _GENERIC_APPOSITION.match(text[first.end :])
        if not after:
            continue
        start, end = first.end + after.start(1), first.end + after.end(1)
        folded = _fold_described(found, mention, start, end, vehicles=True)
        found = folded if folded is not found else _fold_described(found, mention, start, end)
    return found


#: A party's vehicle, said after it in its clause: "the claimant was coming the other way
#: on a motorcycle", "the third party, who was riding a moped": group 1 is the vehicle's phrase.
_PARTY_VEHICLE = re.compile(
    r"^[^.;:]{0,80}?\b(?:on|in|riding|driving|aboard)\s+(?:a|an|his|her|their)\s+"
    r"((?:[\w'-]+\s+){0,3}[\w'-]+)",
    re.I,
)


def _party_vehicles(text: str, found: list[Mention]) -> list[Mention]:
    """A claim party named by its part ("the claimant") and then by the vehicle it rides or
    drives in its clause: one road user, of that vehicle's class."""
    for mention in list(found):
        if mention not in found or not _is_party(mention):
            continue
        first = mention.spans[0]
        after = _PARTY_VEHICLE.match(text[first.end :])
        if after:
            start, end = first.end + after.start(1), first.end + after.end(1)
            found = _fold_described(found, mention, start, end, vehicles=True)
    return found


def _fold_described(
    found: list[Mention], mention: Mention, start: int, end: int, *, vehicles: bool = False
) -> list[Mention]:
    """`mention` described by the first thing named in text[start:end] (a vehicle, if
    `vehicles`): that thing folded into it, its class taken."""
    inner = [
        m
        for m in found
        if m is not mention and start <= m.start < end and (m.cls.is_vehicle or not vehicles)
    ]
    if not inner:
        return found
    named = inner[0]
    merged = replace(
        mention,
        cls=named.cls,
        spans=tuple(sorted({*mention.spans, *named.spans}, key=lambda s: s.start)),
    )
    return [merged if m is mention else m for m in found if m is not named]


def party_number(cast: Cast, mention: Mention) -> int | None:
    """The number a report gives this road user ("V2", "Party 3"), None if it has none."""
    for span in mention.spans:
        numbered = _NUMBERED.fullmatch(cast.text, span.start, span.end)
        if numbered:
            return int(numbered.group(1))
    return None


#: Between a thing named and the report's number for it: "a transit bus (V2)", "a box
#: truck, V2,".
_TAG_BETWEEN = re.compile(r"\s*(?:\(|,)\s*")
#: Between a thing named (or its number) and what it is again: "a pedestrian (P1), an adult
#: male, ...".
_APPOSITION_CLOSES = re.compile(r"(?:\s+[\w'-]+){0,2}\s*[,)](?!\s*(?:and|or)\b)", re.I)
_AGAIN_BETWEEN = re.compile(r"\)?\s*,\s*(?:(?:a|an)\s+(?:[\w'-]+\s+){0,2})?")


def _is_tag(text: str, span: Span) -> bool:
    return bool(
        _NUMBERED.fullmatch(text, span.start, span.end)
        or _NUMBERED_WALKER.fullmatch(text, span.start, span.end)
    )


def _tagged_names(text: str, found: list[Mention]) -> list[Mention]:
    """ "A transit bus (V2)", "a box truck, V2,": the report's number for the thing just
    named is that thing, of the class its noun says (a number alone says a car); and "a
    pedestrian (P1), an adult male," is one walker, not two."""
    for tag in list(found):
        first = tag.spans[0]
        if tag not in found or not _is_tag(text, first):
            continue
        named = next(
            (
                m
                for m in found
                if m is not tag
                and m.spans[0].end <= first.start
                and _TAG_BETWEEN.fullmatch(text, m.spans[0].end, first.start)
            ),
            None,
        )
        if named is not None:
            merged = replace(named, spans=tuple(sorted({*named.spans, *tag.spans}, key=_at)))
            found = [merged if m is named else m for m in found if m is not tag]
    opens = {id(m): phrase_start(text, m.spans[0].start) for m in found}
    for mention in list(found):
        if mention not in found:
            continue
        ends = [s.end for s in mention.spans[:2]]
        again = next(
            (
                m
                for m in found
                if m is not mention
                and m.cls is mention.cls
                and any(
                    end <= opens[id(m)] <= end + 40
                    and _AGAIN_BETWEEN.fullmatch(text, end, opens[id(m)])
                    for end in ends
                )
                # closed like an apposition, not going on like a list ("a man, a woman and
                # a child")
                and _APPOSITION_CLOSES.match(text, m.spans[0].end)
            ),
            None,
        )
        if again is not None:
            merged = replace(mention, spans=tuple(sorted({*mention.spans, *again.spans}, key=_at)))
            opens[id(merged)] = opens[id(mention)]
            found = [merged if m is mention else m for m in found if m is not again]
    return found


def _at(span: Span) -> int:
    return span.start


#: A description in brackets right after a road user: "POV (silver sedan)", "the other
#: car (a grey estate)".
_BRACKETED = re.compile(r"^\s*\(\s*([^()]{1,60})\)")


def _bracketed_descriptions(text: str, found: list[Mention]) -> list[Mention]:
    """A vehicle described in brackets right after another ("POV (silver sedan)") is that
    vehicle, of the class the brackets name, not one more actor."""
    for mention in list(found):
        if mention not in found or not mention.cls.is_vehicle:
            continue
        after = _BRACKETED.match(text[mention.spans[0].end :])
        if not after:
            continue
        end = mention.spans[0].end
        found = _fold_described(
            found, mention, end + after.start(1), end + after.end(1), vehicles=True
        )
    return found


#: A typology heading before the text ("Lead vehicle stopped: ...", "Pedalcyclist crossing,
#: non-junction: ..."): a label of the scene, not a sentence.
_HEADING = re.compile(r"^[^.:;]{3,60}:\s")
#: The same ended by a full stop ("Lead vehicle stopped. SV travels ..."): a short first
#: sentence in the typology's words, with no article and no name of the ego.
_TERSE_HEADING = re.compile(
    r"^(?![^.]*\b(?:a|an|the|my|our|its|sv|av|ego|v1)\b)"
    r"(?=[^.]*\b(?:vehicles?|pedestrian|pedalcyclist|opposite direction|same direction"
    r"|crossing paths|control loss|changing lanes)\b)[A-Z][\w ,/-]{3,60}\.\s",
    re.I,
)


def heading_end(text: str) -> int:
    """Where a typology heading ("Stationary-lead class: ...") ends, 0 without one: it names
    the kind of crash, not what this ego does."""
    heading = _HEADING.match(text) or _TERSE_HEADING.match(text)
    return heading.end() if heading else 0


def _heading_mentions(text: str, found: list[Mention]) -> list[Mention]:
    """A road user the heading names is the one the text then describes: "Lead vehicle
    stopped: ... a disabled passenger car stands still" is one car."""
    end = heading_end(text)
    if not end:
        return found
    for named in [m for m in found if m.start < end and len(m.spans) == 1]:
        later = next(
            (
                m
                for m in found
                if m.start >= end
                and (
                    m.cls == named.cls or (named.cls is ActorClass.CAR and m.cls in VEHICLE_CLASSES)
                )
            ),
            None,
        )
        if later is None:
            continue
        merged = later.with_span(named.spans[0])
        found = [merged if m is later else m for m in found if m is not named]
    return found


def _its_own(text: str, found: list[Mention], cls: ActorClass, start: int) -> Mention | None:
    """ "P2's bicycle" of a cyclist P2, "the van's bodywork": a thing of one's own class
    named by its owner's possessive is the owner."""
    for mention in reversed(found):
        for span in mention.spans:
            if (
                (mention.cls is cls or (mention.cls.is_walker and cls in _RIDDEN))
                and span.end <= start
                and text[span.start : span.end].lower().endswith(("'s", "\u2019s"))
                and re.fullmatch(r"\s+(?:[\w-]+\s+){0,2}", text[span.end : start])
            ):
                return mention
    return None


def _same_thing(
    found: list[Mention],
    cls: ActorClass,
    before: str,
    word: str,
    ego_number: str | None,
    after: str = "",
) -> Mention | None:
    """An earlier mention this one refers back to ("the van", "the other vehicle")."""
    if _is_party_word(word) and (
        _DEFINITE.search(before) or (_BARE_PARTY.match(word) and not _NEW.search(before))
    ):
        # "the third party" after a road user is named: that one, whatever it is; but one
        # that runs into the back of the ego is a vehicle, not a walker named before
        # ("stopped for a pedestrian ... the claimant ran into the back of us")
        drives = _RUNS_INTO_THE_BACK.match(after) is not None
        return next(
            (
                m
                for m in reversed(found)
                if not m.cls.is_place and not m.is_prop and (m.cls.is_vehicle or not drives)
            ),
            None,
        )
    if _POSSESSOR.search(before):
        party = next((m for m in reversed(found) if _is_party(m)), None)
        if party is not None and cls.is_vehicle:
            return party  # "the third party ... their van": the party's own vehicle
    if _THE_OTHER.search(before):
        for earlier in reversed(found):
            if earlier.cls in VEHICLE_CLASSES or cls == earlier.cls:
                return earlier
        return None
    if _NEW.search(before) and not _DEFINITE.search(before[-12:]):
        return None
    if not _DEFINITE.search(before):
        return None
    generic_vehicle = word.lower() in ("vehicle", "vehicles", "driver", "motorist") or (
        word.lower().startswith("car")
    )
    # Many ("the parked cars", "the cars from the other direction") are not one named
    # before, unless they are it and the ego ("both cars", "the two vehicles").
    placed_many = (
        not word.endswith(("'s", "’s"))
        and _is_plural(word, cls)
        and not _BOTH.search(before)
        and word.lower() != "vehicles"
    )
    # "the car" is the car named before it, even with a motorbike named in between; a
    # generic word ("the vehicle") may mean any vehicle, the latest first.
    for earlier in reversed(found):
        if earlier.cls == cls and not (placed_many and earlier.count == 1):
            return earlier
    if _PLACED_BY_THE_EGO.match(after):
        return None  # "the car behind": placed anew by where it is, not the lorry before
    for earlier in reversed(found):
        if generic_vehicle and earlier.cls in VEHICLE_CLASSES and cls is ActorClass.CAR:
            return earlier
        if word.lower() in _ANY_TWO_WHEELER and earlier.cls.is_two_wheeler:
            return earlier  # "a motorcyclist ... let the bike clear the junction"
    return None


#: Words that may mean a bicycle or a motorbike, the one named before.
_ANY_TWO_WHEELER = frozenset({"bike", "bikes", "rider", "riders"})


#: A claim party named with no article, as claim notes write it ("Claimant states ...").
_BARE_PARTY = re.compile(r"claimant(?:'s)?$", re.I)

#: Words after a claim party that make it a vehicle behind the ego: "the claimant ran
#: into the back of us", "the third party rear-ended my car".
_RUNS_INTO_THE_BACK = re.compile(
    r"^[^.;]{0,60}?\b(?:rear-ended|rear ended|rear-ends|(?:into|hit|hits|struck|strikes|"
    r"bumped|clipped|tapped|touched|impacted)\b[^.;]{0,30}?\b(?:back|rear)\b)",
    re.I,
)

#: "both cars", "the two vehicles": the ego and the other, named before.
_BOTH = re.compile(r"\b(?:both|two)\s+(?:[\w'-]+\s+)?$", re.I)

#: "their van", "his car": the vehicle of someone named before.
_POSSESSOR = re.compile(r"\b(?:their|his|her)\s+(?:[\w'-]+[- ]){0,2}$", re.I)


def _is_party_word(words: str) -> bool:
    """ "the third party", "the other party", "the claimant": a road user named by its part
    in the claim, which an apposition or its vehicle ("their van", "on a motorcycle") later
    names properly."""
    return words.lower().removesuffix("'s").endswith(("party", "claimant"))


def _is_party(mention: Mention) -> bool:
    return _is_party_word(mention.quote)


#: After a generic "the car": where it is from the ego, or that it comes towards the ego,
#: which names a new one ("wait behind the lorry until the car coming towards you has gone").
_PLACED_BY_THE_EGO = re.compile(
    r"^\s*(?:(?:(?:which|that|who)\s+(?:was|were|is|are|had\s+been|has\s+been)\s+)?"
    r"(?:behind|in front|ahead|following|next to|beside|alongside)\b(?!\s+(?:it|them)\b)"
    r"|(?:coming|driving|heading|travelling|traveling)\s+(?:towards|toward|at)\s+(?:you|me|us|the ego|the av)\b"
    r"|(?:coming|driving|travelling|traveling)\s+the\s+other\s+way\b"
    r"|(?:from|in)\s+(?:the\s+)?(?:other|opposite)\s+direction\b)",
    re.I,
)


_DETERMINER = re.compile(
    r"^(?:an?|the|another|two|three|four|five|six|\d|one|some|its|their)$", re.I
)
#: A unit after a number: the number is a measure, not a count.
_MEASURED = re.compile(
    r"\s*(?:m|km|ft|feet|foot|metres?|meters?|yards?|mph|kph|km/h|s|sec)\b", re.I
)


@cache
def _bare_modifiers() -> frozenset[str]:
    """Words that open a noun phrase with no article: the lexicon's `bare_modifier` and
    colours."""
    return frozenset(lexicon().classes["bare_modifier"] + lexicon().colours)


#: A pronoun is a phrase of its own: "the AV's right as | it" does not open at "the".
# Pronouns take no article: "on the motorway you ..." opens no phrase at "the".
_NO_ARTICLE = re.compile(r"(?:it|they|them|he|she|him|her|i|we|you|me|us)\b", re.I)
#: Words a noun phrase's modifiers never hold: the phrase of "V2" in "the #3 lane as V2"
#: starts after "as", not at "the".
_PHRASE_STOP = re.compile(
    r"^(?:as|and|or|but|when|while|then|that|which|who|to|from|in|into|on|onto|at|by|"
    r"with|for|was|were|is|are|has|had|lane|lanes|behind|ahead|past|near|beside|alongside|"
    r"toward|towards|across|along|over|under|through|off|around|round|between|than|after|"
    r"before)$",
    re.I,
)


#: How far back (characters) a noun phrase may begin before its noun.
_PHRASE_REACH = 48


def phrase_start(text: str, start: int) -> int:
    """Where the noun phrase of the noun at `start` begins: the nearest article or number
    at most four words before it ("a parked delivery van", "a northbound 2019 Hollis Tern
    sedan"), else the noun itself."""
    if _NO_ARTICLE.match(text, start):
        return start
    reach = max(0, start - _PHRASE_REACH)
    before = text[reach:start]
    words = list(re.finditer(r"[\w'-]+", before))[-5:]
    for word in reversed(words):
        if re.search(r"[.;,!?]", before[word.end() :]) or _PHRASE_STOP.match(word.group(0)):
            break  # the phrase does not reach across punctuation or a joining word
        if (
            _DETERMINER.match(word.group(0))
            and not before[: word.start()].endswith("#")  # "#2 lane" is a lane's number
            and not _MEASURED.match(before, word.end())  # "2 m short of ped" is a distance
        ):
            return reach + word.start()
    # No article: the modifiers right before the noun ("oncoming moto"), if any.
    opened = start
    modifiers = _bare_modifiers()
    for word in reversed(words[-2:]):
        gap = text[reach + word.end() : opened]
        if word.group(0).lower() not in modifiers or re.search(r"[.;,!?()]", gap):
            break
        opened = reach + word.start()
    return opened
