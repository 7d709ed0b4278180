"""The command line handles errors once: one line for an AriseError, a crash report for a bug."""

from __future__ import annotations

from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

from arise.cli import CRASH_EXIT, AriseGroup, app
from arise.errors import AriseError, Interrupted
from arise.llm.types import ProviderUnavailable

runner = CliRunner()
demo = typer.Typer(cls=AriseGroup, add_completion=False, pretty_exceptions_enable=False)


@demo.command()
def mistake() -> None:
    raise AriseError("the [file] x.scenic does not exist")


@demo.command()
def model() -> None:
    raise ProviderUnavailable("llamacpp: cannot reach the server")


@demo.command()
def stopped() -> None:
    raise Interrupted("finished runs are saved; run the same command to resume")


@demo.command()
def bug() -> None:
    raise ZeroDivisionError("division by zero")


@demo.command()
def piped() -> None:
    raise BrokenPipeError(32, "Broken pipe")


def test_an_arise_error_is_one_line_with_its_exit_code() -> None:
    result = runner.invoke(demo, ["mistake"])
    assert result.exit_code == 2
    assert result.output.strip() == "error: the [file] x.scenic does not exist"
    result = runner.invoke(demo, ["model"])
    assert result.exit_code == 1 and "cannot reach" in result.output


def test_an_interruption_is_said_as_one_and_exits_130() -> None:
    result = runner.invoke(demo, ["stopped"])
    assert result.exit_code == 130
    assert result.output.strip() == (
        "interrupted: finished runs are saved; run the same command to resume"
    )


def test_a_bug_writes_a_crash_report_instead_of_a_traceback(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("ARISE_CACHE_DIR", str(tmp_path))
    result = runner.invoke(demo, ["bug"])
    assert result.exit_code == CRASH_EXIT
    assert "Traceback" not in result.output and "ZeroDivisionError" in result.output
    [report] = (tmp_path / "crashes").glob("crash-*.txt")
    assert str(report) in result.output.replace("\n", "")
    text = report.read_text()
    assert "Traceback" in text and "ZeroDivisionError: division by zero" in text


def test_usage_errors_stay_click_s(tmp_path: Path) -> None:
    result = runner.invoke(app, ["generate", "--no-such-option"])
    assert result.exit_code == 2 and "No such option" in result.output
    missing = runner.invoke(app, ["kb", "search", "a car brakes", "--backend", "tfidf"])
    assert missing.exit_code == 2 and "unknown retrieval backend" in missing.output


def test_a_closed_pipe_is_not_a_crash(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # `arise ... | head` closes our output early: no crash report, no traceback.
    monkeypatch.setenv("ARISE_CACHE_DIR", str(tmp_path))
    result = runner.invoke(demo, ["piped"])
    assert result.exit_code == 0
    assert "crashed" not in result.output and not (tmp_path / "crashes").exists()


@pytest.mark.parametrize("text", ["", "   ", "what is the capital of France?"])
def test_a_refused_description_exits_before_anything_loads(
    text: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # No model, no knowledge base, no validator worker: the refusal is all the user waits for.
    import arise.generate.batch as batch

    def no_generator(*_: object, **__: object) -> None:
        raise AssertionError("a refused description built a Generator")

    monkeypatch.setattr(batch, "Generator", no_generator)
    result = runner.invoke(app, ["generate", text, "--out", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert "description is empty" in result.output or "driving scenario" in result.output
    assert not (tmp_path / "out").exists()
