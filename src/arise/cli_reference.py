"""The command reference, docs/cli.md, generated from the command line's own help.

A reference written by hand drifts from the options it describes; this one is rendered
from the Typer app itself: every command and sub-command with its usage line, its help
text, and each argument and option with its help, default, range and environment variable,
as the app's `--help` states them. The output depends on nothing but the app: no terminal
width, colour or Rich panels. `make cli-docs` writes docs/cli.md, and
tests/test_cli_reference.py fails when the committed file is not what this renders.

    python -m arise.cli_reference docs/cli.md
"""

from __future__ import annotations

import inspect
import re
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import typer
from typer.core import TyperArgument, TyperCommand, TyperGroup, TyperOption

from arise.atomic import write_text_atomic
from arise.errors import AriseError

PROGRAM = "arise"
GENERATOR = "src/arise/cli_reference.py"

# Outside code spans, Markdown would turn these into tags or emphasis; help means them literally.
_PROSE_SPECIALS = re.compile(r"([\\<*])")
_CODE_SPAN = re.compile(r"(`[^`]*`)")


@dataclass(frozen=True)
class Entry:
    """One command of the tree, with the context its help is rendered in."""

    path: tuple[str, ...]
    command: TyperCommand | TyperGroup
    context: typer.Context

    @property
    def title(self) -> str:
        return " ".join(self.path)

    @property
    def summary(self) -> str:
        return _help_text(self.command).split("\n\n", 1)[0].replace("\n", " ")


def _help_text(command: TyperCommand | TyperGroup) -> str:
    """The help as the app states it: dedented, cut at click's \\f, without \\b markers."""
    text = inspect.cleandoc(command.help or "").split("\f", 1)[0]
    return "\n".join(line for line in text.splitlines() if line.strip() != "\b").strip()


def walk(app: typer.Typer, program: str = PROGRAM) -> Iterator[Entry]:
    """Every visible command of `app`, depth first, in the order the app lists them."""
    root = typer.main.get_command(app)
    if not isinstance(root, TyperGroup):
        raise TypeError(f"{program}'s app is not a command group")
    yield from _walk(root, typer.Context(root, info_name=program), (program,))


def _walk(
    command: TyperCommand | TyperGroup, context: typer.Context, path: tuple[str, ...]
) -> Iterator[Entry]:
    yield Entry(path, command, context)
    if not isinstance(command, TyperGroup):
        return
    for name in command.list_commands(context):
        sub = command.get_command(context, name)
        if not isinstance(sub, TyperCommand | TyperGroup):
            raise TypeError(f"{' '.join(path)} {name} is not a Typer command")
        if sub.hidden:
            continue
        yield from _walk(sub, typer.Context(sub, info_name=name, parent=context), (*path, name))


def _prose(text: str) -> str:
    parts = _CODE_SPAN.split(text)  # odd items are `code spans`, kept as they are
    return "".join(
        part if i % 2 else _PROSE_SPECIALS.sub(r"\\\1", part) for i, part in enumerate(parts)
    )


def _help_markdown(text: str) -> list[str]:
    """Paragraphs stay prose; runs of indented paragraphs (the examples) become one code block."""
    lines: list[str] = []
    code: list[str] = []

    def flush_code() -> None:
        if code:
            lines.extend(["```text", *code, "```", ""])
            code.clear()

    for paragraph in text.split("\n\n"):
        rows = paragraph.splitlines()
        if rows and all(row.startswith("  ") for row in rows):
            code.extend(row[2:] for row in rows)
            continue
        flush_code()
        lines.extend([*_prose(paragraph).splitlines(), ""])
    flush_code()
    return lines


def _parameters(entry: Entry, kind: type[TyperArgument] | type[TyperOption]) -> list[str]:
    items = []
    for parameter in entry.command.params:
        if not isinstance(parameter, kind):
            continue
        record = parameter.get_help_record(entry.context)
        if record is None:  # hidden
            continue
        name, help_text = record
        help_text = re.sub(r"\s+", " ", help_text).strip()
        items.append(f"- `{name}`" + (f": {_prose(help_text)}" if help_text else ""))
    return items


def _usage(entry: Entry) -> str:
    pieces = entry.command.collect_usage_pieces(entry.context)
    return " ".join([entry.title, *pieces])


def _anchor(title: str) -> str:
    return "#" + title.lower().replace(" ", "-")


def render(app: typer.Typer, program: str = PROGRAM) -> str:
    """docs/cli.md for `app`: a contents list, then one section per command."""
    entries = list(walk(app, program))
    root, commands = entries[0], entries[1:]
    out = [
        "# Command reference",
        "",
        f"Generated from the command line's own help by `make cli-docs` ({GENERATOR}); "
        "do not edit by hand. Every command also takes `--help`.",
        "",
        *_help_markdown(_help_text(root.command)),
        "```text",
        _usage(root),
        "```",
        "",
    ]
    for entry in commands:
        indent = "  " * (len(entry.path) - 2)
        link = f"[`{entry.title}`]({_anchor(entry.title)})"
        out.append(f"{indent}- {link}: {_prose(entry.summary)}")
    out.append("")
    for entry in commands:
        heading = "#" * min(len(entry.path), 4)
        out += [f"{heading} `{entry.title}`", "", "```text", _usage(entry), "```", ""]
        out += _help_markdown(_help_text(entry.command))
        if isinstance(entry.command, TyperGroup):
            names = [e.title for e in commands if e.path[:-1] == entry.path]
            out += ["Commands: " + ", ".join(f"[`{n}`]({_anchor(n)})" for n in names), ""]
        for label, kind in (("Arguments", TyperArgument), ("Options", TyperOption)):
            items = _parameters(entry, kind)
            if items:
                out += [f"**{label}**", "", *items, ""]
    return "\n".join(out).rstrip("\n") + "\n"


def reference() -> str:
    """The reference of arise's own command line."""
    from arise.cli import app

    return render(app)


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 1:
        print("usage: python -m arise.cli_reference OUT.md", file=sys.stderr)
        return 2
    try:
        write_text_atomic(Path(args[0]), reference())
    except AriseError as error:
        print(f"error: {error}", file=sys.stderr)
        return error.exit_code
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
