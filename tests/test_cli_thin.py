"""No CLI module prints an error by hand: each raises an AriseError, and the one handler in
arise.cli prints it (escaped, on one line) and exits with the error's code.

The source of every CLI module is read as a syntax tree, so a new command that slips back
into `errors.print("[red]error: ...")` + `raise typer.Exit(2)` fails here at once.
"""

from __future__ import annotations

import ast
import builtins
import importlib
from pathlib import Path

import pytest
from typer.testing import CliRunner

from arise.cli import app
from arise.errors import AriseError

SRC = Path(__file__).resolve().parents[1] / "src"
ROOT_CLI = SRC / "arise" / "cli.py"
CLI_FILES = sorted({*SRC.glob("arise/**/cli.py"), *SRC.glob("arise/**/*_cli.py")})

#: The modules that may catch an AriseError: only the root, whose AriseGroup is the one
#: handler every command's errors reach.
HANDLERS = {ROOT_CLI}


def _module(path: Path) -> str:
    return ".".join(path.relative_to(SRC).with_suffix("").parts)


def _is_typer_exit(node: ast.Call) -> bool:
    func = node.func
    return (isinstance(func, ast.Attribute) and func.attr == "Exit") or (
        isinstance(func, ast.Name) and func.id == "Exit"
    )


def _exit_code(node: ast.Call) -> ast.expr | None:
    if node.args:
        return node.args[0]
    return next((k.value for k in node.keywords if k.arg == "code"), None)


def hand_made_errors(path: Path) -> list[str]:
    """Where `path` prints an error itself or ends with a fixed error code."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found: list[str] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and _is_typer_exit(node):
            code = _exit_code(node)
            # A literal non-zero code is an error said by hand; a computed code (0 if
            # every script ran else 1) is the command's verdict on its results.
            if isinstance(code, ast.Constant) and code.value not in (0, None):
                found.append(f"line {node.lineno}: typer.Exit({code.value})")
        elif isinstance(node, ast.Constant) and isinstance(node.value, str):
            text = node.value.lower()
            if "[red]error" in text or text.lstrip().startswith(("error:", "interrupted:")):
                found.append(f"line {node.lineno}: prints {node.value[:40]!r}")
    return found


def second_handlers(path: Path) -> list[str]:
    """`except` clauses of `path` that catch an AriseError (or Ctrl-C) instead of letting
    it reach the one handler."""
    module = importlib.import_module(_module(path))
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found: list[str] = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.ExceptHandler) or node.type is None:
            continue
        names = node.type.elts if isinstance(node.type, ast.Tuple) else [node.type]
        for name in names:
            label = ast.unparse(name)
            caught = getattr(module, label, None) or getattr(builtins, label, None)
            if isinstance(caught, type) and issubclass(caught, (AriseError, KeyboardInterrupt)):
                found.append(f"line {node.lineno}: except {label}")
    return found


def test_the_scan_sees_every_command_module() -> None:
    names = {_module(path) for path in CLI_FILES}
    assert {
        "arise.cli",
        "arise.generate.cli",
        "arise.generate.warm_cli",
        "arise.validate.cli",
        "arise.evaluate.cli",
        "arise.evaluate.judge_cli",
        "arise.evaluate.search.cli",
        "arise.kb.cli",
        "arise.llm.cli",
        "arise.present.cli",
        "arise.serve.cli",
    } <= names


@pytest.mark.parametrize("path", CLI_FILES, ids=_module)
def test_no_cli_module_prints_an_error_by_hand(path: Path) -> None:
    assert hand_made_errors(path) == []


@pytest.mark.parametrize("path", [p for p in CLI_FILES if p not in HANDLERS], ids=_module)
def test_no_cli_module_has_an_error_handler_of_its_own(path: Path) -> None:
    assert second_handlers(path) == []


def test_the_scan_finds_what_it_looks_for(tmp_path: Path) -> None:
    # The pattern this test forbids, and a second handler: both found.
    sample = tmp_path / "cli.py"
    sample.write_text(
        "import typer\n"
        "def command(errors):\n"
        "    errors.print('[red]error:[/red] no such file')\n"
        "    raise typer.Exit(2)\n"
        "def verdict(ok):\n"
        "    raise typer.Exit(0 if ok else 1)\n"
    )
    assert sorted(line.split(":")[0] for line in hand_made_errors(sample)) == ["line 3", "line 4"]
    assert second_handlers(SRC / "arise" / "cli.py"), "the root handler catches AriseError"


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["blueprints", "spaceship"], "error: unknown category 'spaceship'; choose from "),
        (["kb", "show", "weather.nowhere"], "error: no entry 'weather.nowhere'"),
        (["kb", "validate", "--entry", "no.such"], "error: no such entries: no.such"),
        (["maps", "list", "--map-dir", "/nonexistent/maps"], "error: "),
        (["generate"], "error: give a description or --file"),
        (["generate", "--file", "/nonexistent/prompts.txt"], "error: no such file: "),
        (["report", "/nonexistent/bench.sqlite"], "error: no such database: "),
        (["bench", "prompts.txt", "--executor", "slurm"], "error: --executor is one of local"),
    ],
)
def test_mistakes_are_one_line_from_the_one_handler(args: list[str], message: str) -> None:
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(message), result.output
