"""The server <-> check process messages: each direction accepts only its own."""

from __future__ import annotations

import pytest

from arise.serve.checkmsg import (
    Check,
    Died,
    Done,
    Failed,
    MessageError,
    Ran,
    Ready,
    Run,
    encode,
    from_process,
    to_process,
)
from arise.validate.types import Diagnostic, SandboxReport, Stage


def test_messages_survive_their_lines() -> None:
    for message in (Ready(pid=7), Run(request={"text": "x"}), Done(view={"a": [1]})):
        assert from_process(encode(message)) == message
    died = Died(
        diagnostic=Diagnostic(stage=Stage.SAMPLE, error_type="Timeout", message="slow"),
        sandbox=SandboxReport(),
    )
    for message in (Check(text="s", folder="/f", map_dir=None, timeout=5), Ran(result={}), died):
        assert to_process(encode(message)) == message


@pytest.mark.parametrize(
    "line",
    [
        b"garbage",
        b'{"op": "ran", "result": {}}',  # the server's word, from the process
        b'{"op": "done", "view": []}',
        b'{"op": "done", "view": {}, "extra": 1}',
        b'{"op": "failed", "error": "x", "internal": "no"}',
        b'{"op": "ready", "pid": "7"}',
        b'{"op": "teleport"}',
    ],
)
def test_the_server_refuses_what_a_process_may_not_say(line: bytes) -> None:
    with pytest.raises(MessageError):
        from_process(line)


def test_the_process_refuses_its_own_words_from_the_server() -> None:
    with pytest.raises(MessageError):
        to_process(encode(Failed(error="x", internal=False)))
