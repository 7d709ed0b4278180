"""Run folders and forged results are untrusted input to `arise replay`, `arise export`
and the server's script check (issue 27).

A crafted trace.json names a secret or a planted Scenic cache as its map, holds NaN or
infinite numbers, thousands of agents or points, or is a link; a crafted report.json
points at another map folder; a script forges its result in a real worker. Every case
ends in a clear one-line error or correct, bounded output: never a crash (exit 70), a
traceback, an unpickled file, a copied secret or a file outside the output folder.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from arise.cli import CRASH_EXIT, app
from arise.maps.cache import trusted_entry
from arise.present.errors import RunNotFound
from arise.present.replay import write_replay
from arise.present.source import RunReport, load_trace, run_check_options
from arise.present.tracefile import TRACE_FILE, script_digest
from arise.present.xosc import write_export
from arise.validate import CheckOptions, WorkerPool
from tests.validate.planted import (
    SECRET_TEXT,
    STRAIGHT,
    files_under,
    forged_facts,
    forged_result,
    forging_script,
    holds_secret,
    plant,
)

runner = CliRunner()
SCRIPT = "param map = localPath('x.xodr')\nmodel scenic.simulators.carla.model\nego = new Car\n"


@pytest.fixture(autouse=True)
def own_cache(tmp_path: Path, request: pytest.FixtureRequest) -> Iterator[Path]:
    """A map cache of the test's own; tests with the warm pool share the pool's, the
    only one its confined worker may read."""
    folder = tmp_path / "cache"
    if "pool" in request.fixturenames:
        folder.symlink_to(request.getfixturevalue("pool_cache"))  # so "outside" skips it
        yield folder
        return
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("ARISE_CACHE_DIR", str(folder))
        yield folder


def make_run(folder: Path, trace: dict[str, Any] | None = None, **report: Any) -> Path:
    """A run folder as `arise generate` writes it, with the trace.json given (raw)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "scenario.scenic").write_text(SCRIPT, encoding="utf-8")
    content = {"status": "executed", "options": {"seed": 0, "steps": 20}, **report}
    (folder / "report.json").write_text(json.dumps(content), encoding="utf-8")
    if trace is not None:
        (folder / TRACE_FILE).write_text(json.dumps(trace), encoding="utf-8")  # NaN allowed
    return folder


def saved(map_name: str, map_path: Path | str, **simulation: Any) -> dict[str, Any]:
    return {
        "version": 1,
        "script_sha256": script_digest(SCRIPT),
        "map": {"requested": map_name, "name": map_name, "path": str(map_path)},
        "simulation": {**forged_facts(), **simulation},
        "seed": 0,
        "steps": 20,
    }


def _agent(name: str, points: int) -> dict[str, Any]:
    return {
        "name": name,
        "kind": "Car",
        "width": 2.0,
        "length": 4.5,
        "trajectory": [
            {"step": i, "x": float(i), "y": 0.0, "heading": 0.0, "speed": 1.0}
            for i in range(points)
        ],
    }


def invoke(tmp_path: Path, *args: str) -> tuple[int, str, set[Path]]:
    """Run the CLI; returns its exit code, output and the files it added outside the
    map cache."""
    before = files_under(tmp_path)
    result = runner.invoke(app, list(args))
    added = {p for p in files_under(tmp_path) - before if not p.is_relative_to(tmp_path / "cache")}
    output = result.output
    assert result.exit_code != CRASH_EXIT, output
    assert "Traceback" not in output, output
    return result.exit_code, output, added


def _one_line_error(output: str) -> str:
    errors = [line for line in output.splitlines() if line.startswith("error:")]
    assert len(errors) == 1, output
    return errors[0]


# --- a trace.json that names other files ---------------------------------------------------------
@pytest.mark.parametrize("command", ["replay", "export"])
def test_a_trace_naming_a_planted_snet_gets_our_map_by_name(tmp_path: Path, command: str) -> None:
    xodr, canary, _ = plant(tmp_path)
    run = make_run(tmp_path / "run", saved("arise_straight", xodr))
    out = tmp_path / "out"
    code, output, added = invoke(tmp_path, command, str(run), "--out", str(out))
    assert code == 0, output
    assert not canary.exists()
    assert added and all(p.is_relative_to(out) for p in added)
    if command == "export":
        assert (out / "arise_straight.xodr").read_bytes() == STRAIGHT.read_bytes()
    else:
        assert (out / "replay.gif").is_file() and (out / "replay.html").is_file()


@pytest.mark.parametrize("command", ["replay", "export"])
def test_a_trace_naming_a_secret_as_its_map_copies_nothing(tmp_path: Path, command: str) -> None:
    _, _, secret = plant(tmp_path)
    run = make_run(tmp_path / "run", saved("secret", secret))
    out = tmp_path / "out"
    code, output, added = invoke(tmp_path, command, str(run), "--out", str(out))
    assert code == 2
    assert "map secret of this trace is not available" in _one_line_error(output)
    assert SECRET_TEXT not in output
    assert holds_secret(tmp_path, exclude=secret.parent) == []
    assert all(p.is_relative_to(out) for p in added)
    assert not (out / "secret.xodr").exists()


def test_a_map_in_the_run_folder_is_used_only_as_a_plain_file(tmp_path: Path) -> None:
    _, _, secret = plant(tmp_path)
    run = make_run(tmp_path / "run", saved("mymap", "/nowhere/mymap.xodr"))
    (run / "mymap.xodr").write_bytes(STRAIGHT.read_bytes())
    out = tmp_path / "out"
    code, output, _ = invoke(tmp_path, "export", str(run), "--out", str(out))
    assert code == 0, output
    assert (out / "mymap.xodr").read_bytes() == STRAIGHT.read_bytes()
    (run / "mymap.xodr").unlink()
    (run / "mymap.xodr").symlink_to(secret)
    other = tmp_path / "other"
    code, output, _ = invoke(tmp_path, "export", str(run), "--out", str(other))
    assert code == 2 and "mymap.xodr" in _one_line_error(output)
    assert holds_secret(tmp_path, exclude=secret.parent) == []


@pytest.mark.parametrize(
    ("trace", "says"),
    [
        (saved("../planted/secret", "/etc/passwd"), "map.name"),
        (saved(".hidden", "x"), "map.name"),
        (saved("arise_straight", "x", timestep=math.nan), "finite number"),
        (saved("arise_straight", "x", agents=[_agent("ego", 3) | {"width": math.inf}]), "width"),
        (saved("arise_straight", "x", agents=[_agent("ego", 3) | {"length": -4.5}]), "length"),
        (saved("arise_straight", "x", agents=[_agent(f"a{i}", 2) for i in range(1500)]), "agents"),
        (saved("arise_straight", "x", agents=[_agent("ego", 30_000)]), "trajectory"),
        ({**saved("arise_straight", "x"), "extra": {"path": "/etc/passwd"}}, "extra"),
        ([1, 2, 3], "not a trace"),
    ],
    ids=[
        "dotdot-name",
        "hidden-name",
        "nan",
        "inf",
        "negative",
        "1500-agents",
        "30k-points",
        "unknown-field",
        "not-an-object",
    ],
)
@pytest.mark.parametrize("command", ["replay", "export"])
def test_a_malformed_trace_is_one_clear_error(
    tmp_path: Path, trace: Any, says: str, command: str
) -> None:
    run = make_run(tmp_path / "run")
    (run / TRACE_FILE).write_text(json.dumps(trace), encoding="utf-8")
    out = tmp_path / "out"
    code, output, added = invoke(tmp_path, command, str(run), "--out", str(out))
    assert code == 2, output
    line = _one_line_error(output)
    assert TRACE_FILE in line and says in line
    assert added == set()


def test_a_trace_that_is_a_link_or_huge_is_not_read(tmp_path: Path) -> None:
    _, _, secret = plant(tmp_path)
    run = make_run(tmp_path / "run")
    (run / TRACE_FILE).symlink_to(secret)
    code, output, added = invoke(tmp_path, "export", str(run), "--out", str(tmp_path / "o"))
    assert code == 2 and "symbolic link" in _one_line_error(output)
    assert SECRET_TEXT not in output and added == set()
    (run / TRACE_FILE).unlink()
    with open(run / TRACE_FILE, "wb") as handle:
        handle.truncate(200 * 2**20)  # sparse: no disk, but 200 MiB to read
    code, output, added = invoke(tmp_path, "replay", str(run), "--out", str(tmp_path / "o"))
    assert code == 2 and "the limit is 64.0 MiB" in _one_line_error(output)
    assert added == set()


def test_a_run_whose_script_or_report_is_a_link_is_refused(tmp_path: Path) -> None:
    _, _, secret = plant(tmp_path)
    run = make_run(tmp_path / "run", saved("arise_straight", "x"))
    (run / "report.json").unlink()
    (run / "report.json").symlink_to(secret)
    code, output, _ = invoke(tmp_path, "replay", str(run), "--out", str(tmp_path / "o"))
    assert code == 2 and "not a run folder" in _one_line_error(output)
    assert SECRET_TEXT not in output


def test_a_report_cannot_choose_the_maps_or_a_huge_time_limit(tmp_path: Path) -> None:
    chosen = run_check_options(
        RunReport.model_validate(
            {"status": "executed", "options": {"seed": 3, "steps": 50, "map_dir": str(tmp_path)}}
        ),
        None,
    )
    assert chosen.map_dir is None and chosen.seed == 3 and chosen.steps == 50
    run = make_run(tmp_path / "run", options={"check_timeout": 1e9, "map_dir": str(tmp_path)})
    with pytest.raises(RunNotFound, match="check_timeout"):
        load_trace(run)


# --- a script that forges its result, through replay, export and the server's check ----------------
@pytest.fixture(scope="module")
def pool_cache(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    folder = tmp_path_factory.mktemp("pool-cache")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("ARISE_CACHE_DIR", str(folder))
        yield folder


@pytest.fixture(scope="module")
def pool(pool_cache: Path) -> Iterator[WorkerPool]:
    with WorkerPool(size=1) as started:
        yield started


def _forger(tmp_path: Path) -> tuple[Path, Path, Path]:
    xodr, canary, secret = plant(tmp_path)
    script = tmp_path / "scripts" / "forger.scenic"
    script.parent.mkdir()
    script.write_text(forging_script(forged_result(xodr, secret, secret)), encoding="utf-8")
    return script, canary, secret


@pytest.mark.slow
def test_a_forged_result_replays_and_exports_on_the_parents_map(
    tmp_path: Path, pool: WorkerPool
) -> None:
    script, canary, secret = _forger(tmp_path)
    options = CheckOptions(seed=0, static_gate=False)
    source = load_trace(script, pool=pool, options=options)
    assert source.map is not None and source.map.name == "arise_intersection4"
    assert trusted_entry(source.map.path) is not None
    out = tmp_path / "out"
    before = files_under(tmp_path)
    write_replay(source, out)
    files = write_export(source, out)
    added = {p for p in files_under(tmp_path) - before if not p.is_relative_to(tmp_path / "cache")}
    assert all(p.is_relative_to(out) for p in added)
    assert files.xodr == out / "arise_intersection4.xodr"
    assert not canary.exists()
    assert holds_secret(tmp_path, exclude=secret.parent) == []


@pytest.mark.slow
def test_a_forged_result_in_the_servers_check(tmp_path: Path, pool: WorkerPool) -> None:
    from arise.present.replay import scene_for
    from arise.present.source import from_check
    from arise.render.html import replay_html
    from arise.serve.checks import check_script, result_view
    from arise.validate import check

    script, canary, secret = _forger(tmp_path)
    text = script.read_text(encoding="utf-8")
    # The server checks with the gate on: the forgery is refused before it runs ...
    view = check_script(text, tmp_path / "served", pool)
    assert view["ok"] is False and view["diagnostic"]["stage"] == "gate"
    # ... and a forgery that got past a gate gets the server's view on the parent's map.
    options = CheckOptions(seed=0, static_gate=False)
    result = check(script, options, pool=pool)
    assert "HOSTILE-FORGED" in result.warnings
    view = result_view(result, text)
    assert view["map"] == "arise_intersection4" and view["ok"] is True
    page = replay_html(scene_for(from_check(script, result, options)))
    assert "replay-data" in page
    assert not canary.exists()
    assert holds_secret(tmp_path, exclude=secret.parent) == []
    assert SECRET_TEXT not in json.dumps(view) + page
