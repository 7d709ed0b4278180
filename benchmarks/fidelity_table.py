"""Fidelity before and after, per labeled set and per fact, from bench databases.

Run:  .venv/bin/python benchmarks/fidelity_table.py \
          --set short out/fidelity-short-before/bench.sqlite out/fidelity-short-after/bench.sqlite \
          --set nhtsa BEFORE.sqlite AFTER.sqlite ...

Prints markdown: per set the runs, ESR, mean fidelity, how often the adversary started on
the labeled side, and the runs with weather or objects the text did not ask for; then per
fact the matched/scored counts of both sides. Every number comes from the verdicts that
`evaluate/fidelity.py` stored in each run (the trace against the hand-written truth).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from arise.evaluate.fidelity import FactKind
from arise.evaluate.metrics import esr_total
from arise.evaluate.records import RunRecord
from arise.evaluate.store import BenchStore


@dataclass
class Summary:
    runs: int
    esr: float | None
    fidelity: float | None
    adversary_side: tuple[int, int]
    unasked_weather: int
    unasked_objects: int
    by_fact: dict[str, tuple[int, int]]


def _adversary_subject(truth: dict[str, Any]) -> str | None:
    """The verdict subject of the labeled adversary (`Car[0]`): role adversary, else the
    first actor."""
    actors = truth.get("actors") or []
    for index, actor in enumerate(actors):
        if actor.get("role") == "adversary":
            return f"{actor['class']}[{index}]"
    return f"{actors[0]['class']}[0]" if actors else None


def summarise(records: Sequence[RunRecord], truths: dict[str, dict[str, Any]]) -> Summary:
    scores: list[float] = []
    side = [0, 0]
    weather = objects = 0
    by_fact: dict[str, list[int]] = {kind.value: [0, 0] for kind in FactKind}
    for record in records:
        fidelity = record.fidelity or {}
        if fidelity.get("score") is not None:
            scores.append(fidelity["score"])
        verdicts = fidelity.get("verdicts") or []
        subject = _adversary_subject(truths.get(record.task.prompt_id, {}))
        for verdict in verdicts:
            if verdict.get("match") is None:
                continue
            row = by_fact.setdefault(verdict["fact"], [0, 0])
            row[1] += 1
            row[0] += bool(verdict["match"])
            if (
                verdict["fact"] == FactKind.START
                and subject
                and (verdict["subject"] == subject or verdict["subject"].startswith(f"{subject}#1"))
            ):
                side[1] += 1
                side[0] += bool(verdict["match"])
            if verdict["fact"] == FactKind.WEATHER and not verdict["match"]:
                weather += "not stated" in str(verdict.get("expected"))
            if verdict["fact"] == FactKind.NO_EXTRA_ACTORS and not verdict["match"]:
                objects += 1
    return Summary(
        runs=len(records),
        esr=esr_total(list(records)),
        fidelity=sum(scores) / len(scores) if scores else None,
        adversary_side=(side[0], side[1]),
        unasked_weather=weather,
        unasked_objects=objects,
        by_fact={name: (row[0], row[1]) for name, row in by_fact.items() if row[1]},
    )


def _share(pair: tuple[int, int]) -> str:
    matched, scored = pair
    return f"{matched}/{scored} ({matched / scored:.2f})" if scored else "-"


def _number(value: float | None) -> str:
    return "-" if value is None else f"{value:.2f}"


def table(name: str, before: Summary, after: Summary) -> str:
    lines = [
        f"### {name}",
        "",
        "| measure | before | after |",
        "|---|---|---|",
        f"| runs | {before.runs} | {after.runs} |",
        f"| ESR | {_number(before.esr)} | {_number(after.esr)} |",
        f"| mean fidelity | {_number(before.fidelity)} | {_number(after.fidelity)} |",
        f"| adversary start side right | {_share(before.adversary_side)} | "
        f"{_share(after.adversary_side)} |",
        f"| runs with weather not asked for | {before.unasked_weather} | {after.unasked_weather} |",
        f"| runs with objects not asked for | {before.unasked_objects} | {after.unasked_objects} |",
    ]
    for fact in FactKind:
        old, new = before.by_fact.get(fact.value), after.by_fact.get(fact.value)
        if old or new:
            lines.append(
                f"| fact: {fact.value} | {_share(old or (0, 0))} | {_share(new or (0, 0))} |"
            )
    return "\n".join(lines)


def _records(path: Path) -> list[RunRecord]:
    with BenchStore(path) as store:
        return list(store.runs())


def _truths(records: Sequence[RunRecord]) -> dict[str, dict[str, Any]]:
    found = {}
    for record in records:
        truth = record.task.truth
        if truth is not None:
            found[record.task.prompt_id] = truth if isinstance(truth, dict) else json.loads(truth)
    return found


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--set", nargs=3, action="append", metavar=("NAME", "BEFORE", "AFTER"), required=True
    )
    args = parser.parse_args(argv)
    for name, before_path, after_path in args.set:
        before, after = _records(Path(before_path)), _records(Path(after_path))
        shared = {r.task.prompt_id for r in before} & {r.task.prompt_id for r in after}
        truths = _truths(after) | _truths(before)
        print(
            table(
                name,
                summarise([r for r in before if r.task.prompt_id in shared], truths),
                summarise([r for r in after if r.task.prompt_id in shared], truths),
            )
        )
        print()
    return 0


if __name__ == "__main__":
    sys.exit(main())
