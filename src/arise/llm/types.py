"""Plain data shared by every provider, wrapper and caller.

Everything here is small and serialisable, so that cassettes, the response cache and
run reports can store exactly what a call sent and got back.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import asdict, dataclass, field, fields, replace
from enum import StrEnum
from typing import Any, Literal

from pydantic import BaseModel

from arise.errors import AriseError

Role = Literal["system", "user", "assistant"]

#: How a backend can be made to emit JSON that matches a schema.
#: - ``json_schema``: OpenAI's ``response_format={"type": "json_schema", ...}``
#: - ``json_object_schema``: llama.cpp's ``{"type": "json_object", "schema": ...}`` (a grammar)
#: - ``json_object``: JSON mode without a schema; the schema goes into the prompt
#: - ``tool``: a forced tool call whose input schema is the schema (Anthropic)
#: - ``prompt``: nothing native; the schema goes into the prompt and the reply is parsed
StructuredStyle = Literal["json_schema", "json_object_schema", "json_object", "tool", "prompt"]


class PrefixUse(StrEnum):
    """How the embedded model got past a call's fixed prompt prefix."""

    NONE = "none"  # the call has no prefix (one message), or the template cannot split it
    IN_CONTEXT = "in_context"  # the context already held it
    LOADED = "loaded"  # restored from memory or the disk store
    BUILT = "built"  # evaluated and written to the disk store
    EVALUATED = "evaluated"  # evaluated, the store being off (or not writable)


@dataclass(frozen=True)
class Message:
    role: Role
    content: str

    @classmethod
    def coerce(cls, item: Message | Mapping[str, Any]) -> Message:
        """Accept the dicts callers naturally write (``{"role": ..., "content": ...}``)."""
        if isinstance(item, Message):
            return item
        role = item.get("role")
        if role not in ("system", "user", "assistant"):
            raise ValueError(f"message role must be system, user or assistant, got {role!r}")
        return cls(role=role, content=str(item.get("content", "")))

    def as_dict(self) -> dict[str, str]:
        return {"role": self.role, "content": self.content}


def system(text: str) -> Message:
    return Message("system", text)


def user(text: str) -> Message:
    return Message("user", text)


def assistant(text: str) -> Message:
    return Message("assistant", text)


@dataclass(frozen=True)
class Capabilities:
    """What a backend can do; callers read these instead of testing provider names."""

    structured: StructuredStyle = "prompt"
    max_context: int = 8192
    seed: bool = False  # honours a sampling seed, so temperature > 0 can be reproduced
    stop: bool = True
    local: bool = False  # runs on this machine (no key, no network bill)


@dataclass(frozen=True)
class Usage:
    """Cost of one or more calls. Adds up, so a run's total is ``sum(usages, Usage())``."""

    calls: int = 0
    cached_calls: int = 0
    prompt_tokens: int = 0
    completion_tokens: int = 0
    seconds: float = 0.0
    #: prompt tokens the embedded model actually evaluated (the rest came from a prefix)
    prompt_tokens_evaluated: int = 0
    prefixes_built: int = 0  # prefix-store entries this usage wrote
    prefixes_loaded: int = 0  # prefixes restored instead of evaluated

    def __add__(self, other: Usage) -> Usage:
        return Usage(
            **{f.name: getattr(self, f.name) + getattr(other, f.name) for f in fields(self)}
        )

    def __sub__(self, other: Usage) -> Usage:
        """What was spent between two readings of a running total."""
        return Usage(
            **{f.name: getattr(self, f.name) - getattr(other, f.name) for f in fields(self)}
        )

    @property
    def total_tokens(self) -> int:
        return self.prompt_tokens + self.completion_tokens

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> Usage:
        return cls(**{k: data[k] for k in cls.__dataclass_fields__ if k in data})


@dataclass(frozen=True)
class Request:
    """One normalised request, as every backend and wrapper sees it.

    ``json_schema`` is the plain JSON schema (already derived from a pydantic model);
    each backend turns it into its own native constraint.
    """

    messages: tuple[Message, ...]
    temperature: float = 0.0
    max_tokens: int = 512
    json_schema: dict[str, Any] | None = None
    schema_name: str | None = None
    stop: tuple[str, ...] = ()
    seed: int | None = None

    @classmethod
    def build(
        cls,
        messages: Iterable[Message | Mapping[str, Any]],
        *,
        temperature: float = 0.0,
        max_tokens: int = 512,
        json_schema: dict[str, Any] | None = None,
        schema_name: str | None = None,
        stop: Sequence[str] | str | None = None,
        seed: int | None = None,
    ) -> Request:
        msgs = tuple(Message.coerce(m) for m in messages)
        if not msgs:
            raise ValueError("a request needs at least one message")
        stops = (stop,) if isinstance(stop, str) else tuple(stop or ())
        return cls(msgs, float(temperature), int(max_tokens), json_schema, schema_name, stops, seed)

    def with_messages(self, messages: Iterable[Message]) -> Request:
        return replace(self, messages=tuple(messages))

    def as_dict(self) -> dict[str, Any]:
        """Canonical form: the same request always gives the same dict (and the same key)."""
        return {
            "messages": [m.as_dict() for m in self.messages],
            "temperature": self.temperature,
            "max_tokens": self.max_tokens,
            "json_schema": self.json_schema,
            "schema_name": self.schema_name,
            "stop": list(self.stop),
            "seed": self.seed,
        }

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> Request:
        return cls.build(
            data["messages"],
            temperature=data.get("temperature", 0.0),
            max_tokens=data.get("max_tokens", 512),
            json_schema=data.get("json_schema"),
            schema_name=data.get("schema_name"),
            stop=data.get("stop") or None,
            seed=data.get("seed"),
        )

    def key(self, **extra: Any) -> str:
        """Stable hash of the request plus ``extra`` (provider, model, run index, ...)."""
        payload = {"request": self.as_dict(), **extra}
        blob = json.dumps(payload, sort_keys=True, ensure_ascii=False, separators=(",", ":"))
        return hashlib.sha256(blob.encode("utf-8")).hexdigest()


@dataclass(frozen=True)
class Completion:
    """What a call returns. ``parsed`` is set only when a schema was asked for."""

    text: str
    usage: Usage
    model: str
    latency: float  # wall seconds for this call (a cache hit: the look-up time)
    provider: str = ""
    parsed: BaseModel | None = None
    cached: bool = False
    finish_reason: str | None = None
    first_token_latency: float | None = None  # seconds until the first token, when known
    #: backend-specific measurements (e.g. prompt tokens actually evaluated by llama.cpp)
    details: dict[str, Any] = field(default_factory=dict)

    def as_record(self) -> dict[str, Any]:
        """The part worth storing in a cache or cassette (``parsed`` is re-derived)."""
        return {
            "text": self.text,
            "usage": self.usage.as_dict(),
            "model": self.model,
            "latency": self.latency,
            "provider": self.provider,
            "finish_reason": self.finish_reason,
            "first_token_latency": self.first_token_latency,
            "details": self.details,
        }

    @classmethod
    def from_record(cls, data: Mapping[str, Any], **overrides: Any) -> Completion:
        values: dict[str, Any] = {
            "text": data["text"],
            "usage": Usage.from_dict(data.get("usage", {})),
            "model": data.get("model", ""),
            "latency": float(data.get("latency", 0.0)),
            "provider": data.get("provider", ""),
            "finish_reason": data.get("finish_reason"),
            "first_token_latency": data.get("first_token_latency"),
            "details": dict(data.get("details") or {}),
        }
        values.update(overrides)
        return cls(**values)


# --------------------------------------------------------------------------- errors


class LLMError(AriseError):
    """Base of every error this package raises on purpose.

    ``str(error)`` is one line a user can act on; the CLI prints exactly that. Exit code 1:
    the model failed or could not be reached (the input itself may be fine).
    """

    exit_code = 1


class MissingCredentials(LLMError):
    def __init__(self, provider: str, env_var: str) -> None:
        self.provider = provider
        self.env_var = env_var
        super().__init__(
            f"{provider}: no API key; set {env_var} in the environment "
            f"(export {env_var}=...), never in a file inside the project"
        )


class ProviderUnavailable(LLMError):
    """The backend cannot be reached or loaded at all (server down, model file missing)."""


class ModelNotInstalled(ProviderUnavailable):
    """The local GGUF file is not where the settings say."""


class ProviderErrorKind(StrEnum):
    """Why a backend call failed; each is one row of ``retry.ERROR_TABLE`` (retried or not).

    The values are the words the docs and any stored text use, so they never change.
    """

    RATE_LIMITED = "rate_limited"
    OVERLOADED = "overloaded"
    SERVER_ERROR = "server_error"
    TIMEOUT = "timeout"
    CONNECTION = "connection"
    AUTH = "auth"
    NOT_FOUND = "not_found"
    BAD_REQUEST = "bad_request"
    OTHER = "other"


class ProviderError(LLMError):
    """The backend answered with an error. ``kind`` is a row of the table in ``retry.py``."""

    def __init__(
        self,
        message: str,
        *,
        kind: ProviderErrorKind,
        status: int | None = None,
        retry_after: float | None = None,
    ) -> None:
        self.kind = ProviderErrorKind(kind)  # a stray string fails here, not in the retry table
        self.status = status
        self.retry_after = retry_after
        super().__init__(message)


class ReplayMiss(LLMError):
    def __init__(self, key: str, cassette: str, request: Request) -> None:
        self.key = key
        self.cassette = cassette
        first_user = next((m.content for m in request.messages if m.role == "user"), "")
        excerpt = " ".join(first_user.split())[:80]
        super().__init__(
            f"replay: no recording for request {key[:16]} in {cassette} "
            f"(user message starts {excerpt!r}); re-record with --record"
        )


class StructuredOutputFailed(LLMError):
    """The reply never validated against the schema within the allowed re-asks."""

    def __init__(
        self,
        schema_name: str,
        attempts: int,
        errors: list[str],
        transcript: list[Message],
        usage: Usage,
    ) -> None:
        self.schema_name = schema_name
        self.attempts = attempts
        self.errors = errors
        self.transcript = transcript
        self.usage = usage
        last = errors[-1].splitlines()[0] if errors else "no reply"
        super().__init__(
            f"the model's reply did not match schema {schema_name} after {attempts} "
            f"attempt(s); last error: {last}"
        )
