"""`arise search` as a user runs it: one-line errors, and a short search's files."""

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
from tests.conftest import DATA

runner = CliRunner()


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["search", "nowhere.scenic"], "no such file: nowhere.scenic"),
        (
            ["search", str(DATA / "base_crossing.scenic"), "--objective", "fast"],
            "unknown objective",
        ),
        (
            ["search", str(DATA / "base_crossing.scenic"), "--sampler", "ce,sa"],
            "unknown sampler 'sa'",
        ),
        (["search", str(DATA / "base_crossing.scenic"), "--executor", "dask"], "unknown executor"),
        (
            ["search", str(DATA / "base_crossing.scenic"), "--objective", "custom"],
            "--objective custom needs --expression",
        ),
        (
            [
                "search",
                str(DATA / "base_crossing.scenic"),
                "--objective",
                "custom",
                "--expression",
                "__import__('os').system('true')",
            ],
            "is not allowed in an objective",
        ),
        (
            ["search", str(DATA / "base_crossing.scenic"), "--expression", "min_ttc"],
            "--expression goes with --objective custom",
        ),
    ],
)
def test_bad_input_is_one_line(args: list[str], message: str, tmp_path: Path) -> None:
    result = runner.invoke(app, [*args, "--out", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert message in result.output
    assert "Traceback" not in result.output
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
def test_a_short_search_writes_its_files(tmp_path: Path) -> None:
    pytest.importorskip("verifai", reason="the verifai extra is not installed")
    out = tmp_path / "out"
    args = ["search", str(DATA / "verifai" / "cut_in.scenic"), "--trials", "2"]
    result = runner.invoke(app, [*args, "--sampler", "random", "--no-replay", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert "random trial 1:" in result.output
    summary = json.loads((out / "search.json").read_text(encoding="utf-8"))
    (search,) = summary["searches"]
    assert search["sampler"] == "random" and search["trials"] == 2
    assert [p["name"] for p in search["params"]] == [
        "EGO_SPEED",
        "CUTTER_SPEED",
        "CUTTER_LEAD",
        "CUT_AT",
    ]
    critical = (out / "critical" / "scenario.scenic").read_text(encoding="utf-8")
    assert "# searched in VerifaiRange(8, 12)" in critical
    assert (out / "objective.png").is_file() and (out / "trials.csv").is_file()
    again = runner.invoke(app, [*args, "--sampler", "random", "--no-replay", "--out", str(out)])
    assert again.exit_code == 0, again.output
    assert json.loads((out / "search.json").read_text())["searches"][0]["resumed"] == 2


@pytest.mark.slow
def test_a_custom_objective_scores_every_trial_from_its_trace(tmp_path: Path) -> None:
    pytest.importorskip("verifai", reason="the verifai extra is not installed")
    out = tmp_path / "out"
    expression = "min_ttc + 0.5 * min_distance"
    args = ["search", str(DATA / "verifai" / "cut_in.scenic"), "--trials", "2", "--no-replay"]
    args += ["--sampler", "halton", "--objective", "custom", "--expression", expression]
    result = runner.invoke(app, [*args, "--out", str(out)])
    assert result.exit_code == 0, result.output
    query = "SELECT ok, value, collision, min_ttc, min_distance FROM trials ORDER BY idx"
    with sqlite3.connect(out / "search.sqlite") as db:
        rows = list(db.execute(query))
    ran = [r for r in rows if r[0]]
    assert ran, rows
    for _, value, _collision, min_ttc, min_distance in ran:  # the trial's own facts
        ttc = min(10.0, min_ttc if min_ttc is not None else 10.0)
        assert value == pytest.approx(ttc + 0.5 * max(0.0, min_distance or 0.0), abs=1e-3)
    assert json.loads((out / "search.json").read_text())["searches"][0]["objective"] == "custom"


def _trials(database: Path) -> list[tuple[int, str]]:
    if not database.exists():
        return []
    try:
        with sqlite3.connect(database) as db:
            return list(db.execute("SELECT idx, finished_at FROM trials ORDER BY idx"))
    except sqlite3.OperationalError:  # created but no tables yet
        return []


@pytest.mark.slow
def test_a_killed_search_resumes_without_redoing_finished_trials(tmp_path: Path) -> None:
    pytest.importorskip("verifai", reason="the verifai extra is not installed")
    out = tmp_path / "out"
    args = ["search", str(DATA / "base_crossing.scenic"), "--trials", "5", "--sampler", "ce"]
    args += ["--no-replay", "--out", str(out)]
    process = subprocess.Popen(
        [sys.executable, "-m", "arise", *args],
        start_new_session=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    database = out / "search.sqlite"
    deadline = time.monotonic() + 300
    try:
        while time.monotonic() < deadline and len(_trials(database)) < 2:
            time.sleep(0.2)
        os.killpg(process.pid, signal.SIGKILL)
    finally:
        process.wait()
    before = _trials(database)
    assert 2 <= len(before) < 5, "the kill should land in the middle of the search"
    again = runner.invoke(app, args)
    assert again.exit_code == 0, again.output
    after = _trials(database)
    assert len(after) == 5 and after[: len(before)] == before  # finished trials kept as they were
    summary = json.loads((out / "search.json").read_text(encoding="utf-8"))
    assert summary["searches"][0]["resumed"] == len(before)
