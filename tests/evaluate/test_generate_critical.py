"""`arise generate --critical`: generation (replayed from a cassette, no model) chained
with a search; the report holds the critical instance next to the sampled one."""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import pytest
from typer.testing import CliRunner

from arise.cli import app
from arise.evaluate.search.critical import executed_runs
from tests.generate_cases import CASES

runner = CliRunner()


def test_only_executed_run_folders_are_searched(tmp_path: Path) -> None:
    for name, status in (("a", "executed"), ("b", "failed"), ("c/run-0", "executed")):
        folder = tmp_path / name
        folder.mkdir(parents=True)
        (folder / "report.json").write_text(json.dumps({"status": status}))
        (folder / "scenario.scenic").write_text("ego = new Car\n")
    (tmp_path / "a" / "search" / "critical").mkdir(parents=True)
    (tmp_path / "a" / "search" / "critical" / "report.json").write_text('{"status": "executed"}')
    assert executed_runs(tmp_path) == [tmp_path / "a", tmp_path / "c" / "run-0"]


def test_generate_lists_the_critical_options() -> None:
    result = runner.invoke(app, ["generate", "--help"], terminal_width=200)
    assert "--critical" in result.output and "--critical-trials" in result.output


@pytest.mark.slow
def test_generate_critical_searches_the_script_it_made(tmp_path: Path) -> None:
    pytest.importorskip("verifai", reason="the verifai extra is not installed")
    case = CASES["first_try"]
    out = tmp_path / "run"
    result = runner.invoke(
        app,
        [
            "generate",
            case.description,
            "--replay",
            str(case.cassette),
            "--no-cache",
            "-o",
            str(out),
            "--critical",
            "--critical-trials",
            "2",
        ],
    )
    assert result.exit_code == 0, result.output
    assert "critical instance: trial" in result.output
    report = json.loads((out / "report.json").read_text(encoding="utf-8"))
    entry = report["critical_search"]
    assert entry["sampler"] == "ce" and entry["trials"] == 2
    assert entry["sampled"] is not None and entry["critical"] is not None
    assert isinstance(entry["critical"]["value"], float)
    assert isinstance(entry["sampled"]["score"], float)
    critical = Path(entry["script"])
    assert critical == out / "search" / "critical" / "scenario.scenic"
    assert "# searched in Range(" in critical.read_text(encoding="utf-8")
    with sqlite3.connect(out / "search" / "search.sqlite") as db:
        assert db.execute("SELECT count(*) FROM trials").fetchone() == (2,)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--agent", "idm"], "--agent goes with --critical"),
        (["--critical", "--agent", "nosuch"], "unknown agent 'nosuch'"),
    ],
)
def test_a_bad_agent_option_stops_before_generation(
    extra: list[str], message: str, tmp_path: Path
) -> None:
    case = CASES["first_try"]
    out = tmp_path / "run"
    args = ["generate", case.description, "--replay", str(case.cassette), "--no-cache"]
    result = runner.invoke(app, [*args, "-o", str(out), *extra])
    assert result.exit_code == 2, result.output
    assert message in result.output and "Traceback" not in result.output
    assert not out.exists()


@pytest.mark.slow
def test_generate_critical_with_an_agent_gives_its_failing_instance(tmp_path: Path) -> None:
    pytest.importorskip("verifai", reason="the verifai extra is not installed")
    case = CASES["first_try"]
    out = tmp_path / "run"
    result = runner.invoke(
        app,
        ["generate", case.description, "--replay", str(case.cassette), "--no-cache"]
        + ["-o", str(out), "--critical", "--critical-trials", "2", "--agent", "blind"],
    )
    assert result.exit_code == 0, result.output
    assert "critical instance for the agent blind: trial" in result.output
    entry = json.loads((out / "report.json").read_text(encoding="utf-8"))["critical_search"]
    assert entry["agent"] == "blind" and entry["trials"] == 2
    assert entry["sampled"] is not None and entry["critical"] is not None
    folder = out / "search-blind"
    assert Path(entry["script"]) == folder / "critical" / "scenario.scenic"
    assert Path(entry["replay"]) == folder / "critical" / "replay.gif"
    assert Path(entry["replay"]).is_file()
    # The replay is blind's drive: the trace names its class as the ego's behavior.
    trace = (folder / "critical" / "trace.json").read_text(encoding="utf-8")
    assert "BlindAgent" in trace
    metrics = entry["critical_metrics"]
    assert 0.0 <= metrics["overall_score"] <= 1.0
    with sqlite3.connect(folder / "search.sqlite") as db:
        assert db.execute("SELECT agent FROM searches").fetchall() == [("blind",)]
        assert db.execute("SELECT count(*) FROM trials").fetchone() == (2,)
