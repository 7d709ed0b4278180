"""Unintended ego lane changes in executed runs, read from their traces against the labels.

For each run of a labeled dev set (`arise bench` output folders), the ego's lane changes,
weaving and steps in an oncoming lane come from the trace (`trace.json`, the validator's
reading of the road network: `arise.validate.lanes`). What was intended comes from the
hand-written label's `ego_maneuver`: a `lane_change_*` label intends at least one change,
every other label none. A run has an unintended change when it changes lanes without a
lane-change label, or weaves.

Run:  .venv/bin/python benchmarks/ego_lane_changes.py out/fidelity-short-after6 \
          out/fidelity-nhtsa-after6 out/fidelity-crash_reports-after6
The dev prompt set has no labels of its own; its ego lane changes are labeled by hand in
benchmarks/data/dev_prompts_ego_lane_changes.json ('either' runs are not counted).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
DEVSETS = REPO / "src" / "arise" / "evaluate" / "devsets"
DEV_PROMPT_LABELS = REPO / "benchmarks" / "data" / "dev_prompts_ego_lane_changes.json"


def labels() -> dict[str, str | None]:
    """The labeled ego maneuver of every dev-set description, by id."""
    found: dict[str, str | None] = {}
    for path in sorted(DEVSETS.glob("*.jsonl")):
        for line in path.read_text(encoding="utf-8").splitlines():
            if line.strip():
                row = json.loads(line)
                found[row["id"]] = (row.get("truth") or {}).get("ego_maneuver")
    for ident, label in json.loads(DEV_PROMPT_LABELS.read_text(encoding="utf-8")).items():
        if not ident.startswith("_"):
            found[ident] = label
    return found


def ego_of(trace: dict[str, Any]) -> dict[str, Any] | None:
    for agent in trace.get("simulation", {}).get("agents", []):
        if agent.get("is_ego"):
            return dict(agent)
    return None


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bench_dirs", nargs="+", type=Path)
    args = parser.parse_args()
    truth = labels()
    print(
        "| set | executed runs | labeled lane change | of those, changed lanes "
        "| no lane change labeled | of those, unintended change | weaving | runs in an "
        "oncoming lane |"
    )
    print("|---|---|---|---|---|---|---|---|")
    notes: list[str] = []
    for folder in args.bench_dirs:
        rows = []
        for trace_path in sorted(folder.glob("runs/*/*/trace.json")):
            ident = trace_path.parent.parent.name
            ego = ego_of(json.loads(trace_path.read_text(encoding="utf-8")))
            if ego is None:
                continue
            if truth.get(ident) != "either":
                rows.append((ident, truth.get(ident), ego))
        wanted = [r for r in rows if (r[1] or "").startswith("lane_change")]
        others = [r for r in rows if not (r[1] or "").startswith("lane_change")]
        changed = [r for r in wanted if r[2].get("lane_changes", 0) >= 1]
        unintended = [r for r in others if r[2].get("lane_changes", 0) > 0]
        weaving = [r for r in rows if r[2].get("weaving")]
        oncoming = [r for r in rows if r[2].get("opposite_lane_steps", 0) > 0]
        print(
            f"| {folder.name} | {len(rows)} | {len(wanted)} | {len(changed)} | {len(others)} "
            f"| {len(unintended)} | {len(weaving)} | {len(oncoming)} |"
        )
        for ident, label, ego in [*unintended, *[r for r in wanted if r not in changed]]:
            notes.append(
                f"{ident} (label {label}): {ego.get('lane_changes')} change(s), "
                f"weaving {ego.get('weaving')}, behavior {ego.get('behavior')}"
            )
        for ident, label, ego in oncoming:
            notes.append(
                f"{ident} (label {label}): {ego.get('opposite_lane_steps')} steps in an "
                f"oncoming lane, behavior {ego.get('behavior')}"
            )
    for note in notes:
        print(f"- {note}")


if __name__ == "__main__":
    main()
