"""Module A: a description becomes a validated ScenarioSpec (or a clear error value)."""

from __future__ import annotations

import json
from dataclasses import dataclass, field

from arise.generate.grounding import answer_from_reading, ground
from arise.generate.spec import ExtractionAnswer, ScenarioSpec
from arise.language.condense import condense
from arise.language.readers import Reading, read_description
from arise.language.sense import is_about_traffic, self_contradictions
from arise.llm.base import BaseProvider
from arise.llm.types import Message, StructuredOutputFailed
from arise.prompts import load, load_jsonl

MAX_DESCRIPTION_CHARS = 2000


@dataclass
class Extraction:
    """A spec, or why there is none; plus what the description contradicts itself on."""

    spec: ScenarioSpec | None = None
    error: str | None = None
    contradictions: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)  # model answers overruled or dropped
    ignored: list[str] = field(default_factory=list)  # input left out (dates, aftermath)


def check_description(description: str) -> str | None:
    """A reason to refuse the description before any model call, or None."""
    text = description.strip()
    if not text:
        return "the description is empty: describe the ego, the adversary and what happens"
    if len(text) > MAX_DESCRIPTION_CHARS:
        return (
            f"the description is {len(text)} characters long; keep it under "
            f"{MAX_DESCRIPTION_CHARS} (one scenario per description)"
        )
    if not is_about_traffic(text):
        return (
            "this does not look like a driving scenario: mention the road users "
            "(ego car, pedestrian, cyclist, ...) and what happens on the road"
        )
    return None


def find_contradictions(reading: Reading) -> list[str]:
    """Statements in the description that cannot all hold (`language.sense`)."""
    return self_contradictions(reading)


def extraction_messages(description: str) -> list[Message]:
    messages = [Message("system", load("extract_system.md"))]
    for example in load_jsonl("extract_examples.jsonl"):
        messages.append(Message("user", example["description"]))
        messages.append(Message("assistant", json.dumps(example["spec"])))
    messages.append(Message("user", description.strip()))
    return messages


#: The note a run carries when the fixed rules read the description without the model.
READ_BY_RULES = "extraction: the fixed rules read the adversary and its start; no model call"
#: The note a run carries when the model's answer never parsed and the rules' reading stood in.
MODEL_ANSWER_UNUSABLE = (
    "extraction: the model's answer was unusable, so the fixed rules' reading was used, "
    "with neutral defaults for what it leaves open"
)


def extract_spec(
    description: str,
    provider: BaseProvider,
    *,
    temperature: float = 0.0,
    seed: int | None = None,
    ask_model: bool = False,
) -> Extraction:
    """Module A: the model's answer, grounded in the description (`grounding.ground`).
    When the fixed rules alone read who the adversary is and where it starts (or that there
    is none), the model is not asked unless `ask_model`: grounding would overrule its
    answers on those facts anyway, and the call is most of a run's time.
    A reply that never parses gives way to the rules' reading; other provider failures
    propagate (the caller records them); bad input does not."""
    refusal = check_description(description)
    if refusal:
        return Extraction(error=refusal)
    condensed = condense(description)  # a crash report without its date and aftermath
    reading = read_description(condensed.text)
    if not ask_model:
        read = answer_from_reading(reading)
        if read is not None:
            grounded = ground(condensed.text, read, reading)
            return Extraction(
                spec=grounded.spec,
                contradictions=find_contradictions(reading),
                notes=[READ_BY_RULES, *grounded.notes],
                ignored=condensed.ignored,
            )
    notes: list[str] = []
    try:
        completion = provider.complete(
            extraction_messages(condensed.text),
            temperature=temperature,
            max_tokens=600,
            schema=ExtractionAnswer,
            seed=seed,
        )
    except StructuredOutputFailed as failure:
        # The rules' reading with neutral defaults for what it leaves open is a scenario
        # of the description; an error instead would lose the run for a model's slip.
        answer = answer_from_reading(reading, partial=True)
        assert answer is not None
        notes.append(f"{MODEL_ANSWER_UNUSABLE} ({failure})")
    else:
        parsed = completion.parsed
        assert isinstance(parsed, ExtractionAnswer)
        answer = parsed
    grounded = ground(condensed.text, answer, reading)
    return Extraction(
        spec=grounded.spec,
        contradictions=find_contradictions(reading),
        notes=[*notes, *grounded.notes],
        ignored=condensed.ignored,
    )
