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
from arise.llm.types import (
    Completion,
    ProviderError,
    ProviderErrorKind,
    ProviderUnavailable,
    Request,
)


@dataclass(frozen=True)
class ErrorRow:
    kind: ProviderErrorKind
    retryable: bool
    description: str


_K = ProviderErrorKind
ERROR_TABLE: dict[ProviderErrorKind, ErrorRow] = {
    row.kind: row
    for row in (
        ErrorRow(_K.RATE_LIMITED, True, "HTTP 429: too many requests or tokens per minute"),
        ErrorRow(_K.OVERLOADED, True, "HTTP 503/529: the service is overloaded for now"),
        ErrorRow(_K.SERVER_ERROR, True, "HTTP 500/502/504 or another 5xx"),
        ErrorRow(_K.TIMEOUT, True, "no answer within the configured timeout"),
        ErrorRow(_K.CONNECTION, True, "connection refused or reset, or the name did not resolve"),
        ErrorRow(_K.AUTH, False, "HTTP 401/403: the key is missing, wrong or not allowed"),
        ErrorRow(_K.NOT_FOUND, False, "HTTP 404: wrong base URL or unknown model name"),
        ErrorRow(_K.BAD_REQUEST, False, "HTTP 400/413/422: the request is wrong (e.g. too long)"),
        ErrorRow(_K.OTHER, False, "anything else the backend reports"),
    )
}


def kind_for_status(status: int | None) -> ProviderErrorKind:
    """Map an HTTP status to a row of ERROR_TABLE."""
    if status is None:
        return _K.OTHER
    if status == 429:
        return _K.RATE_LIMITED
    if status in (503, 529):
        return _K.OVERLOADED
    if 500 <= status < 600:
        return _K.SERVER_ERROR
    if status in (401, 403):
        return _K.AUTH
    if status == 404:
        return _K.NOT_FOUND
    if 400 <= status < 500:
        return _K.BAD_REQUEST
    return _K.OTHER


def is_retryable(error: BaseException) -> bool:
    if isinstance(error, ProviderError):
        return ERROR_TABLE[error.kind].retryable
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
                    if error.kind in (_K.CONNECTION, _K.TIMEOUT):
                        raise ProviderUnavailable(
                            f"{error} (gave up after {attempt} attempt(s))"
                        ) from error
                    raise
                self.retries += 1
                self._sleep(self.policy.delay(attempt - 1, error.retry_after))
