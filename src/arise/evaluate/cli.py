"""`arise bench` and `arise report`: the paper's evaluation on anyone's prompts."""

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
from arise.drive.agent_names import resolve_agent
from arise.evaluate.benchmark import (
    BenchEvent,
    BenchPlanned,
    JudgingStarted,
    Rechecked,
    ReportEvent,
    ReportRequest,
    RunJudged,
    RunSearched,
    RunsStarted,
    bench_report,
    benchmark,
)
from arise.evaluate.prompt_file import read_prompts
from arise.evaluate.runner import BenchConfig
from arise.evaluate.search.errors import SearchError
from arise.executors import parse_executor
from arise.generate.options import GenerateOptions, Mode, ModelExtraction
from arise.llm.cli_options import ModelOption, ProviderOption, ReplayOption

console = terminal.console()

BENCH_HELP = """Run the generator over a prompt file and measure it the paper's way.

Every run goes into DIR/bench.sqlite as it finishes; running the same command again resumes
and only does the runs that are missing. At the end DIR/report/ holds report.md (ESR, RCR,
conformity, SCS, cost and criticality per category), table.csv, runs.csv and two plots.

PROMPTS is .jsonl ({"id", "category", "description"} per line), .csv (columns id,
category, description) or .txt (one description per line, or category<TAB>description).

Examples:

  arise bench benchmarks/data/dev_prompts.jsonl --out out/bench

  arise bench prompts.csv --runs 5 --modes arise,single-pass,chatscene --temperatures 0.3,1.0

  arise bench prompts.txt --provider openai --model gpt-4o-mini --workers 4 --judge

  arise bench prompts.jsonl --executor ray --workers 8

  arise bench prompts.jsonl --no-semantic-gate   # measure without the semantic gate

  arise bench prompts.jsonl --agent idm   # also drive every executed script (arise drive)
"""

REPORT_HELP = """Write the report of a benchmark database (Markdown, CSV and PNG plots).

Examples:

  arise report out/bench/bench.sqlite

  arise report out/bench/bench.sqlite --out docs/eval --title "Dev set, Qwen 1.5B"
"""


def _split(text: str, name: str) -> list[str]:
    items = [item.strip() for item in text.split(",") if item.strip()]
    if not items:
        raise typer.BadParameter("give at least one value", param_hint=name)
    return items


def _modes(text: str) -> list[Mode]:
    try:
        return [Mode(item) for item in _split(text, "--modes")]
    except ValueError:
        raise typer.BadParameter(
            f"modes are {', '.join(m.value for m in Mode)}", param_hint="--modes"
        ) from None


def _temperatures(text: str) -> list[float]:
    try:
        values = [float(item) for item in _split(text, "--temperatures")]
    except ValueError:
        raise typer.BadParameter(
            "temperatures are numbers, e.g. 0.3,1.0", param_hint="--temperatures"
        ) from None
    if any(not 0 <= value <= 2 for value in values):
        raise typer.BadParameter("temperatures lie between 0 and 2", param_hint="--temperatures")
    return values


def bench_command(
    prompts: Annotated[Path, typer.Argument(help="Prompt file (.jsonl, .csv or .txt).")],
    out: Annotated[
        Path, typer.Option("-o", "--out", help="Folder for the database, runs and report.")
    ] = Path("out/bench"),
    runs: Annotated[int, typer.Option(help="Runs per prompt, mode and temperature.", min=1)] = 1,
    modes: Annotated[
        str, typer.Option(help="Comma-separated: arise, single-pass, chatscene.")
    ] = "arise",
    temperatures: Annotated[str, typer.Option(help="Comma-separated temperatures.")] = "0",
    provider: ProviderOption = None,
    model: ModelOption = None,
    workers: Annotated[
        int, typer.Option(help="Parallel generators (each loads the model).", min=1)
    ] = 1,
    executor: Annotated[str, typer.Option(help="local (processes) or ray.")] = "local",
    ray_address: Annotated[
        str | None, typer.Option(help="Ray cluster to join (default: a local Ray instance).")
    ] = None,
    max_repairs: Annotated[int, typer.Option(help="Repair budget per run.", min=0)] = 10,
    seed: Annotated[int, typer.Option(help="Base seed; run i uses seed + i.")] = 0,
    limit: Annotated[int | None, typer.Option(help="Only the first N prompts.")] = None,
    judge: Annotated[
        bool, typer.Option("--judge", help="Score executed scripts with the LLM judge (SCS).")
    ] = False,
    judge_provider: Annotated[
        str | None,
        typer.Option(
            help="Provider of the judge (default: the generating model; a small local model is "
            "a poor judge, see docs/judge.md)."
        ),
    ] = None,
    judge_model: Annotated[str | None, typer.Option(help="Model of the judge.")] = None,
    agent: Annotated[
        str | None,
        typer.Option(
            help="Also drive every executed script with this driving agent (scripted, idm, "
            "cautious, blind, an `arise.agents` entry point or path/to/agent.py:ClassName) "
            "and add SafeBench's metrics to the report, as `arise drive`. Runs executed "
            "earlier are driven too, without generating again."
        ),
    ] = None,
    semantic_gate: Annotated[
        bool,
        typer.Option(
            "--semantic-gate/--no-semantic-gate",
            help="arise-mode runs must also agree with the description or be repaired "
            "(on by default; the baselines never gate). The report shows the seconds it "
            "cost. Example: arise bench prompts.jsonl --no-semantic-gate",
        ),
    ] = True,
    model_extraction: Annotated[
        ModelExtraction,
        typer.Option(
            "--ask-model",
            metavar="WHEN",
            help="when-needed (default) or always: whether the model reads descriptions the "
            "fixed rules read whole (arise mode; the baselines always ask it). "
            "Example: arise bench prompts.jsonl --ask-model always",
        ),
    ] = ModelExtraction.WHEN_NEEDED,
    map_dir: Annotated[str | None, typer.Option(help="Extra maps (e.g. CARLA towns).")] = None,
    replay: ReplayOption = None,
    cache: Annotated[
        bool,
        typer.Option(
            "--cache",
            help="Reuse cached model answers (off by default: a benchmark measures the model).",
        ),
    ] = False,
) -> None:
    chosen = parse_executor(executor)  # before the prompts are read: ExecutorUnavailable, exit 2
    resolved = resolve_agent(agent) if agent is not None else None  # AgentNameError, exit 2
    items = read_prompts(prompts)  # PromptFileError: one line, exit 2
    base = GenerateOptions(
        provider=provider,
        model=model,
        max_repairs=max_repairs,
        seed=seed,
        map_dir=map_dir,
        replay=replay,
        semantic_gate=semantic_gate,
        model_extraction=model_extraction,
        cache=cache,
    )
    config = BenchConfig(
        prompts=items[:limit] if limit else items,
        base=base,
        modes=_modes(modes),
        temperatures=_temperatures(temperatures),
        runs=runs,
        workers=workers,
        executor=chosen,
        judge=judge,
        judge_provider=judge_provider,
        judge_model=judge_model,
        ray_address=ray_address,
        agent=resolved,
    )
    with _BenchPrinter() as printer:
        summary = benchmark(config, out, printer.on_event)  # Ctrl-C: Interrupted, exit 130
    console.print(
        terminal.text(
            f"{summary.executed} of {len(summary.records)} runs executable; report: ",
            terminal.name(summary.report[0]),
        )
    )
    console.print(terminal.text("sandbox: ", summary.sandbox))


class _BenchPrinter:
    """Prints a benchmark's events: a progress bar on a terminal (judging, then runs),
    a line per judged or finished run elsewhere."""

    def __init__(self) -> None:
        self.bar: Progress | None = None
        self.task: TaskID | None = None
        self.executable = 0

    def __enter__(self) -> _BenchPrinter:
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop()

    def on_event(self, event: BenchEvent) -> None:
        if isinstance(event, BenchPlanned):
            console.print(
                terminal.text(
                    f"{event.todo} run(s) to do, {event.done} already in ",
                    terminal.name(event.database),
                )
            )
            if event.to_judge is not None:
                console.print(f"{event.to_judge} finished run(s) to judge first")
        elif isinstance(event, JudgingStarted):
            self._start("judging", event.total)
        elif isinstance(event, RunsStarted):
            self._start("runs", event.total)
        elif isinstance(event, RunJudged):
            self._advance()
            if not console.is_terminal:
                scs = event.record.scs
                console.print(
                    terminal.text(
                        "judged ",
                        terminal.name(event.record.task.label()),
                        f": SCS {'-' if scs is None else f'{scs:.2f}'}",
                    )
                )
        else:
            record = event.record
            self.executable += record.ok
            self._advance(f"runs ({self.executable} executable)")
            if not console.is_terminal:
                console.print(
                    terminal.text(
                        terminal.name(record.task.label()),
                        ": ",
                        terminal.name(record.status),
                        f" ({record.repairs} repairs, {record.seconds:.0f} s)",
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


def report_command(
    database: Annotated[Path, typer.Argument(help="bench.sqlite written by `arise bench`.")],
    out: Annotated[
        Path | None,
        typer.Option("-o", "--out", help="Report folder (default: beside the database, report/)."),
    ] = None,
    title: Annotated[str, typer.Option(help="Title of report.md.")] = "arise benchmark report",
    recheck_runs: Annotated[
        bool,
        typer.Option(
            "--recheck",
            help="First validate every executed run's script again and refresh its "
            "conformity and criticality with the current checks (needs the runs' folders).",
        ),
    ] = False,
    map_dir: Annotated[
        str | None,
        typer.Option(
            help="Extra maps for --recheck (e.g. CARLA towns; the database's own map folder "
            "is not used)."
        ),
    ] = None,
    search_trials: Annotated[
        int,
        typer.Option(
            help="First search each executed run's script for this many trials (VerifAI's "
            "cross-entropy sampler, smallest TTC; see `arise search`) and add 'critical "
            "after search' to the criticality table. 0: no search.",
            min=0,
        ),
    ] = 0,
    agent: Annotated[
        str | None,
        typer.Option(
            help="With --search-trials: the agent that drives the ego in every trial (idm, "
            "cautious, blind, FILE.py:ClassName, as `arise drive --agent`); each run's "
            "criticality then says whether the search made that agent fail."
        ),
    ] = None,
) -> None:
    if agent is not None and not search_trials:
        raise SearchError("--agent goes with --search-trials (the searches drive with it)")
    if agent is not None:
        resolve_agent(agent)  # a bad name: one line, before any re-check or search
    request = ReportRequest(
        database=database,
        out=out,
        title=title,
        recheck=recheck_runs,
        map_dir=map_dir,
        search_trials=search_trials,
        search_agent=agent,
    )
    for path in bench_report(request, _print_report_event):
        console.print(terminal.text(terminal.name(path)))


def _print_report_event(event: ReportEvent) -> None:
    if isinstance(event, Rechecked):
        console.print(
            terminal.text(f"re-checked {event.count} executed run(s); sandbox: ", event.sandbox)
        )
    elif isinstance(event, RunSearched):
        agent = ((event.record.criticality or {}).get("search") or {}).get("agent")
        driver = f" for {agent}" if agent and agent != "scripted" else ""
        console.print(
            terminal.text(
                "searched ",
                terminal.name(event.record.task.label()),
                ": critical" if event.critical else ": not critical",
                driver,
                f" within {event.trials} trials",
            )
        )
    else:
        console.print(f"searched {event.count} executed run(s)")
