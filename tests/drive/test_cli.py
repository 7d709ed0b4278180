"""`arise drive` end to end: real scripts through the real confined worker pool, the
database a killed drive resumes from, and one-line errors for bad input."""

from __future__ import annotations

import csv
import json
import os
import shutil
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from arise.cli import app
from arise.drive.session import DriveRequest, Generating, drive
from arise.executors import Executor
from tests.conftest import EXAMPLES
from tests.generate_cases import CASES

runner = CliRunner()
CATEGORIES = EXAMPLES / "categories"


def _scripts(root: Path, *names: str) -> Path:
    """A folder of the shipped category examples, one sub-folder (category) each."""
    for name in names:
        (root / name).mkdir(parents=True)
        shutil.copy(CATEGORIES / f"{name}.scenic", root / name / "example.scenic")
    return root


def _rows(database: Path) -> list[tuple[str, str, str]]:
    with sqlite3.connect(database) as db:
        return list(db.execute("SELECT scenario, status, finished_at FROM runs ORDER BY id"))


def _rows_so_far(database: Path) -> list[tuple[str, str, str]]:
    """The rows of a store another process is still creating: none before its table is."""
    try:
        return _rows(database)
    except sqlite3.OperationalError:
        return []


def _csv(path: Path) -> list[dict[str, str]]:
    with path.open(newline="") as handle:
        return list(csv.DictReader(handle))


@pytest.mark.slow
def test_drive_a_folder_writes_the_table_the_runs_and_the_collision_replay(
    tmp_path: Path,
) -> None:
    source = _scripts(tmp_path / "scripts", "straight_obstacle", "red_light_running")
    out = tmp_path / "out"
    result = runner.invoke(
        app, ["drive", str(source), "--agent", "scripted", "--out", str(out), "--workers", "2"]
    )
    assert result.exit_code == 0, result.output
    assert "2 run(s) to drive, 0 already" in result.output
    assert "2 of 2 runs driven by scripted" in result.output
    rows = {row["category"]: row for row in _csv(out / "runs.csv")}
    assert set(rows) == {"straight_obstacle", "red_light_running"}
    assert all(row["status"] == "driven" and row["agent"] == "scripted" for row in rows.values())
    assert {row["collision"] for row in rows.values()} <= {"0", "1"}
    # The shipped red-light example's scripted ego is hit at the junction (seed 0).
    crash = rows["red_light_running"]
    assert crash["collision"] == "1"
    replay = out / crash["replay"]
    assert replay.name == "replay.gif" and replay.read_bytes()[:6] == b"GIF89a"
    assert (replay.parent / "replay.html").is_file()
    assert rows["straight_obstacle"]["collision"] == "0" and not rows["straight_obstacle"]["replay"]
    report = (out / "report.md").read_text()
    assert "| red\\_light\\_running | 1 | 1.00 |" in report
    assert "| straight\\_obstacle | 1 | 0.00 |" in report
    assert "| **overall** | 2 | 0.50 |" in report
    assert f"[replay]({crash['replay']})" in report
    # Everything done: the same command again has nothing to drive and keeps the report.
    again = runner.invoke(app, ["drive", str(source), "--agent", "scripted", "--out", str(out)])
    assert again.exit_code == 0 and "0 run(s) to drive, 2 already" in again.output
    assert (out / "report.md").read_text() == report


@pytest.mark.slow
def test_a_killed_drive_resumes_without_redoing_finished_runs(tmp_path: Path) -> None:
    source = _scripts(
        tmp_path / "scripts",
        "turning_obstacle",
        "vehicle_passing",
        "right_turn",
        "straight_obstacle",
    )
    out = tmp_path / "out"
    command = [sys.executable, "-m", "arise", "drive", str(source), "--agent", "scripted"]
    process = subprocess.Popen(
        [*command, "--out", str(out)],
        start_new_session=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    database = out / "drive.sqlite"
    deadline = time.monotonic() + 240
    try:
        while time.monotonic() < deadline:
            if database.exists() and _rows_so_far(database):
                break
            time.sleep(0.1)
        os.killpg(process.pid, signal.SIGKILL)
    finally:
        process.wait()
    first = _rows(database)
    assert 1 <= len(first) < 4, "the kill should land before the last run"
    assert not (out / "report.md").exists()  # the report comes at the end, whole
    result = runner.invoke(app, ["drive", str(source), "--agent", "scripted", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert f"{4 - len(first)} run(s) to drive, {len(first)} already" in result.output
    after = _rows(database)
    assert len(after) == 4 and after[: len(first)] == first  # finished runs were not redone
    assert len(_csv(out / "runs.csv")) == 4


def test_bad_input_is_one_line_and_writes_nothing(tmp_path: Path) -> None:
    script = tmp_path / "s.scenic"
    script.write_text("model scenic.simulators.carla.model\nego = new Car\n")
    out = tmp_path / "out"
    empty = tmp_path / "empty"
    empty.mkdir()
    cases = [
        (["drive", str(tmp_path / "missing"), "--agent", "idm"], "does not exist"),
        (["drive", str(script), "--agent", "reckless"], "unknown agent 'reckless'"),
        (["drive", str(script), "--agent", "nope.py:Agent"], "no such file"),
        (["drive", str(script), "--agent", str(script) + ":Agent"], "must be a .py file"),
        (["drive", str(script), "--agent", "idm", "--executor", "slurm"], "--executor is one of"),
        (["drive", str(empty), "--agent", "idm"], "holds no script to drive"),
    ]
    for arguments, message in cases:
        result = runner.invoke(app, [*arguments, "--out", str(out)])
        assert result.exit_code == 2, (arguments, result.output)
        assert message in result.output, (arguments, result.output)
        assert "Traceback" not in result.output
        assert len(result.output.strip().splitlines()) == 1, result.output
    assert not out.exists()
    assert "Examples" in runner.invoke(app, ["drive", "--help"]).output


@pytest.mark.slow
def test_a_prompt_file_is_generated_first_then_driven(tmp_path: Path) -> None:
    case = CASES["first_try"]
    prompts = tmp_path / "prompts.jsonl"
    prompts.write_text(
        json.dumps(
            {"id": "cyclist", "category": "straight_obstacle", "description": case.description}
        )
        + "\n"
    )
    events: list[object] = []
    request = DriveRequest(
        target=prompts,
        agent="scripted",
        out=tmp_path / "out",
        generate=case.options(replay=str(case.cassette)),
    )
    summary = drive(request, events.append)
    assert events[0] == Generating(todo=1, done=0)
    run = tmp_path / "out" / "scenarios" / "straight_obstacle" / "cyclist"
    assert (run / "scenario.scenic").is_file() and (run / "report.json").is_file()
    [record] = summary.records
    assert record.driven and record.task.scenario == "straight_obstacle/cyclist"
    assert record.task.category == "straight_obstacle"
    [row] = _csv(tmp_path / "out" / "runs.csv")
    assert row["category"] == "straight_obstacle" and row["status"] == "driven"
    # Again: nothing to generate (the model is not asked), nothing to drive.
    events.clear()
    drive(request, events.append)
    assert events[0] == Generating(todo=0, done=1)


@pytest.mark.slow
def test_the_ray_executor_drives_confined(tmp_path: Path) -> None:
    pytest.importorskip("ray")
    source = _scripts(tmp_path / "scripts", "turning_obstacle")
    summary = drive(
        DriveRequest(target=source, agent="scripted", out=tmp_path / "out", executor=Executor.RAY)
    )
    [record] = summary.records
    assert record.driven and (record.sandbox or "").startswith("landlock+seccomp+rlimits")


@pytest.mark.slow
def test_a_users_agent_from_a_file_drives(tmp_path: Path) -> None:
    """The README's agent (examples/agents/careful.py) through `arise drive`: loaded by the
    worker before confinement, it brakes where the script's own ego is hit."""
    source = _scripts(tmp_path / "scripts", "red_light_running")
    out = tmp_path / "out"
    agent = EXAMPLES / "agents" / "careful.py"
    result = runner.invoke(
        app, ["drive", str(source), "--agent", f"{agent}:Careful", "--out", str(out)]
    )
    assert result.exit_code == 0, result.output
    [row] = _csv(out / "runs.csv")
    assert row["agent"] == "careful.py:Careful" and row["status"] == "driven"
    assert row["collision"] == "0"  # the scripted ego collides here (test above)
    assert "careful.py:Careful" in (out / "report.md").read_text().splitlines()[0]
    # A class the file does not have: one line, and no run saved as done for it.
    missing = runner.invoke(
        app, ["drive", str(source), "--agent", f"{agent}:Reckless", "--out", str(out)]
    )
    assert missing.exit_code == 2, missing.output
    assert missing.output.strip().splitlines()[-1].startswith("error: agent ")
    assert "careful.py has no 'Reckless'" in missing.output and "Traceback" not in missing.output
    with sqlite3.connect(out / "drive.sqlite") as db:
        assert [a for (a,) in db.execute("SELECT agent FROM runs")] == [f"{agent}:Careful"]
