"""What the semantic gate costs, as the bench stores and reports it."""

from __future__ import annotations

import sqlite3
from pathlib import Path

from arise.evaluate.records import BenchTask, RunRecord
from arise.evaluate.report import gate_met, gate_seconds_per_run, markdown, runs_csv
from arise.evaluate.store import BenchStore
from arise.generate.run import RunStatus


def _record(index: int, mode: str, gate: str, seconds: float) -> RunRecord:
    task = BenchTask(f"p{index}", "crossing", "A pedestrian crosses.", mode, 0.0, 0)
    return RunRecord(
        task=task,
        status=RunStatus.EXECUTED,
        first_pass_ok=True,
        repairs=1,
        seconds=20.0,
        gate=gate,
        gate_seconds=seconds,
    )


RUNS = [
    _record(1, "arise", "passed", 0.0),
    _record(2, "arise", "contradicts", 12.0),
    _record(3, "single-pass", "off", 0.0),
]


def test_gate_seconds_and_verdicts_are_stored_and_reported(tmp_path: Path) -> None:
    with BenchStore(tmp_path / "bench.sqlite") as store:
        for record in RUNS:
            store.save(record)
        back = store.runs()
    assert [(r.gate, r.gate_seconds) for r in back] == [(r.gate, r.gate_seconds) for r in RUNS]
    rows = sqlite3.connect(tmp_path / "bench.sqlite").execute(
        "SELECT gate, gate_seconds FROM runs ORDER BY id"
    )
    assert list(rows) == [("passed", 0.0), ("contradicts", 12.0), ("off", 0.0)]
    arise = [r for r in back if r.task.mode == "arise"]
    assert gate_seconds_per_run(arise) == 6.0 and gate_met(arise) == 0.5
    assert gate_seconds_per_run(back[2:]) is None, "N/A when the gate was off"
    report = markdown(back, "t", {})
    line = next(x for x in report.splitlines() if x.startswith("| gate seconds / run | arise"))
    assert "**6**" in line
    assert "| gate met | arise | 0 | 0.500 |" in report
    assert "contradicts,12.0" in runs_csv(back)


def test_an_older_database_gets_the_gate_columns(tmp_path: Path) -> None:
    path = tmp_path / "old.sqlite"
    old = sqlite3.connect(path)
    old.execute(
        "CREATE TABLE runs (id INTEGER PRIMARY KEY, prompt_id TEXT NOT NULL, "
        "category TEXT NOT NULL, description TEXT NOT NULL, mode TEXT NOT NULL, "
        "temperature REAL NOT NULL, run_index INTEGER NOT NULL, status TEXT NOT NULL, "
        "first_pass_ok INTEGER NOT NULL, repairs INTEGER NOT NULL, llm_calls INTEGER NOT NULL, "
        "prompt_tokens INTEGER NOT NULL, completion_tokens INTEGER NOT NULL, "
        "seconds REAL NOT NULL, message TEXT, out_dir TEXT, conformity REAL, scs REAL, "
        "collision INTEGER, min_distance REAL, min_ttc REAL, route_completion REAL, "
        "record TEXT NOT NULL, finished_at TEXT NOT NULL, "
        "UNIQUE (prompt_id, mode, temperature, run_index))"
    )
    old.commit()
    old.close()
    with BenchStore(path) as store:
        store.save(RUNS[1])
        assert store.runs()[0].gate_seconds == 12.0
