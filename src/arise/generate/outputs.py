"""What a generation leaves on disk: the script, the report, the picture, every attempt.

Files are written whole (`arise.atomic`), and the report is rewritten after every attempt,
so an interrupted run or a provider failure loses nothing already done.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from arise.atomic import copy_file_atomic, write_text_atomic

#: A run's files stay private to the user, as they always were (mkstemp's mode).
RUN_FILE_MODE = 0o600


def write_atomic(path: Path, text: str) -> None:
    """One file of a run, whole or not at all (OutputError naming the folder otherwise)."""
    write_text_atomic(path, text, RUN_FILE_MODE)


def write_report(folder: Path, report: dict[str, Any]) -> None:
    write_atomic(folder / "report.json", json.dumps(report, indent=2, default=str) + "\n")


def write_script(folder: Path, script: str, ok: bool) -> Path:
    """scenario.scenic; a failed final script carries a first-line marker saying so."""
    text = (
        script
        if ok
        else (
            "# ARISE: FAILED - this script did not execute; see "
            "report.json for the last diagnostic\n" + script
        )
    )
    path = folder / "scenario.scenic"
    write_atomic(path, text)
    return path


def write_attempt(folder: Path, index: int, script: str) -> None:
    write_atomic(folder / "attempts" / f"attempt-{index:02d}.scenic", script)


def attempt_png(folder: Path, index: int) -> Path:
    """Where the picture of attempt `index` is drawn."""
    return folder / "attempts" / f"attempt-{index:02d}.png"


def write_scene_picture(folder: Path, picture: Path) -> None:
    """scene.png: the picture of the final script's attempt (none when it drew none)."""
    target = folder / "scene.png"
    if not picture.is_file():
        target.unlink(missing_ok=True)
        return
    copy_file_atomic(picture, target, mode=RUN_FILE_MODE)
