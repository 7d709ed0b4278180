"""`arise generate` leaves the replay and the OpenSCENARIO export beside every script that
ran (model answers replayed from a cassette, the real validator)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from PIL import Image
from typer.testing import CliRunner

from arise.cli import app
from arise.generate.pipeline import Generator
from arise.present.source import Origin, load_trace
from arise.present.verify import asam_check, read_back, worst_gap, xsd_errors
from arise.validate import WorkerPool
from tests.generate_cases import CASES

pytestmark = pytest.mark.slow


def test_an_executed_run_gets_trace_replay_and_export(
    tmp_path: Path, validator_pool: WorkerPool
) -> None:
    case = CASES["first_try"]
    with Generator(case.options(replay=str(case.cassette)), pool=validator_pool) as generator:
        run = generator.generate(case.description, tmp_path)
    assert run.ok
    report = json.loads((tmp_path / "report.json").read_text())
    for name in ("trace.json", "replay.gif", "replay.html", "scenario.xosc"):
        assert (tmp_path / name).is_file(), name
    assert (tmp_path / f"{report['map']}.xodr").is_file() or list(tmp_path.glob("*.xodr"))
    assert Image.open(tmp_path / "replay.gif").n_frames > 10
    xosc = tmp_path / "scenario.xosc"
    assert xsd_errors(xosc) == [] and asam_check(xosc).ok
    source = load_trace(tmp_path)  # the saved trace: nothing is simulated again
    assert source.origin is Origin.SAVED
    back = read_back(xosc)
    for agent in source.simulation.agents:
        assert worst_gap(agent, back[agent.name], source.simulation.timestep) <= 0.1
    # The same trace as the run's final check.
    final = run.final_attempt
    assert final is not None and final.check is not None and final.check.simulation is not None
    assert source.simulation.collisions == final.check.simulation.collisions
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []


def test_replay_of_a_garbage_script_exits_1_and_writes_nothing(tmp_path: Path) -> None:
    script = tmp_path / "garbage.scenic"
    script.write_text("ego = new Car at (0, 0\n", encoding="utf-8")
    result = CliRunner().invoke(app, ["replay", str(script)])
    assert result.exit_code == 1, result.output
    assert "did not run in the validator" in result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["garbage.scenic"]
