"""Whose is each verb: a description's sentences cut into clauses, each with its subject.

A clause ends at a comma, a semicolon or a joining word (and, then, but, while, when, as,
after, before, until, because, which, that, who). Its subject is:

- the actor named at its start ("a cyclist swerves", "then the ego brakes");
- for a relative clause ("a car that slows", "a van, which stops"), the actor before it;
- for a participle right after an actor ("a car turning left", "a truck parked on the
  right"), that actor;
- otherwise the subject carries over from the clause before that is not a relative one:
  in "the ego follows a car that slows, then moves over to the left lane", it is the ego
  that moves over; a sentence that opens with a participle ("Turning left, the ego ...")
  takes the subject of the clause after it.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from functools import cache

from arise.language.cast import Cast, Clause, Mention, Span, phrase_start
from arise.language.lexicon import class_pattern, not_after_abbreviation
from arise.language.numbered import sentence_start

Actor = Mention | str  # a Mention, or "ego"


@cache
def _boundary() -> re.Pattern[str]:
    """Where a clause may end: punctuation (not the stop of a short form, "unprot. LT"),
    an arrow, or a word that joins clauses."""
    return re.compile(
        rf"[,;:()]|{not_after_abbreviation()}\.(?=\s|$)|[!?]|(?<=\s)[-=]>(?=\s)"
        r"|\b(?:and then|and|then|but|while|whilst|when|as|after|before|until|because|"
        r"so that|which|that|who|whereupon)\b",
        re.I,
    )


_RELATIVE = frozenset({"which", "that", "who"})
_BETWEEN = re.compile(r"\bbetween\b(?!.*\band\b)", re.I)
_SENTENCE_END = frozenset({".", "!", "?", ";"})
# Words that may come before a clause's subject ("then suddenly the ego ...").
_LEAD_WORDS = re.compile(
    r"(?:\s|then|suddenly|also|later|immediately|finally|meanwhile|now|and|but|"
    r"at the same time|at that moment|just then|moments later|seconds later)*",
    re.I,
)
_PARTICIPLE = re.compile(r"\s*,?\s*(?:\w+ly\s+)?(\w+(?:ing|ed))\b", re.I)
_NOT_PARTICIPLE = frozenset({"during", "nothing", "something", "anything", "everything", "bed"})


#: Words that put the noun after them in a place ("to the right of the AV").
_PLACE_PREPOSITION = re.compile(
    r"(?:of|in|into|to|from|behind|by|at|on|onto|toward|towards|past|beside|near|around|"
    r"ahead|front|between|across|along|alongside|over|under|through|off|against)$",
    re.I,
)


def _governed(text: str, span: Span) -> bool:
    """Whether the actor at `span` is the object of a place word ("of the AV")."""
    before = text[: phrase_start(text, span.start)].split()
    return bool(before) and _PLACE_PREPOSITION.match(before[-1].strip(",")) is not None


def _main_verb(word: str) -> bool:
    """A past form that tells what someone did ("swerved"), not a state ("parked")."""
    return word.lower().endswith("ed") and not class_pattern("state_participle").fullmatch(word)


_FIRST_WORD = re.compile(r"\s*(\w+)")


def _participle_opening(cast: Cast, begin: int, after: tuple[int, int, str] | None) -> bool:
    """Whether the clause at `begin` is a participle phrase opening its sentence and ended by
    a comma ("Overtaking a tractor on the hill, the ego ..."): the subject is the next
    clause's, and an actor named in it is the participle's object. Not a word that opens
    an actor's own name ("oncoming box truck goes straight, ...")."""
    text = cast.text
    if after is None or after[2] != ",":
        return False
    sentence = text[:begin].rstrip()
    if sentence and sentence[-1] not in ".!?;:":
        return False
    first = _FIRST_WORD.match(text, begin)
    if first is None or any(
        phrase_start(text, span.start) <= first.start(1) < span.end
        for mention in cast.others
        for span in mention.spans
    ):
        return False
    word = first.group(1).lower()
    return word.endswith("ing") and word not in _NOT_PARTICIPLE


def _spans(cast: Cast) -> list[tuple[Span, Actor]]:
    found: list[tuple[Span, Actor]] = [(span, "ego") for span in cast.ego]
    for mention in cast.others:
        found += [(span, mention) for span in mention.spans]
    return sorted(found, key=lambda item: item[0].start)


# A verb of motion right after an actor makes it the subject even after a preposition
# ("from behind one motorbike is coming"), and right before one where a place opens the
# clause ("from left side is coming a bus").
_MOTION = (
    r"(?:com(?:e|es|ing)|came|go(?:es|ing)?|went|appear(?:s|ed|ing)?|approach(?:es|ed|ing)?|"
    r"arriv(?:e|es|ed|ing)|emerg(?:e|es|ed|ing))"
)
_VERB_AFTER = re.compile(
    rf"\s+(?:(?:is|are|was|were)\s+)?(?:also\s+|suddenly\s+)?{_MOTION}\b", re.I
)
_VERB_BEFORE = re.compile(
    rf"\b(?:(?:is|are|was|were)\s+)?(?:also\s+|suddenly\s+)?{_MOTION}"
    r"(?:\s+(?:\w+ly|fast|very|quick|quickly|also))*\s*$",
    re.I,
)

_PREPOSITION = re.compile(
    r"^(?:of|in|into|to|from|behind|with|by|for|at|on|onto|toward|towards|past|beside|near|"
    r"around|round|ahead|front|than|between|like|before|after|across|along|alongside|over|under|"
    r"through|off|against|follows|following|hits|hit|struck|strikes|strike|overtakes|passes|sees|"
    r"clips|clipped|rams|rammed|touches|touched|scrapes|scraped|sideswipes|sideswiped|bumps|bumped)$",
    re.I,
)


#: The ego's front, as the subject of what the ego ran into ("the AV's front bumper hit").
_EGO_FRONT = re.compile(
    r"(?:'s)?\s+(?:front(?:\s+(?:bumper|end|grille|grill|fascia))?|bonnet|hood|grille)\s+"
    r"(?!was\b|were\b|is\b|got\b)",
    re.I,
)


def _opening_actor(
    cast: Cast, spans: list[tuple[Span, Actor]], start: int, end: int
) -> Actor | None:
    """The actor the clause [start, end) is about: the first one named that no preposition
    (or verb) governs, within its first few words ("At the lights the ego turns", "then a
    speeding red car"; not "in front of the ego")."""
    head = _LEAD_WORDS.match(cast.text, start)
    first_word = head.end() if head else start
    for span, actor in spans:
        if span.start < first_word or span.start >= end:
            continue
        phrase = phrase_start(cast.text, span.start)
        between = cast.text[first_word : max(first_word, phrase)]
        if len(between.split()) > 6:
            break
        words = between.split()
        if (
            words
            and _PREPOSITION.match(words[-1].strip(","))
            and not _VERB_AFTER.match(cast.text, span.end)
        ):
            continue  # governed: "in front of the ego", "behind the bus"
        if cast.text[span.start : span.end].lower().endswith("'s") or re.match(
            r"'s\b", cast.text[span.end : span.end + 2]
        ):
            if actor == "ego" and _EGO_FRONT.match(cast.text, span.end):
                return actor  # "the AV's front bumper struck ...": the ego did it
            continue  # "the ego's lane"
        return actor
    return _inverted_subject(cast, spans, first_word, end)


def _inverted_subject(
    cast: Cast, spans: list[tuple[Span, Actor]], start: int, end: int
) -> Actor | None:
    """The subject after its verb, where a place opens the clause ("from the left side is
    coming a bus", "then from the right also comes a cyclist")."""
    for span, actor in spans:
        if start <= span.start < end:
            between = cast.text[start : phrase_start(cast.text, span.start)]
            if len(between.split()) <= 10 and _motion_verb_before(cast, start, span):
                return actor
            if _FROM_PLACE.fullmatch(between):
                return actor  # its verb left out: "..., and from the front one bus"
    return None


#: Where a subject comes from, opening its clause with the verb left out ("and from front
#: one bus which wants to turn").
_FROM_PLACE = re.compile(r"\s*(?:and\s+|then\s+)?from\s+(?:the\s+)?[\w'-]+(?:\s+[\w'-]+)?\s*", re.I)


def _motion_verb_before(cast: Cast, start: int, span: Span) -> re.Match[str] | None:
    """The verb of motion that ends the words from `start` to the phrase of `span` ("from
    the left side is coming | a bus"), if any."""
    return _VERB_BEFORE.search(cast.text[start : phrase_start(cast.text, span.start)])


def _follows_its_verb(
    cast: Cast, spans: list[tuple[Span, Actor]], subject: Actor | None, start: int, end: int
) -> bool:
    """Whether the clause names its subject after a verb of motion, a place before both."""
    if not isinstance(subject, Mention):
        return False
    for span, actor in spans:
        if actor is subject and start <= span.start < end:
            verb = _motion_verb_before(cast, start, span)
            return verb is not None and bool(cast.text[start : start + verb.start()].strip())
    return False


# A sentence that opens with one of these words opens with a clause of its own
# ("When it is clear, pull out"): the clause after its comma is the sentence's main one.
_SUBORDINATE = re.compile(
    r"\s*(?:when|whenever|once|if|as soon as|before|after|while|until|as|since|unless)\b", re.I
)
# A verb of the imperative class used as a noun or a modifier ("stop sign", "turn signal").
_NOT_IMPERATIVE = re.compile(
    r"\s+(?:sign|signs|line|lines|light|lights|signal|signals|bar|bars|lane|lanes|arrow|arrows)\b",
    re.I,
)


def _imperative(text: str, start: int, end: int) -> bool:
    """Whether the clause [start, end) opens with a bare verb of instruction ("check your
    mirror", "then move over"): an order to the driver, so the ego's."""
    head = _LEAD_WORDS.match(text, start)
    first = head.end() if head else start
    found = class_pattern("imperative").match(text, first, end)
    if found is None:
        return False
    lanes = found.group(0).lower() in ("change", "switch", "swap")  # "change lanes"
    noun = _NOT_IMPERATIVE.match(text, found.end())
    return noun is None or (lanes and noun.group(0).strip().lower().startswith("lane"))


def _actor_ending_at(spans: list[tuple[Span, Actor]], text: str, position: int) -> Actor | None:
    """The actor whose span ends just before `position` (spaces and a comma aside)."""
    gap = re.search(r"[\s,]*$", text[:position])
    edge = gap.start() if gap else position
    for span, actor in spans:
        if span.end == edge:
            return actor
    return None


def read_clauses(cast: Cast) -> list[Clause]:
    """The clauses of `cast.text`, in order, each with its subject (or None)."""
    text = cast.text
    spans = _spans(cast)
    cuts: list[tuple[int, int, str]] = [(0, 0, "")]
    for match in _boundary().finditer(text):
        word = match.group(0).lower()
        if word == "and" and _BETWEEN.search(text, cuts[-1][1], match.start()):
            continue  # "between the ego and the van" joins two places, not two clauses
        cuts.append((match.start(), match.end(), word))
    # A participle right after an actor opens a clause about it ("a car turning left"),
    # but a past form after a place ("in the lane to the right of the AV swerved left") is
    # the main verb of the subject before the place, unless it says a state ("parked").
    for span, _actor in spans:
        found = _PARTICIPLE.match(text, span.end)
        if found and found.group(1).lower() not in _NOT_PARTICIPLE and "," not in found.group(0):
            if _governed(text, span) and _main_verb(found.group(1)):
                continue
            cuts.append((found.start(1), found.start(1), "~participle"))
    cuts.sort()
    clauses: list[Clause] = []
    sentence = 0  # where the current sentence starts
    relative: tuple[str, int] | None = None  # "which" right before "then": still relative
    for index, (_, begin, opener) in enumerate(cuts):
        end = cuts[index + 1][0] if index + 1 < len(cuts) else len(text)
        if opener in _SENTENCE_END or opener in ("", ":"):
            sentence = begin
        if not text[begin:end].strip():
            relative = (opener, cuts[index][0]) if opener in _RELATIVE else None
            continue
        # "a semi, which then swings left": the clause after "then" is the relative one
        cut_at = cuts[index][0]
        if relative is not None and opener in ("then", "and then"):
            opener, cut_at = relative
        relative = None
        subject: Actor | None
        instruction = _imperative(text, begin, end) and opener not in _RELATIVE
        if instruction and (
            sentence == begin or (opener == "," and _SUBORDINATE.match(text, sentence) is not None)
        ):
            subject = "ego"  # "Check your mirror", "When it is clear, pull out"
        elif instruction:
            subject = None  # "... and overtake the tractor": the tractor is its object
        elif opener in _RELATIVE or opener == "~participle":
            subject = _actor_ending_at(spans, text, cut_at if opener != "~participle" else begin)
            if subject is None and opener != "~participle":
                subject = _opening_actor(cast, spans, begin, end)
        elif _participle_opening(cast, begin, cuts[index + 1] if index + 1 < len(cuts) else None):
            subject = None  # "Overtaking a tractor, the ego ...": the tractor is its object
        else:
            subject = _opening_actor(cast, spans, begin, end)
        inverted = _follows_its_verb(cast, spans, subject, begin, end)
        clauses.append(
            Clause(
                begin,
                end,
                opener,
                subject,
                explicit=subject is not None,
                inverted=inverted,
                imperative=subject is None and instruction,
            )
        )
    return _carry_subjects(clauses, text, spans)


_PRONOUN = re.compile(r"(?:\s|then|suddenly|also|and)*\b(it|he|she|they)\b", re.I)


def _agrees(actor: Actor | None, plural: bool) -> bool:
    count = 1 if actor is None or isinstance(actor, str) else actor.count
    return actor is not None and (count > 1) == plural


def _pronoun_referent(
    clause: Clause,
    carried: Actor | None,
    text: str,
    spans: list[tuple[Span, Actor]],
    other: Actor | None = None,
) -> Actor | None:
    """Who a pronoun opening `clause` means: the subject carried on when the number
    agrees ("two pedestrians cross ... while it drives": not the pedestrians); else the
    nearest actor named before it in its sentence that agrees ("I pass a van and it pulls
    out"); else `other`, the last subject that is not the ego ("A hatchback swung in between
    me and the mixer. I braked and it missed me": the hatchback); else the nearest named."""
    found = _PRONOUN.match(text, clause.start, clause.end)
    if found is None:
        return carried
    plural = found.group(1).lower() == "they"
    speaks = _ego_speaks(text, spans, clause)  # then "he" or "it" is not the ego
    if _agrees(carried, plural) and not (carried == "ego" and speaks):
        return carried
    opened = sentence_start(text, clause.start)
    named = [
        actor
        for span, actor in reversed(spans)
        if span.end <= clause.start and _agrees(actor, plural) and not (actor == "ego" and speaks)
    ]
    in_sentence = [
        actor
        for span, actor in reversed(spans)
        if opened <= span.start and span.end <= clause.start and actor in named
    ]
    if in_sentence:
        return in_sentence[0]
    if other is not None and _agrees(other, plural) and speaks:
        return other
    return named[0] if named else carried


_FIRST_OR_SECOND = frozenset({"i", "me", "my", "we", "us", "our", "you", "your"})


def ego_speaks_before(text: str, ego: Iterable[Span], position: int) -> bool:
    """Whether the ego was last named before `position` as "we", "I" or "you": then "he" or
    "it" is someone else ("when we are passing near, he starts suddenly"; "you see a van,
    and behind it you make out a motorcycle")."""
    named = [span for span in ego if span.end <= position]
    return bool(named) and text[named[-1].start : named[-1].end].lower() in _FIRST_OR_SECOND


def _ego_speaks(text: str, spans: list[tuple[Span, Actor]], clause: Clause) -> bool:
    return ego_speaks_before(text, (span for span, actor in spans if actor == "ego"), clause.start)


def _carry_subjects(
    clauses: list[Clause], text: str, spans: list[tuple[Span, Actor]]
) -> list[Clause]:
    """Give each subjectless clause the subject it continues (see the module's docstring)."""
    done: list[Clause] = []
    addressed = any(
        actor == "ego" and text[span.start : span.end].lower().startswith("you")
        for span, actor in spans
    )
    main: Actor | None = None  # the subject of the last clause that is not a relative one
    other: Actor | None = None  # the last such subject that is not the ego
    pending: list[int] = []  # a sentence's opening clauses without a subject yet
    sentence_open = True
    for clause in clauses:
        if clause.opener in _SENTENCE_END or clause.opener == "":
            sentence_open = True
        if clause.subject is not None:
            done.append(clause)
            if clause.opener not in _RELATIVE and clause.opener != "~participle":
                main = clause.subject
                other = main if main != "ego" else other
                for index in pending:
                    done[index] = _with(done[index], clause.subject)
                pending = []
            sentence_open = False
            continue
        opens_with_pronoun = _PRONOUN.match(text, clause.start, clause.end) is not None
        if clause.imperative and addressed and not _agrees(main, plural=True):
            # "Wait until the bike has gone by, then pull out": spoken to the driver
            main = "ego"
            for index in pending:
                done[index] = _with(done[index], "ego")
            pending = []
            sentence_open = False
            done.append(_with(clause, "ego"))
            continue
        if sentence_open and not opens_with_pronoun:
            pending.append(len(done))
            done.append(clause)
            continue
        # a pronoun opening a sentence ("It pulled out") means one named before it, not the
        # subject of a later clause
        sentence_open = False
        referent = _pronoun_referent(clause, main, text, spans, other)
        if opens_with_pronoun:
            main = referent  # "he starts suddenly and goes out": he goes out
        done.append(_with(clause, referent))
    for index in pending:  # no clause after it named anyone
        done[index] = _with(done[index], main)
    return done


def _with(clause: Clause, subject: Actor | None) -> Clause:
    return Clause(clause.start, clause.end, clause.opener, subject, explicit=False)
