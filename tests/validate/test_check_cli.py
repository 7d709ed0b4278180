"""`arise check` as a user runs it: exit codes, JSON, the picture, clear errors."""

from __future__ import annotations

import json
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.conftest import DATA, EXAMPLES


def arise(*args: str, timeout: float = 300) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "arise", *args], capture_output=True, text=True, timeout=timeout
    )


@pytest.mark.slow
def test_check_example_writes_json_and_png(tmp_path: Path) -> None:
    png = tmp_path / "scene.png"
    run = arise(
        "check",
        str(EXAMPLES / "pedestrian_crossing.scenic"),
        "--json",
        "--seed",
        "1",
        "--png",
        str(png),
    )
    assert run.returncode == 0, run.stderr
    result = json.loads(run.stdout)
    assert result["ok"] is True
    assert result["map"]["name"] == "arise_straight"
    assert result["simulation"]["steps"] > 0
    assert {a["kind"] for a in result["simulation"]["agents"]} == {"Car", "Pedestrian"}
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert list(tmp_path.glob("*.png")) == [png], "no temporary file may be left behind"


@pytest.mark.slow
def test_failed_check_exits_1_with_a_readable_diagnostic() -> None:
    run = arise("check", str(DATA / "broken" / "scenic2_no_new.scenic"))
    assert run.returncode == 1
    assert "Traceback" not in run.stdout + run.stderr
    assert "parse" in run.stdout and "line 20" in run.stdout and "new" in run.stdout


@pytest.mark.slow  # a new `arise` process each (about 2 s)
def test_missing_file_is_a_clear_error(tmp_path: Path) -> None:
    run = arise("check", str(tmp_path / "nope.scenic"), "--json")
    assert run.returncode == 1
    assert json.loads(run.stdout)["diagnostic"]["error_type"] == "FileNotFoundError"
    assert "Traceback" not in run.stderr


@pytest.mark.slow  # a new `arise` process each (about 2 s)
def test_empty_and_garbage_scripts(tmp_path: Path) -> None:
    empty = tmp_path / "empty.scenic"
    empty.write_text("   \n")
    run = arise("check", str(empty), "--json")
    assert json.loads(run.stdout)["diagnostic"]["error_type"] == "EmptyScript"
    garbage = tmp_path / "garbage.scenic"
    garbage.write_bytes(b"\xff\xfe\x00 not text")
    run = arise("check", str(garbage), "--json")
    assert run.returncode == 1 and "UTF-8" in json.loads(run.stdout)["diagnostic"]["message"]


@pytest.mark.slow  # a new `arise` process each (about 2 s)
def test_bad_option_and_bad_map_dir_exit_2(tmp_path: Path) -> None:
    script = str(EXAMPLES / "pedestrian_crossing.scenic")
    assert arise("check", script, "--simulator", "gazebo").returncode == 2
    run = arise("check", script, "--map-dir", str(tmp_path / "missing"))
    assert run.returncode == 2 and "does not exist" in run.stderr


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


@pytest.mark.slow  # a new `arise` process each (about 2 s)
def test_unreachable_carla_fails_within_seconds() -> None:
    started = time.monotonic()
    run = arise(
        "check",
        str(EXAMPLES / "pedestrian_crossing.scenic"),
        "--simulator",
        "carla",
        "--carla-port",
        str(_free_port()),
        "--json",
    )
    assert time.monotonic() - started < 15
    diagnostic = json.loads(run.stdout)["diagnostic"]
    assert diagnostic["error_type"] == "CarlaUnreachable"
    assert "--carla-host" in diagnostic["message"]


@pytest.mark.slow  # a new `arise` process each (about 2 s)
def test_maps_list_shows_our_maps() -> None:
    run = arise("maps", "list")
    assert run.returncode == 0
    for name in ("arise_straight", "arise_intersection4", "arise_tjunction", "arise_highway"):
        assert name in run.stdout
