"""Generator benchmark on the dev prompt set: ESR (first pass and after repair), RCR,
median seconds and LLM tokens per executable script, per category and overall.

Run:  .venv/bin/python benchmarks/generate.py [--limit N] [--mode arise] [--provider P]
      [--out out/bench-generate]
Definitions follow the paper: ESR = executable scripts / runs; RCR = mean repair iterations
(including the successful one) over runs that failed first and succeeded after repair.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time
from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from arise.generate.options import GenerateOptions, Mode
from arise.generate.pipeline import Generation, Generator
from arise.llm.types import Usage

REPO = Path(__file__).resolve().parents[1]
PROMPTS = REPO / "benchmarks" / "data" / "dev_prompts.jsonl"


def rcr(runs: list[Any]) -> float | None:
    repaired = [run.repairs for run in runs if run.ok and not run.first_pass_ok]
    return statistics.mean(repaired) if repaired else None


def row(name: str, runs: list[Any]) -> str:
    executed = [run for run in runs if run.ok]
    first = sum(run.first_pass_ok for run in runs)
    seconds = statistics.median(run.seconds for run in executed) if executed else float("nan")
    tokens = (statistics.median(run.usage.total_tokens for run in executed)
              if executed else float("nan"))
    value = rcr(runs)
    return (f"| {name} | {len(runs)} | {first / len(runs):.2f} | {len(executed) / len(runs):.2f} "
            f"| {'-' if value is None else f'{value:.2f}'} | {seconds:.0f} | {tokens:.0f} |")


@dataclass
class Finished:
    """What the table needs from one report.json."""

    ok: bool
    first_pass_ok: bool
    repairs: int
    seconds: float
    usage: Usage


def summarize(out: Path) -> None:
    categories = {json.loads(line)["id"]: json.loads(line)["category"]
                  for line in PROMPTS.read_text().splitlines() if line.strip()}
    runs: dict[str, list[Finished]] = defaultdict(list)
    for path in sorted(out.glob("*/report.json")):
        report = json.loads(path.read_text())
        if report["status"] == "running":
            continue
        runs[categories.get(path.parent.name, "other")].append(Finished(
            ok=report["status"] == "executed", first_pass_ok=report["first_pass_ok"],
            repairs=report["repairs"], seconds=report["seconds"],
            usage=Usage.from_dict(report["llm"])))
    print_table(runs)


def print_table(runs: dict[str, list[Any]]) -> None:
    everything = [run for group in runs.values() for run in group]
    print("| category | runs | ESR first pass | ESR after repair | RCR | median s per "
          "executable script | median LLM tokens per executable script |")
    print("|---|---|---|---|---|---|---|")
    for category in sorted(runs):
        print(row(category, runs[category]))
    print(row("**all**", everything))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=int, default=None, help="first N prompts only")
    parser.add_argument("--mode", default="arise", choices=[m.value for m in Mode])
    parser.add_argument("--provider", default=None)
    parser.add_argument("--out", default=str(REPO / "out" / "bench-generate"))
    parser.add_argument("--summarize", action="store_true",
                        help="only print the table from the reports already in --out "
                             "(e.g. of an interrupted run)")
    args = parser.parse_args()
    if args.summarize:
        summarize(Path(args.out))
        return
    prompts = [json.loads(line) for line in PROMPTS.read_text().splitlines() if line.strip()]
    prompts = prompts[: args.limit] if args.limit else prompts
    options = GenerateOptions(mode=Mode(args.mode), provider=args.provider, cache=False)
    runs: dict[str, list[Generation]] = defaultdict(list)
    started = time.perf_counter()
    with Generator(options) as generator:
        for index, prompt in enumerate(prompts, 1):
            run = generator.generate(prompt["description"], Path(args.out) / prompt["id"])
            runs[prompt["category"]].append(run)
            print(f"[{index}/{len(prompts)}] {prompt['id']}: {run.summary()}", flush=True)
    everything = [run for group in runs.values() for run in group]
    print(f"\nmode {args.mode}, {len(everything)} runs, {time.perf_counter() - started:.0f} s, "
          f"load average {os.getloadavg()[0]:.2f}\n")
    print_table(runs)


if __name__ == "__main__":
    main()
