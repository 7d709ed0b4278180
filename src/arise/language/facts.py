"""A grounded fact: one value of the spec, where it came from and the words it rests on."""

from __future__ import annotations

from enum import StrEnum

from pydantic import BaseModel

from arise.vocabulary import StartDetail


class FactSource(StrEnum):
    TEXT = "text"  # a fixed rule read it from the description's words
    MODEL = "model"  # the model's answer, backed by a quote found in the description
    GUESS = "guess"  # the model's answer with no words of the description behind it
    DEFAULT = "default"  # the description does not say: a neutral value


class GroundedFact(BaseModel):
    name: str
    value: str
    source: FactSource
    quote: str | None = None

    def describe(self) -> str:
        if self.source is FactSource.DEFAULT:
            return f"{self.name}: {self.value} (not stated)"
        if self.source is FactSource.GUESS:
            return f"{self.name}: {self.value} (the model's guess; no words of the text say it)"
        return f'{self.name}: {self.value}  <- "{self.quote}"'


def text_fact(name: str, value: str, quote: str | None) -> GroundedFact:
    """A fact the words of the description say, with those words."""
    return GroundedFact(name=name, value=value, source=FactSource.TEXT, quote=quote)


class StartFact(GroundedFact):
    """Where an actor starts, with a finer point when the words give one (in the lane a
    turning ego enters), so that no later stage reads the words again to find it."""

    detail: StartDetail | None = None


def start_detail(fact: GroundedFact | None) -> StartDetail | None:
    """The finer point of a start, if the fact is a start that has one."""
    return fact.detail if isinstance(fact, StartFact) else None
