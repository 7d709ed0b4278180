"""`arise generate --critical`: after generation, a search of each executable run's script,
and the report gives the critical instance next to the sampled one.

The generate command lives in a lower layer than the search, so the chaining is a wrapper
around that command, made here and registered by the command line: it adds the
`--critical` and `--critical-trials` options, runs the generate command unchanged, then
searches every run folder it left whose script ran.
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
from arise.evaluate.search.runner import SEARCH_SPAWN_ATTEMPTS, SearchConfig, run_search
from arise.evaluate.search.sampler import SamplerKind
from arise.evaluate.search.store import SearchStore
from arise.present.files import write_text_atomic
from arise.present.tracefile import read_trace
from arise.validate import CheckOptions

console = terminal.console()


def executed_runs(out: Path) -> list[Path]:
    """Run folders under `out` (itself included) whose final script ran."""
    found = []
    for report in sorted([out / "report.json", *out.rglob("*/report.json")]):
        if not report.is_file() or report.parent.name in ("critical", "search"):
            continue
        try:
            status = json.loads(report.read_text(encoding="utf-8")).get("status")
        except (OSError, ValueError):
            continue
        if status == "executed" and (report.parent / "scenario.scenic").is_file():
            found.append(report.parent)
    return list(dict.fromkeys(found))


def _sampled(folder: Path) -> dict[str, Any] | None:
    """The criticality of the scene the run itself ran (its saved trace)."""
    text = (folder / "scenario.scenic").read_text(encoding="utf-8")
    saved = read_trace(folder, text)
    facts = criticality(saved.simulation if saved else None)
    if facts is None or facts.min_distance is None:
        return None
    return {
        "collision": facts.collision,
        "min_ttc": facts.min_ttc,
        "min_distance": facts.min_distance,
        "score": score(Objective.MIN_TTC, facts.collision, facts.min_ttc, facts.min_distance),
    }


def search_run(folder: Path, trials: int, seed: int, map_dir: str | None) -> dict[str, Any]:
    """Search one run folder with VerifAI's cross-entropy sampler; record the critical
    instance next to the sampled one in its report.json."""
    config = SearchConfig(
        script=folder / "scenario.scenic",
        objective=Objective.MIN_TTC,
        sampler=SamplerKind.CE,
        trials=trials,
        seed=seed,
        check=CheckOptions(map_dir=map_dir, spawn_attempts=SEARCH_SPAWN_ATTEMPTS),
    )
    out = folder / "search"
    with SearchStore(out / "search.sqlite") as store:
        result = run_search(config, store)
    files = write_outputs([result], out)
    best = result.best
    entry: dict[str, Any] = {
        "objective": config.objective.value,
        "sampler": config.sampler.value,
        "trials": len(result.trials),
        "seed": seed,
        "sampled": _sampled(folder),
        "critical": None
        if best is None
        else {"trial": best.index + 1, "values": best.values, **best.outcome.as_dict()},
        "first_critical_trial": result.first_critical,
        "script": str(files.critical_script) if files.critical_script else None,
        "notes": files.notes,
    }
    report_path = folder / "report.json"
    report = json.loads(report_path.read_text(encoding="utf-8"))
    report["critical_search"] = entry
    write_text_atomic(report_path, json.dumps(report, indent=2, default=str) + "\n")
    if best is not None:
        console.print(terminal.text("  critical instance: ", describe(best, config.objective)))
        console.print(terminal.text("    ", terminal.name(files.critical_script)))
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
    """The generate command with `--critical [--critical-trials N]` added."""
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
    ]

    @functools.wraps(command)
    def generate_then_search(
        *args: Any, critical: bool, critical_trials: int, **kwargs: Any
    ) -> None:
        code = 0
        try:
            command(*args, **kwargs)
        except typer.Exit as done:
            code = done.exit_code
        if critical and code in (0, 1):
            if critical_trials < 1:
                raise SearchError("--critical-trials must be at least 1")
            for folder in executed_runs(Path(kwargs["out"])):
                console.print(
                    terminal.text(
                        "searching ", terminal.name(folder), f" ({critical_trials} trials)"
                    )
                )
                search_run(folder, critical_trials, int(kwargs["seed"]), kwargs.get("map_dir"))
        raise typer.Exit(code)

    parameters = [*signature.parameters.values(), *extra]
    generate_then_search.__signature__ = signature.replace(  # type: ignore[attr-defined]
        parameters=parameters
    )
    generate_then_search.__annotations__ = {p.name: p.annotation for p in parameters}
    return generate_then_search
