"""`arise bench --agent`: every executed script of a benchmark is also driven by a driving
agent, as `arise drive` does, and the report gets the same metric columns and table.

The drive of a run is kept in its record as a `DriveRecord` (JSON); a database is read
back through that strict model, so a forged or older row is left out, never trusted.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from arise.drive.agent_names import agent_label
from arise.drive.records import DriveRecord, DriveTask
from arise.drive.report import metric_columns, table_markdown, table_rows
from arise.drive.runner import DriveConfig, drive_one
from arise.drive.sources import digest_of
from arise.evaluate.records import RunRecord
from arise.generate.options import GenerateOptions
from arise.present.source import RUN_SCRIPT
from arise.validate import WorkerPool


def drive_run(
    record: RunRecord, agent: str, options: GenerateOptions, pool: WorkerPool
) -> dict[str, Any] | None:
    """The run's executed script driven by `agent` with the run's seed (None: no script)."""
    folder = Path(record.out_dir or "")
    script = folder / RUN_SCRIPT
    try:
        text = script.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return None
    task = DriveTask(
        scenario=record.task.prompt_id,
        category=record.task.category,
        script=str(script),
        digest=digest_of(text),
        agent=agent,
        run_index=record.task.run_index,
        seed=options.seed,
    )
    config = DriveConfig(agent=agent, map_dir=options.map_dir, timeout=options.check_timeout)
    return drive_one(task, config, pool, folder).model_dump(mode="json")


def drives_of(runs: Sequence[RunRecord]) -> list[tuple[RunRecord, DriveRecord]]:
    """The runs that were driven, each with its drive (rows that do not validate are out)."""
    found = []
    for run in runs:
        if run.driving is None:
            continue
        try:
            found.append((run, DriveRecord.model_validate(run.driving)))
        except ValidationError:
            continue
    return found


def csv_columns(runs: Sequence[RunRecord]) -> list[str]:
    """runs.csv's extra columns: the agent, whether it drove, then every metric."""
    drives = [drive for _, drive in drives_of(runs)]
    return ["agent", "driven", *metric_columns(drives)] if drives else []


def csv_cells(run: RunRecord, columns: Sequence[str]) -> list[object]:
    if not columns:
        return []
    try:
        drive = DriveRecord.model_validate(run.driving) if run.driving is not None else None
    except ValidationError:
        drive = None
    if drive is None:
        return [""] * len(columns)
    metrics = [drive.metrics.get(name) for name in columns[2:]]
    return [
        agent_label(drive.task.agent),
        int(drive.driven),
        *("" if value is None else value for value in metrics),
    ]


def markdown_section(runs: Sequence[RunRecord]) -> list[str]:
    """The report's driving section: the paper's table per category and overall."""
    pairs = drives_of(runs)
    if not pairs:
        return []
    drives = [drive for _, drive in pairs]
    agents = sorted({agent_label(d.task.agent) for d in drives})
    collided = sum(d.collided for d in drives)
    return [
        f"## Driving metrics: agent {', '.join(agents)}",
        "",
        f"Every executed script driven with the agent in the ego's seat (`--agent`, as "
        f"`arise drive`): {sum(d.driven for d in drives)} of {len(drives)} driven, "
        f"{collided} with a collision (replays in each run's folder, collisions/). "
        "Each cell is the mean over the driven runs of its row (CR: the share with a "
        "collision; min TTC: the median); definitions in docs/agents.md.",
        "",
        *table_markdown(table_rows(drives)),
        "",
    ]
