"""What `arise drive` takes from a script, a folder, a run folder or a prompt file: ids,
categories, and what an untrusted folder may not make it read."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from arise.drive.sources import (
    UNCATEGORISED,
    DriveSourceError,
    SourceKind,
    read_prompts,
    scenarios_of,
    source_kind,
)

SCRIPT = "model scenic.simulators.carla.model\nego = new Car\n"


def _run_folder(folder: Path, status: str = "executed", script: str = SCRIPT) -> Path:
    folder.mkdir(parents=True)
    (folder / "scenario.scenic").write_text(script)
    (folder / "report.json").write_text(json.dumps({"status": status, "options": {"seed": 3}}))
    return folder


def test_a_script_is_one_uncategorised_scenario(tmp_path: Path) -> None:
    script = tmp_path / "cut_in.scenic"
    script.write_text(SCRIPT)
    found = scenarios_of(script)
    assert found.kind is SourceKind.SCRIPT
    [scenario] = found.items
    assert (scenario.id, scenario.category, scenario.script) == ("cut_in", UNCATEGORISED, script)
    assert len(scenario.digest) == 64


def test_a_folder_gives_categories_from_its_sub_folders(tmp_path: Path) -> None:
    (tmp_path / "straight_obstacle").mkdir()
    (tmp_path / "straight_obstacle" / "so-1.scenic").write_text(SCRIPT)
    (tmp_path / "straight_obstacle" / "so-2.scenic").write_text(SCRIPT + "# two\n")
    (tmp_path / "loose.scenic").write_text(SCRIPT)
    (tmp_path / "notes.txt").write_text("not a script")
    _run_folder(tmp_path / "right_turn" / "rt-1")
    _run_folder(tmp_path / "right_turn" / "rt-2", status="failed")
    found = scenarios_of(tmp_path)
    assert found.kind is SourceKind.FOLDER
    assert [(s.id, s.category) for s in found.items] == [
        ("loose", UNCATEGORISED),
        ("right_turn/rt-1", "right_turn"),
        ("straight_obstacle/so-1", "straight_obstacle"),
        ("straight_obstacle/so-2", "straight_obstacle"),
    ]
    assert found.items[1].script == tmp_path / "right_turn" / "rt-1" / "scenario.scenic"
    # The run that never executed is said, not driven.
    assert len(found.skipped) == 1 and "never executed (status: failed)" in found.skipped[0]


def test_a_run_folder_drives_its_script_only_when_it_executed(tmp_path: Path) -> None:
    run = _run_folder(tmp_path / "turn")
    assert source_kind(run) is SourceKind.RUN_DIR
    [scenario] = scenarios_of(run).items
    assert scenario.id == "turn" and scenario.script == run / "scenario.scenic"
    failed = _run_folder(tmp_path / "failed", status="failed")
    with pytest.raises(DriveSourceError, match="no script to drive.*never executed"):
        scenarios_of(failed)
    marked = _run_folder(tmp_path / "marked", script="# ARISE: FAILED\n" + SCRIPT)
    with pytest.raises(DriveSourceError, match="never executed"):
        scenarios_of(marked)


def test_links_in_a_folder_are_not_followed(tmp_path: Path) -> None:
    secret = tmp_path / "secret.scenic"
    secret.write_text(SCRIPT)
    folder = tmp_path / "handed"
    (folder / "cat").mkdir(parents=True)
    (folder / "cat" / "ok.scenic").write_text(SCRIPT)
    os.symlink(secret, folder / "cat" / "link.scenic")
    os.symlink(tmp_path, folder / "loop")
    run = _run_folder(folder / "run")
    (run / "report.json").unlink()
    os.symlink(secret, run / "report.json")  # its report is a link: a plain folder, then
    found = scenarios_of(folder)
    assert [s.id for s in found.items] == ["cat/ok", "run/scenario"]
    assert sum("symbolic link" in line for line in found.skipped) == 2


def test_a_garbled_run_report_is_one_line(tmp_path: Path) -> None:
    run = _run_folder(tmp_path / "cat" / "run")
    (run / "report.json").write_text("{not json")
    with pytest.raises(DriveSourceError, match="not a run report"):
        scenarios_of(tmp_path)


@pytest.mark.parametrize(
    ("name", "message"),
    [
        ("missing.scenic", "does not exist"),
        ("notes.md", "is not a Scenic script"),
    ],
)
def test_a_bad_source_is_one_line(tmp_path: Path, name: str, message: str) -> None:
    path = tmp_path / name
    if name == "notes.md":
        path.write_text("hello")
    with pytest.raises(DriveSourceError, match=message):
        scenarios_of(path)


def test_an_empty_folder_has_nothing_to_drive(tmp_path: Path) -> None:
    with pytest.raises(DriveSourceError, match="holds no script to drive"):
        scenarios_of(tmp_path)


def test_prompt_files_give_ids_categories_and_safe_folders(tmp_path: Path) -> None:
    jsonl = tmp_path / "p.jsonl"
    jsonl.write_text(
        json.dumps({"id": "so-1", "category": "straight_obstacle", "description": "A car brakes."})
        + "\n# a comment\n\n"
        + json.dumps({"id": "../../etc", "description": "A cyclist stops."})
        + "\n"
    )
    assert source_kind(jsonl) is SourceKind.PROMPTS
    first, second = read_prompts(jsonl)
    assert first.folder == "straight_obstacle/so-1"
    assert second.folder == f"{UNCATEGORISED}/etc"  # no way out of OUT/scenarios
    txt = tmp_path / "p.txt"
    txt.write_text("right_turn\tThe ego turns right.\nA pedestrian crosses.\n")
    assert [(p.id, p.category) for p in read_prompts(txt)] == [
        ("p001", "right_turn"),
        ("p002", UNCATEGORISED),
    ]


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("{broken\n", "not JSON"),
        ('["a list"]\n', "expected an object"),
        ('{"id": "x"}\n', "no description"),
        ('{"id": "x", "description": "a"}\n{"id": "x", "description": "b"}\n', "used twice"),
        ("# only a comment\n", "no prompts"),
    ],
)
def test_a_bad_prompt_file_is_one_line(tmp_path: Path, text: str, message: str) -> None:
    path = tmp_path / "p.jsonl"
    path.write_text(text)
    with pytest.raises(DriveSourceError, match=message):
        read_prompts(path)


def test_a_folder_is_walked_to_a_bounded_depth(tmp_path: Path) -> None:
    deep = tmp_path.joinpath(*[f"d{i}" for i in range(9)])
    deep.mkdir(parents=True)
    (deep / "far.scenic").write_text(SCRIPT)
    (tmp_path / "d0" / "near.scenic").write_text(SCRIPT)
    found = scenarios_of(tmp_path)
    assert [s.id for s in found.items] == ["d0/near"]
    assert any("deeper than 6 folders" in line for line in found.skipped)
