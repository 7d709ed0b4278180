"""`arise search` as a user runs it: one-line errors, and a short search's files."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from arise.cli import app
from tests.conftest import DATA

runner = CliRunner()


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["search", "nowhere.scenic"], "no such file: nowhere.scenic"),
        (
            ["search", str(DATA / "base_crossing.scenic"), "--objective", "fast"],
            "unknown objective",
        ),
        (
            ["search", str(DATA / "base_crossing.scenic"), "--sampler", "ce,sa"],
            "unknown sampler 'sa'",
        ),
        (["search", str(DATA / "base_crossing.scenic"), "--executor", "dask"], "unknown executor"),
    ],
)
def test_bad_input_is_one_line(args: list[str], message: str, tmp_path: Path) -> None:
    result = runner.invoke(app, [*args, "--out", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert message in result.output
    assert "Traceback" not in result.output
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
def test_a_short_search_writes_its_files(tmp_path: Path) -> None:
    pytest.importorskip("verifai", reason="the verifai extra is not installed")
    out = tmp_path / "out"
    args = ["search", str(DATA / "verifai" / "cut_in.scenic"), "--trials", "2"]
    result = runner.invoke(app, [*args, "--sampler", "random", "--no-replay", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert "random trial 1:" in result.output
    summary = json.loads((out / "search.json").read_text(encoding="utf-8"))
    (search,) = summary["searches"]
    assert search["sampler"] == "random" and search["trials"] == 2
    assert [p["name"] for p in search["params"]] == [
        "EGO_SPEED",
        "CUTTER_SPEED",
        "CUTTER_LEAD",
        "CUT_AT",
    ]
    critical = (out / "critical" / "scenario.scenic").read_text(encoding="utf-8")
    assert "# searched in VerifaiRange(8, 12)" in critical
    assert (out / "objective.png").is_file() and (out / "trials.csv").is_file()
    again = runner.invoke(app, [*args, "--sampler", "random", "--no-replay", "--out", str(out)])
    assert again.exit_code == 0, again.output
    assert json.loads((out / "search.json").read_text())["searches"][0]["resumed"] == 2
