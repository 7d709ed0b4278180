"""Generator benchmark on the dev prompt set: ESR (first pass and after repair), RCR,
median seconds and LLM tokens per executable script, per category and overall.

Run:  .venv/bin/python benchmarks/generate.py [--limit N] [--mode arise] [--provider P]
      [--out out/bench-dev]
It is `arise bench` on benchmarks/data/dev_prompts.jsonl with the offline default (LLM
cache off), so the runs land in OUT/bench.sqlite, an interrupted run resumes, and
`arise report OUT/bench.sqlite` gives the full evaluation report of the same runs.
Definitions follow the paper: ESR = executable scripts / runs; RCR = mean repair iterations
(the successful one included) over runs that failed first and then ran.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from collections.abc import Sequence
from pathlib import Path

from arise.evaluate.metrics import esr_single, esr_total, rcr
from arise.evaluate.prompt_file import read_prompts
from arise.evaluate.records import RunRecord
from arise.evaluate.runner import BenchConfig, run_bench
from arise.evaluate.store import BenchStore
from arise.generate.options import GenerateOptions, Mode

REPO = Path(__file__).resolve().parents[1]
PROMPTS = REPO / "benchmarks" / "data" / "dev_prompts.jsonl"


def _median(values: list[float]) -> str:
    return f"{statistics.median(values):.0f}" if values else "-"


def row(name: str, runs: Sequence[RunRecord]) -> str:
    executed = [r for r in runs if r.ok]
    value = rcr(runs)
    return (
        f"| {name} | {len(runs)} | {esr_single(runs) or 0:.2f} | {esr_total(runs) or 0:.2f} "
        f"| {'-' if value is None else f'{value:.2f}'} "
        f"| {_median([r.seconds for r in executed])} "
        f"| {_median([float(r.tokens) for r in executed])} |"
    )


def print_table(runs: Sequence[RunRecord]) -> None:
    print(
        "| category | runs | ESR first pass | ESR after repair | RCR | median s per "
        "executable script | median LLM tokens per executable script |"
    )
    print("|---|---|---|---|---|---|---|")
    for category in sorted({r.task.category for r in runs}):
        print(row(category, [r for r in runs if r.task.category == category]))
    print(row("**all**", runs))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=int, default=None, help="first N prompts only")
    parser.add_argument("--mode", default="arise", choices=[m.value for m in Mode])
    parser.add_argument("--provider", default=None)
    parser.add_argument("--out", default=str(REPO / "out" / "bench-dev"))
    parser.add_argument(
        "--record",
        default=None,
        help="also record every model call into this cassette (JSONL), so "
        "the same runs can be replayed through other code",
    )
    parser.add_argument(
        "--replay", default=None, help="answer from this cassette instead of the model"
    )
    parser.add_argument(
        "--summarize",
        action="store_true",
        help="only print the table of the runs already in OUT/bench.sqlite",
    )
    args = parser.parse_args()
    out = Path(args.out)
    with BenchStore(out / "bench.sqlite") as store:
        if not args.summarize:
            prompts = read_prompts(PROMPTS)
            config = BenchConfig(
                prompts=prompts[: args.limit] if args.limit else prompts,
                base=GenerateOptions(
                    provider=args.provider, cache=False, record=args.record, replay=args.replay
                ),
                modes=[Mode(args.mode)],
            )
            started = time.perf_counter()

            def progress(record: RunRecord) -> None:
                print(
                    f"{record.task.label()}: {record.status}, {record.repairs} repair(s), "
                    f"{record.seconds:.0f} s, {record.tokens} tokens",
                    flush=True,
                )

            done = run_bench(config, store, out, progress)
            print(
                f"\n{len(done)} runs in {time.perf_counter() - started:.0f} s, "
                f"load average {os.getloadavg()[0]:.2f}\n"
            )
        print_table([r for r in store.runs() if r.task.mode == args.mode])


if __name__ == "__main__":
    main()
