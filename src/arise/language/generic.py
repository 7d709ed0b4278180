"""Sentences that tell no scene: advice, rules of thumb, what drivers usually do.

Driver-training texts mix the scene with lessons ("Cover the brake whenever you pass parked
cars", "Where there's a ball, there's usually a child"). A road user first named in such a
sentence is a kind, not one more actor, and weather named there ("In wet weather always
leave more room") is no scene's weather. Words of the lexicon class `generic` mark a lesson;
an order to the reader (a sentence opening with a verb of the class `imperative`, maybe
after a short phrase of time or place) is one only for the plural kinds it names ("check for
people on bikes"), since an order may also point at the scene ("Check your mirror: a van
is ...").
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache

from arise.language.lexicon import class_pattern
from arise.language.numbered import sentence_spans

#: A short phrase of time, place or condition before an order ("In wet weather give ...",
#: "Before any right turn, check ...", "At night, slow down"): its first word.
_FRONTED = re.compile(r"\s*(?:in|on|at|before|after|during|with|for|near|approaching|when)\s", re.I)
_WORD = re.compile(r"\s*,?\s*[\w'-]+", re.I)
_FRONTED_WORDS = 5
_SUBJECT = re.compile(r"i|you|we|he|she|it|they|there|this|that", re.I)
#: Orders that set the scene rather than teach: "Picture yourself ...", "Imagine you ...".
_SCENE_SETTING = re.compile(r"(?:picture|imagine|suppose|consider)\b", re.I)
#: The same words used as a noun ("stop sign", "turn signal"): no order.
_NOUN_USE = re.compile(
    r"\s+(?:sign|signs|line|lines|light|lights|signal|signals|lane|lanes)\b", re.I
)


@dataclass(frozen=True)
class Lessons:
    """Where `text` teaches rather than tells: sentences marked as lessons, and orders."""

    lessons: tuple[tuple[int, int], ...]
    orders: tuple[tuple[int, int], ...]

    def in_lesson(self, position: int) -> bool:
        return any(start <= position < end for start, end in self.lessons)

    def in_order(self, position: int) -> bool:
        return any(start <= position < end for start, end in self.orders)

    def masked(self, text: str) -> str:
        """`text` with its lessons blanked, every other offset kept (an order may tell the
        scene: "At night, keep scanning the far-side sidewalk")."""
        chars = list(text)
        for start, end in self.lessons:
            chars[start:end] = " " * (end - start)
        return "".join(chars)


def _opens_with_order(text: str, start: int, end: int) -> bool:
    """Whether the sentence [start, end) opens with an order, maybe after a short phrase
    of time or place."""
    firsts = [start]
    if (lead := _FRONTED.match(text, start, end)) is not None:
        at = lead.end()
        for _ in range(_FRONTED_WORDS):
            word = _WORD.match(text, at, end)
            if word is None or _SUBJECT.fullmatch(word.group(0).strip(" ,")):
                break  # "When you turn left": a clause with its subject, no order
            at = word.end()
            firsts.append(at)
    for first in firsts:
        first = first + len(text[first:end]) - len(text[first:end].lstrip(" ,"))
        if _SCENE_SETTING.match(text, first, end):
            return False
        verb = class_pattern("imperative").match(text, first, end)
        if verb is not None and not _NOUN_USE.match(text, verb.end()):
            return True
    return False


@lru_cache(maxsize=16)  # keyed by the text: bounded, as a server reads many
def lessons_of(text: str) -> Lessons:
    """The lessons and orders of `text` (a sentence or a `;`-part each)."""
    lessons: list[tuple[int, int]] = []
    orders: list[tuple[int, int]] = []
    marker = class_pattern("generic")
    for start, end in sentence_spans(text):
        if marker.search(text, start, end):
            lessons.append((start, end))
        elif _opens_with_order(text, start, end):
            orders.append((start, end))
    return Lessons(tuple(lessons), tuple(orders))
