"""The bench report's 'critical after search': per category, the share of executed
scripts a search made critical; `arise report --search-trials N` fills it."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from arise.cli import app
from arise.evaluate.metrics import search_critical_rate
from arise.evaluate.records import BenchTask, RunRecord
from arise.evaluate.runner import BenchConfig, run_bench
from arise.evaluate.store import BenchStore
from arise.generate.options import GenerateOptions
from tests.evaluate.test_bench import prompts_and_cassette  # noqa: F401  (fixture)

runner = CliRunner()


def _run(status: str, search: dict[str, object] | None, index: int) -> RunRecord:
    task = BenchTask(f"p-{index}", "cat", "d", "arise", 0.0, 0)
    crit = {"collision": False} if search is None else {"collision": False, "search": search}
    return RunRecord(task=task, status=status, first_pass_ok=True, repairs=0, criticality=crit)


def test_share_of_searched_executed_runs_made_critical() -> None:
    runs = [
        _run("executed", {"critical": True}, 0),
        _run("executed", {"critical": False}, 1),
        _run("executed", {"critical": True}, 2),
        _run("executed", None, 3),  # not searched: not counted
        _run("failed", {"critical": True}, 4),  # never ran: not counted
    ]
    assert search_critical_rate(runs) == pytest.approx(2 / 3)
    assert search_critical_rate(runs[3:]) is None


@pytest.mark.slow
def test_report_with_search_trials_adds_the_column(
    tmp_path: Path,
    prompts_and_cassette: tuple[Path, Path],  # noqa: F811
) -> None:
    pytest.importorskip("verifai", reason="the verifai extra is not installed")
    from arise.evaluate.prompt_file import read_prompts

    prompts, cassette = prompts_and_cassette
    out = tmp_path / "bench"
    config = BenchConfig(
        prompts=read_prompts(prompts)[:1],
        base=GenerateOptions(replay=str(cassette), cache=False),
    )
    with BenchStore(out / "bench.sqlite") as store:
        run_bench(config, store, out)
    result = runner.invoke(app, ["report", str(out / "bench.sqlite"), "--search-trials", "2"])
    assert result.exit_code == 0, result.output
    assert "searched 1 executed run(s)" in result.output
    with BenchStore(out / "bench.sqlite") as store:
        (record,) = store.runs()
    search = (record.criticality or {})["search"]
    assert search["trials"] == 2 and isinstance(search["critical"], bool)
    report = (out / "report" / "report.md").read_text(encoding="utf-8")
    row = next(line for line in report.splitlines() if line.startswith("| critical after search"))
    assert ("1.000" if search["critical"] else "0.000") in row
    assert json.loads((Path(record.out_dir or "") / "search" / "search.json").read_text())
    # The same pass against an agent: its own folder, and the record says who drove.
    again = runner.invoke(
        app, ["report", str(out / "bench.sqlite"), "--search-trials", "2", "--agent", "blind"]
    )
    assert again.exit_code == 0, again.output
    with BenchStore(out / "bench.sqlite") as store:
        (record,) = store.runs()
    search = (record.criticality or {})["search"]
    assert search["agent"] == "blind" and search["trials"] == 2
    folder = Path(record.out_dir or "") / "search-blind"
    assert json.loads((folder / "search.json").read_text())["agent"] == "blind"


def test_report_refuses_a_bad_agent_before_searching(tmp_path: Path) -> None:
    database = tmp_path / "bench.sqlite"
    database.write_bytes(b"")
    result = runner.invoke(
        app, ["report", str(database), "--search-trials", "2", "--agent", "nosuch"]
    )
    assert result.exit_code == 2 and "unknown agent 'nosuch'" in result.output
