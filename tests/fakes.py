"""Test doubles for the two things a generation waits on: the model and the validator.

`ScriptedProvider` answers from a queue (a text, or an exception to raise) and keeps every
request; `FakeValidator` returns CheckResults from a queue and keeps every script it saw.
Both fail loudly when a test did not plan for a call.
"""

from __future__ import annotations

from collections.abc import Iterable

from arise.llm.base import BaseProvider
from arise.llm.types import Completion, Request, Usage
from arise.validate.types import CheckOptions, CheckResult, Diagnostic, Stage

CALL_USAGE = Usage(calls=1, prompt_tokens=100, completion_tokens=50)


class ScriptedProvider(BaseProvider):
    """Replies from a queue, and remembers every request."""

    name = "scripted"
    model = "scripted-1"

    def __init__(self, replies: Iterable[str | BaseException] = ()) -> None:
        self.replies = list(replies)
        self.requests: list[Request] = []

    def enqueue(self, *replies: str | BaseException) -> ScriptedProvider:
        self.replies += replies
        return self

    def send(self, request: Request) -> Completion:
        self.requests.append(request)
        assert self.replies, f"unexpected model call: {request.messages[-1].content[:80]!r}"
        reply = self.replies.pop(0)
        if isinstance(reply, BaseException):
            raise reply
        return Completion(
            text=reply, usage=CALL_USAGE, model=self.model, latency=0.5, provider=self.name
        )


class FakeValidator:
    """Check results from a queue; usable as `Validate` (one argument) or as a Generator's
    `checker` (script and options)."""

    def __init__(self, results: Iterable[CheckResult] = ()) -> None:
        self.results = list(results)
        self.scripts: list[str] = []

    def __call__(self, script: str, options: CheckOptions | None = None) -> CheckResult:
        self.scripts.append(script)
        assert self.results, "unexpected validation"
        return self.results.pop(0).model_copy(update={"script": "scenario.scenic"})


def passed() -> CheckResult:
    return CheckResult(ok=True, script="scenario.scenic")


def failed(
    stage: Stage = Stage.SIMULATE,
    error_type: str = "TypeError",
    message: str = "something went wrong",
    section: str | None = None,
    **fields: object,
) -> CheckResult:
    diagnostic = Diagnostic(
        stage=stage, error_type=error_type, message=message, section=section, **fields
    )  # type: ignore[arg-type]
    return CheckResult(ok=False, script="scenario.scenic", diagnostic=diagnostic)
