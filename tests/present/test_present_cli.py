"""`arise replay` and `arise export` on run folders with a saved trace (no simulation), and
the clear errors for what cannot be shown."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from PIL import Image
from typer.testing import CliRunner

from arise.cli import app
from arise.present.errors import RunNotExecuted, RunNotFound
from arise.present.source import Origin, load_trace
from arise.present.tracefile import TRACE_FILE, read_trace, write_trace
from arise.present.verify import xsd_errors
from tests.present.traces import STEPS, source

runner = CliRunner()
SCRIPT = "param map = localPath('x.xodr')\nmodel scenic.simulators.carla.model\nego = new Car\n"


def make_run(folder: Path, status: str = "executed", trace: bool = True) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "scenario.scenic").write_text(SCRIPT, encoding="utf-8")
    report = {"status": status, "options": {"seed": 0, "steps": STEPS}}
    (folder / "report.json").write_text(json.dumps(report), encoding="utf-8")
    if trace:
        write_trace(folder, source(folder / "scenario.scenic").saved())
    return folder


def _leftovers(folder: Path) -> list[str]:
    return [p.name for p in folder.iterdir() if p.name.startswith(".")]


def test_a_saved_trace_is_used_as_it_is(tmp_path: Path) -> None:
    run = make_run(tmp_path / "run")
    loaded = load_trace(run)
    assert loaded.origin is Origin.SAVED
    assert [a.name for a in loaded.simulation.agents] == ["ego", "Pedestrian1", "Car1", "Cone1"]


def test_a_trace_of_another_script_is_not_used(tmp_path: Path) -> None:
    run = make_run(tmp_path / "run")
    (run / "scenario.scenic").write_text(SCRIPT + "# edited\n", encoding="utf-8")
    assert read_trace(run, (run / "scenario.scenic").read_text()) is None


def test_replay_command_writes_gif_and_html(tmp_path: Path) -> None:
    run = make_run(tmp_path / "run")
    result = runner.invoke(app, ["replay", str(run), "--png"])
    assert result.exit_code == 0, result.output
    assert "trace: saved" in result.output
    gif = Image.open(run / "replay.gif")
    assert gif.n_frames == STEPS // 2 + 1
    assert "replay-data" in (run / "replay.html").read_text()
    assert Image.open(run / "scene.png").format == "PNG"
    assert _leftovers(run) == []


def test_export_command_writes_xosc_and_xodr_to_out(tmp_path: Path) -> None:
    run = make_run(tmp_path / "run")
    out = tmp_path / "elsewhere"
    result = runner.invoke(app, ["export", str(run), "--out", str(out), "--ego", "free"])
    assert result.exit_code == 0, result.output
    assert xsd_errors(out / "scenario.xosc") == []
    assert (out / "arise_straight.xodr").is_file()
    assert (out / TRACE_FILE).is_file()
    assert not (run / "scenario.xosc").exists()
    assert "3 agents" in result.output  # the ego is left to the system under test
    assert _leftovers(out) == []


def test_a_missing_run_folder_is_a_clear_error(tmp_path: Path) -> None:
    with pytest.raises(RunNotFound, match="does not exist"):
        load_trace(tmp_path / "nowhere")
    result = runner.invoke(app, ["replay", str(tmp_path / "nowhere")])
    assert result.exit_code == 2
    assert "does not exist" in result.output and "Traceback" not in result.output


def test_a_folder_that_is_no_run_is_a_clear_error(tmp_path: Path) -> None:
    (tmp_path / "empty").mkdir()
    with pytest.raises(RunNotFound, match="not a run folder"):
        load_trace(tmp_path / "empty")


def test_a_file_that_is_no_script_is_a_clear_error(tmp_path: Path) -> None:
    other = tmp_path / "notes.txt"
    other.write_text("hello")
    with pytest.raises(RunNotFound, match="not a Scenic script"):
        load_trace(other)


def test_a_run_that_never_executed_is_refused_and_nothing_is_written(tmp_path: Path) -> None:
    run = make_run(tmp_path / "run", status="failed", trace=False)
    before = sorted(p.name for p in run.iterdir())
    with pytest.raises(RunNotExecuted, match="never executed"):
        load_trace(run)
    result = runner.invoke(app, ["export", str(run)])
    assert result.exit_code == 2 and "never executed" in result.output
    assert sorted(p.name for p in run.iterdir()) == before


def test_a_failed_script_marker_is_refused_even_with_a_wrong_status(tmp_path: Path) -> None:
    run = make_run(tmp_path / "run", trace=False)
    (run / "scenario.scenic").write_text("# ARISE: FAILED - x\n" + SCRIPT, encoding="utf-8")
    with pytest.raises(RunNotExecuted):
        load_trace(run)


def test_an_unreadable_report_is_a_clear_error(tmp_path: Path) -> None:
    run = make_run(tmp_path / "run", trace=False)
    (run / "report.json").write_text("{not json", encoding="utf-8")
    with pytest.raises(RunNotFound, match="cannot be read"):
        load_trace(run)


def test_help_texts_have_examples() -> None:
    for command in ("replay", "export"):
        result = runner.invoke(app, [command, "--help"])
        assert result.exit_code == 0 and "Examples" in result.output
