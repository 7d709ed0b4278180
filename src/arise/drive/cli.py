"""`arise drive`: put a driving agent in the ego's seat of every scenario of a source."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    TaskID,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)

from arise import terminal
from arise.drive.agent_names import agent_label
from arise.drive.runner import DRIVE_STEPS
from arise.drive.session import (
    DriveEvent,
    DrivePlanned,
    DriveRequest,
    Generated,
    Generating,
    RunDriven,
    drive,
)
from arise.executors import parse_executor
from arise.generate.options import GenerateOptions
from arise.limits import MAX_STEPS
from arise.llm.cli_options import ModelOption, ProviderOption, ReplayOption

console = terminal.console()

DRIVE_HELP = """Put a driving agent in the ego's seat of every scenario and measure it.

The metrics are SafeBench's (collision rate, red lights and stop signs run, out-of-road
distance, route following and completion, time spent, acceleration, yaw velocity, lane
invasions, overall score) and the smallest time to collision; docs/agents.md.

SOURCE is a .scenic script, a folder of scripts (walked below; a sub-folder's name is the
category of the scripts in it), a run folder of `arise generate`, or a prompt file
(.jsonl {"id", "category", "description"} per line, or .txt) whose scripts are generated
first into OUT/scenarios/. Every script runs in the confined validator, as `arise check`.

AGENT is a built-in (scripted, idm, cautious, blind), an entry point of the
`arise.agents` group, or path/to/agent.py:ClassName (your own; docs/agents.md).

Every run goes into OUT/drive.sqlite as it finishes; running the same command again
resumes and only does the runs that are missing. OUT/report.md has the paper's table per
category and overall, OUT/runs.csv one row per run, OUT/collisions/ the replay of every
collision with the agent's path drawn.

Examples:

  arise drive examples/categories --agent idm

  arise drive out/turn --agent blind --runs 5 --seed 3

  arise drive my_scripts/ --agent my_agent.py:MyAgent --out out/mine --workers 2

  arise drive benchmarks/data/dev_prompts.jsonl --agent cautious --out out/dev-cautious

  arise drive scripts/ --agent idm --executor ray --workers 8
"""


def drive_command(
    source: Annotated[
        Path,
        typer.Argument(help="A .scenic script, a folder, a run folder or a prompt file."),
    ],
    agent: Annotated[
        str,
        typer.Option(
            "--agent",
            help="scripted, idm, cautious, blind, an `arise.agents` entry point, or "
            "path/to/agent.py:ClassName.",
        ),
    ],
    runs: Annotated[int, typer.Option(help="Runs per scenario; run i uses seed + i.", min=1)] = 1,
    seed: Annotated[int, typer.Option(help="Seed of the first run.")] = 0,
    out: Annotated[
        Path, typer.Option("-o", "--out", help="Folder for the database, report and replays.")
    ] = Path("out/drive"),
    workers: Annotated[int, typer.Option(help="Scenarios driven at once.", min=1)] = 1,
    executor: Annotated[str, typer.Option(help="local (threads on one pool) or ray.")] = "local",
    ray_address: Annotated[
        str | None, typer.Option(help="Ray cluster to join (default: a local Ray instance).")
    ] = None,
    steps: Annotated[
        int, typer.Option(help="Simulation steps per run.", min=1, max=MAX_STEPS)
    ] = DRIVE_STEPS,
    map_dir: Annotated[str | None, typer.Option(help="Extra maps (e.g. CARLA towns).")] = None,
    provider: ProviderOption = None,
    model: ModelOption = None,
    replay: ReplayOption = None,
) -> None:
    request = DriveRequest(
        target=source,
        agent=agent,
        out=out,
        runs=runs,
        seed=seed,
        workers=workers,
        executor=parse_executor(executor),  # ExecutorUnavailable: one line, exit 2
        map_dir=map_dir,
        steps=steps,
        ray_address=ray_address,
        generate=GenerateOptions(
            provider=provider, model=model, replay=replay, seed=seed, map_dir=map_dir
        ),
    )
    with _DrivePrinter() as printer:
        summary = drive(request, printer.on_event)  # Ctrl-C: Interrupted, exit 130
    console.print(
        terminal.text(
            f"{summary.driven} of {len(summary.records)} runs driven by ",
            terminal.name(agent_label(summary.agent)),
            f", {summary.collisions} with a collision; report: ",
            terminal.name(summary.report[0]),
        )
    )
    console.print(terminal.text("sandbox: ", summary.sandbox))


class _DrivePrinter:
    """A progress bar on a terminal (generation, then runs); a line per run elsewhere."""

    def __init__(self) -> None:
        self.bar: Progress | None = None
        self.task: TaskID | None = None
        self.collisions = 0

    def __enter__(self) -> _DrivePrinter:
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop()

    def on_event(self, event: DriveEvent) -> None:
        if isinstance(event, Generating):
            console.print(f"{event.todo} description(s) to generate, {event.done} generated before")
            self._start("generating", event.todo)
        elif isinstance(event, Generated):
            self._advance()
            if not console.is_terminal:
                verdict = "executed" if event.ok else "did not execute"
                console.print(
                    terminal.text("generated ", terminal.name(event.folder), f": {verdict}")
                )
        elif isinstance(event, DrivePlanned):
            self._stop()
            for line in event.skipped[:10]:
                console.print(terminal.text("left out: ", line))
            console.print(
                terminal.text(
                    f"{event.todo} run(s) to drive, {event.done} already in ",
                    terminal.name(event.database),
                )
            )
            self._start("driving", event.todo)
        elif isinstance(event, RunDriven):
            record = event.record
            self.collisions += record.collided
            self._advance(f"driving ({self.collisions} collided)")
            if not console.is_terminal:
                outcome = (
                    ("collision" if record.collided else "no collision")
                    if record.driven
                    else f"did not run: {record.message}"
                )
                console.print(
                    terminal.text(
                        terminal.name(record.task.label()),
                        f": {outcome}",
                        f" ({record.seconds:.1f} s)",
                    )
                )

    def _start(self, description: str, total: int) -> None:
        self._stop()
        self.bar = Progress(
            TextColumn("{task.description}"),
            BarColumn(),
            MofNCompleteColumn(),
            TimeElapsedColumn(),
            TextColumn("ETA"),
            TimeRemainingColumn(),
            console=console,
            disable=not console.is_terminal,
        )
        self.bar.start()
        self.task = self.bar.add_task(description, total=total)

    def _advance(self, description: str | None = None) -> None:
        if self.bar is not None and self.task is not None:
            self.bar.update(self.task, advance=1, description=description)

    def _stop(self) -> None:
        if self.bar is not None:
            self.bar.stop()
            self.bar = None
