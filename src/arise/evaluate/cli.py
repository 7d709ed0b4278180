"""`arise bench` and `arise report`: the paper's evaluation on anyone's prompts."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)

from arise import terminal
from arise.evaluate.prompt_file import read_prompts
from arise.evaluate.records import RunRecord
from arise.evaluate.report import write_report
from arise.evaluate.runner import (
    EXECUTORS,
    BenchConfig,
    judge_missing,
    pending,
    recheck,
    run_bench,
    unjudged,
)
from arise.evaluate.store import BenchStore
from arise.generate.options import GenerateOptions, Mode
from arise.llm.cli_options import ModelOption, ProviderOption, ReplayOption
from arise.validate.types import confinement_summary

console = terminal.console()
errors = terminal.console(stderr=True)

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
    max_repairs: Annotated[int, typer.Option(help="Repair budget per run.")] = 10,
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
    semantic_gate: Annotated[
        bool,
        typer.Option(
            "--semantic-gate/--no-semantic-gate",
            help="arise-mode runs must also agree with the description or be repaired "
            "(on by default; the baselines never gate). The report shows the seconds it "
            "cost. Example: arise bench prompts.jsonl --no-semantic-gate",
        ),
    ] = True,
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
    if executor not in EXECUTORS:
        errors.print(f"[red]error:[/red] --executor is one of {', '.join(EXECUTORS)}")
        raise typer.Exit(2)
    items = read_prompts(prompts)  # PromptFileError: one line, exit 2
    base = GenerateOptions(
        provider=provider,
        model=model,
        max_repairs=max_repairs,
        seed=seed,
        map_dir=map_dir,
        replay=replay,
        semantic_gate=semantic_gate,
        cache=cache,
    )
    config = BenchConfig(
        prompts=items[:limit] if limit else items,
        base=base,
        modes=_modes(modes),
        temperatures=_temperatures(temperatures),
        runs=runs,
        workers=workers,
        executor=executor,
        judge=judge,
        judge_provider=judge_provider,
        judge_model=judge_model,
        ray_address=ray_address,
    )
    with BenchStore(out / "bench.sqlite") as store:  # BenchStoreError: one line, exit 2
        todo = pending(config, store)
        total = len(todo) + len(store.done_keys())
        console.print(
            terminal.text(
                f"{len(todo)} run(s) to do, {total - len(todo)} already in ",
                terminal.name(out / "bench.sqlite"),
            )
        )
        if judge:
            console.print(f"{len(unjudged(config, store))} finished run(s) to judge first")
        try:
            if judge:
                _judge_with_bar(config, store, out)
            _run_with_bar(config, store, out, len(todo))
        except KeyboardInterrupt:
            errors.print("\ninterrupted: finished runs are saved; run the same command to resume")
            raise typer.Exit(130) from None
        records = store.runs()
        written = write_report(records, out / "report", store.meta())
    executed = sum(r.ok for r in records)
    console.print(
        terminal.text(
            f"{executed} of {len(records)} runs executable; report: ", terminal.name(written[0])
        )
    )
    console.print(
        terminal.text("sandbox: ", confinement_summary([r.sandbox for r in records if r.ok]))
    )


def _judge_with_bar(config: BenchConfig, store: BenchStore, out: Path) -> None:
    columns = [
        TextColumn("judging"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        TextColumn("ETA"),
        TimeRemainingColumn(),
    ]
    with Progress(*columns, console=console, disable=not console.is_terminal) as bar:
        task = bar.add_task("judge", total=len(unjudged(config, store)))

        def advance(record: RunRecord) -> None:
            bar.update(task, advance=1)
            if not console.is_terminal:
                scs = record.scs
                console.print(
                    terminal.text(
                        "judged ",
                        terminal.name(record.task.label()),
                        f": SCS {'-' if scs is None else f'{scs:.2f}'}",
                    )
                )

        judge_missing(config, store, out, advance)


def _run_with_bar(config: BenchConfig, store: BenchStore, out: Path, count: int) -> None:
    columns = [
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        TextColumn("ETA"),
        TimeRemainingColumn(),
    ]
    with Progress(*columns, console=console, disable=not console.is_terminal) as bar:
        task = bar.add_task("runs", total=count)
        ok = [0]

        def advance(record: RunRecord) -> None:
            ok[0] += record.ok
            bar.update(task, advance=1, description=f"runs ({ok[0]} executable)")
            if not console.is_terminal:
                console.print(
                    terminal.text(
                        terminal.name(record.task.label()),
                        ": ",
                        terminal.name(record.status),
                        f" ({record.repairs} repairs, {record.seconds:.0f} s)",
                    )
                )

        run_bench(config, store, out, advance)


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
) -> None:
    if not database.is_file():
        errors.print(
            terminal.text(("error:", "red"), " no such database: ", terminal.name(database))
        )
        raise typer.Exit(2)
    with BenchStore(database) as store:  # BenchStoreError: one line, exit 2
        if recheck_runs:
            count = recheck(store, map_dir=map_dir)
            console.print(
                terminal.text(
                    f"re-checked {count} executed run(s); sandbox: ",
                    confinement_summary([r.sandbox for r in store.runs() if r.ok]),
                )
            )
        if search_trials:
            from arise.evaluate.search.bench import search_runs

            count = search_runs(
                store,
                search_trials,
                on_record=lambda r: console.print(
                    terminal.text(
                        "searched ",
                        terminal.name(r.task.label()),
                        ": critical"
                        if (r.criticality or {})["search"]["critical"]
                        else ": not critical",
                        f" within {search_trials} trials",
                    )
                ),
            )
            console.print(f"searched {count} executed run(s)")
        records, meta = store.runs(), store.meta()
    if not records:
        errors.print(
            terminal.text(
                ("error:", "red"), " ", terminal.name(database), " holds no finished runs yet"
            )
        )
        raise typer.Exit(2)
    written = write_report(records, out or database.parent / "report", meta, title)
    for path in written:
        console.print(terminal.text(terminal.name(path)))
