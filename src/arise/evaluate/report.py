"""`arise report`: Markdown and CSV tables shaped like the paper's Table I, and two plots."""

from __future__ import annotations

import csv
import io
import math
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from arise.evaluate.metrics import METRICS, Group, Metric, by_category, categories, groups
from arise.evaluate.records import RunRecord
from arise.generate.options import Mode
from arise.generate.outputs import write_atomic
from arise.validate.types import confinement_summary
from arise.vocabulary import PAPER_CATEGORIES

# Rows of the main table: (metric, "pass" column as the paper prints it).
TABLE_METRICS = [("ESR single", "single"), ("ESR total", "total"), ("RCR", "total")]
COST_METRICS = [
    "LLM calls / exec",
    "tokens / exec",
    "seconds / exec",
    "median s (exec)",
    "gate seconds / run",
]
QUALITY_METRICS = ["fidelity", "conformity", "gate met", "SCS"]
CRITICALITY_METRICS = [
    "collision rate",
    "min distance (m)",
    "min TTC (s)",
    "route completion",
    "critical after search",
]
PAPER_ORDER = list(PAPER_CATEGORIES)


def gate_seconds_per_run(runs: Sequence[RunRecord]) -> float | None:
    """Mean seconds a gated run spent on attempts made only because of the semantic gate."""
    gated = [r.gate_seconds for r in runs if r.gate_on]
    return sum(gated) / len(gated) if gated else None


def gate_met(runs: Sequence[RunRecord]) -> float | None:
    """Share of executed gated runs whose final script agrees with the spec."""
    judged = [r for r in runs if r.ok and r.gate in ("passed", "contradicts")]
    return sum(r.gate == "passed" for r in judged) / len(judged) if judged else None


# The paper's metrics and the semantic gate's own two.
REPORT_METRICS: dict[str, Metric] = {
    **METRICS,
    "gate seconds / run": gate_seconds_per_run,
    "gate met": gate_met,
}


@dataclass(frozen=True)
class Cell:
    metric: str
    group: Group
    values: dict[str, float | None]
    average: float | None


def ordered_categories(runs: Sequence[RunRecord]) -> list[str]:
    found = categories(runs)
    return [c for c in PAPER_ORDER if c in found] + [c for c in found if c not in PAPER_ORDER]


def _format(value: float | None, metric: str) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "N/A"
    if metric in (
        "SCS",
        "conformity",
        "gate met",
        "collision rate",
        "route completion",
        "critical after search",
    ) or metric.startswith("ESR"):
        return f"{value:.3f}"
    if metric.startswith(("tokens", "seconds", "median", "gate seconds")):
        return f"{value:.0f}"
    return f"{value:.2f}"


def cells(runs: Sequence[RunRecord], metrics: Sequence[str]) -> list[Cell]:
    names = ordered_categories(runs)
    found = []
    for metric in metrics:
        for group, members in groups(runs).items():
            if metric == "RCR" and group.mode is not Mode.ARISE:
                continue  # no repair loop, no RCR (the paper leaves the row out)
            values, average = by_category(members, REPORT_METRICS[metric], names)
            found.append(Cell(metric, group, values, average))
    return found


def _markdown_table(
    runs: Sequence[RunRecord], metrics: Sequence[str], with_pass: bool = False
) -> str:
    names = ordered_categories(runs)
    passes = dict(TABLE_METRICS)
    head = ["Metric", "Method", "T"] + (["Pass"] if with_pass else []) + names + ["Average"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for cell in cells(runs, metrics):
        row = [
            cell.metric.split(" ")[0] if with_pass else cell.metric,
            cell.group.mode,
            f"{cell.group.temperature:g}",
        ]
        if with_pass:
            row.append(passes.get(cell.metric, ""))
        row += [_format(cell.values[n], cell.metric) for n in names]
        row.append(f"**{_format(cell.average, cell.metric)}**")
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines)


def table_csv(runs: Sequence[RunRecord]) -> str:
    names = ordered_categories(runs)
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow(["metric", "mode", "temperature", *names, "average"])
    for cell in cells(
        runs, [m for m, _ in TABLE_METRICS] + QUALITY_METRICS + COST_METRICS + CRITICALITY_METRICS
    ):
        writer.writerow(
            [
                cell.metric,
                cell.group.mode,
                cell.group.temperature,
                *("" if cell.values[n] is None else round(cell.values[n] or 0, 4) for n in names),
                "" if cell.average is None else round(cell.average, 4),
            ]
        )
    return buffer.getvalue()


def runs_csv(runs: Sequence[RunRecord]) -> str:
    from arise.evaluate.driving import csv_cells, csv_columns

    driving = csv_columns(runs)
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow(
        [
            "prompt_id",
            "category",
            "mode",
            "temperature",
            "run",
            "status",
            "first_pass_ok",
            "repairs",
            "llm_calls",
            "tokens",
            "seconds",
            "conformity",
            "gate",
            "gate_seconds",
            "scs",
            "collision",
            "min_distance",
            "min_ttc",
            "route_completion",
            "message",
            *driving,
        ]
    )
    for r in runs:
        crit = r.criticality or {}
        writer.writerow(
            [
                r.task.prompt_id,
                r.task.category,
                r.task.mode,
                r.task.temperature,
                r.task.run_index,
                r.status,
                int(r.first_pass_ok),
                r.repairs,
                r.llm_calls,
                r.tokens,
                round(r.seconds, 1),
                r.conformity_score,
                r.gate,
                round(r.gate_seconds, 1),
                r.scs,
                crit.get("collision"),
                crit.get("min_distance"),
                crit.get("min_ttc"),
                crit.get("route_completion"),
                (r.message or "")[:200],
                *csv_cells(r, driving),
            ]
        )
    return buffer.getvalue()


def _failure_kinds(runs: Sequence[RunRecord]) -> str:
    first = Counter(f"{a.stage}: {a.error_type}" for r in runs for a in r.attempts[:1] if not a.ok)
    fixes = Counter(a.kind for r in runs for a in r.attempts[1:])
    if not first and not fixes:
        return "Every run that produced a script ran on its first attempt."
    lines = ["| first-attempt failure | runs |", "|---|---|"]
    lines += [f"| {kind} | {count} |" for kind, count in first.most_common()]
    lines += ["", "| repair kind | attempts | of which ran |", "|---|---|---|"]
    ran = Counter(a.kind for r in runs for a in r.attempts[1:] if a.ok)
    lines += [f"| {kind} | {count} | {ran[kind]} |" for kind, count in fixes.most_common()]
    return "\n".join(lines)


def _mismatches(runs: Sequence[RunRecord]) -> str:
    counts = Counter(
        m.split(":")[0] for r in runs if r.ok for m in (r.conformity or {}).get("mismatches", [])
    )
    if not counts:
        return "No mismatches."
    return "\n".join(
        ["| check | runs that disagree |", "|---|---|"]
        + [f"| {name} | {count} |" for name, count in counts.most_common()]
    )


def _settings(meta: dict[str, object]) -> str:
    options = meta.get("options")
    options = options if isinstance(options, dict) else {}
    shown = {
        key: options.get(key)
        for key in (
            "provider",
            "model",
            "max_repairs",
            "spawn_attempts",
            "simulator",
            "seed",
            "semantic_gate",
        )
        if key in options
    }
    shown["provider"] = shown.get("provider") or "embedded local model"
    shown.update({key: meta[key] for key in ("modes", "temperatures", "runs") if key in meta})
    return "Settings: " + ", ".join(f"{key} = {value}" for key, value in shown.items()) + "."


def markdown(runs: Sequence[RunRecord], title: str, meta: dict[str, object]) -> str:
    from arise.evaluate.driving import markdown_section as driving_section

    statuses = Counter(r.status for r in runs)
    parts = [
        f"# {title}",
        "",
        f"{len(runs)} runs over {len({r.task.prompt_id for r in runs})} prompts; "
        + ", ".join(f"{n} {s}" for s, n in statuses.most_common())
        + ".",
        "",
        _settings(meta),
        "",
        "Confinement of the scripts' final checks: "
        + confinement_summary([r.sandbox for r in runs if r.ok])
        + ".",
        "",
        "## ESR and RCR per category (the paper's Table I)",
        "",
        "ESR single: the first assembled script ran. ESR total: it ran after at most the "
        "repair budget. RCR: mean repair iterations, the successful one included, over runs "
        "that failed first and then ran (N/A: no such run). Average: mean of the category "
        "values.",
        "",
        _markdown_table(runs, [m for m, _ in TABLE_METRICS], with_pass=True),
        "",
        "## Semantic conformity",
        "",
        "fidelity: share of the hand-written facts of the prompt (actor classes and counts, "
        "start sides and directions, ego maneuver, road, weather, required objects, "
        "closeness) that the trace bears out (N/A: the prompt has no truth). conformity: "
        "share of the deterministic facts (adversary class, ego maneuver, road, start "
        "position, reach of the ego's path, weather, other objects) that agree with the "
        "model's own extracted spec, a weaker, second number. gate met: share of the "
        "scripts the semantic gate judged that agree with the spec; the others ran but "
        "kept contradictions when the repair budget was spent (N/A: gate off). SCS: the "
        "LLM judge's score (N/A when not judged). All over executed runs.",
        "",
        _markdown_table(runs, QUALITY_METRICS),
        "",
        _mismatches(runs),
        "",
        "## Cost per executable script",
        "",
        "What all runs of a category spent divided by its executable scripts; the median is "
        "over executed runs. gate seconds / run: mean seconds per gated run spent on "
        "checks and repairs made only because the semantic gate failed a script that ran "
        "(N/A: gate off).",
        "",
        _markdown_table(runs, COST_METRICS),
        "",
        "## Criticality from the traces",
        "",
        "Between the ego and the adversary in executed runs: collision rate, mean closest "
        "approach, mean smallest time-to-collision, mean ego route completion. critical "
        "after search: share of the executed scripts whose search (`arise report "
        "--search-trials N`, VerifAI's cross-entropy sampler) reached a collision or a TTC "
        "under 1 s (N/A: not searched).",
        "",
        _markdown_table(runs, CRITICALITY_METRICS),
        "",
        *driving_section(runs),
        "## Failures and repairs",
        "",
        _failure_kinds(runs),
        "",
        "Plots: `esr_by_category.png`, `repair_iterations.png`. Per-run rows: `runs.csv`.",
    ]
    return "\n".join(parts) + "\n"


def plot_esr(runs: Sequence[RunRecord], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = ordered_categories(runs)
    bars = cells(runs, ["ESR single", "ESR total"])
    figure, axis = plt.subplots(figsize=(max(6.0, 1.1 * len(names) + 2), 4))
    width = 0.8 / max(1, len(bars))
    for i, cell in enumerate(bars):
        xs = [k + i * width for k in range(len(names))]
        axis.bar(
            xs,
            [cell.values[n] or 0 for n in names],
            width,
            label=f"{cell.metric} ({cell.group.label()})",
        )
    axis.set_xticks([k + 0.4 - width / 2 for k in range(len(names))])
    axis.set_xticklabels([n.replace("_", "\n") for n in names], fontsize=8)
    axis.set_ylim(0, 1.05)
    axis.set_ylabel("ESR")
    axis.legend(fontsize=8)
    figure.tight_layout()
    _save(figure, path)


def plot_repairs(runs: Sequence[RunRecord], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    repaired = [r.repairs for r in runs if r.ok and not r.first_pass_ok]
    figure, axis = plt.subplots(figsize=(6, 3.5))
    if repaired:
        top = max(repaired)
        axis.hist(repaired, bins=range(1, top + 2), align="left", rwidth=0.8)
        axis.set_xticks(range(1, top + 1))
    axis.set_xlabel("repair iterations until the script ran")
    axis.set_ylabel("runs")
    axis.set_title(f"Repaired runs: {len(repaired)}")
    figure.tight_layout()
    _save(figure, path)


def _save(figure: object, path: Path) -> None:
    import matplotlib.pyplot as plt

    partial = path.with_name(path.name + ".partial.png")
    figure.savefig(partial, dpi=110)  # type: ignore[attr-defined]
    plt.close(figure)  # type: ignore[arg-type]
    partial.replace(path)


def write_report(
    runs: Sequence[RunRecord],
    out_dir: Path,
    meta: dict[str, object],
    title: str = "arise benchmark report",
) -> list[Path]:
    """All report files into out_dir (each written whole or not at all)."""
    out_dir.mkdir(parents=True, exist_ok=True)
    written = []
    for name, text in (
        ("report.md", markdown(runs, title, meta)),
        ("table.csv", table_csv(runs)),
        ("runs.csv", runs_csv(runs)),
    ):
        write_atomic(out_dir / name, text)
        written.append(out_dir / name)
    plot_esr(runs, out_dir / "esr_by_category.png")
    plot_repairs(runs, out_dir / "repair_iterations.png")
    return written + [out_dir / "esr_by_category.png", out_dir / "repair_iterations.png"]
