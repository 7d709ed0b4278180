"""The one table of provider errors, and bounded retries with backoff for the retryable ones.

Backends translate their client's exceptions into ``ProviderError(kind=...)``; the kind
is a row of ``ERROR_TABLE``. Nothing else in the package decides what is retryable.
"""

from __future__ import annotations

import random
import time
from collections.abc import Callable
from dataclasses import dataclass

from arise.llm.base import BaseProvider, Wrapper
from arise.llm.types import Completion, ProviderError, ProviderUnavailable, Request


@dataclass(frozen=True)
class ErrorKind:
    name: str
    retryable: bool
    description: str


ERROR_TABLE: dict[str, ErrorKind] = {
    k.name: k
    for k in (
        ErrorKind("rate_limited", True, "HTTP 429: too many requests or tokens per minute"),
        ErrorKind("overloaded", True, "HTTP 503/529: the service is overloaded for now"),
        ErrorKind("server_error", True, "HTTP 500/502/504 or another 5xx"),
        ErrorKind("timeout", True, "no answer within the configured timeout"),
        ErrorKind("connection", True, "connection refused or reset, or the name did not resolve"),
        ErrorKind("auth", False, "HTTP 401/403: the key is missing, wrong or not allowed"),
        ErrorKind("not_found", False, "HTTP 404: wrong base URL or unknown model name"),
        ErrorKind("bad_request", False, "HTTP 400/413/422: the request is wrong (e.g. too long)"),
        ErrorKind("other", False, "anything else the backend reports"),
    )
}


def kind_for_status(status: int | None) -> str:
    """Map an HTTP status to a row of ERROR_TABLE."""
    if status is None:
        return "other"
    if status == 429:
        return "rate_limited"
    if status in (503, 529):
        return "overloaded"
    if 500 <= status < 600:
        return "server_error"
    if status in (401, 403):
        return "auth"
    if status == 404:
        return "not_found"
    if 400 <= status < 500:
        return "bad_request"
    return "other"


def is_retryable(error: BaseException) -> bool:
    if isinstance(error, ProviderError):
        row = ERROR_TABLE.get(error.kind)
        return bool(row and row.retryable)
    return False


@dataclass(frozen=True)
class RetryPolicy:
    """``attempts`` counts the first try. Delays grow ``base * 2**n`` up to ``cap``."""

    attempts: int = 4
    base: float = 1.0
    cap: float = 30.0
    jitter: float = 0.25  # +-25 %, so parallel runs do not retry in lockstep

    def delay(self, retry_number: int, retry_after: float | None = None) -> float:
        if retry_after is not None and retry_after >= 0:
            return min(retry_after, self.cap)
        raw = min(self.cap, self.base * (2**retry_number))
        return max(0.0, raw * (1 + random.uniform(-self.jitter, self.jitter)))


class RetryingProvider(Wrapper):
    def __init__(
        self,
        inner: BaseProvider,
        policy: RetryPolicy | None = None,
        sleep: Callable[[float], None] = time.sleep,
    ) -> None:
        super().__init__(inner)
        self.policy = policy or RetryPolicy()
        self._sleep = sleep
        self.retries = 0  # how many times this wrapper waited and tried again

    def send(self, request: Request) -> Completion:
        attempt = 0
        while True:
            try:
                return self.inner.send(request)
            except ProviderError as error:
                attempt += 1
                if not is_retryable(error) or attempt >= self.policy.attempts:
                    if error.kind in ("connection", "timeout"):
                        raise ProviderUnavailable(
                            f"{error} (gave up after {attempt} attempt(s))"
                        ) from error
                    raise
                self.retries += 1
                self._sleep(self.policy.delay(attempt - 1, error.retry_after))
