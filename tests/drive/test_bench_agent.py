"""`arise bench --agent`: every executed script of a benchmark is also driven, and the
bench report gets the drive's metric columns and the paper's table."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest

from arise.drive.agent_names import resolve_agent
from arise.evaluate.benchmark import BenchPlanned, benchmark
from arise.evaluate.prompt_file import read_prompts
from arise.evaluate.runner import BenchConfig
from arise.evaluate.store import BenchStore
from tests.generate_cases import CASES

pytestmark = pytest.mark.slow


def _prompts(tmp_path: Path) -> Path:
    prompts = tmp_path / "prompts.jsonl"
    row = {
        "id": "cyclist-brakes",
        "category": "straight_obstacle",
        "description": CASES["first_try"].description,
    }
    prompts.write_text(json.dumps(row) + "\n")
    return prompts


def test_bench_with_an_agent_adds_the_drive_columns_and_table(tmp_path: Path) -> None:
    case = CASES["first_try"]
    out = tmp_path / "bench"
    base = case.options(replay=str(case.cassette))
    config = BenchConfig(prompts=read_prompts(_prompts(tmp_path)), base=base)
    first = benchmark(config, out)  # without an agent: no drive, no drive columns
    assert [r.driving for r in first.records] == [None]
    plain = (out / "report" / "runs.csv").read_text()
    assert "overall_score" not in plain.splitlines()[0]
    # The same benchmark with --agent: the executed run is driven, not generated again.
    config.agent = resolve_agent("idm")
    events: list[object] = []
    summary = benchmark(config, out, events.append)
    assert [e.todo for e in events if isinstance(e, BenchPlanned)] == [0]
    [record] = summary.records
    assert record.ok and record.driving is not None
    assert record.driving["task"]["agent"] == "idm" and record.driving["status"] == "driven"
    with (out / "report" / "runs.csv").open(newline="") as handle:
        [row] = list(csv.DictReader(handle))
    assert row["agent"] == "idm" and row["driven"] == "1"
    assert row["collision"] in ("0", "1") and float(row["route_completion"]) >= 0
    assert row["overall_score"] != ""
    report = (out / "report" / "report.md").read_text()
    assert "## Driving metrics: agent idm" in report
    assert "| straight\\_obstacle | 1 |" in report and "| **overall** | 1 |" in report
    with BenchStore(out / "bench.sqlite") as store:
        assert store.meta()["agent"] == "idm"
        [stored] = store.runs()
    assert stored.driving == record.driving
