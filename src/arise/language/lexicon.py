"""The lexicon (data/lexicon.yaml) loaded once: word classes, nouns by class, makes."""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import Any

import yaml

from arise.language.errors import RuleError
from arise.language.patterns import WORD_END, compile_pattern

#: libyaml's safe loader when PyYAML has it (about 10x faster on our rule files), else
#: the pure-Python one; both build plain data only.
SAFE_LOADER: type[yaml.SafeLoader] = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


@dataclass(frozen=True)
class Lexicon:
    classes: dict[str, tuple[str, ...]]
    #: A slot's word -> the word a value takes ("r" -> "right"), keyed by `slot_key`.
    slot_words: dict[str, str]
    #: (Scenic class, phrases), most specific class first.
    nouns: tuple[tuple[str, tuple[str, ...]], ...]
    not_an_actor_before: tuple[str, ...]
    not_an_actor_after: tuple[str, ...]
    makes: tuple[str, ...]
    colours: tuple[str, ...]
    #: A verb -> its irregular forms ("ride" -> "rode", "ridden"), for ``ride+`` in a pattern.
    verbs: dict[str, tuple[str, ...]]
    #: Every noun, one named group per class (see `_noun_pattern`).
    noun_pattern: re.Pattern[str]


def _strings(data: Any, where: str) -> tuple[str, ...]:
    if not isinstance(data, list) or not all(isinstance(item, str) for item in data):
        raise RuleError(f"lexicon: {where} must be a list of words")
    return tuple(item.lower() for item in data)


@cache
def lexicon() -> Lexicon:
    """The shipped lexicon; a malformed file is a RuleError naming the part."""
    text = resources.files("arise.language").joinpath("data/lexicon.yaml").read_text("utf-8")
    data = yaml.load(text, Loader=SAFE_LOADER)
    if not isinstance(data, dict):
        raise RuleError("lexicon: not a mapping")
    classes = {name: _strings(words, f"classes.{name}") for name, words in data["classes"].items()}
    nouns = tuple((cls, _strings(words, f"nouns.{cls}")) for cls, words in data["nouns"].items())
    slot_words = data.get("slot_words") or {}
    if not isinstance(slot_words, dict) or not all(
        isinstance(k, str) and isinstance(v, str) for k, v in slot_words.items()
    ):
        raise RuleError("lexicon: slot_words must map words to words")
    return Lexicon(
        classes=classes,
        slot_words={slot_key(k): v.lower() for k, v in slot_words.items()},
        nouns=nouns,
        not_an_actor_before=_strings(data["not_an_actor_before"], "not_an_actor_before"),
        not_an_actor_after=_strings(data.get("not_an_actor_after", []), "not_an_actor_after"),
        makes=_strings(data["makes"], "makes"),
        colours=_strings(data["colours"], "colours"),
        verbs={
            verb.lower(): _strings(forms, f"verbs.{verb}")
            for verb, forms in (data.get("verbs") or {}).items()
        },
        noun_pattern=_noun_pattern(nouns),
    )


_SLOT_GAP = re.compile(r"[\s()>,'-]+")


def slot_key(word: str) -> str:
    """A slot's word as `slot_words` knows it, however the text spaces or hyphenates it:
    "Near-side", "near side" and "nearside" are one key, as are "2 o'clock" and "2 oclock"."""
    return _SLOT_GAP.sub("", word.lower())


def slot_word(word: str) -> str:
    """The word a rule's value takes for a slot's matched `word` ("R" -> "right")."""
    return lexicon().slot_words.get(slot_key(word), word.lower())


def _noun_pattern(nouns: tuple[tuple[str, tuple[str, ...]], ...]) -> re.Pattern[str]:
    """One regex for every noun, the longest phrase first whatever its class ("box truck"
    is a Truck, not a Box); each phrase's group is named CLASS_N (see `noun_class`)."""
    phrases = [(phrase, cls) for cls, words in nouns for phrase in words]
    phrases.sort(key=lambda item: len(item[0]), reverse=True)
    groups = []
    for index, (phrase, cls) in enumerate(phrases):
        inner = compile_pattern("@x", {"x": (phrase,)}).pattern
        # with its possessive: "the bus's nose" names the bus
        inner = inner.removesuffix(WORD_END) + rf"(?:'s\b|{WORD_END})"
        groups.append(f"(?P<{cls}_{index}>{inner})")
    return re.compile("|".join(groups), re.I)


def noun_class(match: re.Match[str]) -> str:
    """The Scenic class of a match of `Lexicon.noun_pattern`."""
    assert match.lastgroup is not None
    return match.lastgroup.rsplit("_", 1)[0]


@cache
def class_pattern(name: str) -> re.Pattern[str]:
    """The phrases of one word class as a regex (`ego`, `side`, ...), built once: the
    clause reader asks for one per clause."""
    return compile_pattern(f"@{name}", lexicon().classes)


@cache
def not_after_abbreviation() -> str:
    """A regex guard for a stop that ends a sentence: not the stop of a short form of the
    lexicon class `abbreviation` ("unprot. LT", "approx. 30 m"), which ends no sentence."""
    words = lexicon().classes["abbreviation"]
    return "".join(rf"(?<!\b{re.escape(word)})(?<!\b{re.escape(word.title())})" for word in words)
