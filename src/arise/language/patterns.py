"""The phrase patterns our reading rules are written in, compiled once to regular expressions.

A pattern is words separated by spaces, matched as whole words, case aside:

- ``oncoming``: the word itself; ``left-hand`` also matches "left hand" and "lefthand", and words
  apart match words joined by a hyphen (``right front`` matches "right-front");
- ``overtak*``: any word that starts so ("overtakes", "overtaking");
- ``ride+``: every form of the verb ("ride", "rides", "rode", "ridden", "riding"): the
  regular ones are made here, the irregular ones come from the lexicon's ``verbs``;
- ``left|right``: one of these words;
- ``the?``: the word, or nothing;
- ``~``: any one word; ``~?``: any one word, or nothing;
- ``#``: a number ("30", "2.5"); the word after it may be joined to it (``# m`` matches
  "20 m" and "20m"), and a unit may hang on it ("within #" matches "within 2m");
- ``!left|right`` (last only): not followed by one of these words;
- ``...``: up to eight words in between, within the sentence;
- ``<side>``: a named slot, one of the words of the lexicon class ``side``; a rule's facts
  can name the slot (``start: adjacent_{side}``) to take the matched word;
- ``@ego``: a phrase of the lexicon class ``ego`` (several words allowed).

Why a language of our own and not raw regular expressions: the rules are data that people
who do not read regular expressions add to, every pattern compiles to a regex that is linear
(no nested quantifiers), and a pattern can only match words, never parts of words.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

from arise.language.errors import RuleError

#: Between two words: spaces, a hyphen, a slash, a comma, a colon, an arrow, an at sign, a
#: number sign or brackets ("right front" matches "right-front", "ahead in" "ahead, in",
#: "l r" "L->R", "lane 3 right" "lane 3 (right)", "the 2 lane" "the #2 lane", "stopped stop
#: line" "stopped @ stop line", "surface wet" "Road surface: wet").
_GAP = r"(?:\s*[,:]\s*|\s*->\s*|\s*@\s*|[\s()/#-]+)"
#: `...`: up to eight words, within the sentence.
_SKIP = r"(?:[\w'-]+(?:\s*,\s*|\s+)){0,8}?"  # no hyphen between: one way to split
_WORD = re.compile(r"^[a-z0-9'][a-z0-9'-]*[*+]?$")
#: After a pattern's last word: no more of a word ("van" is not "vans" or "van's").
WORD_END = r"(?![\w'])"
#: `#`: a number, with a unit joined to it or not ("20", "2.5", "20m").
_NUMBER = r"\d+(?:\.\d+)?[a-z]*"


def _word(item: str, verbs: Mapping[str, tuple[str, ...]] | None = None) -> str:
    """One word of a pattern as a regex: hyphens optional, a trailing * a prefix, a
    trailing + every form of a verb."""
    if not _WORD.match(item):
        raise RuleError(f"pattern word {item!r}: use letters, digits, ' and -")
    if item.endswith("+"):
        forms = verb_forms(item[:-1], (verbs or {}).get(item[:-1], ()))
        return "(?:" + "|".join(_word(form) for form in forms) + ")"
    prefix = item.endswith("*")
    core = item[:-1] if prefix else item
    parts = [re.escape(part) for part in core.split("-")]
    body = r"[- ]?".join(parts)
    return rf"{body}[\w'-]*" if prefix else body


_SIBILANT = re.compile(r"(?:s|x|z|ch|sh|o)$")
_CONSONANT_Y = re.compile(r"[^aeiou]y$")


def verb_forms(verb: str, irregular: tuple[str, ...] = ()) -> tuple[str, ...]:
    """A verb's forms: the base, -s, -ed and -ing made by the regular rules, and the
    irregular forms given (a past, a participle, or a doubled "stopped", "stopping")."""
    if _CONSONANT_Y.search(verb):
        third, past, ing = verb[:-1] + "ies", verb[:-1] + "ied", verb + "ing"
    elif verb.endswith("ee"):
        third, past, ing = verb + "s", verb + "d", verb + "ing"
    elif verb.endswith("e"):
        third, past, ing = verb + "s", verb + "d", verb[:-1] + "ing"
    else:
        third = verb + ("es" if _SIBILANT.search(verb) else "s")
        past, ing = verb + "ed", verb + "ing"
    return tuple(dict.fromkeys((verb, third, past, ing, *irregular)))


def _alternatives(words: list[str], verbs: Mapping[str, tuple[str, ...]] | None = None) -> str:
    return "(?:" + "|".join(_word(word, verbs) for word in words) + ")"


_POSSESSIVES = frozenset({"its", "my", "our", "your", "his", "her", "their"})


def _check_determiners(pattern: str, items: list[str]) -> None:
    """ "the ego's|its lane" reads as "the its lane": alternatives are single words, so a
    plain "the" before a possessive never matches it. Such a pattern is a mistake."""
    for word, following in zip(items, items[1:], strict=False):
        if word == "the" and _POSSESSIVES & set(following.rstrip("?").split("|")):
            raise RuleError(f"pattern {pattern!r}: 'the' before {following!r}; write 'the?'")


def compile_pattern(
    pattern: str,
    classes: Mapping[str, tuple[str, ...]],
    verbs: Mapping[str, tuple[str, ...]] | None = None,
) -> re.Pattern[str]:
    """`pattern` as a case-insensitive regex over text; raises RuleError when malformed.
    verbs: the irregular forms of verbs (`ride` -> rode, ridden) for words like ``ride+``."""
    items = pattern.strip().lower().split()
    if not items:
        raise RuleError("an empty pattern")
    _check_determiners(pattern, items)
    pieces: list[tuple[str, bool]] = []
    not_next = ""
    if items[-1].startswith("!") and len(items) > 1:
        not_next = f"(?!{_GAP}{_alternatives(items.pop()[1:].split('|'), verbs)}(?![\\w']))"
    for item in items:
        optional = item.endswith("?") and len(item) > 1
        core = item[:-1] if optional else item
        if core == "...":
            pieces.append((_SKIP, False))
            continue
        if core == "~":
            piece = r"[\w'-]+"
        elif core == "#":
            piece = _NUMBER
        elif core.startswith("<") and core.endswith(">"):
            name = core[1:-1]
            if name not in classes:
                raise RuleError(f"pattern {pattern!r}: no lexicon class {name!r}")
            piece = f"(?P<{name}>{_phrases(classes[name])})"
        elif core.startswith("@"):
            name = core[1:]
            if name not in classes:
                raise RuleError(f"pattern {pattern!r}: no lexicon class {name!r}")
            piece = f"(?:{_phrases(classes[name])})"
        else:
            piece = _alternatives(core.split("|"), verbs)
        pieces.append((piece, optional))
    if all(optional for _, optional in pieces):
        raise RuleError(f"pattern {pattern!r}: every word is optional")
    body = ""
    for index, (piece, optional) in enumerate(pieces):
        last = index == len(pieces) - 1
        gap = f"(?:{_GAP})?" if piece == _NUMBER else _GAP  # "20m": a unit joined to it
        if piece == _SKIP:
            body += piece  # it takes its own gaps
        elif not optional:
            body += piece if last else piece + gap
        elif not last:
            body += f"(?:{piece}{gap})?"
        else:  # an optional last word hangs on the separator before it
            body = body.removesuffix(_GAP) + f"(?:{_GAP}{piece})?"
    try:
        return re.compile(rf"(?<![\w'-]){body}{WORD_END}{not_next}", re.I)
    except re.error as error:  # a slot named twice, ...
        raise RuleError(f"pattern {pattern!r}: {error}") from error


def _phrases(phrases: tuple[str, ...]) -> str:
    """Several-word phrases of a class, longest first so "ego vehicle" beats "ego"."""
    ordered = sorted(phrases, key=len, reverse=True)
    return "|".join(_GAP.join(_word(word) for word in phrase.split()) for phrase in ordered)
