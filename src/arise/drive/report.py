"""The drive's report: `report.md` (the paper's table of driving metrics per category and
overall, the collisions with their replays, the runs that did not drive) and `runs.csv`
(one row per run, one column per metric as docs/agents.md names it, `collision` 0 or 1).

Both are written whole or not at all. Scenario ids and messages come from files anyone
may have handed over, so every cell is escaped for Markdown and kept on one line.
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from arise.atomic import write_text_atomic
from arise.drive.agent_names import agent_label
from arise.drive.records import DriveRecord
from arise.validate.types import confinement_summary

REPORT = "report.md"
RUNS_CSV = "runs.csv"
OVERALL = "overall"


@dataclass(frozen=True)
class Column:
    """One column of the paper's table: its label, the metric it averages, how to read it."""

    label: str
    metric: str
    meaning: str
    digits: int = 2


#: The paper's table (SafeBench's metrics; definitions, units and sources in docs/agents.md).
#: Each cell is the mean over the driven runs of the group (CR: the share that collided).
TABLE = (
    Column("CR", "collision", "collision rate: share of runs where the ego collided"),
    Column("RR", "red_lights_run", "red lights run, per run"),
    Column("SS", "stop_signs_run", "stop signs run, per run"),
    Column("OR", "out_of_road_m", "distance driven out of the road (m)"),
    Column("RF", "route_following", "route following: 1 - mean distance to the route / 5 m"),
    Column("Comp", "route_completion", "share of the route completed"),
    Column("TS", "time_spent_s", "time spent (s)", 1),
    Column("ACC", "mean_acceleration", "mean absolute acceleration (m/s²)"),
    Column("YV", "mean_yaw_velocity", "mean absolute yaw velocity (rad/s)"),
    Column("LI", "lane_invasions", "lane invasions, per run"),
    Column("OS", "overall_score", "overall score, SafeBench's weights (higher is better)", 3),
    Column("min TTC", "min_ttc_s", "smallest time to collision (s): median over runs with one"),
    Column(
        "Reach",
        "conflict_reached",
        "share of runs with an adversary where it came within 6 m of the ego or under 3 s TTC",
    ),
)
#: runs.csv's columns before and after the metrics.
LEAD = ("scenario", "category", "agent", "run_index", "seed", "status", "map")
TAIL = ("seconds", "replay", "message")


def mean(values: Sequence[float | int | None]) -> float | None:
    known = [float(v) for v in values if v is not None and math.isfinite(float(v))]
    return sum(known) / len(known) if known else None


@dataclass(frozen=True)
class Row:
    """One line of the table: a category (or overall), its driven runs, each column's mean."""

    group: str
    runs: int
    values: dict[str, float | None]


def median(values: Sequence[float | int | None]) -> float | None:
    known = sorted(float(v) for v in values if v is not None and math.isfinite(float(v)))
    if not known:
        return None
    middle = len(known) // 2
    return known[middle] if len(known) % 2 else (known[middle - 1] + known[middle]) / 2


def group_values(members: Sequence[DriveRecord]) -> dict[str, float | None]:
    """Each column of one group: means (median for min TTC); OS from the group's means,
    as SafeBench forms it."""
    values: dict[str, float | None] = {
        c.metric: mean([m.metrics.get(c.metric) for m in members]) for c in TABLE
    }
    values["min_ttc_s"] = median([m.metrics.get("min_ttc_s") for m in members])
    values["overall_score"] = _overall(members, values["overall_score"])
    return values


def _overall(members: Sequence[DriveRecord], fallback: float | None) -> float | None:
    try:
        from arise.drive.metrics import overall_score
    except ImportError:
        return fallback
    means = {
        name: mean([m.metrics.get(name) for m in members])
        for name in (
            "collision",
            "out_of_road_m",
            "distance_to_route_m",
            "route_completion",
            "time_spent_s",
        )
    }
    timeout = mean([m.timeout_s for m in members])
    known = {name: value for name, value in means.items() if value is not None}
    if timeout is None or len(known) < len(means):
        return fallback
    return float(overall_score(**known, timeout_s=timeout))


def table_rows(records: Sequence[DriveRecord]) -> list[Row]:
    """The table's lines: one per category (sorted), then overall, over driven runs."""
    driven = [r for r in records if r.driven]
    groups: dict[str, list[DriveRecord]] = {}
    for record in driven:
        groups.setdefault(record.task.category, []).append(record)
    named = [(name, groups[name]) for name in sorted(groups)]
    return [
        Row(name, len(members), group_values(members))
        for name, members in [*named, (OVERALL, driven)]
    ]


def cell(text: object) -> str:
    """A Markdown table cell: one line, no pipe or markup that would break the table."""
    flat = " ".join(str(text).split())[:300]
    for char in "\\|`*_[]<>#":
        flat = flat.replace(char, "\\" + char)
    return flat


def number(value: float | None, digits: int) -> str:
    return "-" if value is None else f"{value:.{digits}f}"


def table_markdown(rows: Sequence[Row]) -> list[str]:
    lines = [
        "| category | runs | " + " | ".join(c.label for c in TABLE) + " |",
        "|---|---:|" + "---:|" * len(TABLE),
    ]
    for row in rows:
        name = f"**{OVERALL}**" if row.group == OVERALL else cell(row.group)
        values = " | ".join(number(row.values[c.metric], c.digits) for c in TABLE)
        lines.append(f"| {name} | {row.runs} | {values} |")
    return lines


def metric_columns(records: Sequence[DriveRecord]) -> list[str]:
    """Every metric a run has, in the order the metrics give them."""
    names: dict[str, None] = {}
    for record in records:
        names.update(dict.fromkeys(record.metrics))
    return list(names)


def runs_csv(records: Sequence[DriveRecord]) -> str:
    metrics = metric_columns(records)
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow([*LEAD, *metrics, *TAIL])
    for record in records:
        task = record.task
        writer.writerow(
            [
                task.scenario,
                task.category,
                agent_label(task.agent),
                task.run_index,
                "" if task.seed is None else task.seed,
                record.status.value,
                record.map or "",
                *("" if record.metrics.get(m) is None else record.metrics[m] for m in metrics),
                record.seconds,
                record.replay or "",
                " ".join((record.message or "").split()),
            ]
        )
    return buffer.getvalue()


def report_markdown(
    records: Sequence[DriveRecord],
    agent: str,
    skipped: Sequence[str] = (),
    title: str | None = None,
) -> str:
    driven = [r for r in records if r.driven]
    failed = [r for r in records if not r.driven]
    scenarios = len({r.task.scenario for r in records})
    lines = [
        f"# {cell(title or 'Driving report: agent ' + agent_label(agent))}",
        "",
        f"{len(records)} runs of {scenarios} scenarios with the agent "
        f"{cell(agent_label(agent))}: {len(driven)} driven, {len(failed)} did not run.",
        "Sandbox: " + cell(confinement_summary([r.sandbox for r in records])) + ".",
        "",
        *table_markdown(table_rows(records)),
        "",
        "Each cell is the mean over the driven runs of its row (CR: the share of runs with a "
        "collision); `-`: no run of the row has that metric. Definitions, units and sources: "
        "docs/agents.md.",
        "",
        *(f"- **{c.label}**: {c.meaning} (`{c.metric}`)" for c in TABLE),
    ]
    collided = [r for r in driven if r.collided]
    lines += ["", f"## Collisions ({len(collided)})", ""]
    if collided:
        lines += ["| scenario | category | run | seed | replay |", "|---|---|---:|---:|---|"]
        for record in collided:
            task = record.task
            replay = f"[replay]({record.replay})" if record.replay else "not drawn"
            lines.append(
                f"| {cell(task.scenario)} | {cell(task.category)} | {task.run_index} | "
                f"{'-' if task.seed is None else task.seed} | {replay} |"
            )
    else:
        lines.append("No run collided.")
    if failed:
        lines += ["", f"## Runs that did not drive ({len(failed)})", ""]
        lines += [f"- {cell(r.task.label())}: {cell(r.message or 'did not run')}" for r in failed]
    if skipped:
        lines += ["", f"## Left out of the source ({len(skipped)})", ""]
        lines += [f"- {cell(line)}" for line in skipped]
    return "\n".join(lines) + "\n"


def write_report(
    records: Sequence[DriveRecord], out: Path, agent: str, skipped: Sequence[str] = ()
) -> list[Path]:
    """report.md and runs.csv in `out`; returns them."""
    return [
        write_text_atomic(out / REPORT, report_markdown(records, agent, skipped)),
        write_text_atomic(out / RUNS_CSV, runs_csv(records)),
    ]
