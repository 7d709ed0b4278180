"""Usage per call, rolled up per run.

The ledger sits outermost in the stack, so it sees every attempt of a structured call and
every cache hit; a run report can store ``ledger.calls`` and ``ledger.total``.
"""

from __future__ import annotations

import threading
import time
from dataclasses import asdict, dataclass
from typing import Any

from arise.llm.base import BaseProvider, Wrapper
from arise.llm.types import Completion, Request, Usage


@dataclass(frozen=True)
class CallRecord:
    provider: str
    model: str
    usage: Usage
    latency: float
    cached: bool
    first_token_latency: float | None
    started: float  # wall-clock time.time()
    label: str = ""  # what the caller was doing, e.g. "extract" or "repair:behavior"

    def as_dict(self) -> dict[str, Any]:
        data = asdict(self)
        data["usage"] = self.usage.as_dict()
        return data


class UsageLedger(Wrapper):
    def __init__(self, inner: BaseProvider) -> None:
        super().__init__(inner)
        self._lock = threading.Lock()
        self.calls: list[CallRecord] = []
        self.label = ""

    def send(self, request: Request) -> Completion:
        started = time.time()
        reply = self.inner.send(request)
        with self._lock:
            self.calls.append(
                CallRecord(
                    provider=reply.provider or self.name,
                    model=reply.model,
                    usage=reply.usage,
                    latency=reply.latency,
                    cached=reply.cached,
                    first_token_latency=reply.first_token_latency,
                    started=started,
                    label=self.label,
                )
            )
        return reply

    @property
    def total(self) -> Usage:
        with self._lock:
            return sum((c.usage for c in self.calls), Usage())

    def by_label(self) -> dict[str, Usage]:
        out: dict[str, Usage] = {}
        with self._lock:
            for call in self.calls:
                out[call.label] = out.get(call.label, Usage()) + call.usage
        return out

    def report(self) -> dict[str, Any]:
        """What a run report stores about its LLM use."""
        return {
            "provider": self.name,
            "model": self.model,
            "total": self.total.as_dict(),
            "calls": [c.as_dict() for c in self.calls],
        }
