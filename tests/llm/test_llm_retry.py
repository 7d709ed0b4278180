"""Retries: the one table, and real HTTP errors from a scripted server on loopback.

The server is a plain ``http.server`` that answers a queue of (status, body) pairs, so the
real ``openai`` client, our error translation and the retry wrapper all run for real.
"""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Iterator
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

import pytest

from arise.llm.openai_compat import OpenAICompatProvider
from arise.llm.retry import (
    ERROR_TABLE,
    RetryingProvider,
    RetryPolicy,
    is_retryable,
    kind_for_status,
)
from arise.llm.types import (
    Capabilities,
    ProviderError,
    ProviderErrorKind,
    ProviderUnavailable,
    Request,
    user,
)


def chat_body(text: str) -> dict[str, Any]:
    return {
        "id": "chatcmpl-1",
        "object": "chat.completion",
        "created": 0,
        "model": "scripted",
        "choices": [
            {"index": 0, "message": {"role": "assistant", "content": text}, "finish_reason": "stop"}
        ],
        "usage": {"prompt_tokens": 7, "completion_tokens": 1, "total_tokens": 8},
    }


class Scripted:
    """A loopback server that plays a list of replies, then repeats the last one."""

    def __init__(self, script: list[tuple[int, dict[str, Any], dict[str, str]]], delay: float = 0):
        self.script = list(script)
        self.delay = delay
        self.hits = 0
        self.bodies: list[dict[str, Any]] = []
        outer = self

        class Handler(BaseHTTPRequestHandler):
            def do_POST(self) -> None:  # noqa: N802 - http.server's naming
                length = int(self.headers.get("content-length", 0))
                outer.bodies.append(json.loads(self.rfile.read(length) or b"{}"))
                outer.hits += 1
                index = min(outer.hits - 1, len(outer.script) - 1)
                status, body, headers = outer.script[index]
                if outer.delay:
                    time.sleep(outer.delay)
                payload = json.dumps(body).encode()
                try:
                    self.send_response(status)
                    self.send_header("content-type", "application/json")
                    self.send_header("content-length", str(len(payload)))
                    for k, v in headers.items():
                        self.send_header(k, v)
                    self.end_headers()
                    self.wfile.write(payload)
                except (BrokenPipeError, ConnectionResetError):
                    pass  # the client gave up (timeout test)

            def log_message(self, *args: object) -> None:
                pass

        self.server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.server.daemon_threads = True
        self.thread = threading.Thread(target=self.server.serve_forever, daemon=True)

    @property
    def base_url(self) -> str:
        return f"http://127.0.0.1:{self.server.server_address[1]}/v1"

    def __enter__(self) -> Scripted:
        self.thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.server.shutdown()
        self.server.server_close()


def provider_for(url: str, timeout: float = 10.0) -> OpenAICompatProvider:
    return OpenAICompatProvider(
        name="scripted",
        model="scripted",
        base_url=url,
        api_key=None,
        capabilities=Capabilities(structured="json_schema"),
        timeout=timeout,
        key_env="SCRIPTED_API_KEY",
    )


REQUEST = Request.build([user("hi")], max_tokens=4)
ERROR = {"error": {"message": "scripted failure", "type": "x"}}


@pytest.fixture
def sleeps() -> Iterator[list[float]]:
    yield []


def retrying(
    inner: OpenAICompatProvider, waits: list[float], attempts: int = 4
) -> RetryingProvider:
    def sleep(seconds: float) -> None:
        waits.append(seconds)
        time.sleep(seconds)

    return RetryingProvider(inner, RetryPolicy(attempts=attempts, base=0.05, cap=1.0), sleep=sleep)


K = ProviderErrorKind


def test_the_table() -> None:
    assert set(ERROR_TABLE) == set(K)  # every kind has a row, so none is silently not retried
    retryable = {kind for kind, row in ERROR_TABLE.items() if row.retryable}
    assert retryable == {K.RATE_LIMITED, K.OVERLOADED, K.SERVER_ERROR, K.TIMEOUT, K.CONNECTION}
    assert kind_for_status(429) is K.RATE_LIMITED
    assert kind_for_status(500) is K.SERVER_ERROR and kind_for_status(502) is K.SERVER_ERROR
    assert kind_for_status(503) is K.OVERLOADED and kind_for_status(529) is K.OVERLOADED
    assert kind_for_status(401) is K.AUTH and kind_for_status(403) is K.AUTH
    assert kind_for_status(404) is K.NOT_FOUND
    assert kind_for_status(400) is K.BAD_REQUEST and kind_for_status(422) is K.BAD_REQUEST
    assert kind_for_status(None) is K.OTHER
    assert is_retryable(ProviderError("x", kind=K.RATE_LIMITED))
    assert not is_retryable(ProviderError("x", kind=K.AUTH))
    assert not is_retryable(ValueError("a bug is not retried"))


def test_kind_words_are_stable() -> None:
    """The values are the words docs/llm.md's table and any stored text use."""
    assert [k.value for k in K] == [
        "rate_limited",
        "overloaded",
        "server_error",
        "timeout",
        "connection",
        "auth",
        "not_found",
        "bad_request",
        "other",
    ]
    assert f"{K.NOT_FOUND}" == "not_found" and ProviderErrorKind("auth") is K.AUTH
    with pytest.raises(ValueError):
        ProviderError("x", kind="unauthorised")  # type: ignore[arg-type]


def test_backoff_grows_and_honours_retry_after() -> None:
    policy = RetryPolicy(base=1.0, cap=8.0, jitter=0.0)
    assert [policy.delay(n) for n in range(5)] == [1.0, 2.0, 4.0, 8.0, 8.0]
    assert policy.delay(0, retry_after=3.0) == 3.0
    assert policy.delay(0, retry_after=100.0) == 8.0  # never wait longer than the cap


def test_429_then_503_then_success(sleeps: list[float]) -> None:
    script = [
        (429, ERROR, {"retry-after": "0.2"}),
        (503, ERROR, {}),
        (200, chat_body("ok"), {}),
    ]
    with Scripted(script) as server:
        llm = retrying(provider_for(server.base_url), sleeps)
        reply = llm.send(REQUEST)
        assert reply.text == "ok" and reply.usage.prompt_tokens == 7
        assert server.hits == 3
    assert llm.retries == 2
    assert sleeps[0] == pytest.approx(0.2)  # the server's Retry-After wins over backoff
    assert 0.07 <= sleeps[1] <= 0.13  # base 0.05 * 2, +-25 % jitter


def test_auth_error_is_not_retried_and_names_the_key(sleeps: list[float]) -> None:
    with Scripted([(401, ERROR, {})]) as server:
        llm = retrying(provider_for(server.base_url), sleeps)
        with pytest.raises(ProviderError) as info:
            llm.send(REQUEST)
        assert server.hits == 1
    assert info.value.kind is K.AUTH and info.value.status == 401
    assert "SCRIPTED_API_KEY" in str(info.value)
    assert sleeps == []


def test_server_errors_stop_after_the_bound(sleeps: list[float]) -> None:
    with Scripted([(500, ERROR, {})]) as server:
        llm = retrying(provider_for(server.base_url), sleeps, attempts=3)
        with pytest.raises(ProviderError) as info:
            llm.send(REQUEST)
        assert server.hits == 3
    assert info.value.kind is K.SERVER_ERROR
    assert len(sleeps) == 2


def test_timeout_is_retried_then_unavailable(sleeps: list[float]) -> None:
    with Scripted([(200, chat_body("late"), {})], delay=1.0) as server:
        llm = retrying(provider_for(server.base_url, timeout=0.3), sleeps, attempts=2)
        with pytest.raises(ProviderUnavailable, match="timeout"):
            llm.send(REQUEST)
        assert server.hits == 2


def test_connection_refused_says_what_to_set(sleeps: list[float]) -> None:
    import socket

    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    llm = retrying(provider_for(f"http://127.0.0.1:{port}/v1"), sleeps, attempts=2)
    with pytest.raises(ProviderUnavailable) as info:
        llm.send(REQUEST)
    message = str(info.value)
    assert "cannot reach" in message and "ARISE_BASE_URL" in message and "2 attempt" in message
    assert len(sleeps) == 1


def test_anthropic_overloaded_then_tool_answer(
    sleeps: list[float], monkeypatch: pytest.MonkeyPatch
) -> None:
    """Anthropic's client, our error translation and the forced tool call, on loopback."""
    pytest.importorskip("anthropic")
    from pydantic import BaseModel

    from arise.llm import get_provider

    class Weather(BaseModel):
        condition: str

    answer = {
        "id": "msg_1",
        "type": "message",
        "role": "assistant",
        "model": "claude-scripted",
        "content": [
            {"type": "tool_use", "id": "toolu_1", "name": "Weather", "input": {"condition": "rain"}}
        ],
        "stop_reason": "tool_use",
        "stop_sequence": None,
        "usage": {"input_tokens": 12, "output_tokens": 5},
    }
    overloaded = {"type": "error", "error": {"type": "overloaded_error", "message": "busy"}}
    monkeypatch.setenv("ANTHROPIC_API_KEY", "test-key-not-real")
    with Scripted([(529, overloaded, {}), (200, answer, {})]) as server:
        llm = get_provider(
            "anthropic",
            base_url=server.base_url.removesuffix("/v1"),
            cache=False,
            retry=RetryPolicy(attempts=3, base=0.01),
        )
        reply = llm.complete(
            [{"role": "system", "content": "Extract."}, {"role": "user", "content": "Rainy."}],
            max_tokens=50,
            schema=Weather,
        )
        assert server.hits == 2
    assert isinstance(reply.parsed, Weather) and reply.parsed.condition == "rain"
    assert reply.usage.prompt_tokens == 12 and reply.model == "claude-scripted"
    sent = server.bodies[-1]
    assert sent["system"] == "Extract." and sent["messages"] == [
        {"role": "user", "content": "Rainy."}
    ]
    assert sent["tool_choice"] == {"type": "tool", "name": "Weather"}
    assert sent["tools"][0]["input_schema"]["properties"]["condition"]["type"] == "string"
