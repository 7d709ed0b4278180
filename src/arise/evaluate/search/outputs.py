"""What a search leaves behind: the most critical concrete script (and its replay and
OpenSCENARIO file), every trial as CSV, a plot of the score against the trials, and a
JSON summary."""

from __future__ import annotations

import csv
import io
import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from arise.drive.measure import MetricRow
from arise.evaluate.search.objective import CRITICAL_TTC, Objective, outcome
from arise.evaluate.search.runner import SearchResult
from arise.evaluate.search.store import TrialRecord
from arise.present.files import write_bytes_atomic, write_text_atomic
from arise.validate import CheckOptions, WorkerPool, check


@dataclass
class SearchFiles:
    out_dir: Path
    trials_csv: Path
    plot: Path
    summary: Path
    critical_script: Path | None = None
    replay: list[Path] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    #: The driving metrics of the critical script's replay (`arise drive`'s row), when run.
    critical_metrics: MetricRow | None = None


def _fmt(value: float | None, unit: str = "") -> str:
    return "-" if value is None else f"{value:.2f}{unit}"


def describe(trial: TrialRecord, objective: Objective) -> str:
    """One line: the trial's score and its facts."""
    facts = trial.outcome
    if not facts.ok:
        return f"trial {trial.index + 1}: did not run ({facts.message})"
    score = "" if facts.overall_score is None else f", overall score {facts.overall_score:.3f}"
    unit = f" {objective.unit}" if objective.unit else ""
    return (
        f"trial {trial.index + 1}: {objective.value} {_fmt(facts.value)}{unit}; "
        f"collision {'yes' if facts.collision else 'no'}, min TTC {_fmt(facts.min_ttc, ' s')}, "
        f"min distance {_fmt(facts.min_distance, ' m')}{score}"
    )


def critical_header(result: SearchResult, trial: TrialRecord) -> str:
    config = result.config
    if config.agent is None:
        who, again = "", f"arise check scenario.scenic --seed {config.seed}"
    else:
        who = f"# The agent '{config.agent_label}' drove the ego in every trial.\n"
        again = f"arise drive scenario.scenic --agent {config.agent} --seed {config.seed}"
    return (
        f"# arise search: the most critical instance of {config.script.name} found by VerifAI's "
        f"'{config.sampler.value}' sampler in {len(result.trials)} trials (seed {config.seed})\n"
        f"{who}# {describe(trial, config.objective)}\n"
        f"# The same scene again: {again}\n"
    )


def write_trials_csv(results: Sequence[SearchResult], path: Path) -> Path:
    names: list[str] = []
    for result in results:
        names += [p.name for p in result.params if p.name not in names]
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow(
        ["sampler", "agent", "objective", "seed", "trial", *names, "ok", "score", "best_so_far"]
        + ["collision", "min_ttc", "min_distance", "critical", "overall_score", "seconds"]
        + ["message"]
    )
    for result in results:
        config = result.config
        curve = result.best_so_far()
        for trial, best in zip(result.trials, curve, strict=True):
            facts = trial.outcome
            overall = "" if facts.overall_score is None else facts.overall_score
            writer.writerow(
                [config.sampler.value, config.agent_label, config.objective.value, config.seed]
                + [trial.index + 1, *[trial.values.get(n, "") for n in names]]
                + [int(facts.ok), facts.value, best, int(facts.collision), facts.min_ttc]
                + [facts.min_distance, int(facts.critical), overall, facts.seconds]
                + [facts.message or ""]
            )
    return write_text_atomic(path, buffer.getvalue())


def plot_scores(results: Sequence[SearchResult], path: Path, title: str) -> Path:
    """The score of every trial (dots) and the best so far (line), one colour per search."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axis = plt.subplots(figsize=(7, 4))
    objective = results[0].config.objective if results else Objective.MIN_TTC
    for number, result in enumerate(results):
        colour = f"C{number % 10}"
        label = result.config.sampler.value
        ran = [t for t in result.trials if t.outcome.ok and t.outcome.value is not None]
        xs = [t.index + 1 for t in ran]
        ys = [float(t.outcome.value or 0.0) for t in ran]
        axis.scatter(xs, ys, s=14, color=colour, alpha=0.55)
        failed = [t.index + 1 for t in result.trials if not t.outcome.ok]
        if failed:
            axis.scatter(failed, [0] * len(failed), marker="x", color=colour, alpha=0.7)
        curve = result.best_so_far()
        steps = [(i + 1, v) for i, v in enumerate(curve) if v is not None]
        if steps:
            axis.step(
                *zip(*steps, strict=True), where="post", color=colour, label=f"{label}: best so far"
            )
    if objective is Objective.MIN_TTC:
        axis.axhline(CRITICAL_TTC, color="grey", linestyle="--", linewidth=1)
        axis.text(1, CRITICAL_TTC, " critical (TTC < 1 s)", va="bottom", fontsize=8, color="grey")
    axis.set_xlabel("trial")
    axis.set_ylabel(objective.label)
    axis.set_title(title, fontsize=10)
    axis.legend(fontsize=8)
    figure.tight_layout()
    partial = path.with_name(path.name + ".partial.png")
    figure.savefig(partial, dpi=110)
    plt.close(figure)
    partial.replace(path)
    return path


def summary(result: SearchResult) -> dict[str, Any]:
    best = result.best
    return {
        "script": str(result.config.script),
        "key": result.key,
        "sampler": result.config.sampler.value,
        "agent": result.config.agent_label,
        "objective": result.config.objective.value,
        "seed": result.config.seed,
        "trials": len(result.trials),
        "resumed": result.resumed,
        "ran": sum(t.outcome.ok for t in result.trials),
        "critical_trials": sum(t.outcome.critical for t in result.trials),
        "first_found": result.first_found,
        "first_critical": result.first_critical,
        "first_collision": result.first_collision,
        "trial_seconds": round(sum(t.outcome.seconds for t in result.trials), 1),
        "params": [
            {"name": p.name, "kind": p.kind.value, "range": p.describe()} for p in result.params
        ],
        "best": None
        if best is None
        else {"trial": best.index + 1, "values": best.values, **best.outcome.as_dict()},
    }


@dataclass
class CriticalInstance:
    """The best trial's script as written, and what running it again left."""

    script: Path | None
    replay: list[Path] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    metrics: MetricRow | None = None  # its driving metrics, when measured


def write_critical(
    result: SearchResult,
    out_dir: Path,
    *,
    replay: bool = True,
    pool: WorkerPool | None = None,
) -> CriticalInstance:
    """critical/scenario.scenic (the best trial's script) and, when it runs again (with
    the search's agent in the ego's seat), its trace, replay and OpenSCENARIO export
    beside it."""
    best = result.best
    if best is None:
        return CriticalInstance(
            None, notes=["no trial ran: there is no critical instance to write"]
        )
    folder = out_dir / "critical"
    for relative, data in result.files.items():
        write_bytes_atomic(folder / relative, data)
    script = write_text_atomic(
        folder / "scenario.scenic",
        critical_header(result, best) + result.concrete_script(best.values),
    )
    if not replay:
        return CriticalInstance(script, metrics=best.outcome.metrics)
    from arise.present.errors import PresentError
    from arise.present.outputs import write_run_files
    from arise.present.source import from_check

    config = result.config
    options: CheckOptions = config.check.model_copy(update={"seed": config.seed, "png": None})
    checked = check(script, options, pool=pool)
    notes: list[str] = []
    again = outcome(
        checked,
        config.objective,
        0.0,
        config.expression,
        metrics_steps=options.steps if config.measures else None,
    )
    if again.value != best.outcome.value:
        notes.append(
            f"the critical script scored {_fmt(again.value)} when run again "
            f"(the trial: {_fmt(best.outcome.value)}); the scene depends on more than its seed"
        )
    try:
        files = write_run_files(
            from_check(script, checked, options), folder, map_dir=options.map_dir
        )
    except PresentError as error:
        return CriticalInstance(
            script, notes=[*notes, f"no replay: {error}"], metrics=again.metrics
        )
    written = [files.trace, files.replay.gif, files.replay.html, files.export.xosc]
    written += [files.export.xodr] if files.export.xodr is not None else []
    return CriticalInstance(script, written, [*notes, *files.export.notes], again.metrics)


def write_outputs(
    results: Sequence[SearchResult],
    out_dir: Path,
    *,
    replay: bool = True,
    pool: WorkerPool | None = None,
) -> SearchFiles:
    """Everything a search (or several searches of one script) leaves in out_dir."""
    out_dir.mkdir(parents=True, exist_ok=True)
    names = ", ".join(r.config.sampler.value for r in results)
    script_name = results[0].config.script.name if results else "?"
    files = SearchFiles(
        out_dir=out_dir,
        trials_csv=write_trials_csv(results, out_dir / "trials.csv"),
        plot=plot_scores(results, out_dir / "objective.png", f"{script_name}: {names}"),
        summary=out_dir / "search.json",
    )
    ranked = [r for r in results if r.best is not None]
    if ranked:
        winner = min(ranked, key=lambda r: (r.best.outcome.value, r.best.index))  # type: ignore[union-attr]
        critical = write_critical(winner, out_dir, replay=replay, pool=pool)
        files.critical_script, files.replay = critical.script, critical.replay
        files.notes, files.critical_metrics = critical.notes, critical.metrics
    else:
        files.notes.append("no trial ran: there is no critical instance to write")
    document: dict[str, Any] = {
        "agent": results[0].config.agent_label if results else None,
        "searches": [summary(r) for r in results],
        "notes": files.notes,
    }
    if files.critical_script is not None:
        document["critical_script"] = str(files.critical_script)
        document["critical_metrics"] = files.critical_metrics
    write_text_atomic(files.summary, json.dumps(document, indent=2) + "\n")
    return files
