"""`arise generate`: descriptions in, executable Scenic scripts (and reports) out."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.live import Live
from rich.text import Text

from arise import terminal
from arise.generate.events import AttemptChecked, ProgressEvent, StageStarted
from arise.generate.extract import check_description
from arise.generate.options import GenerateOptions, Mode
from arise.generate.pipeline import Generator, slug
from arise.generate.run import GateVerdict, Generation, RunStatus
from arise.llm.cli_options import (
    ModelOption,
    NoCacheOption,
    ProviderOption,
    RecordOption,
    ReplayOption,
)
from arise.llm.prefix_store import default_store_dir
from arise.validate.types import Simulator, confinement_summary

console = terminal.console()
errors = terminal.console(stderr=True)

GENERATE_HELP = """Turn traffic-scenario descriptions into executable Scenic 3 scripts.

Each description goes through extraction, retrieval from the knowledge base, assembly and
the test-and-repair loop; DIR gets scenario.scenic, report.json, scene.png and attempts/,
and for a script that ran trace.json, replay.gif, replay.html, scenario.xosc and its map.

Examples:

  arise generate "The ego turns right; a pedestrian crosses from the left and stops." -o out/

  arise generate --file prompts.txt -o out/ --count 3

  arise generate "..." --mode single-pass --provider openai --model gpt-4o-mini

  arise generate "..." --no-semantic-gate   # keep the first script that runs, as it is
"""


def _read_descriptions(text: str | None, file: Path | None) -> list[tuple[str, str]]:
    """(id, description) pairs from the argument and/or a .txt (one per line) or .jsonl file."""
    found: list[tuple[str, str]] = []
    if text is not None:
        found.append((slug(text), text))
    if file is not None:
        if not file.is_file():
            raise typer.BadParameter(f"no such file: {file}", param_hint="--file")
        for number, line in enumerate(file.read_text(encoding="utf-8").splitlines(), 1):
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            if file.suffix == ".jsonl":
                try:
                    row = json.loads(line)
                except json.JSONDecodeError as error:
                    raise typer.BadParameter(
                        f"{file}:{number}: not JSON ({error.msg})", param_hint="--file"
                    ) from None
                description = str(row.get("description", ""))
                ident = str(row.get("id") or f"{number:03d}-{slug(description)}")
            else:
                description, ident = line.strip(), f"{number:03d}-{slug(line)}"
            found.append((ident, description))
    return found


def generate_command(
    description: Annotated[str | None, typer.Argument(help="The scenario, in words.")] = None,
    out: Annotated[Path, typer.Option("-o", "--out", help="Output folder.")] = Path("out"),
    file: Annotated[
        Path | None,
        typer.Option(
            help="Descriptions, one per line (.txt) or JSON lines with 'description' (.jsonl)."
        ),
    ] = None,
    count: Annotated[int, typer.Option(help="Runs per description.")] = 1,
    provider: ProviderOption = None,
    model: ModelOption = None,
    temperature: Annotated[float, typer.Option(help="Sampling temperature.")] = 0.0,
    topk: Annotated[
        int,
        typer.Option(
            help="Candidates kept per component: the first is used, the others replace it when "
            "repair swaps a section.",
            min=1,
        ),
    ] = 10,
    max_repairs: Annotated[int, typer.Option(help="Repair budget per run.")] = 10,
    spawn_attempts: Annotated[int, typer.Option(help="Scenes tried per check.")] = 15,
    simulator: Annotated[Simulator, typer.Option(help="offline or carla.")] = Simulator.OFFLINE,
    mode: Annotated[Mode, typer.Option(help="arise, single-pass or chatscene.")] = Mode.ARISE,
    map_dir: Annotated[str | None, typer.Option(help="Extra maps (e.g. CARLA towns).")] = None,
    seed: Annotated[int, typer.Option(help="Seed for sampling and the model.")] = 0,
    no_cache: NoCacheOption = False,
    record: RecordOption = None,
    replay: ReplayOption = None,
    semantic_gate: Annotated[
        bool,
        typer.Option(
            "--semantic-gate/--no-semantic-gate",
            help="In arise mode (the default), a script that runs must also agree with the "
            "description (adversary class, start side, ego maneuver, road, reach of the "
            "ego's path, missing or extra actors, weather) or be repaired; when the budget "
            "runs out, the script that ran with the fewest contradictions is kept and they "
            "are reported. Never on in the single-pass and chatscene baselines. "
            'Example: arise generate "..." --no-semantic-gate',
        ),
    ] = True,
    as_json: Annotated[bool, typer.Option("--json", help="Print the reports as JSON.")] = False,
) -> None:
    descriptions = _read_descriptions(description, file)
    if not descriptions:
        errors.print("[red]error:[/red] give a description or --file")
        raise typer.Exit(2)
    single = len(descriptions) == 1 and count == 1
    refusal = check_description(descriptions[0][1]) if single and not as_json else None
    if refusal:  # said before the model, the KB or a validator worker is loaded
        errors.print(terminal.text(("error:", "red"), " ", refusal))
        raise typer.Exit(2)
    options = GenerateOptions(
        mode=mode,
        provider=provider,
        model=model,
        temperature=temperature,
        topk=topk,
        max_repairs=max_repairs,
        spawn_attempts=spawn_attempts,
        simulator=simulator,
        map_dir=map_dir,
        seed=seed,
        cache=False if no_cache else None,
        record=record,
        replay=replay,
        semantic_gate=semantic_gate,
    )
    runs: list[Generation] = []
    with Generator(options) as generator:  # bad KB or map folders raise AriseError
        for ident, text in descriptions:
            for index in range(count):
                folder = out if single else out / (ident if count == 1 else f"{ident}/run-{index}")
                generator.reconfigure(
                    options.model_copy(update={"run_index": index, "seed": seed + index})
                )
                run = _run_with_progress(generator, text, folder, quiet=as_json)
                runs.append(run)
                if not as_json:
                    mark = ("✔", "green") if run.ok else ("✘", "red")
                    console.print(
                        terminal.text(mark, " ", terminal.name(folder), ": ", run.summary())
                    )
                    if run.usage.prefixes_built:
                        console.print(
                            terminal.text(
                                "  prefix store: first run, kept the model's state after "
                                f"{run.usage.prefixes_built} fixed prompt prefix(es) in "
                                f"{default_store_dir()}; later runs load it instead of "
                                "reading them again"
                            )
                        )
                    labels = [
                        a.check.sandbox.label if a.check and a.check.sandbox else None
                        for a in run.attempts
                        if a.check is not None
                    ]
                    if labels:
                        console.print(terminal.text("  sandbox: ", confinement_summary(labels)))
                    _print_grounding(run)
                    for note in run.contradictions:
                        console.print(terminal.text("  ", ("contradiction:", "yellow"), " ", note))
                    _print_gate(run)
    if as_json:
        payload = [run.report() for run in runs]
        print(json.dumps(payload[0] if single else payload, indent=2, default=str))
    elif not single:
        done = sum(run.ok for run in runs)
        console.print(f"\n{done} of {len(runs)} runs produced an executable script")
    if single and runs[0].status is RunStatus.REFUSED:
        errors.print(terminal.text(("error:", "red"), " ", runs[0].message))
        raise typer.Exit(2)
    raise typer.Exit(0 if all(run.ok for run in runs) else 1)


def _print_grounding(run: Generation) -> None:
    """What the spec rests on: each fact with the words it came from, or "not stated";
    and what the model said that the description does not."""
    if run.spec is None or not run.spec.grounding:
        return
    console.print("  read from the description:")
    for fact in run.spec.grounding:
        console.print(terminal.text("    ", fact.describe()))
    for actor in run.spec.actors:
        console.print(terminal.text("    ", actor.describe()))
    for note in run.hint_notes:
        console.print(terminal.text("    ", (note, "dim")))
    if run.ignored_text:
        console.print("  left out (not part of the scenario):")
        for text in run.ignored_text:
            console.print(terminal.text("    ", (text, "dim")))


def _print_gate(run: Generation) -> None:
    """The semantic gate's verdict on the final script and what it cost (the summary line
    already lists the contradictions left)."""
    verdict = run.gate
    if verdict is GateVerdict.OFF or verdict is GateVerdict.NOT_REACHED:
        return
    cost = f"; {run.gate_seconds:.0f} s of checks and repairs for it" if run.gate_seconds else ""
    if verdict is GateVerdict.PASSED:
        console.print(f"  semantic gate: agrees with the description{cost}")
        return
    sections = ", ".join(dict.fromkeys(c.section for c in run.contradictions_left))
    console.print(
        terminal.text(
            "  ",
            ("semantic gate:", "yellow"),
            " not met within the repair budget; section(s) to change: ",
            sections,
            cost,
        )
    )


def _run_with_progress(generator: Generator, text: str, folder: Path, quiet: bool) -> Generation:
    if quiet or not console.is_terminal:
        return generator.generate(text, folder)
    state: dict[str, Any] = {"stage": "starting", "attempt": 0, "error": ""}

    def render() -> Text:
        line = terminal.text(terminal.name(folder), ": ", state["stage"])
        if state["attempt"]:
            line.append(f" (attempt {state['attempt']})")
        if state["error"]:
            error = terminal.shown(state["error"], 90, one_line=True)
            line.append_text(terminal.text(("  last error: " + error, "yellow")))
        return line

    with Live(render(), console=console, transient=True, refresh_per_second=4) as live:

        def update(event: ProgressEvent) -> None:
            if isinstance(event, StageStarted):
                state["stage"] = event.stage.value
                if event.attempt is not None:
                    state["attempt"] = event.attempt
            elif isinstance(event, AttemptChecked):
                state["attempt"] = event.index
                state["error"] = event.error or ""
            live.update(render())

        return generator.generate(text, folder, update)
