"""Replay and OpenSCENARIO export: how long they take and how big the files are, and
whether every export passes the XSD, ASAM's checker and the 10 cm round trip.

Each script is checked once in a warm confined worker (not timed here: see validate.py);
then, from its trace, the replay (scene + GIF + HTML), the still PNG and the export
(scenario.xosc + .xodr copy) are timed, their sizes recorded, and the export verified.
Run folders (`arise generate -o DIR`, status executed) can be added with --runs.

Run:  .venv/bin/python benchmarks/present.py [--steps 200] [--runs out/some-bench/runs]
Prints Markdown tables; copy them into docs/benchmarks.md with the machine and date.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from arise.present.errors import PresentError
from arise.present.replay import write_replay
from arise.present.source import TraceSource, load_trace
from arise.present.verify import asam_check, read_back, worst_gap, xsd_errors
from arise.present.xosc import write_export
from arise.validate import CheckOptions, WorkerPool

REPO = Path(__file__).resolve().parents[1]
SCRIPTS = [
    REPO / "examples" / "pedestrian_crossing.scenic",
    *sorted((REPO / "examples" / "categories").glob("*.scenic")),
]


@dataclass
class Row:
    name: str
    map: str
    agents: int
    steps: int
    replay_s: float
    gif_s: float
    png_s: float
    export_s: float
    gif_kb: float
    html_kb: float
    png_kb: float
    xosc_kb: float
    vertices: int
    xsd_ok: bool
    asam_ok: bool
    worst_gap_m: float


def measure(name: str, source: TraceSource, folder: Path) -> Row:
    started = time.perf_counter()
    replay = write_replay(source, folder, still=True)
    replay_s = time.perf_counter() - started
    export = write_export(source, folder)
    back = read_back(export.xosc)
    gap = max(
        worst_gap(agent, back[agent.name], source.simulation.timestep)
        for agent in source.simulation.agents
        if agent.trajectory
    )
    assert replay.png is not None
    return Row(
        name=name,
        map=source.map.name if source.map else "-",
        agents=len(source.simulation.agents),
        steps=source.simulation.steps,
        replay_s=replay_s - replay.seconds.get("png", 0.0),
        gif_s=replay.seconds["gif"],
        png_s=replay.seconds.get("png", 0.0),
        export_s=export.seconds,
        gif_kb=replay.gif.stat().st_size / 1024,
        html_kb=replay.html.stat().st_size / 1024,
        png_kb=replay.png.stat().st_size / 1024,
        xosc_kb=export.xosc.stat().st_size / 1024,
        vertices=sum(export.vertices.values()),
        xsd_ok=not xsd_errors(export.xosc),
        asam_ok=asam_check(export.xosc).ok,
        worst_gap_m=gap,
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument(
        "--runs", type=Path, action="append", default=[], help="a folder of run folders to add"
    )
    parser.add_argument("--no-examples", action="store_true", help="only the run folders")
    parser.add_argument("--summary", action="store_true", help="one line per group, no table")
    args = parser.parse_args()
    rows: list[Row] = []
    groups: dict[str, list[Row]] = {}
    with WorkerPool(size=1) as pool, tempfile.TemporaryDirectory() as scratch:
        if not args.no_examples:
            for script in SCRIPTS:
                options = CheckOptions(seed=1, steps=args.steps)
                source = load_trace(script, pool=pool, options=options)
                row = measure(script.stem, source, Path(scratch) / script.stem)
                rows.append(row)
                groups.setdefault("examples", []).append(row)
        for folder in args.runs:
            for report in sorted(folder.glob("**/report.json")):
                run = report.parent
                if json.loads(report.read_text()).get("status") != "executed":
                    continue
                try:
                    source = load_trace(run, pool=pool)
                except PresentError as error:
                    print(f"skipped {run}: {error}")
                    continue
                name = f"{folder.name}/{run.relative_to(folder)}"
                row = measure(name, source, Path(scratch) / name.replace("/", "_"))
                rows.append(row)
                groups.setdefault(str(folder), []).append(row)
    load = os.getloadavg()[0]
    print(
        f"machine: {os.cpu_count()} cores, {platform.machine()}, Python "
        f"{platform.python_version()}; load average at the end {load:.1f}\n"
    )
    if args.summary:
        _summary(groups)
        return
    print(
        "| script | map | agents | steps | replay s (scene+GIF+HTML) | GIF s | PNG s | export s"
        " | GIF KiB | HTML KiB | PNG KiB | xosc KiB | vertices | XSD | ASAM | worst gap m |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(
            f"| {r.name} | {r.map} | {r.agents} | {r.steps} | {r.replay_s:.2f} | {r.gif_s:.2f}"
            f" | {r.png_s:.2f} | {r.export_s:.3f} | {r.gif_kb:.0f} | {r.html_kb:.0f}"
            f" | {r.png_kb:.0f} | {r.xosc_kb:.1f} | {r.vertices} | {'ok' if r.xsd_ok else 'FAIL'}"
            f" | {'ok' if r.asam_ok else 'FAIL'} | {r.worst_gap_m:.3f} |"
        )

    def median(values: list[float]) -> str:
        return f"{statistics.median(values):.2f}"

    print(
        f"\nmedian of {len(rows)}: replay {median([r.replay_s for r in rows])} s, "
        f"export {statistics.median([r.export_s for r in rows]):.3f} s, "
        f"GIF {median([r.gif_kb for r in rows])} KiB, HTML {median([r.html_kb for r in rows])} "
        f"KiB, xosc {median([r.xosc_kb for r in rows])} KiB; "
        f"XSD ok {sum(r.xsd_ok for r in rows)}/{len(rows)}, "
        f"ASAM ok {sum(r.asam_ok for r in rows)}/{len(rows)}, "
        f"worst gap {max(r.worst_gap_m for r in rows):.3f} m"
    )


def _summary(groups: dict[str, list[Row]]) -> None:
    print(
        "| traces | n | replay s median (max) | export s median | GIF KiB median (max) "
        "| HTML KiB median | xosc KiB median (max) | XSD ok | ASAM ok | worst gap m |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, rows in groups.items():
        print(
            f"| {name} | {len(rows)} | {statistics.median(r.replay_s for r in rows):.2f} "
            f"({max(r.replay_s for r in rows):.2f}) | "
            f"{statistics.median(r.export_s for r in rows):.3f} | "
            f"{statistics.median(r.gif_kb for r in rows):.0f} ({max(r.gif_kb for r in rows):.0f}) | "
            f"{statistics.median(r.html_kb for r in rows):.0f} | "
            f"{statistics.median(r.xosc_kb for r in rows):.0f} ({max(r.xosc_kb for r in rows):.0f}) | "
            f"{sum(r.xsd_ok for r in rows)}/{len(rows)} | {sum(r.asam_ok for r in rows)}/{len(rows)} | "
            f"{max(r.worst_gap_m for r in rows):.3f} |"
        )


if __name__ == "__main__":
    main()
