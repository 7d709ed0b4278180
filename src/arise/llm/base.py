"""The one provider protocol, and the base class that gives every provider ``complete``.

A backend only implements ``send(Request) -> Completion``. Wrappers (retry, cache,
recorder, usage ledger) implement ``send`` too and hold an ``inner`` provider, so they
stack in any order. ``complete`` lives here once: it builds the request and, when a
pydantic schema is given, runs the validate-and-re-ask loop of ``structured.py``.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Any, Protocol, runtime_checkable

from pydantic import BaseModel

from arise.llm.types import Capabilities, Completion, Message, Request


@runtime_checkable
class Provider(Protocol):
    name: str
    model: str
    capabilities: Capabilities

    def send(self, request: Request) -> Completion: ...

    def complete(
        self,
        messages: Iterable[Message | Mapping[str, Any]],
        *,
        temperature: float = 0.0,
        max_tokens: int = 512,
        schema: type[BaseModel] | None = None,
        stop: Sequence[str] | str | None = None,
        seed: int | None = None,
    ) -> Completion: ...


class BaseProvider:
    """Shared behaviour of backends and wrappers."""

    name: str = "base"
    model: str = ""
    capabilities: Capabilities = Capabilities()
    #: re-asks after the first invalid structured reply (so at most 1 + max_reasks calls)
    max_reasks: int = 2

    def send(self, request: Request) -> Completion:
        raise NotImplementedError

    def complete(
        self,
        messages: Iterable[Message | Mapping[str, Any]],
        *,
        temperature: float = 0.0,
        max_tokens: int = 512,
        schema: type[BaseModel] | None = None,
        stop: Sequence[str] | str | None = None,
        seed: int | None = None,
    ) -> Completion:
        request = Request.build(
            messages, temperature=temperature, max_tokens=max_tokens, stop=stop, seed=seed
        )
        if schema is None:
            return self.send(request)
        from arise.llm.structured import complete_structured

        return complete_structured(self, request, schema, max_reasks=self.max_reasks)

    def close(self) -> None:
        """Release sockets or model memory; safe to call twice."""

    def __enter__(self) -> BaseProvider:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class Wrapper(BaseProvider):
    """A provider that adds one concern around another provider."""

    def __init__(self, inner: BaseProvider) -> None:
        self.inner = inner
        self.name = inner.name
        self.model = inner.model
        self.capabilities = inner.capabilities
        self.max_reasks = inner.max_reasks

    def send(self, request: Request) -> Completion:
        return self.inner.send(request)

    def close(self) -> None:
        self.inner.close()

    def unwrap(self) -> BaseProvider:
        """The backend at the bottom of the stack."""
        inner = self.inner
        while isinstance(inner, Wrapper):
            inner = inner.inner
        return inner
