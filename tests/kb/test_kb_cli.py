"""`arise kb ...` end to end through the real command line app."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from arise.cli import app

runner = CliRunner()


def test_list_and_show() -> None:
    result = runner.invoke(app, ["kb", "list", "--component", "weather"])
    assert result.exit_code == 0, result.output
    assert "weather.clear_noon" in result.output and "behavior." not in result.output
    shown = runner.invoke(app, ["kb", "show", "behavior.sudden_brake"])
    assert shown.exit_code == 0 and "AdversaryBehavior" in shown.output
    missing = runner.invoke(app, ["kb", "show", "behavior.sudden_brak"])
    assert missing.exit_code == 2


def test_search_bm25() -> None:
    result = runner.invoke(
        app,
        [
            "kb",
            "search",
            "the car in front slams on its brakes",
            "--component",
            "behavior",
            "--backend",
            "bm25",
            "-k",
            "2",
        ],
    )
    assert result.exit_code == 0, result.output
    assert "behavior.sudden_brake" in result.output


def test_bad_user_file_is_reported_and_the_rest_still_works(tmp_path: Path) -> None:
    (tmp_path / "weather.yaml").write_text(
        "entries:\n  - id: weather.user_fog\n    snippet: \"param weather = 'ClearNoon'\"\n",
        encoding="utf-8",
    )
    result = runner.invoke(app, ["kb", "list", "--kb-dir", str(tmp_path), "-c", "weather"])
    assert result.exit_code == 0
    assert "weather.yaml" in result.output and "weather.user_fog" in result.output
    assert "descriptions" in result.output and "weather.clear_noon" in result.output


@pytest.mark.slow
def test_validate_one_entry() -> None:
    result = runner.invoke(app, ["kb", "validate", "--entry", "weather.dense_fog"])
    assert result.exit_code == 0, result.output
    assert "1/1 entries proven" in result.output
