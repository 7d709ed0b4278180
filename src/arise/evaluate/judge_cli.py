"""`arise judge`: a language model scores a Scenic script against its description (SCS)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import typer
from rich.table import Table

from arise import terminal
from arise.evaluate.judge import CRITERIA, DEFAULT_WEIGHTS, Consistency, Judgement, parse_weights
from arise.evaluate.judge_pair import JudgeRequest, judge_pair
from arise.llm.cli_options import (
    ModelOption,
    NoCacheOption,
    ProviderOption,
    RecordOption,
    ReplayOption,
)

console = terminal.console()
errors = terminal.console(stderr=True)

JUDGE_HELP = """Score how well a Scenic script says what its description says (SCS).

A language model rates seven criteria from 0 to 10: adversary_type, behavior,
geometry, weather, participants, requirements, spawn. SCS is the weighted sum
of the scores over 10 x the sum of the weights (equal weights: sum / 70).

SCRIPT is a .scenic file, or a folder written by `arise generate`
(scenario.scenic + report.json); with such a folder, DESCRIPTION "-" takes the
description from its report.json.

--repeat N judges the same pair N times (seed, seed+1, ...) and shows
min/max/mean/std (population std). Exit codes: 0 judged, 1 the model failed or
could not be reached, 2 a mistake in the arguments.

Examples:

  arise judge "A pedestrian crosses in front of the ego and stops." x.scenic

  arise judge - out/

  arise judge - out/ --repeat 10 --temperature 0.7 --json

  arise judge - out/ --weights adversary_type=2,behavior=1.5 --provider gemini
"""


def judge_command(
    description: Annotated[
        str,
        typer.Argument(
            help="The scenario description the script was made from; '-' takes it from "
            "SCRIPT/report.json."
        ),
    ],
    script: Annotated[
        Path, typer.Argument(help="A .scenic file, or a folder written by `arise generate`.")
    ],
    repeat: Annotated[
        int,
        typer.Option(help="Judge the same pair N times (seed, seed+1, ...) and show the spread."),
    ] = 1,
    weights: Annotated[
        str | None,
        typer.Option(
            help="Criterion weights, e.g. adversary_type=2,behavior=1.5 (the rest stay 1)."
        ),
    ] = None,
    provider: ProviderOption = None,
    model: ModelOption = None,
    temperature: Annotated[float, typer.Option(help="Sampling temperature.")] = 0.0,
    seed: Annotated[int, typer.Option(help="Seed for the model (repeat i uses seed + i).")] = 0,
    no_cache: NoCacheOption = False,
    record: RecordOption = None,
    replay: ReplayOption = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print the result as JSON.")] = False,
) -> None:
    # Mistakes (UserMistake, WeightsError) and model failures (LLMError) are AriseErrors:
    # the command line prints them on one line (exit 2 and 1).
    judged = judge_pair(
        JudgeRequest(
            description=description,
            script=script,
            repeat=repeat,
            weights=parse_weights(weights),
            provider=provider,
            model=model,
            temperature=temperature,
            seed=seed,
            cache=False if no_cache else None,
            record=record,
            replay=replay,
        )
    )
    result = judged.result
    if as_json:
        payload = {
            "description": judged.description,
            "script": str(judged.script),
            **result.as_dict(),
        }
        # ASCII: a C1 control or a bidi override in a reason stays an escape in the output
        print(json.dumps(payload, indent=2))
        return
    if isinstance(result, Judgement):
        _print_judgement(result)
    else:
        if temperature == 0:
            errors.print(
                "[dim]note: at temperature 0 a deterministic model (the local one) "
                "gives the same answer for every seed; try --temperature 0.7[/dim]"
            )
        _print_consistency(result)


def _weighted(weights: dict[str, float]) -> bool:
    return weights != DEFAULT_WEIGHTS


def _print_judgement(result: Judgement) -> None:
    table = Table(show_edge=False, pad_edge=False)
    table.add_column("criterion")
    table.add_column("score", justify="right")
    if _weighted(result.weights):
        table.add_column("weight", justify="right")
    table.add_column("reason", overflow="fold")
    for name in CRITERIA:
        row = [name, f"{result.scores[name]}/10"]
        if _weighted(result.weights):
            row.append(f"{result.weights[name]:g}")
        table.add_row(*row, terminal.text(result.reasons[name]))
    console.print(table)
    source = "cache" if result.cached else f"{result.seconds:.1f} s"
    console.print(
        terminal.text(
            (f"SCS {100 * result.scs:.2f} %", "bold"),
            "  ",
            (
                f"({terminal.name(result.model)}, {source}, {result.usage.prompt_tokens} prompt"
                f" + {result.usage.completion_tokens} completion tokens)",
                "dim",
            ),
        )
    )


def _print_consistency(result: Consistency) -> None:
    table = Table(
        show_edge=False,
        pad_edge=False,
        title=f"{len(result.runs)} judgements of the same script (population std)",
    )
    for column in ("criterion", "min", "max", "mean", "std"):
        table.add_column(column, justify="left" if column == "criterion" else "right")
    for name, stats in result.criteria.items():
        table.add_row(
            name, f"{stats.min:g}", f"{stats.max:g}", f"{stats.mean:.2f}", f"{stats.std:.2f}"
        )
    scs = result.scs
    table.add_row(
        "[bold]SCS %[/bold]",
        f"{100 * scs.min:.2f}",
        f"{100 * scs.max:.2f}",
        f"{100 * scs.mean:.2f}",
        f"{100 * scs.std:.2f} pp",
    )
    console.print(table)
    for line in result.failures:
        console.print(terminal.text(("failed:", "yellow"), " ", line))
    usage = result.usage
    console.print(
        f"[dim]{usage.calls} calls, {usage.seconds:.1f} s, {usage.prompt_tokens} "
        f"prompt + {usage.completion_tokens} completion tokens[/dim]"
    )
