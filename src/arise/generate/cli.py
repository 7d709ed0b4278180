"""`arise generate`: descriptions in, executable Scenic scripts (and reports) out."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import typer
from rich.live import Live
from rich.text import Text

from arise import terminal
from arise.generate.batch import (
    BatchEvent,
    BatchRequest,
    DescriptionError,
    RunProgress,
    RunStarted,
    run_batch,
)
from arise.generate.events import AttemptChecked, ProgressEvent, StageStarted
from arise.generate.options import GenerateOptions, Mode, ModelExtraction
from arise.generate.run import GateVerdict, Generation
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

GENERATE_HELP = """Turn traffic-scenario descriptions into executable Scenic 3 scripts.

Each description goes through extraction, retrieval from the knowledge base, assembly and
the test-and-repair loop; DIR gets scenario.scenic, report.json, scene.png and attempts/,
and for a script that ran trace.json, replay.gif, replay.html, scenario.xosc and its map.

Examples:

  arise generate "The ego turns right; a pedestrian crosses from the left and stops." -o out/

  arise generate --file prompts.txt -o out/ --count 3

  arise generate "..." --mode single-pass --provider openai --model gpt-4o-mini

  arise generate "..." --no-semantic-gate   # keep the first script that runs, as it is

  arise generate "..." --ask-model always   # the model reads every description
"""


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
    max_repairs: Annotated[int, typer.Option(help="Repair budget per run.", min=0)] = 10,
    spawn_attempts: Annotated[int, typer.Option(help="Scenes tried per check.", min=1)] = 15,
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
    gate_model_fixes: Annotated[
        bool,
        typer.Option(
            "--model-fixes/--no-model-fixes",
            help="Let the semantic gate ask the model to fix a contradiction once no other "
            "candidate fits (off by default: the embedded model's fixes never removed one "
            "on our sets, and each took about 100 s; worth trying with a hosted model). "
            'Example: arise generate "..." --provider openai --model-fixes',
        ),
    ] = False,
    model_extraction: Annotated[
        ModelExtraction,
        typer.Option(
            "--ask-model",
            metavar="WHEN",
            help="when-needed (default): the model reads the description only when the fixed "
            "rules leave the adversary or its start open; always: on every description, as "
            "the paper does (one more model call, same grounding). "
            'Example: arise generate "..." --ask-model always',
        ),
    ] = ModelExtraction.WHEN_NEEDED,
    as_json: Annotated[bool, typer.Option("--json", help="Print the reports as JSON.")] = False,
) -> None:
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
        gate_model_fixes=gate_model_fixes,
        model_extraction=model_extraction,
    )
    request = BatchRequest(
        description=description,
        file=file,
        out=out,
        count=count,
        options=options,
        refuse_early=not as_json,
    )
    with _Printer(quiet=as_json) as printer:
        batch = run_batch(request, printer.on_event)
    if as_json:
        payload = [done.run.report() for done in batch.runs]
        print(json.dumps(payload[0] if batch.single else payload, indent=2, default=str))
    elif not batch.single:
        console.print(f"\n{batch.executed} of {len(batch.runs)} runs produced an executable script")
    if batch.refusal is not None:
        raise DescriptionError(batch.refusal)
    raise typer.Exit(0 if batch.ok else 1)


class _Printer:
    """Prints a batch's events: a live status line per run on a terminal, then what the
    run made of the description."""

    def __init__(self, quiet: bool):
        self.quiet = quiet
        self.live: Live | None = None
        self.folder = Path()
        self.stage, self.attempt, self.error = "starting", 0, ""

    def __enter__(self) -> _Printer:
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop()

    def on_event(self, event: BatchEvent) -> None:
        if self.quiet:
            return
        if isinstance(event, RunStarted):
            self._start(event.folder)
        elif isinstance(event, RunProgress):
            self._progress(event.event)
        else:
            self._stop()
            _print_run(event.folder, event.run)

    def _start(self, folder: Path) -> None:
        self.folder, self.stage, self.attempt, self.error = folder, "starting", 0, ""
        if console.is_terminal:
            self.live = Live(self._render(), console=console, transient=True, refresh_per_second=4)
            self.live.start()

    def _progress(self, event: ProgressEvent) -> None:
        if self.live is None:
            return
        if isinstance(event, StageStarted):
            self.stage = event.stage.value
            if event.attempt is not None:
                self.attempt = event.attempt
        elif isinstance(event, AttemptChecked):
            self.attempt = event.index
            self.error = event.error or ""
        self.live.update(self._render())

    def _stop(self) -> None:
        if self.live is not None:
            self.live.stop()
            self.live = None

    def _render(self) -> Text:
        line = terminal.text(terminal.name(self.folder), ": ", self.stage)
        if self.attempt:
            line.append(f" (attempt {self.attempt})")
        if self.error:
            error = terminal.shown(self.error, 90, one_line=True)
            line.append_text(terminal.text(("  last error: " + error, "yellow")))
        return line


def _print_run(folder: Path, run: Generation) -> None:
    mark = ("✔", "green") if run.ok else ("✘", "red")
    console.print(terminal.text(mark, " ", terminal.name(folder), ": ", run.summary()))
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
