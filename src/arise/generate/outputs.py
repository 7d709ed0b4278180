"""What a generation leaves on disk: the script, the report, the picture, every attempt.

Files are written atomically (temporary file + rename), and the report is rewritten after
every attempt, so an interrupted run or a provider failure loses nothing already done.
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path
from typing import Any


def write_atomic(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        with os.fdopen(handle, "w", encoding="utf-8") as out:
            out.write(text)
        os.replace(temporary, path)
    finally:
        if os.path.exists(temporary):
            os.unlink(temporary)


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
    handle, temporary = tempfile.mkstemp(prefix=".scene.png.", dir=folder)
    try:
        with os.fdopen(handle, "wb") as out:
            out.write(picture.read_bytes())
        os.replace(temporary, target)
    finally:
        if os.path.exists(temporary):
            os.unlink(temporary)
