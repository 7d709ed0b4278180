"""Compare two bench databases run for run: did a change keep the behaviour?

Run:  .venv/bin/python benchmarks/compare_runs.py BEFORE.sqlite AFTER.sqlite
For each prompt both ran, it compares what the model was asked and answered (prompt and
completion tokens, the extracted spec), what ran (status, first-pass result, repairs, the
kinds of attempts) and what the script did (criticality: closest approach, TTC,
collision, route completion), then prints the differences and the ESR of each side.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from arise.evaluate.metrics import esr_single, esr_total
from arise.evaluate.records import RunRecord
from arise.evaluate.store import BenchStore


def facts(record: RunRecord) -> dict[str, object]:
    return {
        "status": str(record.status),
        "first_pass_ok": record.first_pass_ok,
        "repairs": record.repairs,
        "prompt_tokens": record.prompt_tokens,
        "completion_tokens": record.completion_tokens,
        "spec": record.spec,
        "attempts": [a.kind for a in record.attempts],
        "criticality": record.criticality,
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before", type=Path)
    parser.add_argument("after", type=Path)
    args = parser.parse_args()
    with BenchStore(args.before) as first, BenchStore(args.after) as second:
        before = {r.task.key: r for r in first.runs()}
        after = {r.task.key: r for r in second.runs()}
    shared = sorted(set(before) & set(after))
    differing = 0
    for key in shared:
        old, new = facts(before[key]), facts(after[key])
        changed = [name for name in old if old[name] != new[name]]
        if changed:
            differing += 1
            print(f"{key[0]}: differs in {', '.join(changed)}")
            for name in changed:
                print(f"    before {name}: {old[name]}\n    after  {name}: {new[name]}")
    for name, runs in (
        ("before", [before[k] for k in shared]),
        ("after", [after[k] for k in shared]),
    ):
        print(
            f"{name}: {len(runs)} runs, ESR single {esr_single(runs) or 0:.2f}, "
            f"ESR total {esr_total(runs) or 0:.2f}"
        )
    print(f"{len(shared) - differing} of {len(shared)} runs identical in every compared fact")
    return 0 if differing == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
