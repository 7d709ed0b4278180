"""A benchmark from its database to its report: what `arise bench` and `arise report` do.

The command line parses its options, calls `benchmark` or `bench_report` and prints the
typed events they send and the summary they return. Every finished run is saved in the
database at once, so an interrupted benchmark resumes where it stopped.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from arise.errors import AriseError, Interrupted
from arise.evaluate.records import RunRecord
from arise.evaluate.report import write_report
from arise.evaluate.runner import (
    BenchConfig,
    judge_missing,
    pending,
    recheck,
    run_bench,
    unjudged,
)
from arise.evaluate.store import BenchStore, BenchStoreError
from arise.validate.types import confinement_summary

DATABASE = "bench.sqlite"


class NoFinishedRuns(AriseError):
    """A report was asked of a database that holds no finished run."""


@dataclass(frozen=True)
class BenchPlanned:
    """What the benchmark will do: `todo` runs, `done` already in `database`; with --judge,
    `to_judge` finished runs are scored first."""

    database: Path
    todo: int
    done: int
    to_judge: int | None


@dataclass(frozen=True)
class JudgingStarted:
    total: int


@dataclass(frozen=True)
class RunJudged:
    record: RunRecord


@dataclass(frozen=True)
class RunsStarted:
    total: int


@dataclass(frozen=True)
class RunSaved:
    """A run finished (or was judged after it) and is in the database."""

    record: RunRecord


BenchEvent = BenchPlanned | JudgingStarted | RunJudged | RunsStarted | RunSaved
OnBenchEvent = Callable[[BenchEvent], None]


@dataclass(frozen=True)
class BenchSummary:
    """Every run in the database after the benchmark, and the report's files."""

    records: list[RunRecord]
    report: list[Path]

    @property
    def executed(self) -> int:
        return sum(r.ok for r in self.records)

    @property
    def sandbox(self) -> str:
        """Which confinement the executed runs' checks ran under, in one line."""
        return confinement_summary([r.sandbox for r in self.records if r.ok])


def benchmark(config: BenchConfig, out: Path, on_event: OnBenchEvent | None = None) -> BenchSummary:
    """Do the runs `out/bench.sqlite` does not hold yet (judging finished runs first with
    --judge), then write `out/report/`. Ctrl-C raises Interrupted: what finished is saved."""
    emit = on_event or (lambda event: None)
    with BenchStore(out / DATABASE) as store:  # BenchStoreError: one line, exit 2
        todo = pending(config, store)
        total = len(todo) + len(store.done_keys())
        to_judge = len(unjudged(config, store)) if config.judge else None
        emit(BenchPlanned(out / DATABASE, len(todo), total - len(todo), to_judge))
        try:
            if to_judge is not None:
                emit(JudgingStarted(to_judge))
                judge_missing(config, store, out, lambda r: emit(RunJudged(r)))
            emit(RunsStarted(len(todo)))
            run_bench(config, store, out, lambda r: emit(RunSaved(r)))
        except KeyboardInterrupt:
            raise Interrupted("finished runs are saved; run the same command to resume") from None
        records = store.runs()
        written = write_report(records, out / "report", store.meta())
    return BenchSummary(records, written)


@dataclass(frozen=True)
class Rechecked:
    """Executed runs validated again with the current checks."""

    count: int
    sandbox: str


@dataclass(frozen=True)
class RunSearched:
    """An executed run's script was searched for its most critical instance."""

    record: RunRecord
    trials: int

    @property
    def critical(self) -> bool:
        search = (self.record.criticality or {}).get("search") or {}
        return bool(search.get("critical"))


@dataclass(frozen=True)
class SearchedAll:
    count: int


ReportEvent = Rechecked | RunSearched | SearchedAll
OnReportEvent = Callable[[ReportEvent], None]


@dataclass(frozen=True)
class ReportRequest:
    """`arise report`'s options: the database, where the report goes (default: beside it,
    report/), its title, and what to refresh first."""

    database: Path
    out: Path | None = None
    title: str = "arise benchmark report"
    recheck: bool = False
    map_dir: str | None = None
    search_trials: int = 0
    #: The agent that drives the ego in those searches (as `arise drive --agent`).
    search_agent: str | None = None

    @property
    def folder(self) -> Path:
        return self.out or self.database.parent / "report"


def bench_report(request: ReportRequest, on_event: OnReportEvent | None = None) -> list[Path]:
    """Write the report of a benchmark database; returns its files. With `recheck`, first
    validate every executed run's script again; with `search_trials`, first search each
    for its most critical instance."""
    emit = on_event or (lambda event: None)
    if not request.database.is_file():
        raise BenchStoreError(f"no such database: {request.database}")
    with BenchStore(request.database) as store:  # BenchStoreError: one line, exit 2
        if request.recheck:
            count = recheck(store, map_dir=request.map_dir)
            sandbox = confinement_summary([r.sandbox for r in store.runs() if r.ok])
            emit(Rechecked(count, sandbox))
        if request.search_trials:
            from arise.evaluate.search.bench import search_runs

            trials = request.search_trials
            count = search_runs(
                store,
                trials,
                agent=request.search_agent,
                on_record=lambda r: emit(RunSearched(r, trials)),
            )
            emit(SearchedAll(count))
        records, meta = store.runs(), store.meta()
    if not records:
        raise NoFinishedRuns(f"{request.database} holds no finished runs yet")
    return write_report(records, request.folder, meta, request.title)
