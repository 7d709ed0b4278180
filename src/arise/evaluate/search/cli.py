"""`arise search`: the command line over `arise.evaluate.search`."""

from __future__ import annotations

from enum import StrEnum
from pathlib import Path
from typing import Annotated, TypeVar

import typer
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table

from arise import terminal
from arise.evaluate.search.errors import SearchError
from arise.evaluate.search.executor import Executor
from arise.evaluate.search.expression import FACTS, parse_expression
from arise.evaluate.search.objective import Objective
from arise.evaluate.search.outputs import describe, write_outputs
from arise.evaluate.search.runner import (
    SEARCH_SPAWN_ATTEMPTS,
    SearchConfig,
    SearchResult,
    resolve_script,
    run_search,
)
from arise.evaluate.search.sampler import SamplerKind
from arise.evaluate.search.store import SearchStore, TrialRecord
from arise.limits import MAX_STEPS
from arise.validate import CheckOptions

console = terminal.console()

SEARCH_HELP = """Find the most critical instance of a script with VerifAI's samplers.

The script's free parameters (`param OPT_X = Range(a, b)`, VerifaiRange, VerifaiOptions,
...) span the space; the sampler proposes values, each trial runs in the confined
validator with them fixed, and the trace scores it (smaller is more critical). Every trial
goes into OUT/search.sqlite as it finishes: the same command resumes a killed search.

OUT gets critical/scenario.scenic (the best trial's script, values fixed) with its replay
and OpenSCENARIO file, trials.csv, objective.png and search.json.

Examples:

  arise search out/demo --trials 30

  arise search my.scenic --sampler ce,random,halton --objective min-ttc --seed 1

  arise search my.scenic --objective collision --workers 2 --out out/my-search

  arise search my.scenic --objective custom --expression 'min_ttc + 0.2 * min_distance'

  arise search my.scenic --executor ray --workers 8
"""

E = TypeVar("E", bound=StrEnum)


def _choice(kind: type[E], text: str, option: str) -> E:
    try:
        return kind(text.strip())
    except ValueError:
        names = ", ".join(member.value for member in kind)
        raise SearchError(f"unknown {option} '{text}': use one of {names}") from None


def search_command(
    target: Annotated[
        Path, typer.Argument(help="A Scenic script, or a run folder of `arise generate`.")
    ],
    objective: Annotated[
        str,
        typer.Option(
            help="What to minimise: min-ttc, min-distance, collision, or custom (with "
            "--expression)."
        ),
    ] = "min-ttc",
    expression: Annotated[
        str | None,
        typer.Option(
            help="The custom objective, smaller = more critical: arithmetic over "
            + ", ".join(FACTS)
            + " (min, max, abs, comparisons and 'a if c else b' too). "
            "Example: --objective custom --expression 'min_ttc + 0.2 * min_distance'"
        ),
    ] = None,
    sampler: Annotated[
        str,
        typer.Option(
            help="VerifAI sampler: random, halton, ce (cross-entropy) or bo (needs GPyOpt); "
            "several, comma-separated, are compared."
        ),
    ] = "ce",
    trials: Annotated[int, typer.Option(help="Trials per sampler.")] = 30,
    workers: Annotated[int, typer.Option(help="Trials run at the same time.")] = 1,
    executor: Annotated[str, typer.Option(help="local (worker processes) or ray.")] = "local",
    ray_address: Annotated[
        str | None, typer.Option(help="Ray cluster to join (default: a local one).")
    ] = None,
    seed: Annotated[int, typer.Option(help="Seed of the sampler and of every trial's scene.")] = 0,
    out: Annotated[
        Path | None,
        typer.Option(
            "-o", "--out", help="Output folder (default: RUN_DIR/search or out/search-NAME)."
        ),
    ] = None,
    steps: Annotated[
        int, typer.Option(min=1, max=MAX_STEPS, help="Simulation steps per trial.")
    ] = 300,
    timeout: Annotated[float, typer.Option(help="Seconds per trial before it is stopped.")] = 60.0,
    spawn_attempts: Annotated[
        int,
        typer.Option(help="Scenes a trial may try before its values count as failed."),
    ] = SEARCH_SPAWN_ATTEMPTS,
    map_dir: Annotated[
        str | None,
        typer.Option(envvar="ARISE_MAP_DIR", help="Folder of extra .xodr maps (CARLA towns)."),
    ] = None,
    replay: Annotated[
        bool, typer.Option(help="Run the critical script again for its replay and .xosc.")
    ] = True,
) -> None:
    script = resolve_script(target)
    chosen_objective = _choice(Objective, objective, "objective")
    if expression is not None and chosen_objective is not Objective.CUSTOM:
        raise SearchError("--expression goes with --objective custom")
    goal = parse_expression(expression or "") if chosen_objective is Objective.CUSTOM else None
    samplers = [_choice(SamplerKind, s, "sampler") for s in sampler.split(",") if s.strip()]
    chosen_executor = _choice(Executor, executor, "executor")
    if not samplers:
        raise SearchError("--sampler needs at least one sampler")
    folder = out or (
        target / "search" if target.is_dir() else Path("out") / f"search-{script.stem}"
    )
    check = CheckOptions(
        steps=steps, timeout=timeout, map_dir=map_dir, spawn_attempts=spawn_attempts
    )
    results: list[SearchResult] = []
    with SearchStore(folder / "search.sqlite") as store:
        for kind in samplers:
            config = SearchConfig(
                script=script,
                objective=chosen_objective,
                expression=goal,
                sampler=kind,
                trials=trials,
                workers=workers,
                executor=chosen_executor,
                seed=seed,
                check=check,
                ray_address=ray_address,
            )
            try:
                results.append(_run_with_bar(config, store))
            except KeyboardInterrupt:
                console.print(
                    terminal.text(
                        "\ninterrupted: finished trials are in ",
                        terminal.name(store.path),
                        "; run the same command to resume",
                    )
                )
                raise typer.Exit(130) from None
    _print_table(results)
    files = write_outputs(results, folder, replay=replay)
    if files.critical_script is not None:
        console.print(terminal.text("critical instance: ", terminal.name(files.critical_script)))
    for path in files.replay:
        console.print(terminal.text("  ", terminal.name(path)))
    for note in files.notes:
        console.print(terminal.text("note: ", note))
    console.print(
        terminal.text(
            "trials: ",
            terminal.name(files.trials_csv),
            "; plot: ",
            terminal.name(files.plot),
            "; summary: ",
            terminal.name(files.summary),
        )
    )


def _run_with_bar(config: SearchConfig, store: SearchStore) -> SearchResult:
    columns = [
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
    ]
    name = config.sampler.value
    with Progress(*columns, console=console, disable=not console.is_terminal) as bar:
        task = bar.add_task(f"{name}: starting", total=config.trials)

        def advance(record: TrialRecord, result: SearchResult) -> None:
            best = result.best
            if best is None:
                text = f"{name}: no trial ran yet"
            else:
                text = (
                    f"{name}: best {config.objective.value} {best.outcome.value:.2f} "
                    f"{config.objective.unit} (trial {best.index + 1})"
                )
            bar.update(task, advance=1, description=text)
            if not console.is_terminal:
                console.print(terminal.text(name, " ", describe(record, config.objective)))

        return run_search(config, store, advance)


def _print_table(results: list[SearchResult]) -> None:
    if not results:
        return
    objective = results[0].config.objective
    table = Table(
        title=terminal.text(
            terminal.name(results[0].config.script.name),
            f": {objective.label}, smaller is more critical",
        )
    )
    for column in (
        "sampler",
        "trials",
        "ran",
        "best",
        "at trial",
        "first critical",
        "critical trials",
        "seconds",
    ):
        table.add_column(column)
    for result in results:
        best = result.best
        table.add_row(
            result.config.sampler.value,
            str(len(result.trials)),
            str(sum(t.outcome.ok for t in result.trials)),
            "-" if best is None else f"{best.outcome.value:.2f} {objective.unit}",
            "-" if best is None else str(best.index + 1),
            str(result.first_critical or "-"),
            str(sum(t.outcome.critical for t in result.trials)),
            f"{sum(t.outcome.seconds for t in result.trials):.0f}",
        )
    console.print(table)
