"""`arise bench` end to end on replayed model answers: resume after a kill, Ray, report.

The cassettes are the generator's (recorded from the real embedded Qwen2.5-Coder-1.5B-
Instruct Q4_K_M, temperature 0, seed 0); both prompts run on their first attempt, so
mode arise sends exactly the requests that were recorded.
"""

from __future__ import annotations

import json
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from arise.cli import app
from arise.evaluate.prompt_file import BenchPrompt, read_prompts
from arise.evaluate.runner import BenchConfig, pending, run_bench
from arise.evaluate.store import BenchStore, BenchStoreError
from arise.executors import Executor
from arise.generate.options import GenerateOptions, Mode
from arise.generate.run import AttemptKind
from tests.generate_cases import CASES

runner = CliRunner()


@pytest.fixture()
def prompts_and_cassette(tmp_path: Path) -> tuple[Path, Path]:
    prompts = tmp_path / "prompts.jsonl"
    rows = [
        {
            "id": "cyclist-brakes",
            "category": "vehicle_passing",
            "description": CASES["first_try"].description,
        },
        {
            "id": "left-turn",
            "category": "unprotected_left_turn",
            "description": CASES["single_pass"].description,
        },
    ]
    prompts.write_text("".join(json.dumps(row) + "\n" for row in rows))
    cassette = tmp_path / "both.jsonl"
    cassette.write_text(
        CASES["first_try"].cassette.read_text() + CASES["single_pass"].cassette.read_text()
    )
    return prompts, cassette


def _rows(database: Path) -> list[tuple[str, str, str]]:
    """The runs so far; none while the benchmark has not made its table yet."""
    with sqlite3.connect(database) as db:
        try:
            return list(db.execute("SELECT prompt_id, status, finished_at FROM runs ORDER BY id"))
        except sqlite3.OperationalError:
            return []


@pytest.mark.slow
def test_a_killed_benchmark_resumes_without_redoing_finished_runs(
    tmp_path: Path, prompts_and_cassette: tuple[Path, Path]
) -> None:
    prompts, cassette = prompts_and_cassette
    out = tmp_path / "bench"
    command = [
        sys.executable,
        "-m",
        "arise",
        "bench",
        str(prompts),
        "--out",
        str(out),
        "--replay",
        str(cassette),
    ]
    process = subprocess.Popen(
        command, start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    database = out / "bench.sqlite"
    deadline = time.monotonic() + 240
    try:
        while time.monotonic() < deadline:
            if database.exists() and _rows(database):
                break
            time.sleep(0.2)
        os.killpg(process.pid, signal.SIGKILL)
    finally:
        process.wait()
    first = _rows(database)
    assert len(first) == 1, "the kill should land between the two runs"
    result = runner.invoke(
        app, ["bench", str(prompts), "--out", str(out), "--replay", str(cassette)]
    )
    assert result.exit_code == 0, result.output
    assert "1 run(s) to do, 1 already" in result.output
    after = _rows(database)
    assert len(after) == 2 and after[0] == first[0]  # the finished run was not redone
    assert {status for _, status, _ in after} == {"executed"}
    report = (out / "report" / "report.md").read_text()
    assert "| ESR | arise | 0 | total | 1.000 | 1.000 | **1.000** |" in report
    assert (out / "report" / "esr_by_category.png").read_bytes()[:4] == b"\x89PNG"
    with BenchStore(database) as store:
        runs = store.runs()
    assert all(r.conformity and r.conformity["score"] is not None for r in runs)
    assert all(r.criticality and r.criticality["min_distance"] is not None for r in runs)
    # Everything done: a third call has nothing to do.
    again = runner.invoke(
        app, ["bench", str(prompts), "--out", str(out), "--replay", str(cassette)]
    )
    assert again.exit_code == 0 and "0 run(s) to do, 2 already" in again.output


@pytest.mark.slow
def test_ray_executor_on_a_local_instance(
    tmp_path: Path, prompts_and_cassette: tuple[Path, Path]
) -> None:
    pytest.importorskip("ray")
    prompts, cassette = prompts_and_cassette
    config = BenchConfig(
        prompts=read_prompts(prompts),
        executor=Executor.RAY,
        workers=2,
        base=GenerateOptions(replay=str(cassette)),
    )
    with BenchStore(tmp_path / "bench.sqlite") as store:
        finished = run_bench(config, store, tmp_path)
        stored = store.runs()
    assert sorted(r.task.prompt_id for r in finished) == ["cyclist-brakes", "left-turn"]
    assert [r.ok for r in stored] == [True, True]
    assert all(Path(r.out_dir or "").joinpath("scenario.scenic").is_file() for r in stored)
    # Scripts checked inside Ray actors ran confined like everywhere else.
    assert all((r.sandbox or "").startswith("landlock+seccomp+rlimits") for r in stored)


def test_user_mistakes_get_clear_errors(tmp_path: Path) -> None:
    missing = runner.invoke(app, ["bench", str(tmp_path / "nope.jsonl")])
    assert missing.exit_code == 2 and "no such file" in missing.output
    bad = tmp_path / "p.txt"
    bad.write_text("A car brakes ahead.\n")
    wrong_mode = runner.invoke(app, ["bench", str(bad), "--modes", "fast"])
    assert wrong_mode.exit_code == 2 and "modes are" in wrong_mode.output
    executor = runner.invoke(app, ["bench", str(bad), "--executor", "slurm"])
    assert executor.exit_code == 2 and "--executor" in executor.output
    garbage = tmp_path / "bench.sqlite"
    garbage.write_text("this is not a database" * 100)
    report = runner.invoke(app, ["report", str(garbage)])
    assert report.exit_code == 2 and "not a benchmark database" in report.output
    empty = runner.invoke(app, ["report", str(tmp_path / "none.sqlite")])
    assert empty.exit_code == 2 and "no such database" in empty.output
    help_text = runner.invoke(app, ["bench", "--help"])
    assert help_text.exit_code == 0 and "Examples" in help_text.output


@pytest.mark.slow
def test_judge_pass_scores_finished_runs_later(tmp_path: Path) -> None:
    # The judge cassette was recorded from the embedded Qwen2.5-Coder-1.5B with
    # `arise judge ... --record` on the script this replayed generation writes.
    prompts = tmp_path / "prompts.jsonl"
    prompts.write_text(
        json.dumps(
            {"id": "ft", "category": "cyclist", "description": CASES["first_try"].description}
        )
        + "\n"
    )
    cassette = tmp_path / "both.jsonl"
    cassette.write_text(
        CASES["first_try"].cassette.read_text()
        + (
            Path(__file__).resolve().parents[1] / "cassettes" / "judge" / "bench_first_try.jsonl"
        ).read_text()
    )
    out = tmp_path / "bench"
    # The judge's cassette holds the script written when the model read the description.
    command = [
        "bench",
        str(prompts),
        "--out",
        str(out),
        "--replay",
        str(cassette),
        "--ask-model",
        "always",
    ]
    assert runner.invoke(app, command).exit_code == 0
    judged = runner.invoke(app, [*command, "--judge"])
    assert judged.exit_code == 0, judged.output
    assert "0 run(s) to do, 1 already" in judged.output
    assert "1 finished run(s) to judge first" in judged.output
    with BenchStore(out / "bench.sqlite") as store:
        [record] = store.runs()
    assert record.judge is not None and record.scs is not None
    names = {criterion["name"] for criterion in record.judge["criteria"]}
    assert names == {
        "adversary_type",
        "behavior",
        "geometry",
        "weather",
        "participants",
        "requirements",
        "spawn",
    }
    assert record.scs == pytest.approx(sum(c["score"] for c in record.judge["criteria"]) / 70)
    assert "| SCS | arise | 0 |" in (out / "report" / "report.md").read_text()


def _old_row(db: sqlite3.Connection, prompt_id: str, mode: str) -> None:
    """A run as an older arise wrote it: the mode is plain text in the column and the JSON."""
    task = {
        "prompt_id": prompt_id,
        "category": "crossing",
        "description": "A pedestrian crosses.",
        "mode": mode,
        "temperature": 0.0,
        "run_index": 0,
    }
    record = {
        "task": task,
        "status": "executed",
        "first_pass_ok": False,
        "repairs": 1,
        "attempts": [{"index": 0, "kind": "initial", "ok": False}],
    }
    db.execute(
        "INSERT INTO runs (prompt_id, category, description, mode, temperature, run_index, "
        "status, first_pass_ok, repairs, llm_calls, prompt_tokens, completion_tokens, seconds, "
        "record, finished_at) VALUES (?, 'crossing', 'd', ?, 0.0, 0, 'executed', 0, 1, 0, 0, "
        "0, 1.0, ?, '2024-01-01T00:00:00+00:00')",
        (prompt_id, mode, json.dumps(record)),
    )
    db.execute(
        "INSERT INTO attempts VALUES (last_insert_rowid(), 0, 'initial', 0, NULL, NULL, NULL, "
        "NULL, 0.5, 0, 0)"
    )


def test_an_older_store_reads_back_as_enums_and_resumes(tmp_path: Path) -> None:
    path = tmp_path / "bench.sqlite"
    BenchStore(path).close()  # the schema, as every version writes it
    with sqlite3.connect(path) as db:
        _old_row(db, "cross", "single-pass")
    with BenchStore(path) as store:
        [run] = store.runs()
        [attempt] = store.attempts()
        assert run.task.mode is Mode.SINGLE_PASS and attempt.kind is AttemptKind.INITIAL
        assert store.done_keys() == {("cross", Mode.SINGLE_PASS, 0.0, 0)}
        prompt = BenchPrompt("cross", "A pedestrian crosses.", "crossing")
        config = BenchConfig([prompt], modes=[Mode.SINGLE_PASS, Mode.ARISE])
        assert [task.mode for task in pending(config, store)] == [Mode.ARISE]
        store.save(run)  # written again: the same words as before, not "Mode.SINGLE_PASS"
    with sqlite3.connect(path) as db:
        [(column, text)] = db.execute("SELECT mode, record FROM runs")
    assert column == "single-pass" and json.loads(text)["task"]["mode"] == "single-pass"


def test_a_store_row_this_version_cannot_read_is_one_line(tmp_path: Path) -> None:
    path = tmp_path / "bench.sqlite"
    BenchStore(path).close()
    with sqlite3.connect(path) as db:
        _old_row(db, "cross", "fast")  # no such mode
    with BenchStore(path) as store, pytest.raises(BenchStoreError, match="'fast'"):
        store.runs()
    report = runner.invoke(app, ["report", str(path)])
    assert report.exit_code == 2 and "a row of runs is not one this arise reads" in report.output
    assert "Traceback" not in report.output
