"""docs/cli.md is the command line's own help, regenerated and compared here."""

from __future__ import annotations

from pathlib import Path

import pytest
import typer

from arise import cli_reference
from arise.cli import app
from tests.conftest import REPO

COMMITTED = REPO / "docs" / "cli.md"


def test_the_committed_reference_is_the_current_help() -> None:
    assert COMMITTED.read_text(encoding="utf-8") == cli_reference.reference(), (
        "docs/cli.md no longer matches the command line's help: run `make cli-docs` "
        "and commit docs/cli.md"
    )


def test_every_command_and_option_is_in_the_reference() -> None:
    text = cli_reference.reference()
    entries = list(cli_reference.walk(app))
    assert len(entries) > 20
    for entry in entries[1:]:
        assert f"`{entry.title}`" in text
        for parameter in entry.command.params:
            if isinstance(parameter, typer.core.TyperOption) and not parameter.hidden:
                assert all(opt in text for opt in parameter.opts), (entry.title, parameter.opts)


def test_the_terminal_width_changes_nothing(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("COLUMNS", "40")
    narrow = cli_reference.reference()
    monkeypatch.setenv("COLUMNS", "250")
    assert cli_reference.reference() == narrow


toy = typer.Typer(help="A toy: the <root> of *everything*.", add_completion=False)
sub = typer.Typer(help="Things underneath.")
toy.add_typer(sub, name="things")


@toy.command("make")
def make(
    name: str = typer.Argument(..., help="What to make."),
    count: int = typer.Option(3, "--count", "-n", min=1, help="How many, a <number>."),
    secret: bool = typer.Option(False, "--secret", hidden=True, help="Never shown."),
) -> None:
    """Make something.

    It is made `<now>`.

    Examples:

      toy make cake -n 2

      toy make bread
    """


@sub.command("list")
def list_things() -> None:
    """List the things."""


def test_a_toy_app_renders_usage_help_examples_and_options() -> None:
    text = cli_reference.render(toy, program="toy")
    assert text.startswith("# Command reference\n")
    assert "A toy: the \\<root> of \\*everything\\*." in text  # prose escaped
    assert "It is made `<now>`." in text  # code spans left as they are
    assert "```text\ntoy make [OPTIONS] {name}\n```" in text
    assert "```text\ntoy make cake -n 2\ntoy make bread\n```" in text
    assert "- `-n, --count <int range>`: How many, a \\<number>. [default: 3; x>=1]" in text
    assert "- `name <str>`: What to make. [required]" in text
    assert "--secret" not in text
    assert "### `toy things list`" in text
    assert "  - [`toy things list`](#toy-things-list): List the things." in text


def test_main_writes_the_file_and_refuses_a_folder_it_cannot_write(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "cli.md"
    assert cli_reference.main([str(out)]) == 0
    assert out.read_text(encoding="utf-8") == cli_reference.reference()

    blocker = tmp_path / "file"
    blocker.write_text("not a folder", encoding="utf-8")
    assert cli_reference.main([str(blocker / "cli.md")]) == 2
    error = capsys.readouterr().err
    assert error.startswith("error: cannot write cli.md") and error.count("\n") == 1
    assert cli_reference.main([]) == 2
