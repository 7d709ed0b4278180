"""`arise check` and `arise maps`: thin wrappers that print what the library returns."""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.panel import Panel
from rich.table import Table

from arise import terminal
from arise.limits import MAX_STEPS
from arise.maps.registry import MapError, MapRegistry
from arise.validate.api import check
from arise.validate.pool import WorkerPool
from arise.validate.types import CheckOptions, CheckResult, Diagnostic, SandboxReport, Simulator

console = terminal.console()
errors = terminal.console(stderr=True)

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


def _png_target(png: str | None, script: Path, many: bool) -> str | None:
    if png is None:
        return None
    if many:
        folder = Path(png)
        folder.mkdir(parents=True, exist_ok=True)
        return str(folder / f"{script.stem}.png")
    return png


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
    try:
        registry = MapRegistry(map_dir)
    except MapError as error:
        errors.print(terminal.text(("error:", "red"), " ", str(error)))
        raise typer.Exit(2) from None
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
    many = len(scripts) > 1
    results: list[CheckResult] = []
    with WorkerPool(size=max(1, min(workers, len(scripts))), memory_mb=memory_mb) as pool:

        def run_one(script: Path, on_stage: Callable[[str], None] | None = None) -> CheckResult:
            per_script = options.model_copy(update={"png": _png_target(png, script, many)})
            return check(script, per_script, pool=pool, registry=registry, on_stage=on_stage)

        if workers > 1 and many:
            with ThreadPoolExecutor(max_workers=pool.size) as executor:
                for result in executor.map(run_one, scripts):
                    results.append(result)
                    if not as_json:
                        _print_result(result)
        else:
            for script in scripts:
                if as_json or not console.is_terminal:
                    result = run_one(script)
                else:
                    shown = terminal.markup_name(script)
                    with console.status(f"{shown}: starting") as status:

                        def show(stage: str, status: Any = status, shown: str = shown) -> None:
                            words = STAGE_WORDS.get(stage) or terminal.markup_name(stage)
                            status.update(f"{shown}: {words}…")

                        result = run_one(script, show)
                results.append(result)
                if not as_json:
                    _print_result(result)
    if as_json:
        payload = [r.model_dump(mode="json") for r in results]
        print(json.dumps(payload if many else payload[0], indent=2))
    elif many:
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
    try:
        registry = MapRegistry(map_dir)
    except MapError as error:
        errors.print(terminal.text(("error:", "red"), " ", str(error)))
        raise typer.Exit(2) from None
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
    import scenic.simulators.carla.blueprints as table

    categories = sorted(
        name.removesuffix("Models")
        for name in dir(table)
        if name.endswith("Models") and isinstance(getattr(table, name), list)
    )
    if category is not None and category not in categories:
        errors.print(
            terminal.text(
                ("error:", "red"),
                f" unknown category {category!r}; choose from {', '.join(categories)}",
            )
        )
        raise typer.Exit(2)
    for name in [category] if category else categories:
        models = ", ".join(getattr(table, f"{name}Models"))
        console.print(terminal.text((name, "bold"), ": ", models))
