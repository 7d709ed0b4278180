"""A job's events: the generator's progress in its typed form, and what a run folder's
events.jsonl may hold."""

from __future__ import annotations

import json

import pytest

from arise.generate.events import AttemptChecked, RunFinished, RunStage, StageStarted, event_dict
from arise.generate.run import AttemptKind, RunStatus
from arise.serve.events import (
    AttemptEvent,
    EventKind,
    JobState,
    StageEvent,
    StateEvent,
    event_data,
    event_json,
    from_progress,
    read_event,
)


@pytest.mark.parametrize(
    "progress",
    [
        StageStarted(RunStage.VALIDATE, attempt=0),
        StageStarted(RunStage.REPAIR, attempt=2, error="NameError: x"),
        AttemptChecked(1, AttemptKind.LLM, False, "rewrote a section", error="boom"),
        RunFinished(RunStatus.EXECUTED, "the script ran"),
    ],
)
def test_every_progress_event_keeps_its_json_form(progress: object) -> None:
    event = from_progress(progress)  # type: ignore[arg-type]
    assert event_data(event) == event_dict(progress)  # type: ignore[arg-type]
    assert read_event(event_json(event)) == event


def test_a_state_event_says_its_message_even_when_there_is_none() -> None:
    event = StateEvent(state=JobState.QUEUED)
    assert json.loads(event_json(event)) == {"event": "state", "state": "queued", "message": None}
    assert event.event is EventKind.STATE


def test_a_long_live_message_is_cut_not_refused() -> None:
    event = from_progress(StageStarted(RunStage.REPAIR, attempt=1, error="x" * 200_000))
    assert isinstance(event, StageEvent) and event.error is not None
    assert 0 < len(event.error) < 200_000


@pytest.mark.parametrize(
    "line",
    [
        '{"event": "state", "x": "SECRET"}',  # an unknown field
        '{"event": "state", "state": "hacked", "message": null}',
        '{"event": "script", "text": "<script>"}',  # not one of ours
        '{"event": "attempt", "index": -1, "kind": "llm", "ok": true, "detail": ""}',
        '{"event": "attempt", "index": 0, "kind": "llm", "ok": true, "detail": "x", "n": NaN}',
        '{"event": "done", "status": "executed", "summary": "' + "x" * 70_000 + '"}',
        '{"event": "stage", "stage": "validate"',  # cut short by a killed server
        "[]",
    ],
)
def test_a_line_that_is_not_our_event_is_skipped(line: str) -> None:
    assert read_event(line) is None


def test_an_attempt_reads_back_typed() -> None:
    event = read_event(
        '{"event": "attempt", "index": 3, "kind": "swap", "ok": true, "detail": "d"}'
    )
    assert isinstance(event, AttemptEvent)
    assert event.kind is AttemptKind.SWAP and event.index == 3
