"""The labeled dev sets as bench prompts: truth travels with the task and into the report."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from arise.evaluate.fidelity import DEVSET_DIR, DevsetError
from arise.evaluate.metrics import METRICS
from arise.evaluate.prompt_file import read_prompts
from arise.evaluate.records import BenchTask, RunRecord
from arise.evaluate.report import markdown
from arise.evaluate.runner import BenchConfig, plan
from arise.generate.options import Mode


def test_a_dev_set_file_is_a_prompt_file_with_truth() -> None:
    prompts = read_prompts(DEVSET_DIR / "short.jsonl")
    assert len(prompts) >= 30 and all(p.truth for p in prompts)
    first = json.loads(prompts[0].truth or "{}")
    assert "actors" in first or "ego_maneuver" in first


def test_a_bad_truth_is_refused_with_its_line(tmp_path: Path) -> None:
    bad = tmp_path / "bad.jsonl"
    bad.write_text(
        json.dumps(
            {
                "id": "x",
                "text": "A car turns.",
                "truth": {"actors": [{"class": "Lorry", "count": 1}]},
            }
        )
        + "\n"
    )
    with pytest.raises(DevsetError, match=r"bad.jsonl:1.*Lorry"):
        read_prompts(bad)


def test_tasks_carry_the_truth_and_records_keep_the_fidelity() -> None:
    prompts = read_prompts(DEVSET_DIR / "nhtsa.jsonl")[:2]
    config = BenchConfig(prompts=prompts, modes=[Mode.ARISE], temperatures=[0.0], runs=1)
    tasks = plan(config)
    assert [t.truth for t in tasks] == [p.truth for p in prompts]
    record = RunRecord(
        task=tasks[0],
        status="executed",
        first_pass_ok=True,
        repairs=0,
        fidelity={"executed": True, "score": 0.75, "verdicts": []},
    )
    again = RunRecord.from_dict(json.loads(json.dumps(record.as_dict())))
    assert again.task.truth == tasks[0].truth and again.fidelity_score == 0.75
    assert METRICS["fidelity"]([again]) == 0.75
    assert "| fidelity |" in markdown([again], "t", {})


def test_old_rows_without_truth_still_load() -> None:
    row = {
        "task": {
            "prompt_id": "p",
            "category": "c",
            "description": "d",
            "mode": "arise",
            "temperature": 0.0,
            "run_index": 0,
        },
        "status": "executed",
        "first_pass_ok": True,
        "repairs": 0,
    }
    record = RunRecord.from_dict(row)
    assert record.task.truth is None and record.fidelity is None
    assert isinstance(record.task, BenchTask)
