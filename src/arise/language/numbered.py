"""Sentences, and the numbered parties of a report ("V1", "Unit 2"): which one is the ego.

Reports number their parties, and the one under test is not always the first. The reading
rules name the ego's numbered forms as "V1", "Vehicle 1", "Unit 1" ("struck V1's right
rear"); `ego_number_view` gives them a text in which the ego's number and 1 trade places,
the same length, so every offset and quote still points at the description itself.
"""

from __future__ import annotations

import re
from bisect import bisect_right
from functools import cache, lru_cache

from arise.language.lexicon import class_pattern, not_after_abbreviation

# Numbered parties of a report: "V1", "Vehicle 2", "Veh. 1", "Unit 1"; pedestrians "P1".
NUMBERED = re.compile(r"\b(?:V|Veh\.?\s?|Vehicle\s|Unit\s|Party\s)([1-9])\b(?:'s)?")
# What says a numbered vehicle is the one under test.
_AUTONOMOUS = re.compile(
    r"\b(?:autonomous|driverless|self-driving|automated|av|ads|robotaxi|test vehicle)\b", re.I
)
# "Unit 2, a hatchback in the right lane, struck the AV": "the AV" further on is another
# party, not what the numbered one is ("V1 (the autonomous test vehicle)" is).
_ANOTHER_AV = re.compile(r"^.{25,}\bthe\s+$", re.S)


@cache
def _sentence_stop() -> re.Pattern[str]:
    """A stop that ends a sentence: not one after a short form ("unprot. LT")."""
    return re.compile(rf"{not_after_abbreviation()}[.;!?](?:\s|$)")


def sentence_start(text: str, position: int) -> int:
    """Where the sentence holding `position` starts."""
    stops = _stops(text)
    at = bisect_right(stops, position)
    return stops[at - 1] if at else 0


@lru_cache(maxsize=16)  # keyed by the text: bounded, as a server reads many
def _stops(text: str) -> tuple[int, ...]:
    """Where each sentence of `text` but the first starts, found once per text."""
    return tuple(m.end() for m in _sentence_stop().finditer(text))


def sentence_spans(text: str) -> list[tuple[int, int]]:
    """Every sentence of `text`, as (start, end) with its stop included."""
    stops = [m.end() for m in _sentence_stop().finditer(text)]
    return list(zip([0, *stops], [*stops, len(text)], strict=True))


def sentence_end(text: str, position: int) -> int:
    """Where the sentence holding `position` ends (a stop followed by a space, or the end)."""
    found = _sentence_stop().search(text, position)
    return found.start() if found else len(text)


@lru_cache(maxsize=16)  # keyed by the text: bounded, as a server reads many
def numbered_ego(text: str) -> str | None:
    """Which number the ego has among numbered vehicles ("V1"...), or None if none are.

    The one whose sentence says it is autonomous; else 1, the usual first party; else, when
    the text names the ego in words ("the AV ... Unit 2, a hatchback"), none of them."""
    numbers = {m.group(1) for m in NUMBERED.finditer(text)}
    if not numbers:
        return None
    for match in NUMBERED.finditer(text):
        # its sentence, at most 80 characters on (a search bounded there: a text of
        # hundreds of numbered names must not cost a pass to its end for each)
        stop = _sentence_stop().search(text, match.end(), match.end() + 80)
        end = stop.start() if stop else min(len(text), match.end() + 80)
        following = NUMBERED.search(text, match.end(), end)
        window = text[match.end() : following.start() if following else end]
        if any(
            not _ANOTHER_AV.search(window[: hit.start()]) for hit in _AUTONOMOUS.finditer(window)
        ):
            return match.group(1)
    if "1" in numbers:
        return "1"
    worded = any(m.group(0) != "i" for m in class_pattern("ego").finditer(text))
    return None if worded else min(numbers)


@lru_cache(maxsize=16)  # keyed by the text: bounded, as a server reads many
def ego_number_view(text: str) -> str:
    """`text` as the rules read it: when the ego is a party numbered other than 1 ("Vehicle
    2 (the AV)"), its number and 1 trade places in every numbered name, so "Vehicle 2's
    right rear" reads as the ego's part ("vehicle 1's" in the rules) and "V1" as another."""
    ego = numbered_ego(text)
    if ego is None or ego == "1":
        return text
    swap = {ego: "1", "1": ego}
    chars = list(text)
    for match in NUMBERED.finditer(text):
        at = match.start(1)
        chars[at] = swap.get(chars[at], chars[at])
    return "".join(chars)
