"""`arise check` and `arise maps`: thin wrappers that print what the library returns."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Annotated

import typer
from rich.panel import Panel
from rich.status import Status
from rich.table import Table

from arise import terminal
from arise.limits import MAX_STEPS
from arise.maps.registry import MapRegistry
from arise.validate.batch import CheckEvent, ScriptStage, ScriptStarted, check_scripts
from arise.validate.catalog import blueprints
from arise.validate.types import CheckOptions, CheckResult, Diagnostic, SandboxReport, Simulator

console = terminal.console()

STAGE_WORDS = {
    "gate": "static gate",
    "parse": "parsing",
    "compile": "compiling",
    "sample": "sampling a scene",
    "simulate": "simulating",
}

CHECK_HELP = """Prove that Scenic 3 scripts execute: static gate, compile, sample a scene, simulate.

Scripts written for `model scenic.simulators.carla.model` run unchanged on arise's
offline CARLA-compatible world model; `--simulator carla` uses a real CARLA server.
Every script runs in a confined worker (Landlock, seccomp, rlimits); the output says
which confinement was active.

Examples:

  arise check examples/pedestrian_crossing.scenic

  arise check my.scenic --png scene.png --steps 200 --seed 7

  arise check out/*.scenic --json > results.json

  arise check my.scenic --map-dir ../shared/maps/CARLA

  arise check downloaded.scenic --require-sandbox
"""


def _diagnostic_panel(d: Diagnostic) -> Panel:
    """The diagnostic in a red box; every word of it came from the worker (untrusted)."""
    body = terminal.text((d.error_type, "bold"), ": ", d.message)
    where = []
    if d.line:
        where.append(f"line {d.line}" + (f", column {d.column}" if d.column else ""))
    if d.section:
        where.append(f"section {terminal.name(d.section)}")
    if where:
        body.append("\nat " + ", ".join(where))
    if d.excerpt:
        body.append_text(terminal.text("\n\n", d.excerpt))
    for rejection in d.rejections[:5]:
        body.append_text(terminal.text(f"\nrejected {rejection.count}x: ", rejection.reason))
    if d.hint:
        body.append_text(terminal.text("\n\n", ("hint:", "cyan"), " ", d.hint))
    return Panel(
        body,
        title=terminal.text(f"failed in stage '{d.stage.value}'"),
        border_style="red",
        expand=False,
    )


def _print_result(result: CheckResult) -> None:
    mark = ("✔ ", "green") if result.ok else ("✘ ", "red")
    script = terminal.name(result.script)
    console.print(terminal.text(mark, (script, "bold"), "  ", result.summary()))
    if result.map is not None:
        note = (
            f" (substitute for {result.map.requested})"
            if result.map.substituted and result.map.requested
            else ""
        )
        console.print(terminal.text("  map: ", f"{result.map.name}{note}"))
    print_sandbox(result.sandbox)
    for rejection in result.simulation_rejections:
        console.print(
            terminal.text(
                "  ",
                ("note:", "yellow"),
                f" {rejection.count} simulation(s) rejected before this one: ",
                rejection.reason,
            )
        )
    for warning in result.warnings:
        console.print(terminal.text("  ", ("note:", "yellow"), " ", warning))
    if result.diagnostic is not None:
        console.print(_diagnostic_panel(result.diagnostic))
    if result.simulation is not None and result.simulation.ego_pairs:
        table = Table(title="ego vs. others", show_edge=False)
        for column in ("agent", "min distance (m)", "at step", "min TTC (s)", "collision"):
            table.add_column(column)
        for pair in result.simulation.ego_pairs:
            table.add_row(
                terminal.text(terminal.name(pair.other)),
                f"{pair.min_distance:.2f}",
                str(pair.min_distance_step),
                "-" if pair.min_ttc is None else f"{pair.min_ttc:.2f}",
                "yes" if pair.collided else "no",
            )
        console.print(table)
    if result.timings:
        console.print(
            terminal.text(
                "  timings: ", ", ".join(f"{k} {v:.2f}s" for k, v in result.timings.items())
            )
        )
    if result.png:
        console.print(terminal.text("  picture: ", result.png))


def print_sandbox(sandbox: SandboxReport | None, indent: str = "  ") -> None:
    """One line saying which confinement a script ran under; loud when incomplete."""
    if sandbox is None:
        console.print(
            terminal.text(
                f"{indent}sandbox: ", ("none (the script never reached a worker)", "yellow")
            )
        )
    elif sandbox.full:
        console.print(terminal.text(f"{indent}sandbox: ", sandbox.label))
    else:
        console.print(terminal.text(indent, (f"sandbox: {sandbox.label}", "bold red")))
        for note in sandbox.notes:
            console.print(terminal.text(f"{indent}  ", (note, "red")))


class _CheckPrinter:
    """Prints a check's events: a status line while one script runs on a terminal, then
    each script's verdict."""

    def __init__(self, quiet: bool):
        self.quiet = quiet
        self.status: Status | None = None
        self.shown = ""

    def __enter__(self) -> _CheckPrinter:
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop()

    def on_event(self, event: CheckEvent) -> None:
        if self.quiet:
            return
        if isinstance(event, ScriptStarted):
            if console.is_terminal:
                self.shown = terminal.markup_name(event.script)
                self.status = console.status(f"{self.shown}: starting")
                self.status.start()
        elif isinstance(event, ScriptStage):
            if self.status is not None:
                words = STAGE_WORDS.get(event.stage) or terminal.markup_name(event.stage)
                self.status.update(f"{self.shown}: {words}…")
        else:
            self._stop()
            _print_result(event.result)

    def _stop(self) -> None:
        if self.status is not None:
            self.status.stop()
            self.status = None


def check_command(
    scripts: Annotated[list[Path], typer.Argument(help="Scenic files to check.")],
    simulator: Annotated[
        Simulator, typer.Option(help="offline (arise's world model) or carla (a CARLA server).")
    ] = Simulator.OFFLINE,
    map_dir: Annotated[
        str | None,
        typer.Option(help="Folder of extra .xodr maps, e.g. CARLA towns (env ARISE_MAP_DIR)."),
    ] = None,
    steps: Annotated[
        int, typer.Option(min=1, max=MAX_STEPS, help="Simulation steps to run.")
    ] = 300,
    spawn_attempts: Annotated[
        int, typer.Option(help="Scenes to try when a spawn fails or a simulation is rejected.")
    ] = 15,
    sample_iterations: Annotated[
        int, typer.Option(help="Rejection-sampling iterations per scene.")
    ] = 500,
    seed: Annotated[int | None, typer.Option(help="Random seed, for a repeatable run.")] = None,
    timeout: Annotated[float, typer.Option(help="Wall-clock limit per script, seconds.")] = 60,
    memory_mb: Annotated[int, typer.Option(help="Memory limit per check, MB.")] = 1536,
    as_json: Annotated[bool, typer.Option("--json", help="Print results as JSON.")] = False,
    png: Annotated[
        str | None,
        typer.Option(
            help="Write a picture of the scene and trajectories (a folder if several scripts)."
        ),
    ] = None,
    carla_host: Annotated[str, typer.Option(help="CARLA server host.")] = "127.0.0.1",
    carla_port: Annotated[int, typer.Option(help="CARLA server port.")] = 2000,
    workers: Annotated[int, typer.Option(help="Parallel worker processes.")] = 1,
    require_sandbox: Annotated[
        bool,
        typer.Option(
            "--require-sandbox",
            help="Refuse to run a script unless every confinement mechanism is active "
            "(also ARISE_REQUIRE_SANDBOX=1 or `[sandbox] require = true` in the config).",
        ),
    ] = False,
) -> None:
    options = CheckOptions(
        simulator=simulator,
        map_dir=map_dir,
        steps=steps,
        spawn_attempts=spawn_attempts,
        sample_iterations=sample_iterations,
        seed=seed,
        timeout=timeout,
        memory_mb=memory_mb,
        carla_host=carla_host,
        carla_port=carla_port,
        require_sandbox=require_sandbox,
    )
    with _CheckPrinter(quiet=as_json) as printer:
        results = check_scripts(
            scripts, options, workers=workers, png=png, on_event=printer.on_event
        )
    if as_json:
        payload = [r.model_dump(mode="json") for r in results]
        print(json.dumps(payload if len(results) > 1 else payload[0], indent=2))
    elif len(results) > 1:
        passed = sum(r.ok for r in results)
        console.print(f"\n{passed} of {len(results)} scripts executed")
    raise typer.Exit(0 if all(r.ok for r in results) else 1)


maps_app = typer.Typer(
    help="Maps: what is available and what each one offers.", no_args_is_help=True
)


@maps_app.command("list")
def maps_list(
    map_dir: Annotated[str | None, typer.Option(help="Folder of extra .xodr maps.")] = None,
) -> None:
    """List the maps a script can run on, with their features."""
    registry = MapRegistry(map_dir)  # MapError: one line, exit 2
    table = Table(title="maps")
    for column in ("name", "source", "features", "file"):
        table.add_column(column)
    for name in registry.names():
        entry = registry.entries[name]
        table.add_row(
            terminal.text(terminal.name(name)),
            terminal.text(terminal.name(entry.source)),
            terminal.text(", ".join(sorted(entry.features)) or "?"),
            terminal.text(terminal.name(os.path.relpath(entry.path))) if entry.path else "-",
        )
    console.print(table)


def blueprints_command(
    category: Annotated[
        str | None,
        typer.Argument(
            help="car, truck, motorcycle, bicycle, walker, busStop, ... (all if omitted)"
        ),
    ] = None,
) -> None:
    """List the CARLA blueprints of the installed CARLA version, by category."""
    for name, models in blueprints(category).items():  # UnknownCategory: one line, exit 2
        console.print(terminal.text((name, "bold"), ": ", ", ".join(models)))
