"""A description read once: its cast, with its clauses and pronouns resolved."""

from __future__ import annotations

import re
from dataclasses import replace

from arise.language.cast import Cast, Mention, Span, read_cast
from arise.language.clauses import read_clauses
from arise.language.rules import Fact, rulebook
from arise.vocabulary import ActorClass

# A pronoun that opens a clause ("..., it then stops", "He braked").
_PRONOUN = re.compile(r"(?:\s|then|suddenly|also|and)*\b(it|he|she|they)\b", re.I)


#: The class of an actor the words imply without naming it.
_IMPLIED_CLASS = {
    "oncoming": ActorClass.CAR,
    "crossing": ActorClass.CAR,
    "obstacle": ActorClass.DEBRIS,
}


def _implied(cast: Cast) -> Cast:
    """A cast that names no road user or object but implies one ("yielding to oncoming
    traffic", "an obstruction in its lane") gets that one, on the words that imply it."""
    if cast.others:
        return cast
    hit = rulebook().first(Fact.IMPLIED, cast.text)
    if hit is None:
        return cast
    span = Span(hit.start, hit.end)
    cls = _IMPLIED_CLASS[hit.value]
    counted = hit.value == "obstacle"  # traffic is any number of cars
    mention = Mention(cls, 1, hit.start, hit.end, hit.quote, (span,), counted=counted)
    return replace(cast, others=(mention,))


def parse(text: str) -> Cast:
    """The cast and clauses of `text`; a pronoun opening a clause joins the spans of the
    subject that clause carries on, so the words after it count as that actor's."""
    cast = _implied(read_cast(text))
    clauses = read_clauses(cast)
    ego = list(cast.ego)
    others = list(cast.others)
    for clause in clauses:
        found = _PRONOUN.match(text, clause.start, clause.end)
        if found is None or clause.explicit or clause.subject is None:
            continue
        span = Span(found.start(1), found.end(1))
        plural = found.group(1).lower() == "they"
        if clause.subject == "ego":
            if not plural:
                ego.append(span)
            continue
        assert isinstance(clause.subject, Mention)
        current = next((m for m in others if m.spans[0] == clause.subject.spans[0]), None)
        if current is None or (plural and current.count == 1):
            continue
        others[others.index(current)] = current.with_span(span)
    if len(ego) == len(cast.ego) and all(a is b for a, b in zip(others, cast.others, strict=True)):
        return replace(cast, clauses=tuple(clauses))
    resolved = Cast(text, tuple(sorted(ego, key=lambda s: s.start)), tuple(others), cast.skipped)
    return replace(resolved, clauses=tuple(read_clauses(resolved)))
