"""`arise replay` and `arise export`: thin wrappers that print what the library wrote."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from arise import terminal
from arise.present.source import TraceSource
from arise.present.targets import export_target, replay_target
from arise.present.xosc import EgoMode

console = terminal.console()

REPLAY_HELP = """Draw the animated replay of a run: replay.gif and replay.html.

TARGET is a run folder of `arise generate` (its saved trace.json is used; without one the
script is checked again in the confined validator with the run's seed) or a .scenic script
(checked in the confined validator first). replay.html is one self-contained page (no
network) with play, pause, scrub, a clock and a legend beside the map.

Examples:

  arise replay out/demo

  arise replay examples/pedestrian_crossing.scenic --out /tmp/crossing

  arise replay out/demo --png        # also redraw scene.png with the same drawing
"""

EXPORT_HELP = """Export a run as ASAM OpenSCENARIO 1.2: scenario.xosc and the .xodr it references.

Every agent becomes an entity (class, bounding box, CARLA blueprint) with its initial
world position and speed and one timed FollowTrajectoryAction from the trace; the weather
it ran with (a preset, or its parameters: fog as a visual range, the sun's angles) becomes
the environment and the scenario stops when the trace ends. With
`--ego free` the ego keeps its start but no trajectory: the system under test drives it.
TARGET is a run folder or a .scenic script, as for `arise replay`. See docs/export.md.

Examples:

  arise export out/demo

  arise export out/demo --ego free --out /tmp/demo-sut

  arise export examples/pedestrian_crossing.scenic --out /tmp/crossing
"""

TargetArgument = Annotated[
    Path, typer.Argument(help="A run folder (scenario.scenic + report.json) or a .scenic script.")
]
OutOption = Annotated[
    Path | None,
    typer.Option(
        "--out",
        "-o",
        help="Folder for the files (default: the run folder; for a script, a folder named "
        "after it beside it).",
    ),
]
MapDirOption = Annotated[
    str | None,
    typer.Option(help="Folder of extra .xodr maps, e.g. CARLA towns (env ARISE_MAP_DIR)."),
]


def _say_source(source: TraceSource) -> None:
    console.print(
        terminal.text(
            f"trace: {source.origin.value}, {source.simulation.steps} steps, "
            f"{len(source.simulation.agents)} agents",
            f", map {terminal.name(source.map.name)}" if source.map else "",
        )
    )
    for note in source.notes:
        console.print(terminal.text("  note: ", note))


def replay_command(
    target: TargetArgument,
    out: OutOption = None,
    png: Annotated[
        bool, typer.Option("--png", help="Also write scene.png, the still at the interaction.")
    ] = False,
    map_dir: MapDirOption = None,
) -> None:
    replayed = replay_target(target, out, still=png, map_dir=map_dir)
    _say_source(replayed.source)
    files = replayed.files
    for path in (files.gif, files.html, files.png):
        if path is not None:
            size = path.stat().st_size // 1024
            console.print(terminal.text("wrote ", terminal.name(path), f" ({size} KiB)"))


def export_command(
    target: TargetArgument,
    out: OutOption = None,
    ego: Annotated[
        EgoMode,
        typer.Option(
            help="replay: the ego follows its trace; free: the system under test drives it."
        ),
    ] = EgoMode.REPLAY,
    map_dir: MapDirOption = None,
) -> None:
    exported = export_target(target, out, ego, map_dir=map_dir)
    _say_source(exported.source)
    files = exported.files
    console.print(
        terminal.text(
            "wrote ",
            terminal.name(files.xosc),
            f" (OpenSCENARIO 1.2, {sum(files.vertices.values())} trajectory vertices "
            f"for {len(files.vertices)} agents)",
        )
    )
    if files.xodr is not None:
        console.print(
            terminal.text("wrote ", terminal.name(files.xodr), " (the map it references)")
        )
    for note in files.notes:
        console.print(terminal.text("  note: ", note))
