"""A drive from its source to its report: what `arise drive` does.

The command line parses its options into a `DriveRequest`, calls `drive` and prints the
typed events it sends and the summary it returns. Every finished run is saved in the
database at once, so an interrupted drive resumes where it stopped.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from arise.drive.agent_names import resolve_agent
from arise.drive.records import DriveRecord
from arise.drive.report import write_report
from arise.drive.runner import (
    DRIVE_STEPS,
    DriveConfig,
    pending,
    plan,
    planned_records,
    run_drive,
)
from arise.drive.sources import Scenarios, SourceKind, scenarios_of, source_kind
from arise.drive.store import DATABASE, DriveStore
from arise.errors import Interrupted
from arise.executors import Executor
from arise.generate.options import GenerateOptions
from arise.validate.types import confinement_summary


@dataclass(frozen=True)
class DriveRequest:
    """`arise drive`'s options. `generate` is how a prompt file's scripts are made."""

    target: Path
    agent: str
    out: Path = Path("out/drive")
    runs: int = 1
    seed: int = 0
    workers: int = 1
    executor: Executor = Executor.LOCAL
    map_dir: str | None = None
    steps: int = DRIVE_STEPS
    timeout: float = 60.0
    ray_address: str | None = None
    generate: GenerateOptions = field(default_factory=GenerateOptions)


@dataclass(frozen=True)
class Generating:
    """A prompt file: `todo` descriptions to generate first, `done` generated before."""

    todo: int
    done: int


@dataclass(frozen=True)
class Generated:
    """One description was generated (`ok`: its script executed) into `folder`."""

    folder: Path
    ok: bool


@dataclass(frozen=True)
class DrivePlanned:
    """`todo` runs to drive, `done` already in `database`; `skipped` left out of the source."""

    database: Path
    todo: int
    done: int
    skipped: list[str]


@dataclass(frozen=True)
class RunDriven:
    record: DriveRecord


DriveEvent = Generating | Generated | DrivePlanned | RunDriven
OnDriveEvent = Callable[[DriveEvent], None]


@dataclass(frozen=True)
class DriveSummary:
    """This drive's runs (all of its plan in the database) and the report's files."""

    agent: str
    records: list[DriveRecord]
    report: list[Path]

    @property
    def driven(self) -> int:
        return sum(r.driven for r in self.records)

    @property
    def collisions(self) -> int:
        return sum(r.collided for r in self.records)

    @property
    def sandbox(self) -> str:
        return confinement_summary([r.sandbox for r in self.records])


def scenarios_for(request: DriveRequest, emit: OnDriveEvent) -> Scenarios:
    """The scenarios to drive; a prompt file's are generated first."""
    if source_kind(request.target) is not SourceKind.PROMPTS:
        return scenarios_of(request.target)
    # The generator (and its model stack) loads only for a prompt file.
    from arise.drive.prompts import GenerationPlanned, generate_prompts
    from arise.generate.batch import BatchEvent, RunDone

    def planned(event: GenerationPlanned) -> None:
        emit(Generating(event.todo, event.done))

    def generated(event: BatchEvent) -> None:
        if isinstance(event, RunDone):
            emit(Generated(event.folder, event.run.ok))

    folder = generate_prompts(request.target, request.out, request.generate, planned, generated)
    return scenarios_of(folder)


def drive(request: DriveRequest, on_event: OnDriveEvent | None = None) -> DriveSummary:
    """Drive every scenario of the request's source with its agent (runs the database does
    not hold yet), then write report.md and runs.csv in `out`. Raises AgentError,
    DriveSourceError or ExecutorUnavailable before any run; Ctrl-C raises Interrupted
    with every finished run saved."""
    emit = on_event or (lambda event: None)
    agent = resolve_agent(request.agent)
    config = DriveConfig(
        agent=agent,
        runs=request.runs,
        seed=request.seed,
        workers=request.workers,
        executor=request.executor,
        map_dir=request.map_dir,
        steps=request.steps,
        timeout=request.timeout,
        ray_address=request.ray_address,
    )
    try:
        scenarios = scenarios_for(request, emit)
        tasks = plan(scenarios.items, config)
        with DriveStore(request.out / DATABASE) as store:
            todo = pending(tasks, store)
            emit(
                DrivePlanned(
                    request.out / DATABASE, len(todo), len(tasks) - len(todo), scenarios.skipped
                )
            )
            run_drive(tasks, config, store, request.out, lambda r: emit(RunDriven(r)))
            records = planned_records(tasks, store)
    except KeyboardInterrupt:
        raise Interrupted("finished runs are saved; run the same command to resume") from None
    written = write_report(records, request.out, agent, scenarios.skipped)
    return DriveSummary(agent, records, written)
