"""`arise generate --critical`: after generation, a search of each executable run's script,
and the report gives the critical instance next to the sampled one.

The generate command lives in a lower layer than the search, so the chaining is a wrapper
around that command, made here and registered by the command line: it adds the
`--critical`, `--critical-trials` and `--agent` options, runs the generate command
unchanged, then searches every run folder it left whose script ran. With `--agent`, the
agent drives the ego in every trial, so the critical instance is where that agent fails,
and its replay (run again with the agent) shows it failing.
"""

from __future__ import annotations

import functools
import inspect
import json
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any

import typer

from arise import terminal
from arise.evaluate.criticality import criticality
from arise.evaluate.search.errors import SearchError
from arise.evaluate.search.objective import Objective, score
from arise.evaluate.search.outputs import describe, write_outputs
from arise.evaluate.search.runner import (
    SEARCH_SPAWN_ATTEMPTS,
    SearchConfig,
    run_search,
    search_agent,
    search_folder_name,
)
from arise.evaluate.search.sampler import SamplerKind
from arise.evaluate.search.store import SearchStore
from arise.present.files import write_text_atomic
from arise.present.tracefile import read_trace
from arise.validate import CheckOptions, check
from arise.validate.types import SimulationFacts

console = terminal.console()


def executed_runs(out: Path) -> list[Path]:
    """Run folders under `out` (itself included) whose final script ran."""
    found = []
    for report in sorted([out / "report.json", *out.rglob("*/report.json")]):
        name = report.parent.name
        if not report.is_file() or name in ("critical", "search") or name.startswith("search-"):
            continue
        try:
            status = json.loads(report.read_text(encoding="utf-8")).get("status")
        except (OSError, ValueError):
            continue
        if status == "executed" and (report.parent / "scenario.scenic").is_file():
            found.append(report.parent)
    return list(dict.fromkeys(found))


def _facts(simulation: SimulationFacts | None) -> dict[str, Any] | None:
    facts = criticality(simulation)
    if facts is None or facts.min_distance is None:
        return None
    return {
        "collision": facts.collision,
        "min_ttc": facts.min_ttc,
        "min_distance": facts.min_distance,
        "score": score(Objective.MIN_TTC, facts.collision, facts.min_ttc, facts.min_distance),
    }


def _sampled(folder: Path, check_options: CheckOptions) -> dict[str, Any] | None:
    """The criticality of the scene the run itself ran: its saved trace, or with an agent
    the same script and seed driven by the agent (the run's own ego was scripted)."""
    script = folder / "scenario.scenic"
    if check_options.agent is None:
        saved = read_trace(folder, script.read_text(encoding="utf-8"))
        return _facts(saved.simulation if saved else None)
    result = check(script, check_options)
    return _facts(result.simulation if result.ok else None)


def search_run(
    folder: Path, trials: int, seed: int, map_dir: str | None, agent: str | None = None
) -> dict[str, Any]:
    """Search one run folder with VerifAI's cross-entropy sampler, with `agent` (checked by
    `search_agent`) in the ego's seat if given; record the critical instance next to the
    sampled one in its report.json."""
    config = SearchConfig(
        script=folder / "scenario.scenic",
        objective=Objective.MIN_TTC,
        sampler=SamplerKind.CE,
        trials=trials,
        seed=seed,
        check=CheckOptions(map_dir=map_dir, spawn_attempts=SEARCH_SPAWN_ATTEMPTS, agent=agent),
    )
    out = folder / search_folder_name(agent)
    with SearchStore(out / "search.sqlite") as store:
        result = run_search(config, store)
    files = write_outputs([result], out)
    best = result.best
    replay = next((p for p in files.replay if p.suffix == ".gif"), None)
    entry: dict[str, Any] = {
        "objective": config.objective.value,
        "sampler": config.sampler.value,
        "agent": config.agent_label,
        "trials": len(result.trials),
        "seed": seed,
        "sampled": _sampled(folder, config.check.model_copy(update={"seed": seed})),
        "critical": None
        if best is None
        else {"trial": best.index + 1, "values": best.values, **best.outcome.as_dict()},
        "first_critical_trial": result.first_critical,
        "script": str(files.critical_script) if files.critical_script else None,
        "replay": str(replay) if replay else None,
        "critical_metrics": files.critical_metrics,
        "notes": files.notes,
    }
    report_path = folder / "report.json"
    report = json.loads(report_path.read_text(encoding="utf-8"))
    report["critical_search"] = entry
    write_text_atomic(report_path, json.dumps(report, indent=2, default=str) + "\n")
    if best is not None:
        driver = "" if config.agent is None else f" for the agent {config.agent_label}"
        console.print(
            terminal.text(f"  critical instance{driver}: ", describe(best, config.objective))
        )
        console.print(terminal.text("    ", terminal.name(files.critical_script)))
        if replay is not None:
            console.print(terminal.text("    replay: ", terminal.name(replay)))
    sampled = entry["sampled"]
    if sampled is not None:
        console.print(
            terminal.text(
                f"  sampled instance: min TTC {sampled['min_ttc']}, "
                f"min distance {sampled['min_distance']} m, "
                f"collision {'yes' if sampled['collision'] else 'no'}"
            )
        )
    return entry


def with_critical_search(command: Callable[..., None]) -> Callable[..., None]:
    """The generate command with `--critical [--critical-trials N] [--agent NAME]` added."""
    signature = inspect.signature(command, eval_str=True)
    extra = [
        inspect.Parameter(
            "critical",
            inspect.Parameter.KEYWORD_ONLY,
            default=False,
            annotation=Annotated[
                bool,
                typer.Option(
                    help="Then search each executable script for its most critical instance "
                    "(VerifAI's cross-entropy sampler, min TTC); see `arise search`."
                ),
            ],
        ),
        inspect.Parameter(
            "critical_trials",
            inspect.Parameter.KEYWORD_ONLY,
            default=30,
            annotation=Annotated[int, typer.Option(help="Trials of the --critical search.")],
        ),
        inspect.Parameter(
            "agent",
            inspect.Parameter.KEYWORD_ONLY,
            default=None,
            annotation=Annotated[
                str | None,
                typer.Option(
                    help="With --critical: the agent that drives the ego in every trial "
                    "(idm, cautious, blind, FILE.py:ClassName, as `arise drive --agent`); "
                    "the search looks for where it fails."
                ),
            ],
        ),
    ]

    @functools.wraps(command)
    def generate_then_search(
        *args: Any, critical: bool, critical_trials: int, agent: str | None, **kwargs: Any
    ) -> None:
        if agent is not None and not critical:
            raise SearchError("--agent goes with --critical (the search drives with it)")
        driver = search_agent(agent)  # a bad name: one line, before any generation
        if critical and critical_trials < 1:
            raise SearchError("--critical-trials must be at least 1")
        code = 0
        try:
            command(*args, **kwargs)
        except typer.Exit as done:
            code = done.exit_code
        if critical and code in (0, 1):
            for folder in executed_runs(Path(kwargs["out"])):
                console.print(
                    terminal.text(
                        "searching ", terminal.name(folder), f" ({critical_trials} trials)"
                    )
                )
                search_run(
                    folder, critical_trials, int(kwargs["seed"]), kwargs.get("map_dir"), driver
                )
        raise typer.Exit(code)

    parameters = [*signature.parameters.values(), *extra]
    generate_then_search.__signature__ = signature.replace(  # type: ignore[attr-defined]
        parameters=parameters
    )
    generate_then_search.__annotations__ = {p.name: p.annotation for p in parameters}
    return generate_then_search
