"""Untrusted text on the terminal: control characters spelled out, markup inert, length
capped; and `arise check` printing hostile diagnostics and file names that way."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import typer
from rich.markup import render
from typer.testing import CliRunner

from arise import terminal
from arise.cli import AriseGroup, app
from arise.errors import AriseError
from arise.validate import cli as validate_cli
from arise.validate.types import CheckResult, Diagnostic, Rejection, Stage

OSC52 = "\x1b]52;c;SGVsbG8=\x07"  # writes "Hello" to the clipboard
CLEAR = "\x1b[2J\x1b[H"  # clears the screen
HOSTILE = f"x{OSC52}[/x]{CLEAR}\r OK \u202eevil\x9b1m\x7f"


def test_control_characters_become_visible_escapes() -> None:
    text = terminal.shown(HOSTILE)
    assert text == ("x\\x1b]52;c;SGVsbG8=\\x07[/x]\\x1b[2J\\x1b[H\\x0d OK \\u202eevil\\x9b1m\\x7f")
    assert all(c.isprintable() for c in text)


def test_newlines_and_tabs_stay_in_a_message_but_not_in_a_name() -> None:
    assert terminal.shown("a\n\tb") == "a\n\tb"
    assert terminal.shown("a\n\tb", one_line=True) == "a\\n\\tb"
    assert terminal.name("dir/\x1b[31mred\u2066.scenic") == "dir/\\x1b[31mred\\u2066.scenic"


def test_every_bidi_control_is_escaped() -> None:
    controls = [*range(0x202A, 0x202F), *range(0x2066, 0x206A)]
    shown = terminal.shown("".join(chr(c) for c in controls))
    assert shown == "".join(f"\\u{c:04x}" for c in controls)


def test_long_text_is_cut_with_a_count() -> None:
    text = terminal.shown("a" * 10_000)
    assert text == "a" * terminal.MAX_SHOWN + f"... ({10_000 - terminal.MAX_SHOWN} more characters)"
    assert terminal.name("b" * 300).endswith("... (44 more characters)")
    assert terminal.shown("short") == "short"


@pytest.mark.parametrize(
    "value",
    [
        "[/x]",
        "[bold]not bold[/bold]",
        "\\[b]",
        "\\\\[b]",
        "a\\[1]",
        "[link=file:///etc/passwd]x[/link]",
        "[@click=app.bell]x[/]",
        "[a[b]c]",
        "ends with \\",
        "\\" * 5000 + "[/x]",
        "[a]" * 2000,
    ],
)
def test_escaped_markup_renders_exactly_as_written(value: str) -> None:
    escaped = terminal.escape_markup(value)
    assert render(f"[red]{escaped}[/red]").plain == value
    assert render(escaped + "[red]after[/red]").plain == value + "after"


def test_text_is_never_parsed_as_markup_and_never_highlighted() -> None:
    console = terminal.console()
    with console.capture() as captured:
        console.print(terminal.text(("error:", "red"), " ", HOSTILE, " 127.0.0.1 [/x]"))
    out = captured.get()
    assert "\x1b]" not in out and "\x07" not in out and "\r" not in out
    assert "[/x]" in out and "\\x1b]52;c;SGVsbG8=\\x07" in out
    assert "\u202e" not in out


runner = CliRunner()


def test_check_prints_hostile_file_names_escaped_and_keeps_the_batch(tmp_path: Path) -> None:
    missing = tmp_path / f"gone{OSC52}[/x].scenic"
    empty = tmp_path / f"empty{CLEAR}[bold].scenic"
    empty.write_text("  \n")
    run = runner.invoke(app, ["check", str(missing), str(empty)])
    assert run.exit_code == 1, run.output  # two failed checks, not a crash (70)
    assert "\x1b" not in run.output and "\x07" not in run.output
    assert "gone\\x1b]52;c;SGVsbG8=\\x07[/x].scenic" in run.output
    assert "empty\\x1b[2J\\x1b[H[bold].scenic" in run.output
    assert "0 of 2 scripts executed" in run.output
    assert "crashed" not in run.output


def test_json_output_keeps_the_names_as_data(tmp_path: Path) -> None:
    missing = tmp_path / f"gone{OSC52}.scenic"
    run = runner.invoke(app, ["check", str(missing), "--json"])
    assert run.exit_code == 1
    assert "\x1b" not in run.output  # JSON spells it \u001b
    assert json.loads(run.output)["script"] == str(missing)


def test_an_error_message_with_escapes_and_markup_is_one_escaped_line() -> None:
    demo = typer.Typer(cls=AriseGroup, add_completion=False, pretty_exceptions_enable=False)

    @demo.command()
    def hostile() -> None:
        raise AriseError(f"cannot read {HOSTILE}")

    @demo.command()
    def other() -> None:  # a second command: typer makes a lone one the root
        pass

    run = runner.invoke(demo, ["hostile"])
    assert run.exit_code == 2  # the AriseError's code, not a crash
    assert run.output.strip() == "error: cannot read " + terminal.shown(HOSTILE)


def _arise(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "arise", *args], capture_output=True, text=True, timeout=300
    )


@pytest.mark.slow
def test_a_diagnostic_excerpt_with_escapes_and_markup_prints_escaped(tmp_path: Path) -> None:
    script = tmp_path / "excerpt.scenic"
    script.write_text(
        f'model scenic.simulators.carla.model\nego = new Car\nx = "{OSC52}[/x]{CLEAR}" +\n'
    )
    run = _arise("check", str(script))
    assert run.returncode == 1, run.stderr
    assert "\x1b" not in run.stdout + run.stderr
    assert '> 3 | x = "\\x1b]52;c;SGVsbG8=\\x07[/x]\\x1b[2J\\x1b[H" +' in run.stdout


def test_a_forged_diagnostic_prints_escaped_and_cut_without_the_highlighter(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # A script's forged result: every field of the diagnostic at its schema's limit, full
    # of what rich's highlighter matches (numbers, IPs, paths) and of escapes and markup.
    # Highlighted, a 250 KB message took minutes; here it is cut to MAX_SHOWN.
    filler = "1.2.3.4 /etc/x 0x1f [/x] " * 2600  # 65,000 characters
    result = CheckResult(
        ok=False,
        script=f"forged{OSC52}.scenic",
        diagnostic=Diagnostic(
            stage=Stage.SIMULATE,
            error_type="Forged[/x]",
            message=HOSTILE + filler[: 64 * 1024 - len(HOSTILE)],
            excerpt=f"> 3 | {CLEAR}",
            hint=f"[link=https://example.com]{HOSTILE}",
            section="A\x1b[2J",
            line=3,
            rejections=[Rejection(reason=f"{OSC52}[/x]", count=2)],
        ),
        warnings=[f"{CLEAR}OK"],
    )
    validate_cli._print_result(result)
    out = capsys.readouterr().out
    assert "\x1b" not in out and "\x07" not in out and "\r" not in out
    assert "Forged[/x]" in out and "section A\\x1b[2J" in out
    assert "more characters)" in out
    assert len(out) < 5 * terminal.MAX_SHOWN
    assert "\\x1b[2J\\x1b[HOK" in out and "rejected 2x: \\x1b]52;c;SGVsbG8=\\x07[/x]" in out
