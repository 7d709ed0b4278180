"""Generator benchmark on the dev prompt set: ESR (first pass and after repair), RCR,
median seconds and LLM tokens per executable script, per category and overall.

Run:  .venv/bin/python benchmarks/generate.py [--limit N] [--mode arise] [--provider P]
      [--out out/bench-dev]
It is `arise bench` on benchmarks/data/dev_prompts.jsonl with the offline default (LLM
cache off), so the runs land in OUT/bench.sqlite, an interrupted run resumes, and
`arise report OUT/bench.sqlite` gives the full evaluation report of the same runs.

With `--prefix-store off|on|both` it runs instead each description in a new
`arise generate` process, as a user would, with the embedded model's prefix store off or
on (both: alternately, off then on for each description, in one run). The store starts
empty in OUT/cache, so the first run with it on builds it; with `--warm` it is built by
`arise llm warm` before any timed run, as on a machine where arise has run once. It prints the median seconds
and tokens per executable script and where the tokens go per call kind; rows go to
OUT/prefix-runs.jsonl, and an interrupted run resumes.
Definitions follow the paper: ESR = executable scripts / runs; RCR = mean repair iterations
(the successful one included) over runs that failed first and then ran.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from arise.evaluate.metrics import esr_single, esr_total, rcr
from arise.evaluate.prompt_file import BenchPrompt, read_prompts
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


def _one_process(prompt_id: str, text: str, store: str, out: Path) -> dict[str, Any]:
    """`arise generate` in a new process; the row of what its report.json says."""
    folder = out / "runs" / f"{prompt_id}-{store}"
    env = {
        **os.environ,
        "ARISE_CACHE_DIR": str(out / "cache"),
        "ARISE_PREFIX_STORE": store,
        "ARISE_LLM_CACHE": "off",
    }
    started = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-m", "arise", "generate", text, "--out", str(folder), "--no-cache"],
        env=env,
        capture_output=True,
        text=True,
        timeout=1800,
    )
    wall = time.perf_counter() - started
    report = (
        json.loads((folder / "report.json").read_text())
        if (folder / "report.json").is_file()
        else {}
    )
    calls = report.get("llm_calls", [])
    return {
        "id": prompt_id,
        "store": store,
        "ok": report.get("status") == "executed",
        "exit": done.returncode,
        "wall_seconds": round(wall, 2),
        "run_seconds": report.get("seconds"),
        "llm": report.get("llm", {}),
        "calls": [
            {"label": c.get("label", ""), "latency": c.get("latency"), **c.get("usage", {})}
            for c in calls
        ],
        "load_average": os.getloadavg()[0],
    }


def _median_of(rows: list[dict[str, Any]], pick: Any) -> float:
    values = [float(pick(r)) for r in rows]
    return statistics.median(values) if values else float("nan")


def select_prompts(args: argparse.Namespace) -> list[BenchPrompt]:
    """The prompt file (the dev set by default), its first --limit prompts, or --sample
    prompts spread evenly over it."""
    prompts = read_prompts(Path(args.prompts))
    if args.sample:
        step = len(prompts) / args.sample
        return [prompts[int(i * step)] for i in range(args.sample)]
    return prompts[: args.limit] if args.limit else prompts


def warm_store(out: Path) -> float:
    """`arise llm warm` into OUT/cache, as an install would do once: the seconds it took."""
    started = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "arise", "llm", "warm"],
        env={**os.environ, "ARISE_CACHE_DIR": str(out / "cache")},
        check=True,
        capture_output=True,
        timeout=1800,
    )
    return time.perf_counter() - started


def prefix_store_runs(args: argparse.Namespace, out: Path) -> None:
    prompts = select_prompts(args)
    stores = ["off", "on"] if args.prefix_store == "both" else [args.prefix_store]
    rows_path = out / "prefix-runs.jsonl"
    out.mkdir(parents=True, exist_ok=True)
    if args.warm and not rows_path.is_file():
        print(f"store built ahead by `arise llm warm` in {warm_store(out):.0f} s", flush=True)
    rows = (
        [json.loads(x) for x in rows_path.read_text().splitlines()] if rows_path.is_file() else []
    )
    done = {(r["id"], r["store"]) for r in rows}
    for prompt in prompts:
        for store in stores:
            if (prompt.id, store) in done:
                continue
            row = _one_process(prompt.id, prompt.description, store, out)
            rows.append(row)
            with rows_path.open("a") as fh:
                fh.write(json.dumps(row) + "\n")
            print(
                f"{prompt.id} store {store}: {'executed' if row['ok'] else 'failed'}, "
                f"{row['wall_seconds']:.0f} s wall, {row['llm'].get('prompt_tokens', 0)} prompt "
                f"tokens ({row['llm'].get('prompt_tokens_evaluated', 0)} evaluated), "
                f"load {row['load_average']:.2f}",
                flush=True,
            )
    print_prefix_table(rows)


def print_prefix_table(rows: list[dict[str, Any]]) -> None:
    print(
        "\n| prefix store | runs | executed | median s per executable script (wall) | p90 s "
        "| median prompt tokens | median prompt tokens evaluated | median completion tokens |"
    )
    print("|---|---|---|---|---|---|---|---|")
    medians: dict[str, float] = {}
    for store in ("off", "on"):
        mine = [r for r in rows if r["store"] == store]
        if not mine:
            continue
        ok = [r for r in mine if r["ok"]]
        medians[store] = _median_of(ok, lambda r: r["wall_seconds"])
        walls = sorted(r["wall_seconds"] for r in ok)
        p90 = walls[min(len(walls) - 1, int(0.9 * len(walls)))] if walls else float("nan")
        print(
            f"| {store} | {len(mine)} | {len(ok)} | {medians[store]:.1f} | {p90:.1f} "
            f"| {_median_of(ok, lambda r: r['llm'].get('prompt_tokens', 0)):.0f} "
            f"| {_median_of(ok, lambda r: r['llm'].get('prompt_tokens_evaluated', 0)):.0f} "
            f"| {_median_of(ok, lambda r: r['llm'].get('completion_tokens', 0)):.0f} |"
        )
    if len(medians) == 2:
        print(f"\nratio off/on of the median seconds: {medians['off'] / medians['on']:.2f}x")
    print(
        "\n| call | store | calls | median prompt tokens | median evaluated | median completion "
        "| median s |"
    )
    print("|---|---|---|---|---|---|---|")
    for label in ("extract", "adapt", "repair"):
        for store in ("off", "on"):
            calls = [
                c for r in rows if r["store"] == store for c in r["calls"] if c["label"] == label
            ]
            if not calls:
                continue
            print(
                f"| {label} | {store} | {len(calls)} "
                f"| {_median_of(calls, lambda c: c.get('prompt_tokens', 0)):.0f} "
                f"| {_median_of(calls, lambda c: c.get('prompt_tokens_evaluated', 0)):.0f} "
                f"| {_median_of(calls, lambda c: c.get('completion_tokens', 0)):.0f} "
                f"| {_median_of(calls, lambda c: c.get('latency') or 0):.1f} |"
            )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--prompts", default=str(PROMPTS), help="prompt file (default: the dev prompt set)"
    )
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
    parser.add_argument(
        "--prefix-store",
        choices=["off", "on", "both"],
        default=None,
        help="run each description in a new `arise generate` process with the prefix store "
        "off, on, or both (alternately); see the module docstring",
    )
    parser.add_argument(
        "--sample", type=int, default=None, help="N prompts spread evenly over the set"
    )
    parser.add_argument(
        "--warm",
        action="store_true",
        help="with --prefix-store: build the store with `arise llm warm` before the first run "
        "(as an installed machine has it), so no timed run pays for building it",
    )
    args = parser.parse_args()
    out = Path(args.out).resolve()
    if args.prefix_store:
        if args.summarize:
            rows_path = out / "prefix-runs.jsonl"
            print_prefix_table([json.loads(x) for x in rows_path.read_text().splitlines()])
        else:
            prefix_store_runs(args, out)
        return
    with BenchStore(out / "bench.sqlite") as store:
        if not args.summarize:
            config = BenchConfig(
                prompts=select_prompts(args),
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
