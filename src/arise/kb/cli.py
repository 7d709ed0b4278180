"""`arise kb`: list, show, search and validate the knowledge base (ours plus the user's)."""

from __future__ import annotations

import json
from typing import Annotated

import typer
from rich.syntax import Syntax
from rich.table import Table

from arise import terminal
from arise.kb.loader import ENV_VAR, KnowledgeBase, load_kb
from arise.kb.schema import Component
from arise.kb.select import find_entry, select_ids
from arise.limits import MAX_STEPS

console = terminal.console()
errors = terminal.console(stderr=True)

app = typer.Typer(
    name="kb",
    help="The knowledge base of validated Scenic 3 snippets: list, show, search, validate.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)

KbDirs = Annotated[
    list[str] | None,
    typer.Option(
        "--kb-dir",
        help=f"a folder of your own entries that extends ours (repeatable; also "
        f"{ENV_VAR}, path-separated)",
    ),
]
ComponentOpt = Annotated[
    Component | None, typer.Option("--component", "-c", help="only this component")
]


def _load(kb_dirs: list[str] | None) -> KnowledgeBase:
    """Load everything; a bad user file is reported, and the rest still loads."""
    kb = load_kb(kb_dirs or ())
    for problem in kb.problems:
        errors.print(terminal.text(("skipped:", "yellow"), " ", problem))
    return kb


@app.command("list")
def list_command(kb_dirs: KbDirs = None, component: ComponentOpt = None) -> None:
    """List entries: id, component, first description, adversary classes."""
    kb = _load(kb_dirs)
    table = Table(show_lines=False)
    table.add_column("id", no_wrap=True)
    for column in ("description", "adversaries", "map features"):
        table.add_column(column)
    for entry in kb:
        if component is not None and entry.component is not component:
            continue
        table.add_row(
            terminal.text(terminal.name(entry.id)),
            terminal.text(entry.descriptions[0]),
            terminal.text(", ".join(entry.adversaries) or "any"),
            terminal.text(", ".join(entry.map_features)),
        )
    console.print(table)
    counts = kb.counts()
    console.print(
        ", ".join(f"{name}: {count}" for name, count in counts.items()) + f"; {len(kb)} entries"
    )


@app.command("show")
def show_command(
    entry_id: Annotated[str, typer.Argument(help="entry id")], kb_dirs: KbDirs = None
) -> None:
    """Show one entry: descriptions, interface and snippet."""
    entry = find_entry(_load(kb_dirs), entry_id)  # UnknownEntry: one line, exit 2
    console.print(
        terminal.text(
            (terminal.name(entry.id), "bold"),
            f"  ({entry.component.value}, from ",
            terminal.name(entry.source),
            ")",
        )
    )
    for description in entry.descriptions:
        console.print(terminal.text("  - ", description))
    for label, values in (
        ("defines", entry.defines),
        ("needs", entry.needs),
        ("params", entry.params),
        ("placeholders", entry.placeholders),
        ("adversaries", entry.adversaries),
        ("map features", entry.map_features),
        ("tags", entry.tags),
        ("companions", entry.companions),
    ):
        if values:
            console.print(terminal.text(f"  {label}: ", ", ".join(values)))
    snippet = terminal.shown(entry.snippet, terminal.MAX_SCRIPT_SHOWN)
    console.print(Syntax(snippet, "python", line_numbers=False))


@app.command("search")
def search_command(
    query: Annotated[str, typer.Argument(help="what you are looking for, in your words")],
    component: ComponentOpt = None,
    k: Annotated[int, typer.Option("-k", help="results per component")] = 2,
    backend: Annotated[str, typer.Option(help="auto | bm25 | embedding | hybrid")] = "auto",
    model: Annotated[str | None, typer.Option(help="local embedding model folder")] = None,
    kb_dirs: KbDirs = None,
) -> None:
    """Top-k entries per component for a description (BM25 unless a model is present)."""
    from arise.kb.retrieval import make_retriever

    kb = _load(kb_dirs)
    retriever = make_retriever(kb, backend, model)  # RetrieverError: one line, exit 2
    components = [component] if component is not None else list(Component)
    table = Table(title=terminal.text("backend: ", terminal.name(retriever.name)))
    for column in ("component", "rank"):
        table.add_column(column)
    table.add_column("id", no_wrap=True)
    for column in ("score", "description"):
        table.add_column(column)
    for chosen in components:
        for rank, hit in enumerate(retriever.search(query, chosen, k), start=1):
            table.add_row(
                chosen.value,
                str(rank),
                terminal.text(terminal.name(hit.entry.id)),
                f"{hit.score:.3f}",
                terminal.text(hit.entry.descriptions[0]),
            )
    console.print(table)


@app.command("validate")
def validate_command(
    kb_dirs: KbDirs = None,
    component: ComponentOpt = None,
    entry: Annotated[
        list[str] | None, typer.Option("--entry", "-e", help="only this entry (repeatable)")
    ] = None,
    workers: Annotated[int, typer.Option(help="validator workers in parallel")] = 2,
    seed: Annotated[int, typer.Option(help="random seed for every script")] = 1,
    steps: Annotated[
        int, typer.Option(min=1, max=MAX_STEPS, help="simulation steps per script")
    ] = 200,
    as_json: Annotated[bool, typer.Option("--json", help="print the report as JSON")] = False,
    show_scripts: Annotated[bool, typer.Option(help="print each composed script")] = False,
) -> None:
    """Lint every entry, compose covering scripts and run each through the validator.

    Exit code 0 when every entry is proven, 1 otherwise (a bad user file counts).
    """
    from arise.kb.runner import ScriptOutcome, validate_kb
    from arise.validate import CheckOptions
    from arise.validate.types import confinement_summary

    kb = _load(kb_dirs)
    only = select_ids(kb, component, entry or ())  # UnknownEntry: one line, exit 2

    def progress(outcome: ScriptOutcome) -> None:
        if as_json:
            return
        mark = ("✔", "green") if outcome.ok else ("✘", "red")
        console.print(terminal.text(mark, f" {outcome.seconds:5.1f}s ", outcome.describe()))
        if show_scripts:
            script = terminal.shown(outcome.composition.script(), terminal.MAX_SCRIPT_SHOWN)
            console.print(Syntax(script, "python", line_numbers=True))

    options = CheckOptions(seed=seed, steps=steps, timeout=90)
    report = validate_kb(kb, only=only, options=options, workers=workers, on_outcome=progress)
    if as_json:  # ensure_ascii: a control character in a name stays an escape
        print(
            json.dumps(
                {
                    "ok": report.ok,
                    "checked": len(report.checked),
                    "pass_rate": report.pass_rate(),
                    "seconds": round(report.seconds, 1),
                    "failures": report.failures(),
                    "load_problems": [str(p) for p in report.load_problems],
                    "scripts": [
                        {
                            "name": o.composition.name,
                            "entries": o.composition.ids,
                            "adversary": o.composition.adversary_class,
                            "map": o.composition.map_name,
                            "ok": o.ok,
                            "error": None if o.ok else o.result.summary(),
                            "sandbox": o.result.sandbox.label if o.result.sandbox else None,
                        }
                        for o in report.outcomes
                    ],
                },
                indent=2,
            )
        )
    else:
        console.print(terminal.text(report.summary()))
        console.print(
            terminal.text(
                "sandbox: ",
                confinement_summary(
                    [o.result.sandbox.label if o.result.sandbox else None for o in report.outcomes]
                ),
            )
        )
    raise typer.Exit(0 if report.ok else 1)
