"""Structured output: a pydantic schema in, a validated object out.

The schema becomes the backend's own constraint (a grammar, ``json_schema``, a forced
tool call) so a small model cannot drift out of the format; the reply is still
validated, because a grammar fixes the shape, not the field validators. An invalid reply
is shown back to the model with the validation errors a bounded number of times.
"""

from __future__ import annotations

import json
import re
from dataclasses import replace
from functools import cache
from importlib import resources
from typing import TYPE_CHECKING, Any

from pydantic import BaseModel, ValidationError

from arise.llm.types import (
    Completion,
    Message,
    Request,
    StructuredOutputFailed,
    StructuredStyle,
    Usage,
    assistant,
    system,
    user,
)

if TYPE_CHECKING:
    from arise.llm.base import BaseProvider


@cache
def template(name: str) -> str:
    """Prompt texts live in files next to this module, not in code."""
    return resources.files("arise.llm").joinpath("templates", name).read_text("utf-8")


def json_schema_of(model: type[BaseModel]) -> dict[str, Any]:
    return model.model_json_schema()


def response_format(
    style: StructuredStyle, schema: dict[str, Any] | None, name: str | None
) -> dict[str, Any] | None:
    """The OpenAI-style ``response_format`` for a backend, or None when it has none."""
    if schema is None:
        return None
    if style == "json_schema":
        safe = re.sub(r"[^A-Za-z0-9_-]", "_", name or "reply")[:64]
        return {"type": "json_schema", "json_schema": {"name": safe, "schema": schema}}
    if style == "json_object_schema":
        return {"type": "json_object", "schema": schema}
    if style == "json_object":
        return {"type": "json_object"}
    return None


def needs_schema_in_prompt(style: StructuredStyle) -> bool:
    """Styles whose backend never sees the schema must be told it in words."""
    return style in ("json_object", "prompt")


def schema_instruction(schema: dict[str, Any]) -> str:
    return template("schema_instruction.txt").format(schema=json.dumps(schema, indent=None))


def with_schema_instruction(messages: tuple[Message, ...], schema: dict[str, Any]) -> list[Message]:
    """Put the instruction in the system message, or add one."""
    text = schema_instruction(schema)
    out = list(messages)
    if out and out[0].role == "system":
        out[0] = system(out[0].content.rstrip() + "\n\n" + text)
    else:
        out.insert(0, system(text))
    return out


_FENCE = re.compile(r"^```(?:json)?\s*(.*?)\s*```$", re.DOTALL)


def extract_json(text: str) -> str:
    """Strip code fences and surrounding prose that hosted models like to add."""
    stripped = text.strip()
    match = _FENCE.match(stripped)
    if match:
        return match.group(1)
    if stripped.startswith(("{", "[")):
        return stripped
    start = stripped.find("{")
    end = stripped.rfind("}")
    if 0 <= start < end:
        return stripped[start : end + 1]
    return stripped


def describe_error(error: ValidationError | ValueError) -> str:
    """One line per problem, without pydantic's documentation links."""
    if isinstance(error, ValidationError):
        lines = []
        for item in error.errors(include_url=False):
            loc = ".".join(str(p) for p in item.get("loc", ())) or "(root)"
            got = item.get("input")
            got_text = json.dumps(got, default=str)
            if len(got_text) > 80:
                got_text = got_text[:77] + "..."
            lines.append(f"- {loc}: {item.get('msg')} (got {got_text})")
        return "\n".join(lines)
    return f"- {error}"


def parse_reply(text: str, model: type[BaseModel]) -> BaseModel:
    """Validate a reply; raises ValidationError or ValueError with a useful message."""
    body = extract_json(text)
    if not body:
        raise ValueError("the reply was empty")
    return model.model_validate_json(body)


#: The finish reasons of a reply stopped by the token limit (OpenAI and llama.cpp, Anthropic).
CUT_OFF = frozenset({"length", "max_tokens"})


def complete_structured(
    provider: BaseProvider,
    request: Request,
    model: type[BaseModel],
    *,
    max_reasks: int,
) -> Completion:
    """Send, validate, and re-ask with the errors; raise StructuredOutputFailed at the end."""
    schema = json_schema_of(model)
    style = provider.capabilities.structured
    messages = list(request.messages)
    if needs_schema_in_prompt(style):
        messages = with_schema_instruction(request.messages, schema)
    errors: list[str] = []
    total = Usage()
    latency = 0.0
    attempts = 0
    allowed = max(0, max_reasks) + 1
    for _ in range(allowed):
        attempts += 1
        current = replace(
            request, messages=tuple(messages), json_schema=schema, schema_name=model.__name__
        )
        reply = provider.send(current)
        total = total + reply.usage
        latency += reply.latency
        try:
            parsed = parse_reply(reply.text, model)
        except (ValidationError, ValueError) as exc:
            problem = describe_error(exc)
            messages.append(assistant(reply.text))
            if reply.finish_reason in CUT_OFF:
                # A reply that ran into the token limit (a string that never closes) comes
                # back the same when re-asked with the same limit: minutes for nothing.
                errors.append(f"{problem}\n- the reply was cut off at the token limit")
                break
            errors.append(problem)
            if attempts < allowed:  # the transcript ends with the last reply, not an unsent ask
                messages.append(user(template("reask.txt").format(errors=problem)))
            continue
        return replace(
            reply,
            parsed=parsed,
            usage=total,
            latency=latency,
            details={**reply.details, "attempts": attempts},
        )
    raise StructuredOutputFailed(model.__name__, attempts, errors, messages, total)
