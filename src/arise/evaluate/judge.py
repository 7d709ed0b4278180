"""The SCS judge: a language model scores how well a Scenic script says what a description says.

Seven criteria, each scored 0..10 by the model with a short reason. The semantic conformity
score is the weighted mean of the scores on a 0..1 scale::

    SCS = sum(w_i * score_i) / (10 * sum(w_i))

With all weights equal this is the paper's SCS = sum(score_i) / (10 * 7). ``consistency``
judges one script several times (seed + i per repeat) and reports the spread, as in the
paper's consistency study. See docs/judge.md.
"""

from __future__ import annotations

import math
import re
import statistics
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, field_validator

from arise.errors import AriseError
from arise.llm.base import BaseProvider
from arise.llm.types import LLMError, Message, StructuredOutputFailed, Usage
from arise.prompts import load, load_jsonl
from arise.sections import MarkerKind, begin_marker, parse_marker

#: The criteria, in the order the model answers them and every table shows them.
CRITERIA: tuple[str, ...] = (
    "adversary_type",
    "behavior",
    "geometry",
    "weather",
    "participants",
    "requirements",
    "spawn",
)
MAX_SCORE = 10
DEFAULT_WEIGHTS: dict[str, float] = dict.fromkeys(CRITERIA, 1.0)
#: Reasons are capped in the schema (a grammar for the local model), so a call stays short.
REASON_CHARS = 90
#: Bound on the reply: 7 x (reason + score + JSON) is about 250 tokens for the local model.
MAX_TOKENS = 420
MAX_DESCRIPTION_CHARS = 2000
MAX_SCRIPT_CHARS = 12000  # after compacting; longer scripts do not fit a small model's prompt


# --------------------------------------------------------------------------- the answer schema


# The reason comes before the score: a model that explains first scores more steadily.
class CriterionVerdict(BaseModel):
    """A short reason, then a score from 0 to 10."""

    model_config = ConfigDict(extra="ignore")

    reason: str = Field(json_schema_extra={"maxLength": REASON_CHARS})
    score: int = Field(ge=0, le=MAX_SCORE, json_schema_extra={"enum": list(range(MAX_SCORE + 1))})

    @field_validator("reason")
    @classmethod
    def _short(cls, value: str) -> str:
        # Hosted models are not held to maxLength by a grammar; cut rather than re-ask.
        value = " ".join(value.split())
        return value if len(value) <= REASON_CHARS else value[: REASON_CHARS - 1] + "…"


class JudgeAnswer(BaseModel):
    """One verdict per criterion."""

    model_config = ConfigDict(extra="ignore")

    adversary_type: CriterionVerdict
    behavior: CriterionVerdict
    geometry: CriterionVerdict
    weather: CriterionVerdict
    participants: CriterionVerdict
    requirements: CriterionVerdict
    spawn: CriterionVerdict

    def verdicts(self) -> dict[str, CriterionVerdict]:
        return {name: getattr(self, name) for name in CRITERIA}


# --------------------------------------------------------------------------------- weights


class WeightsError(AriseError):
    """Weights that cannot be used; ``str(error)`` is one line for the user."""


class JudgeInputError(AriseError):
    """A description or script the judge cannot take (see ``input_problem``)."""


def weights_problem(weights: Mapping[str, Any] | None) -> str | None:
    """Why these weights cannot be used, or None when they can (the error as a value)."""
    if weights is None:
        return None
    unknown = sorted(set(weights) - set(CRITERIA))
    if unknown:
        return (
            f"unknown criterion {', '.join(map(repr, unknown))} in the weights; "
            f"the criteria are {', '.join(CRITERIA)}"
        )
    for name, value in weights.items():
        if isinstance(value, bool) or not isinstance(value, int | float):
            return f"weight of {name} must be a number, got {value!r}"
        if not math.isfinite(value) or value < 0:
            return f"weight of {name} must be a finite number >= 0, got {value}"
    full = {**DEFAULT_WEIGHTS, **weights}
    if not any(full.values()):
        return "the weights are all zero; give at least one criterion a weight above 0"
    return None


def resolve_weights(weights: Mapping[str, Any] | None = None) -> dict[str, float]:
    """All seven weights: the given ones, 1.0 for the rest. Raises WeightsError."""
    problem = weights_problem(weights)
    if problem:
        raise WeightsError(problem)
    return {name: float((weights or {}).get(name, DEFAULT_WEIGHTS[name])) for name in CRITERIA}


def parse_weights(text: str | None) -> dict[str, float]:
    """``"adversary_type=2,behavior=1.5"`` -> all seven weights. Raises WeightsError."""
    if text is None or not text.strip():
        return dict(DEFAULT_WEIGHTS)
    given: dict[str, float] = {}
    for part in text.split(","):
        if not part.strip():
            continue
        name, sep, value = part.partition("=")
        name = name.strip()
        if not sep or not name:
            raise WeightsError(f"weights are NAME=NUMBER pairs separated by commas; got {part!r}")
        try:
            given[name] = float(value)
        except ValueError:
            raise WeightsError(
                f"weight of {name} must be a number, got {value.strip()!r}"
            ) from None
    return resolve_weights(given)


def compute_scs(
    scores: Mapping[str, int | float],
    weights: Mapping[str, float] | None = None,
) -> float:
    """Weighted SCS on 0..1: sum(w * score) / (10 * sum(w)) over the seven criteria."""
    full = resolve_weights(weights)
    missing = [name for name in CRITERIA if name not in scores]
    if missing:
        raise ValueError(f"scores missing for {', '.join(missing)}")
    total = sum(full.values())
    return sum(full[name] * scores[name] for name in CRITERIA) / (MAX_SCORE * total)


# ------------------------------------------------------------------------------ judgement


@dataclass
class Judgement:
    """One judge call: a score and a reason per criterion, and the SCS they give."""

    scores: dict[str, int]
    reasons: dict[str, str]
    weights: dict[str, float] = field(default_factory=lambda: dict(DEFAULT_WEIGHTS))
    provider: str = ""
    model: str = ""
    temperature: float = 0.0
    seed: int | None = None
    usage: Usage = field(default_factory=Usage)
    seconds: float = 0.0
    cached: bool = False

    @property
    def scs(self) -> float:
        return compute_scs(self.scores, self.weights)

    def rescored(self, weights: Mapping[str, float] | None) -> Judgement:
        """The same scores under other weights (no model call)."""
        return Judgement(**{**self.__dict__, "weights": resolve_weights(weights)})

    def as_dict(self) -> dict[str, Any]:
        return {
            "scs": self.scs,
            "criteria": [
                {
                    "name": name,
                    "score": self.scores[name],
                    "reason": self.reasons[name],
                    "weight": self.weights[name],
                }
                for name in CRITERIA
            ],
            "provider": self.provider,
            "model": self.model,
            "temperature": self.temperature,
            "seed": self.seed,
            "usage": self.usage.as_dict(),
            "seconds": self.seconds,
            "cached": self.cached,
        }


# ------------------------------------------------------------------------------ the prompt

_COMMENT = re.compile(r"^\s*#")
_HEADER_NOISE = re.compile(r"^\s*(model\s|param\s+map\s*=)")


def compact_script(text: str) -> str:
    """The script as the judge sees it: code lines and ``# BEGIN X`` markers only.

    Comments go (the generator puts the description itself in the first comment, and the
    ``# kb:`` lines name knowledge-base entries: both would tell the judge what to think),
    and so do blank lines, ``# END X`` markers, the ``model`` line and the map file path;
    ``param carla_map`` stays, it names the road layout.
    """
    kept: list[str] = []
    for raw in text.splitlines():
        line = raw.rstrip()
        stripped = line.strip()
        if not stripped:
            continue
        marker = parse_marker(stripped)
        if marker is not None and marker.kind is MarkerKind.BEGIN:
            kept.append(begin_marker(marker.name))
            continue
        if _COMMENT.match(line) or _HEADER_NOISE.match(line):
            continue
        kept.append(_without_inline_comment(line))
    return "\n".join(kept)


def _without_inline_comment(line: str) -> str:
    """`line` without a trailing `  # comment` (a `#` after space, no quote after it).
    String scans: the regular expression for it backtracked quadratically on a long run
    of spaces, and a script is untrusted text."""
    last_quote = max(line.rfind("'"), line.rfind('"'))
    at = line.find("#", last_quote + 1)
    while at >= 0 and (at == 0 or not line[at - 1].isspace()):
        at = line.find("#", at + 1)
    return line if at < 0 else line[:at].rstrip()


def input_problem(description: str, script_text: str) -> str | None:
    """Why this pair cannot be judged (before any model call), or None."""
    if not description.strip():
        return "the description is empty: give the scenario description the script was made from"
    if len(description.strip()) > MAX_DESCRIPTION_CHARS:
        return (
            f"the description is {len(description.strip())} characters long; "
            f"the judge takes at most {MAX_DESCRIPTION_CHARS}"
        )
    compact = compact_script(script_text)
    if not compact.strip():
        return "the script is empty (or only comments)"
    if len(compact) > MAX_SCRIPT_CHARS:
        return (
            f"the script is {len(compact)} characters long without comments; "
            f"the judge takes at most {MAX_SCRIPT_CHARS}"
        )
    return None


def judge_user_message(description: str, script_text: str) -> str:
    return (
        f"DESCRIPTION:\n{description.strip()}\n\n"
        f"SCRIPT:\n{compact_script(script_text)}\n\n"
        f"Score the seven criteria."
    )


def few_shot_examples() -> list[dict[str, Any]]:
    """Worked examples from prompts/judge_examples.jsonl (none when the file is absent)."""
    try:
        return load_jsonl("judge_examples.jsonl")
    except FileNotFoundError:
        return []


def judge_messages(description: str, script_text: str) -> list[Message]:
    """System prompt, the few-shot examples, then the pair to judge (shared part first, so
    the local model can reuse its evaluated prefix from one call to the next)."""
    messages = [Message("system", load("judge_system.md").strip())]
    for example in few_shot_examples():
        messages.append(
            Message("user", judge_user_message(example["description"], example["script"]))
        )
        answer = JudgeAnswer.model_validate(example["answer"])
        messages.append(Message("assistant", answer.model_dump_json()))
    messages.append(Message("user", judge_user_message(description, script_text)))
    return messages


def judge_script(
    description: str,
    script_text: str,
    provider: BaseProvider,
    *,
    temperature: float = 0.0,
    seed: int | None = 0,
    weights: Mapping[str, float] | None = None,
) -> Judgement:
    """Ask the model for the seven scores of one (description, script) pair.

    Bad input (see ``input_problem``) and bad weights raise JudgeInputError / WeightsError: check
    them first. Provider failures (LLMError, including a reply that never matched the
    schema after the provider's re-asks) propagate for the caller to report.
    """
    full = resolve_weights(weights)
    problem = input_problem(description, script_text)
    if problem:
        raise JudgeInputError(problem)
    completion = provider.complete(
        judge_messages(description, script_text),
        temperature=temperature,
        max_tokens=MAX_TOKENS,
        schema=JudgeAnswer,
        seed=seed,
    )
    answer = completion.parsed
    if not isinstance(answer, JudgeAnswer):  # complete() with a schema always parses
        raise LLMError(f"the judge's reply was not parsed: {completion.text[:80]!r}")
    verdicts = answer.verdicts()
    return Judgement(
        scores={name: verdicts[name].score for name in CRITERIA},
        reasons={name: verdicts[name].reason for name in CRITERIA},
        weights=full,
        provider=completion.provider or provider.name,
        model=completion.model,
        temperature=temperature,
        seed=seed,
        usage=completion.usage,
        seconds=completion.latency,
        cached=completion.cached,
    )


# ---------------------------------------------------------------------------- consistency


@dataclass(frozen=True)
class Stats:
    """Spread of repeated values. ``std`` is the population standard deviation (ddof=0)."""

    min: float
    max: float
    mean: float
    std: float

    @classmethod
    def of(cls, values: list[float]) -> Stats:
        if not values:
            raise ValueError("no values")
        return cls(min(values), max(values), statistics.fmean(values), statistics.pstdev(values))

    def as_dict(self) -> dict[str, float]:
        return {"min": self.min, "max": self.max, "mean": self.mean, "std": self.std}


@dataclass
class Consistency:
    """The same pair judged several times: every judgement and the spread."""

    runs: list[Judgement]
    failures: list[str] = field(default_factory=list)  # one line per repeat that failed

    @property
    def scs(self) -> Stats:
        """SCS spread on 0..1 (multiply by 100 for % and percentage points)."""
        return Stats.of([run.scs for run in self.runs])

    @property
    def criteria(self) -> dict[str, Stats]:
        """Per criterion, the spread of the raw 0..10 scores."""
        return {name: Stats.of([float(run.scores[name]) for run in self.runs]) for name in CRITERIA}

    @property
    def usage(self) -> Usage:
        return sum((run.usage for run in self.runs), Usage())

    def as_dict(self) -> dict[str, Any]:
        return {
            "repeats": len(self.runs) + len(self.failures),
            "judged": len(self.runs),
            "failures": self.failures,
            "std": "population",
            "scs": self.scs.as_dict(),
            "criteria": {name: stats.as_dict() for name, stats in self.criteria.items()},
            "runs": [run.as_dict() for run in self.runs],
            "usage": self.usage.as_dict(),
        }


def consistency(
    description: str,
    script_text: str,
    provider: BaseProvider,
    *,
    repeat: int = 10,
    temperature: float = 0.0,
    seed: int | None = 0,
    weights: Mapping[str, float] | None = None,
) -> Consistency:
    """Judge one pair ``repeat`` times, with seed, seed+1, ... (so each repeat is its own
    request for the cache and for cassettes, whatever the temperature).

    A repeat whose reply never matched the schema is listed in ``failures`` and left out of
    the statistics; if every repeat fails, the last error is raised. Any other provider
    error (server down, replay miss) is raised at once.
    """
    if repeat < 1:
        raise ValueError("repeat must be at least 1")
    base = 0 if seed is None else seed
    runs: list[Judgement] = []
    failures: list[str] = []
    last: LLMError | None = None
    for index in range(repeat):
        try:
            runs.append(
                judge_script(
                    description,
                    script_text,
                    provider,
                    temperature=temperature,
                    seed=base + index,
                    weights=weights,
                )
            )
        except StructuredOutputFailed as error:
            failures.append(f"seed {base + index}: {error}")
            last = error
    if not runs:
        assert last is not None
        raise last
    return Consistency(runs=runs, failures=failures)
