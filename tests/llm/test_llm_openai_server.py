"""The OpenAI-compatible provider against a real llama.cpp server on loopback.

Also where structured output is exercised for real: the native constraint, validation,
the bounded re-ask with the validation error, and the clear failure at the end.
"""

from __future__ import annotations

from typing import Literal

import pytest
from pydantic import BaseModel, field_validator

from arise.llm import StructuredOutputFailed, get_provider
from arise.llm.accounting import UsageLedger
from arise.llm.openai_compat import OpenAICompatProvider
from arise.llm.retry import RetryPolicy
from arise.llm.types import Capabilities, ProviderError, ProviderErrorKind, Request, user

pytestmark = pytest.mark.slow


class Verdict(BaseModel):
    actor: Literal["pedestrian", "cyclist", "vehicle"]
    crosses_road: bool


class Shout(BaseModel):
    """A constraint a JSON grammar cannot express: only the validator knows it."""

    word: str

    @field_validator("word")
    @classmethod
    def capitals_only(cls, value: str) -> str:
        if value != value.upper():
            raise ValueError("word must be written in capital letters only")
        return value


class NeverValid(BaseModel):
    word: str

    @field_validator("word")
    @classmethod
    def reject(cls, value: str) -> str:
        raise ValueError("this schema rejects every answer")


def test_plain_completion_reports_usage(llama_server: str) -> None:
    llm = get_provider("llamacpp", base_url=llama_server, cache=False)
    reply = llm.complete([user("Reply with exactly one word: pong")], max_tokens=8, temperature=0.0)
    assert "pong" in reply.text.lower()
    assert reply.provider == "llamacpp"
    assert reply.usage.calls == 1 and reply.usage.prompt_tokens > 5
    assert 0 < reply.usage.completion_tokens <= 8
    assert reply.latency > 0
    assert llm.total == reply.usage  # one call, one ledger line
    llm.close()


def test_stop_sequences_are_honoured(llama_server: str) -> None:
    llm = get_provider("llamacpp", base_url=llama_server, cache=False)
    reply = llm.complete(
        [user("Count from 1 to 10, separated by commas.")], max_tokens=40, stop=["5"]
    )
    assert "5" not in reply.text and "4" in reply.text
    llm.close()


def test_structured_output_uses_the_grammar(llama_server: str) -> None:
    llm = get_provider("llamacpp", base_url=llama_server, cache=False)
    reply = llm.complete(
        [
            user(
                "A woman walks across the street in front of the car. Who is she, and does she cross?"
            )
        ],
        max_tokens=60,
        schema=Verdict,
    )
    assert isinstance(reply.parsed, Verdict)
    assert reply.parsed.actor == "pedestrian" and reply.parsed.crosses_road is True
    assert reply.details["attempts"] == 1
    llm.close()


def test_openai_json_schema_style_is_refused_by_this_server(llama_server: str) -> None:
    """Why llama.cpp servers carry structured='json_object_schema' and OpenAI 'json_schema'."""
    backend = OpenAICompatProvider(
        name="as-openai",
        model="qwen-local",
        base_url=llama_server,
        api_key=None,
        capabilities=Capabilities(structured="json_schema"),
        timeout=120,
    )
    request = Request.build(
        [user("Who crosses?")],
        max_tokens=20,
        json_schema=Verdict.model_json_schema(),
        schema_name="Verdict",
    )
    with pytest.raises(ProviderError) as info:
        backend.send(request)
    assert info.value.status == 500 and info.value.kind is ProviderErrorKind.SERVER_ERROR
    backend.close()


def test_invalid_reply_is_re_asked_with_the_error(llama_server: str) -> None:
    llm = get_provider("llamacpp", base_url=llama_server, cache=False)
    reply = llm.complete(
        [user('Return this JSON object unchanged: {"word": "hello"}')],
        max_tokens=30,
        schema=Shout,
    )
    assert isinstance(reply.parsed, Shout) and reply.parsed.word == "HELLO"
    assert reply.details["attempts"] == 2
    assert reply.usage.calls == 2  # the completion's usage covers both attempts
    second = llm.calls[1]
    assert second.usage.prompt_tokens > llm.calls[0].usage.prompt_tokens  # error was sent back
    llm.close()


def _one_try_per_call(llama_server: str, max_reasks: int) -> UsageLedger:
    """A provider that never retries a call, so every attempt counted is a re-ask."""
    llm = get_provider(
        "llamacpp", base_url=llama_server, cache=False, retry=RetryPolicy(attempts=1)
    )
    llm.max_reasks = max_reasks
    return llm


def test_re_asks_are_bounded_and_the_failure_carries_the_transcript(llama_server: str) -> None:
    llm = _one_try_per_call(llama_server, max_reasks=1)
    with pytest.raises(StructuredOutputFailed) as info:
        llm.complete([user('Return {"word": "x"}')], max_tokens=20, schema=NeverValid)
    failure = info.value
    assert failure.attempts == 2 and len(failure.errors) == 2
    assert "rejects every answer" in failure.errors[-1]
    roles = [m.role for m in failure.transcript]
    assert roles == ["user", "assistant", "user", "assistant"]
    assert "rejects every answer" in failure.transcript[2].content
    assert failure.usage.calls == 2 and failure.usage.completion_tokens > 0
    assert "NeverValid" in str(failure) and "\n" not in str(failure)
    assert len(llm.calls) == 2
    llm.close()


def test_a_reply_cut_off_at_the_token_limit_is_not_re_asked(llama_server: str) -> None:
    """Three tokens cannot hold the object: the same limit would cut every re-ask too."""
    llm = _one_try_per_call(llama_server, max_reasks=2)
    with pytest.raises(StructuredOutputFailed) as info:
        llm.complete([user('Return {"word": "HELLO"}')], max_tokens=3, schema=Shout)
    failure = info.value
    assert failure.attempts == 1 and len(llm.calls) == 1
    assert "cut off at the token limit" in failure.errors[-1]
    llm.close()


def test_cli_ping_names_the_server_model(llama_server: str) -> None:
    from typer.testing import CliRunner

    from arise.llm.cli import app

    result = CliRunner().invoke(app, ["ping", "-p", "llamacpp", "--base-url", llama_server])
    assert result.exit_code == 0, result.output
    # the server echoes the requested name; ping also shows what the server has loaded
    assert result.stdout.startswith("llamacpp (local) answered")
    assert "server has qwen-local" in result.stdout
    assert "prompt +" in result.stdout
