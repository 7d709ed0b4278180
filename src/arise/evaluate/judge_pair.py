"""Judging one (description, script) pair as `arise judge` is asked to: the arguments read
into a pair, the model chosen, one judgement or a spread of several.

The command line parses its options into a `JudgeRequest`, calls `judge_pair` and prints
the `JudgedPair` it returns. A mistake in the request is a `UserMistake` (exit 2); the
model failing is an `LLMError` (exit 1).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from arise.errors import AriseError
from arise.evaluate.judge import (
    DEFAULT_WEIGHTS,
    Consistency,
    Judgement,
    consistency,
    input_problem,
    judge_script,
)
from arise.llm.registry import get_provider


class UserMistake(AriseError):
    """A bad argument: the command line prints it on one line and exits 2."""


@dataclass(frozen=True)
class JudgeRequest:
    """What to judge and with which model. `description` "-" takes it from the report.json
    of a folder written by `arise generate`, which `script` may be."""

    description: str
    script: Path
    repeat: int = 1
    weights: dict[str, float] = field(default_factory=lambda: dict(DEFAULT_WEIGHTS))
    provider: str | None = None
    model: str | None = None
    temperature: float = 0.0
    seed: int = 0
    cache: bool | None = None
    record: str | None = None
    replay: str | None = None


@dataclass(frozen=True)
class JudgedPair:
    """The pair judged (the description as read, the script file) and the verdict: one
    Judgement, or the Consistency of `repeat` of them."""

    description: str
    script: Path
    result: Judgement | Consistency


def load_pair(description: str, script: Path) -> tuple[str, str, Path]:
    """(description, script text, script file) from the arguments; a generation folder
    supplies the script and, for DESCRIPTION "-", the description."""
    if script.is_dir():
        scenic = script / "scenario.scenic"
        if not scenic.is_file():
            raise UserMistake(
                f"{script} is a folder without scenario.scenic; give a .scenic "
                "file or a folder written by `arise generate`"
            )
        if description.strip() == "-":
            description = _reported_description(script)
        script = scenic
    elif description.strip() == "-":
        raise UserMistake(
            "'-' takes the description from report.json, which only a folder "
            "written by `arise generate` has; give the description in words"
        )
    if not script.is_file():
        raise UserMistake(f"no such script: {script}")
    try:
        text = script.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise UserMistake(f"cannot read {script}: {error}") from None
    problem = input_problem(description, text)
    if problem:
        raise UserMistake(problem)
    return description, text, script


def _reported_description(folder: Path) -> str:
    report = folder / "report.json"
    try:
        data = json.loads(report.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise UserMistake(
            f"{folder} has no report.json to take the description from; "
            "give the description instead of '-'"
        ) from None
    except (OSError, json.JSONDecodeError, UnicodeDecodeError) as error:
        raise UserMistake(f"{report} is not JSON ({error})") from None
    found = data.get("description") if isinstance(data, dict) else None
    if not isinstance(found, str) or not found.strip():
        raise UserMistake(f"{report} has no description; give it instead of '-'")
    return found


def judge_pair(request: JudgeRequest) -> JudgedPair:
    """Read the pair, then ask the model once, or `repeat` times with seed, seed+1, ..."""
    if request.repeat < 1:
        raise UserMistake("--repeat must be at least 1")
    if request.temperature < 0:
        raise UserMistake("--temperature must be >= 0")
    description, script_text, script = load_pair(request.description, request.script)
    overrides: dict[str, Any] = {"model": request.model} if request.model else {}
    llm = get_provider(
        request.provider,
        cache=request.cache,
        record=request.record,
        replay=request.replay,
        **overrides,
    )
    with llm:
        if request.repeat == 1:
            result: Judgement | Consistency = judge_script(
                description,
                script_text,
                llm,
                temperature=request.temperature,
                seed=request.seed,
                weights=request.weights,
            )
        else:
            result = consistency(
                description,
                script_text,
                llm,
                repeat=request.repeat,
                temperature=request.temperature,
                seed=request.seed,
                weights=request.weights,
            )
    return JudgedPair(description, script, result)
