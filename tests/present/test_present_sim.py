"""Replay and export of scripts the real validator runs (Scenic's compiler and simulator,
confined worker) on the maps we ship, checked by the XSD, ASAM's checker and a round trip."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from PIL import Image

from arise.present.errors import ScriptDidNotRun
from arise.present.outputs import write_run_files
from arise.present.source import Origin, TraceSource, from_check, load_trace
from arise.present.verify import asam_check, read_back, worst_gap, xsd_errors
from arise.present.xosc import EgoMode, write_export
from arise.validate import CheckOptions, WorkerPool, check
from arise.validate.types import Stage
from tests.conftest import EXAMPLES
from tests.fakes import failed

pytestmark = pytest.mark.slow

SCRIPTS = [
    EXAMPLES / "pedestrian_crossing.scenic",
    *sorted((EXAMPLES / "categories").glob("*.scenic")),
]


def _verify_export(source: TraceSource, xosc: Path, ego_free: bool = False) -> None:
    assert xsd_errors(xosc) == []
    report = asam_check(xosc)
    assert report.ok, report.issues
    back = read_back(xosc)
    timestep = source.simulation.timestep
    for agent in source.simulation.agents:
        if not agent.trajectory:
            continue
        motion = back[agent.name]
        if agent.is_ego and ego_free:
            assert motion.times == []
            continue
        assert worst_gap(agent, motion, timestep) <= 0.1, agent.name


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.stem)
def test_every_example_gets_a_replay_and_a_valid_export(
    script: Path, validator_pool: WorkerPool, tmp_path: Path
) -> None:
    source = load_trace(script, pool=validator_pool, options=CheckOptions(seed=1, steps=120))
    assert source.origin is Origin.CHECKED
    files = write_run_files(source, tmp_path)
    gif = Image.open(files.replay.gif)
    assert gif.n_frames >= source.simulation.steps // 2
    page = files.replay.html.read_text(encoding="utf-8")
    assert "http://" not in page.split("<body>")[1] and "https://" not in page
    for agent in source.simulation.agents:
        assert f'"name":"{agent.name}"' in page
    _verify_export(source, files.export.xosc)
    assert files.export.xodr is not None and files.export.xodr.stat().st_size > 0


def test_ego_free_export_of_a_simulated_run(validator_pool: WorkerPool, tmp_path: Path) -> None:
    source = load_trace(
        EXAMPLES / "pedestrian_crossing.scenic", pool=validator_pool, options=CheckOptions(seed=2)
    )
    files = write_export(source, tmp_path, EgoMode.FREE)
    _verify_export(source, files.xosc, ego_free=True)


def test_a_run_folder_without_trace_is_checked_again_and_gives_the_same_scene(
    validator_pool: WorkerPool, tmp_path: Path
) -> None:
    script = EXAMPLES / "pedestrian_crossing.scenic"
    original = check(
        script, CheckOptions(seed=5, steps=100, sample_iterations=250), pool=validator_pool
    )
    assert original.ok and original.simulation is not None
    run = tmp_path / "run"
    run.mkdir()
    shutil.copy(script, run / "scenario.scenic")
    report = {"status": "executed", "options": {"seed": 5, "steps": 100, "check_timeout": 60}}
    (run / "report.json").write_text(json.dumps(report), encoding="utf-8")
    again = load_trace(run, pool=validator_pool)
    assert again.origin is Origin.CHECKED
    assert any("seed 5" in note for note in again.notes)
    assert again.simulation.collisions == original.simulation.collisions
    for first, second in zip(original.simulation.agents, again.simulation.agents, strict=True):
        assert first.trajectory == second.trajectory
    files = write_run_files(again, run)
    # Now the run folder has its trace, and a second look simulates nothing.
    assert load_trace(run).origin is Origin.SAVED
    assert files.trace.is_file()


def test_a_garbage_script_is_a_clear_error_and_writes_nothing(
    validator_pool: WorkerPool, tmp_path: Path
) -> None:
    script = tmp_path / "garbage.scenic"
    script.write_text("this is not ( a scenic script\n", encoding="utf-8")
    with pytest.raises(ScriptDidNotRun, match="did not run in the validator: parse"):
        load_trace(script, pool=validator_pool)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["garbage.scenic"]


@pytest.mark.carla_towns
def test_export_on_a_carla_town(
    validator_pool: WorkerPool, carla_maps: Path, tmp_path: Path
) -> None:
    source = load_trace(
        EXAMPLES / "categories" / "straight_obstacle.scenic",
        pool=validator_pool,
        map_dir=str(carla_maps),
        options=CheckOptions(seed=1, steps=100),
    )
    assert source.map is not None and source.map.name.startswith("Town")
    files = write_run_files(source, tmp_path, map_dir=str(carla_maps))
    _verify_export(source, files.export.xosc)
    assert files.export.xodr is not None
    assert files.export.xodr.read_bytes() == (carla_maps / f"{source.map.name}.xodr").read_bytes()


def test_a_script_the_semantic_gate_faulted_still_gets_its_replay(
    validator_pool: WorkerPool, tmp_path: Path
) -> None:
    script = EXAMPLES / "pedestrian_crossing.scenic"
    options = CheckOptions(seed=1, steps=60)
    ran = check(script, options, pool=validator_pool)
    assert ran.ok and ran.simulation is not None
    faulted = ran.model_copy(
        update={"ok": False, "diagnostic": failed(Stage.SEMANTIC, "ConformityMismatch").diagnostic}
    )
    source = from_check(script, faulted, options)
    files = write_run_files(source, tmp_path)
    assert files.replay.gif.is_file() and files.export.xosc.is_file()
    crashed = ran.model_copy(update={"ok": False, "diagnostic": failed().diagnostic})
    with pytest.raises(ScriptDidNotRun, match="did not run in the validator: simulate"):
        from_check(script, crashed, options)
