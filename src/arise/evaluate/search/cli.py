"""`arise search`: the command line over `arise.evaluate.search`."""

from __future__ import annotations

from enum import StrEnum
from pathlib import Path
from typing import Annotated, TypeVar

import typer
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    TaskID,
    TextColumn,
    TimeElapsedColumn,
)
from rich.table import Table

from arise import terminal
from arise.evaluate.search.errors import SearchError
from arise.evaluate.search.executor import Executor
from arise.evaluate.search.expression import FACTS
from arise.evaluate.search.objective import Objective
from arise.evaluate.search.outputs import describe
from arise.evaluate.search.runner import SEARCH_SPAWN_ATTEMPTS, SearchResult
from arise.evaluate.search.sampler import SamplerKind
from arise.evaluate.search.session import (
    SamplerStarted,
    SearchEvent,
    SearchRequest,
    TrialDone,
    search,
)
from arise.limits import MAX_STEPS
from arise.validate import CheckOptions

console = terminal.console()

SEARCH_HELP = """Find the most critical instance of a script with VerifAI's samplers.

The script's free parameters (`param OPT_X = Range(a, b)`, VerifaiRange, VerifaiOptions,
...) span the space; the sampler proposes values, each trial runs in the confined
validator with them fixed, and the trace scores it (smaller is more critical). Every trial
goes into OUT/search.sqlite as it finishes: the same command resumes a killed search.

With --agent, a driving agent (as `arise drive --agent`: idm, cautious, blind, FILE.py:Class
or an entry point) drives the ego in every trial, and the search looks for the values where
that agent fails (a collision, or a TTC under 1 s). --objective score minimises SafeBench's
overall score of its drive.

OUT gets critical/scenario.scenic (the best trial's script, values fixed) with its replay
and OpenSCENARIO file, trials.csv, objective.png and search.json.

Examples:

  arise search out/demo --trials 30

  arise search out/demo --agent idm --trials 30

  arise search my.scenic --agent blind --objective collision

  arise search my.scenic --agent my_agent.py:Careful --objective score

  arise search my.scenic --objective custom --expression 'overall_score + red_lights_run'

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
            help="What to minimise: min-ttc, min-distance, collision, score (SafeBench's "
            "overall score of the ego's drive, 1 = perfect), or custom (with --expression)."
        ),
    ] = "min-ttc",
    expression: Annotated[
        str | None,
        typer.Option(
            help="The custom objective, smaller = more critical: arithmetic over "
            + ", ".join(FACTS)
            + " and every `arise drive` metric by its name (overall_score, red_lights_run, "
            "route_completion, min_ttc_s, ...; docs/search.md), with min, max, abs, "
            "comparisons and 'a if c else b'. "
            "Example: --objective custom --expression 'min_ttc + 0.2 * min_distance'"
        ),
    ] = None,
    sampler: Annotated[
        str,
        typer.Option(
            help="Sampler: VerifAI's random, halton, ce (cross-entropy) or bo (needs GPyOpt), "
            "or our surrogate (a Gaussian process fitted to the trials so far, trying where "
            "it expects the most gain); "
            "several, comma-separated, are compared."
        ),
    ] = "ce",
    agent: Annotated[
        str | None,
        typer.Option(
            help="Who drives the ego in every trial: scripted (the script, the default), "
            "idm, cautious, blind, FILE.py:ClassName or an entry point of 'arise.agents' "
            "(as `arise drive --agent`)."
        ),
    ] = None,
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
    until_found: Annotated[
        bool,
        typer.Option(
            "--until-found",
            help="Stop at the first trial that finds a failure (a collision, or a TTC under "
            "1 s; with --objective collision, a collision) instead of spending every trial.",
        ),
    ] = False,
) -> None:
    request = SearchRequest(
        target=target,
        objective=_choice(Objective, objective, "objective"),
        expression=expression,
        samplers=[_choice(SamplerKind, s, "sampler") for s in sampler.split(",") if s.strip()],
        executor=_choice(Executor, executor, "executor"),
        trials=trials,
        workers=workers,
        ray_address=ray_address,
        seed=seed,
        out=out,
        check=CheckOptions(
            steps=steps, timeout=timeout, map_dir=map_dir, spawn_attempts=spawn_attempts
        ),
        replay=replay,
        agent=agent,
        until_found=until_found,
    )
    with _SearchPrinter() as printer:
        session = search(request, printer.on_event)  # Ctrl-C: Interrupted, exit 130
    files = session.files
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


class _SearchPrinter:
    """Prints a search's events: a bar per sampler on a terminal (a line per trial
    elsewhere), then the table of the samplers' results."""

    def __init__(self) -> None:
        self.bar: Progress | None = None
        self.task: TaskID | None = None

    def __enter__(self) -> _SearchPrinter:
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop()

    def on_event(self, event: SearchEvent) -> None:
        if isinstance(event, SamplerStarted):
            self._stop()
            self.bar = Progress(
                TextColumn("{task.description}"),
                BarColumn(),
                MofNCompleteColumn(),
                TimeElapsedColumn(),
                console=console,
                disable=not console.is_terminal,
            )
            self.bar.start()
            name = event.config.sampler.value
            self.task = self.bar.add_task(f"{name}: starting", total=event.config.trials)
        elif isinstance(event, TrialDone):
            self._trial(event)
        else:
            self._stop()
            _print_table(event.results)

    def _trial(self, event: TrialDone) -> None:
        config, name = event.config, event.config.sampler.value
        best = event.result.best
        if best is None:
            text = f"{name}: no trial ran yet"
        else:
            text = (
                f"{name}: best {config.objective.value} {best.outcome.value:.2f} "
                f"{config.objective.unit} (trial {best.index + 1})"
            )
        if self.bar is not None and self.task is not None:
            self.bar.update(self.task, advance=1, description=text)
        if not console.is_terminal:
            console.print(terminal.text(name, " ", describe(event.record, config.objective)))

    def _stop(self) -> None:
        if self.bar is not None:
            self.bar.stop()
            self.bar = None


def _print_table(results: list[SearchResult]) -> None:
    if not results:
        return
    config = results[0].config
    objective = config.objective
    driver = "" if config.agent is None else f" with the agent {config.agent_label}"
    table = Table(
        title=terminal.text(
            terminal.name(config.script.name),
            f"{driver}: {objective.label}, smaller is more critical",
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
