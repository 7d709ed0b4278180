"""The worker's messages: what the pool accepts from a worker's channel, and what not."""

from __future__ import annotations

import json

import pytest

from arise.validate.protocol import (
    ChildDied,
    ProtocolError,
    Ready,
    Result,
    StageEntered,
    WorkerEvent,
    dump_message,
    parse_message,
)
from arise.validate.types import Mechanism, SandboxReport, Stage


@pytest.mark.parametrize(
    "message",
    [
        Ready(pid=42, sandbox=SandboxReport(active=[Mechanism.SECCOMP], notes=["a note"])),
        StageEntered(stage=Stage.SIMULATE),
        Result(result={"ok": True, "timings": {"gate": 0.1}, "warnings": ["é"]}),
        ChildDied(code=-9, flooded=True),
    ],
)
def test_every_message_survives_its_line(message: object) -> None:
    line = dump_message(message)  # type: ignore[arg-type]
    assert line.endswith("\n") and line.count("\n") == 1
    assert parse_message(line) == message


def test_stage_is_the_enum() -> None:
    message = parse_message('{"event": "stage", "stage": "compile"}')
    assert isinstance(message, StageEntered)
    assert message.stage is Stage.COMPILE
    assert message.event is WorkerEvent.STAGE


def test_a_nan_in_a_result_stays_a_nan_for_the_result_schema_to_refuse() -> None:
    line = dump_message(Result(result={"x": float("nan")}))
    assert "NaN" in line
    message = parse_message(line)
    assert isinstance(message, Result) and message.result["x"] != message.result["x"]


@pytest.mark.parametrize(
    "line",
    [
        b"not json at all",
        b"[1, 2]",
        b'"ready"',
        b"{}",
        b'{"event": "hello"}',  # unknown event
        b'{"event": "stage", "stage": "unpickle"}',  # not a Stage
        b'{"event": "stage", "stage": "gate", "extra": 1}',
        b'{"event": "result", "result": [1]}',  # a result is an object
        b'{"event": "result", "result": {}, "ok": true}',  # an extra field
        b'{"event": "result"}',
        b'{"event": "child_died", "code": "9"}',  # strict: a string is not a number
        b'{"event": "child_died", "code": 9, "flooded": "yes"}',
        b'{"event": "ready", "pid": 1}',  # no sandbox report
        b'{"event": "ready", "pid": 1, "sandbox": {"active": ["telepathy"]}}',
        b'{"event": "result", "result": ' + b"[" * 10_000 + b"]" * 10_000 + b"}",  # too deep
    ],
)
def test_anything_else_is_refused(line: bytes) -> None:
    with pytest.raises(ProtocolError):
        parse_message(line)


def test_a_refusal_does_not_echo_the_line() -> None:
    secret = "SECRET-" + "x" * 50
    with pytest.raises(ProtocolError) as caught:
        parse_message(json.dumps({"event": "result", "result": secret}))
    assert secret not in str(caught.value)


def test_a_lone_surrogate_in_a_result_still_makes_a_line_that_parses() -> None:
    line = dump_message(Result(result={"diagnostic": {"message": "bad \ud800 text", "x": [1.5]}}))
    message = parse_message(line)
    assert isinstance(message, Result)
    assert message.result == {"diagnostic": {"message": "bad \ufffd text", "x": [1.5]}}
