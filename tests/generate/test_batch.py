"""`run_batch`, the library call behind `arise generate`: what it reads, what it refuses
before anything loads, and the events and runs of a real (replayed) batch."""

from __future__ import annotations

from pathlib import Path

import pytest

from arise.generate.batch import (
    BatchEvent,
    BatchRequest,
    DescriptionError,
    RunDone,
    RunProgress,
    RunStarted,
    read_descriptions,
    run_batch,
)
from arise.generate.events import AttemptChecked, StageStarted
from arise.generate.options import GenerateOptions
from arise.generate.run import RunStatus
from tests.generate_cases import CASES


def test_descriptions_come_from_the_argument_and_the_file(tmp_path: Path) -> None:
    lines = tmp_path / "prompts.txt"
    lines.write_text("# a comment\n\nA car cuts in.\nA cyclist brakes.\n", encoding="utf-8")
    assert read_descriptions("A truck stops.", lines) == [
        ("a-truck-stops", "A truck stops."),
        ("003-a-car-cuts-in", "A car cuts in."),
        ("004-a-cyclist-brakes", "A cyclist brakes."),
    ]
    rows = tmp_path / "prompts.jsonl"
    rows.write_text('{"id": "cut-in", "description": "A car cuts in."}\n', encoding="utf-8")
    assert read_descriptions(None, rows) == [("cut-in", "A car cuts in.")]


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ('{"description": "A car cuts in."\n', "prompts.jsonl:1: not JSON"),
        ('["A car cuts in."]\n', "prompts.jsonl:1: not a JSON object"),
        (b"\xff\xfe not text", "cannot read"),
    ],
)
def test_a_bad_descriptions_file_is_one_line(
    tmp_path: Path, content: str | bytes, message: str
) -> None:
    rows = tmp_path / "prompts.jsonl"
    if isinstance(content, bytes):
        rows.write_bytes(content)
    else:
        rows.write_text(content, encoding="utf-8")
    with pytest.raises(DescriptionError, match=message):
        read_descriptions(None, rows)
    with pytest.raises(DescriptionError, match="no such file"):
        read_descriptions(None, tmp_path / "none.txt")


@pytest.mark.parametrize(
    ("description", "message"),
    [(None, "give a description or --file"), ("What is the capital of France?", "driving")],
)
def test_nothing_loads_for_a_request_that_cannot_run(
    tmp_path: Path, description: str | None, message: str
) -> None:
    # An unknown provider would fail as soon as the Generator asked for its model: the
    # refusal comes first, and no folder is written.
    options = GenerateOptions(provider="no-such-provider")
    request = BatchRequest(description=description, out=tmp_path / "out", options=options)
    with pytest.raises(DescriptionError, match=message):
        run_batch(request)
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
def test_a_replayed_batch_sends_its_events_and_returns_its_runs(tmp_path: Path) -> None:
    case = CASES["first_try"]
    options = case.options(provider="replay", replay=str(case.cassette))
    request = BatchRequest(description=case.description, out=tmp_path / "run", options=options)
    events: list[BatchEvent] = []
    batch = run_batch(request, events.append)
    assert batch.single and batch.ok and batch.executed == 1 and batch.refusal is None
    [done] = batch.runs
    assert done.folder == tmp_path / "run" and done.run.status is RunStatus.EXECUTED
    assert (tmp_path / "run" / "scenario.scenic").is_file()
    assert events[0] == RunStarted(tmp_path / "run") and events[-1] == done
    progress = [e.event for e in events[1:-1] if isinstance(e, RunProgress)]
    assert len(progress) == len(events) - 2, "only the run's own progress between"
    assert any(isinstance(e, StageStarted) for e in progress)
    assert any(isinstance(e, AttemptChecked) and e.ok for e in progress)
    assert isinstance(events[-1], RunDone)
