"""The paper's metrics, computed exactly as it defines them, per category and averaged.

ESR = executable scripts / scripts generated. "Single" counts a run as executable when its
first attempt ran (no repair); "total" when any attempt ran. RCR = mean number of repair
iterations A_i (the successful one included) over the runs that failed first and then ran;
runs that ran first time or never ran are left out, and a group without such runs has no
RCR (the paper's "N/A"). The average row is the mean over categories of the category
values (how the paper's Table I averages), skipping categories without a value.
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

from arise.evaluate.records import RunRecord
from arise.generate.options import Mode


def esr_single(runs: Sequence[RunRecord]) -> float | None:
    return sum(r.first_pass_ok for r in runs) / len(runs) if runs else None


def esr_total(runs: Sequence[RunRecord]) -> float | None:
    return sum(r.ok for r in runs) / len(runs) if runs else None


def rcr(runs: Sequence[RunRecord]) -> float | None:
    repaired = [r.repairs for r in runs if r.ok and not r.first_pass_ok]
    return statistics.mean(repaired) if repaired else None


def _per_executable(runs: Sequence[RunRecord], value: Callable[[RunRecord], float]) -> float | None:
    """What all runs of a group spent, divided by the executable scripts they produced."""
    executed = sum(r.ok for r in runs)
    return sum(value(r) for r in runs) / executed if executed else None


def calls_per_executable(runs: Sequence[RunRecord]) -> float | None:
    return _per_executable(runs, lambda r: r.llm_calls)


def tokens_per_executable(runs: Sequence[RunRecord]) -> float | None:
    return _per_executable(runs, lambda r: r.tokens)


def seconds_per_executable(runs: Sequence[RunRecord]) -> float | None:
    return _per_executable(runs, lambda r: r.seconds)


def median_seconds_executed(runs: Sequence[RunRecord]) -> float | None:
    seconds = [r.seconds for r in runs if r.ok]
    return statistics.median(seconds) if seconds else None


def _mean(values: Iterable[float | None]) -> float | None:
    known = [v for v in values if v is not None and not math.isnan(v)]
    return statistics.mean(known) if known else None


def mean_scs(runs: Sequence[RunRecord]) -> float | None:
    return _mean(r.scs for r in runs if r.ok)


def mean_fidelity(runs: Sequence[RunRecord]) -> float | None:
    """Mean share of hand-labeled facts the traces bear out, over executed runs."""
    return _mean(r.fidelity_score for r in runs if r.ok)


def mean_conformity(runs: Sequence[RunRecord]) -> float | None:
    return _mean(r.conformity_score for r in runs if r.ok)


def collision_rate(runs: Sequence[RunRecord]) -> float | None:
    judged = [r for r in runs if r.ok and r.criticality]
    return (
        sum(bool(r.criticality and r.criticality.get("collision")) for r in judged) / len(judged)
        if judged
        else None
    )


def search_critical_rate(runs: Sequence[RunRecord]) -> float | None:
    """Share of the searched executed runs whose search (`arise report --search-trials`)
    reached a collision or a TTC under 1 s."""
    searched = [
        r.criticality["search"]
        for r in runs
        if r.ok and r.criticality and isinstance(r.criticality.get("search"), dict)
    ]
    return sum(bool(s.get("critical")) for s in searched) / len(searched) if searched else None


def _criticality_mean(name: str) -> Callable[[Sequence[RunRecord]], float | None]:
    def metric(runs: Sequence[RunRecord]) -> float | None:
        return _mean((r.criticality or {}).get(name) for r in runs if r.ok)

    return metric


Metric = Callable[[Sequence[RunRecord]], float | None]
METRICS: dict[str, Metric] = {
    "ESR single": esr_single,
    "ESR total": esr_total,
    "RCR": rcr,
    "SCS": mean_scs,
    "conformity": mean_conformity,
    "fidelity": mean_fidelity,
    "LLM calls / exec": calls_per_executable,
    "tokens / exec": tokens_per_executable,
    "seconds / exec": seconds_per_executable,
    "median s (exec)": median_seconds_executed,
    "collision rate": collision_rate,
    "min distance (m)": _criticality_mean("min_distance"),
    "min TTC (s)": _criticality_mean("min_ttc"),
    "route completion": _criticality_mean("route_completion"),
    "critical after search": search_critical_rate,
}


@dataclass(frozen=True)
class Group:
    """Runs of one method setting: a mode at a temperature (rows of the paper's table)."""

    mode: Mode
    temperature: float

    def label(self) -> str:
        return f"{self.mode} T={self.temperature:g}"


def groups(runs: Iterable[RunRecord]) -> dict[Group, list[RunRecord]]:
    found: dict[Group, list[RunRecord]] = {}
    for run in runs:
        found.setdefault(Group(run.task.mode, run.task.temperature), []).append(run)
    return dict(sorted(found.items(), key=lambda item: (item[0].mode, item[0].temperature)))


def categories(runs: Iterable[RunRecord]) -> list[str]:
    return sorted({run.task.category for run in runs})


def by_category(
    runs: Sequence[RunRecord], metric: Metric, names: Sequence[str]
) -> tuple[dict[str, float | None], float | None]:
    """The metric per category and the mean of the category values (the 'Average' column)."""
    values = {name: metric([r for r in runs if r.task.category == name]) for name in names}
    return values, _mean(values.values())
