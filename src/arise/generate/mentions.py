"""Who and what a description names: the ego, and each road user or object with its words.

A fixed reader, no model. It finds nouns of road users and props (a van, two cones, the
bus stop), folds repeated references to one thing ("a van ... the van ... the vehicle")
into one mention, and keeps each mention's span, so every later fact (a side, a turn) can be
tied to the words it rests on and to the actor those words are about.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

#: Noun patterns -> Scenic class, most specific first ("bus stop" before "bus").
_NOUNS: tuple[tuple[str, str], ...] = (
    ("BusStop", r"bus[- ]stops?|bus shelters?"),
    ("Cone", r"(?:traffic )?cones?|pylons?"),
    ("Debris", r"debris|tire scraps?|tyre scraps?|scrap metal|(?:piece|pieces) of tire"),
    ("TrafficWarning", r"warning (?:signs?|triangles?)"),
    ("Barrier", r"barriers?|barricades?|jersey barriers?"),
    ("Trash", r"(?:recycling|trash|garbage|wheelie|rubbish) (?:bins?|cans?|carts?)|bins?"),
    ("VendingMachine", r"vending machines?"),
    ("Barrel", r"barrels?|drums?"),
    ("Box", r"(?:cardboard )?box(?:es)?(?![- ]trucks?)|crates?"),
    ("Bus", r"minibus(?:es)?|buses|bus|coach(?:es)?"),
    (
        "Truck",
        r"tractor[- ]trailers?|semi[- ]trucks?|semis?|lorr(?:y|ies)|box trucks?|"
        r"pickup trucks?|pickups?|trucks?|dump trucks?",
    ),
    ("Van", r"minivans?|vans?"),
    (
        "Motorcycle",
        r"motorcyclists?|motorcycles?|motorbikes?|motor scooters?|scooters?|mopeds?|"
        r"motorcycle riders?",
    ),
    ("Bicycle", r"bicyclists?|bicycles?|cyclists?|bikes?|e-bikes?"),
    (
        "Pedestrian",
        r"pedestrians?|walkers?|joggers?|runners?|persons?|people|child(?:ren)?|kids?|"
        r"boys?|girls?|man|men|woman|women|someone|toddlers?",
    ),
    (
        "Car",
        r"passenger cars?|cars?|vehicles?|sedans?|suvs?|taxis?|cabs?|hatchbacks?|"
        r"coupes?|automobiles?",
    ),
)
PROP_NOUN_CLASSES = frozenset(
    {"BusStop", "Cone", "Debris", "TrafficWarning", "Barrier", "Trash", "VendingMachine"}
    | {"Barrel", "Box"}
)
VEHICLE_CLASSES = frozenset({"Car", "Van", "Truck", "Bus", "Motorcycle", "Bicycle"})

_EGO = re.compile(
    r"\b(?:the |our |an? )?(?:ego(?:[- ](?:vehicle|car))?|av|autonomous vehicle|"
    r"self[- ]driving (?:car|vehicle)|test vehicle|automated vehicle)(?:'s)?\b",
    re.I,
)
# Nouns that are not road users here: "bike lane", "car park", "bus lane", "crosswalk".
_NOT_ACTOR = re.compile(
    r"^(?:\s|-)*(?:lanes?|park|parks|parking|stations?|routes?|paths?|racks?|"
    r"signals?|lights?|doors?|bumpers?|mirrors?|wash)\b",
    re.I,
)
_COUNT_WORDS = {
    "two": 2,
    "three": 3,
    "four": 4,
    "five": 5,
    "six": 6,
    "pair of": 2,
    "couple of": 2,
}
_COUNT = re.compile(r"\b(two|three|four|five|six|\d|pair of|couple of)\s+(?:\w+[- ]){0,2}$", re.I)
_NEW = re.compile(r"\b(?:a|an|another|second|third|one|some|other)\s+(?:\w+[- ]){0,3}$", re.I)
_DEFINITE = re.compile(r"\b(?:the|that|this|its|their)\s+(?:\w+[- ]){0,3}$", re.I)
# "both vehicles", "no other vehicle": a summary or a negation, not one more thing.
_NOT_NEW_THING = re.compile(
    r"\b(?:both|all|neither|either|no|any|none of the|no one|nobody)\s+(?:other\s+)?"
    r"(?:\w+\s+)?$",
    re.I,
)
_PLURAL = re.compile(r"(?:s|ren|men|ple|ies)$", re.I)


@dataclass(frozen=True)
class Span:
    start: int
    end: int


@dataclass(frozen=True)
class Mention:
    """One thing the text names: its class, how many, and its first words in the text."""

    cls: str
    count: int
    start: int
    end: int
    quote: str
    spans: tuple[Span, ...]

    @property
    def is_prop(self) -> bool:
        return self.cls in PROP_NOUN_CLASSES


@dataclass(frozen=True)
class Cast:
    """The ego's spans and the other things a description names, in order of first mention."""

    text: str
    ego: tuple[Span, ...]
    others: tuple[Mention, ...]

    def subject_before(self, position: int) -> Mention | str | None:
        """The actor ("ego" or a Mention) named last before `position` in its sentence."""
        sentence_start = _sentence_start(self.text, position)
        best: tuple[int, Mention | str] | None = None
        for span in self.ego:
            possessive = self.text[span.start : span.end].lower().endswith("'s")
            if (
                sentence_start <= span.start < position
                and not possessive
                and (best is None or span.start > best[0])
            ):
                best = (span.start, "ego")
        for mention in self.others:
            for span in mention.spans:
                if sentence_start <= span.start < position and (
                    best is None or span.start > best[0]
                ):
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


_SENTENCE = re.compile(r"[.;!?](?:\s|$)")


def _sentence_start(text: str, position: int) -> int:
    ends = [m.end() for m in _SENTENCE.finditer(text, 0, position)]
    return ends[-1] if ends else 0


def sentence_end(text: str, position: int) -> int:
    """Where the sentence holding `position` ends (a stop followed by a space, or the end)."""
    found = _SENTENCE.search(text, position)
    return found.start() if found else len(text)


def _noun_pattern() -> re.Pattern[str]:
    alternatives = "|".join(f"(?P<{cls}>{pattern})" for cls, pattern in _NOUNS)
    return re.compile(rf"\b(?:{alternatives})\b", re.I)


_NOUN = _noun_pattern()


def read_cast(text: str) -> Cast:
    """The ego and the things `text` names (each thing once, with a count)."""
    ego = tuple(Span(m.start(), m.end()) for m in _EGO.finditer(text))
    taken = [(s.start, s.end) for s in ego]
    found: list[Mention] = []
    for match in _NOUN.finditer(text):
        start, end = match.span()
        if any(a < end and start < b for a, b in taken):
            continue
        if _NOT_ACTOR.match(text[end:]):
            continue
        cls = match.lastgroup
        assert cls is not None
        word = match.group(0)
        before = text[max(0, start - 40) : start]
        if _NOT_NEW_THING.search(before):
            continue
        count_match = _COUNT.search(before)
        count = 1
        if count_match:
            token = count_match.group(1).lower()
            count = int(token) if token.isdigit() else _COUNT_WORDS.get(token, 1)
        span = Span(start, end)
        earlier = _same_thing(found, cls, before, word)
        if earlier is not None:
            index = found.index(earlier)
            found[index] = Mention(
                earlier.cls,
                earlier.count,
                earlier.start,
                earlier.end,
                earlier.quote,
                (*earlier.spans, span),
            )
            continue
        if count == 1 and _PLURAL.search(word) and cls not in ("Bus", "Debris", "Pedestrian"):
            count = 2 if not count_match else count
        quote_start = phrase_start(text, start)
        found.append(Mention(cls, count, start, end, text[quote_start:end], (span,)))
    return Cast(text, ego, tuple(found))


def _same_thing(found: list[Mention], cls: str, before: str, word: str) -> Mention | None:
    """An earlier mention this one refers back to ("the van", "the other vehicle")."""
    if _NEW.search(before) and not _DEFINITE.search(before[-12:]):
        return None
    if not _DEFINITE.search(before):
        return None
    generic_vehicle = word.lower() in ("vehicle", "vehicles") or word.lower().startswith("car")
    for earlier in reversed(found):
        if earlier.cls == cls:
            return earlier
        if generic_vehicle and earlier.cls in VEHICLE_CLASSES and cls == "Car":
            return earlier
        if cls == "Pedestrian" and earlier.cls == "Pedestrian":
            return earlier
    return None


_DETERMINER = re.compile(
    r"^(?:an?|the|another|two|three|four|five|six|\d|one|some|its|their)$", re.I
)


def phrase_start(text: str, start: int) -> int:
    """Where the noun phrase of the noun at `start` begins: the nearest article or number
    at most three words before it ("a parked delivery van"), else the noun itself."""
    before = text[max(0, start - 40) : start]
    words = list(re.finditer(r"[\w'-]+", before))[-4:]
    for word in reversed(words):
        if re.search(r"[.;,!?]", before[word.end() :]):
            break  # the phrase does not reach across punctuation
        if _DETERMINER.match(word.group(0)):
            return max(0, start - 40) + word.start()
    return start
