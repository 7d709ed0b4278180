"""VerifAI's samplers compared on the dev set's executable scripts (`arise search`).

Every sampler gets the same budget of trials per script and the same seeds (a seed fixes
the sampler's draws and the scene's other random choices; each script and seed is one
search). For each
sampler: the share of scripts the search made critical (a collision or a TTC under 1 s in
some trial), the trials it took to the first such trial, the share of critical trials
among all trials (an active sampler should keep finding them once it has one), the best
score, and the wall time of one search. `--timing` also times one search on the local
executor with 1 and 2 workers and on the Ray executor.

The scripts are the dev prompt set's final scripts (benchmarks/data/runs/eval-dev, commit
f83d1cc), copied into benchmarks/data/search_dev/. By default only the ones whose dev-run
scene was not critical are searched (`--all` takes every one): the others are critical at
their first sample, and a search has nothing to find there.

Run:  .venv/bin/python benchmarks/search.py [--trials 30] [--samplers random,halton,ce]
          [--seeds 0,1] [--workers 2] [--out out/bench-search] [--ids so-4,lc-1] [--timing]
Trials go to OUT/search.sqlite: a killed run resumes. Prints Markdown tables; copy them
into docs/benchmarks.md with the machine, the date and the load.
"""

from __future__ import annotations

import argparse
import os
import platform
import sqlite3
import statistics
import time
from pathlib import Path

from arise.evaluate.search import (
    Executor,
    Objective,
    SamplerKind,
    SearchConfig,
    SearchResult,
    SearchStore,
    run_search,
)
from arise.evaluate.search.runner import SEARCH_SPAWN_ATTEMPTS
from arise.validate import CheckOptions

REPO = Path(__file__).resolve().parents[1]
SCRIPTS = REPO / "benchmarks" / "data" / "search_dev"
DEV_BENCH = REPO / "benchmarks" / "data" / "runs" / "eval-dev" / "bench.sqlite"


def not_critical_at_dev_run() -> set[str]:
    """Prompt ids whose dev-run scene had no collision and a TTC of at least 1 s."""
    with sqlite3.connect(DEV_BENCH) as db:
        rows = db.execute(
            "SELECT prompt_id FROM runs WHERE status = 'executed' AND collision = 0 "
            "AND (min_ttc IS NULL OR min_ttc >= 1.0)"
        ).fetchall()
    return {r[0] for r in rows}


def pick_scripts(ids: str | None, take_all: bool) -> list[Path]:
    scripts = sorted(SCRIPTS.glob("*.scenic"))
    if ids:
        wanted = {i.strip() for i in ids.split(",")}
        return [s for s in scripts if s.stem in wanted]
    if take_all:
        return scripts
    calm = not_critical_at_dev_run()
    return [s for s in scripts if s.stem in calm]


def search(
    script: Path,
    sampler: SamplerKind,
    args: argparse.Namespace,
    store: SearchStore,
    executor: Executor = Executor.LOCAL,
    workers: int | None = None,
    seed: int = 0,
) -> tuple[SearchResult, float]:
    config = SearchConfig(
        script=script,
        objective=Objective.MIN_TTC,
        sampler=sampler,
        trials=args.trials,
        workers=workers or args.workers,
        executor=executor,
        seed=seed,
        check=CheckOptions(timeout=60, spawn_attempts=SEARCH_SPAWN_ATTEMPTS),
    )
    started = time.perf_counter()
    result = run_search(config, store)
    return result, time.perf_counter() - started


def _mean(values: list[float], digits: int = 1) -> str:
    return f"{statistics.mean(values):.{digits}f}" if values else "-"


def sampler_table(results: dict[SamplerKind, list[tuple[SearchResult, float]]], budget: int) -> str:
    lines = [
        "| sampler | scripts made critical | trials to first critical (mean over found; "
        "median) | critical trials (mean share) | scripts with a collision | trials to first "
        "collision (mean over found) | collision trials (mean share) | mean best TTC (s) "
        "| wall time of one search (mean s; fresh ones) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for sampler, runs in results.items():
        found = [r.first_critical for r, _ in runs if r.first_critical is not None]
        made = len(found)
        share = [sum(t.outcome.critical for t in r.trials) / max(1, len(r.trials)) for r, _ in runs]
        collided = sum(any(t.outcome.collision for t in r.trials) for r, _ in runs)
        first_collision = [
            float(min(t.index for t in r.trials if t.outcome.collision) + 1)
            for r, _ in runs
            if any(t.outcome.collision for t in r.trials)
        ]
        contact = [
            sum(t.outcome.collision for t in r.trials) / max(1, len(r.trials)) for r, _ in runs
        ]
        best = [
            r.best.outcome.value for r, _ in runs if r.best and r.best.outcome.value is not None
        ]
        fresh = [s for r, s in runs if r.resumed == 0]
        median = f"{statistics.median(found):g}" if found else "-"
        lines.append(
            f"| {sampler.value} | {made}/{len(runs)} ({made / max(1, len(runs)):.0%}) "
            f"| {_mean([float(f) for f in found])}; {median} (budget {budget}) "
            f"| {statistics.mean(share):.0%} | {collided}/{len(runs)} "
            f"| {_mean(first_collision)} | {statistics.mean(contact):.0%} "
            f"| {_mean([float(b) for b in best], 2)} | {_mean(fresh)} |"
        )
    return "\n".join(lines)


def script_table(results: dict[SamplerKind, list[tuple[SearchResult, float]]]) -> str:
    samplers = list(results)
    header = "| script | " + " | ".join(f"{s.value}: best TTC (first critical)" for s in samplers)
    lines = [header + " |", "|---" * (len(samplers) + 1) + "|"]
    names = [f"{r.config.script.stem} (seed {r.config.seed})" for r, _ in results[samplers[0]]]
    for index, name in enumerate(names):
        cells = []
        for sampler in samplers:
            result = results[sampler][index][0]
            best = result.best
            value = "-" if best is None else f"{best.outcome.value:.2f}"
            cells.append(f"{value} ({result.first_critical or '-'})")
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def timing(script: Path, args: argparse.Namespace, seeds: list[int]) -> str:
    """One search of the same script on each executor, each into a fresh database."""
    lines = [
        "| executor | workers | trials | wall time (s) | s per trial |",
        "|---|---|---|---|---|",
    ]
    setups = [(Executor.LOCAL, 1), (Executor.LOCAL, 2), (Executor.RAY, 2)]
    for executor, workers in setups:
        folder = Path(args.out) / f"timing-{executor.value}-{workers}"
        database = folder / "search.sqlite"
        if database.exists():
            database.unlink()
        with SearchStore(database) as store:
            try:
                result, seconds = search(
                    script,
                    SamplerKind.CE,
                    args,
                    store,
                    executor=executor,
                    workers=workers,
                    seed=seeds[0],
                )
            except Exception as error:  # noqa: BLE001  (report, then time the others)
                lines.append(f"| {executor.value} | {workers} | - | failed: {error} | - |")
                continue
        lines.append(
            f"| {executor.value} | {workers} | {len(result.trials)} | {seconds:.0f} "
            f"| {seconds / max(1, len(result.trials)):.2f} |"
        )
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=30)
    parser.add_argument("--samplers", default="random,halton,ce")
    parser.add_argument("--seeds", default="0", help="comma-separated, e.g. 0,1")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out", default="out/bench-search")
    parser.add_argument("--ids", default=None, help="comma-separated prompt ids (e.g. so-4,lc-1)")
    parser.add_argument("--all", action="store_true", help="every dev script, critical or not")
    parser.add_argument("--timing", action="store_true", help="also time the executors")
    args = parser.parse_args()

    samplers = [SamplerKind(s.strip()) for s in args.samplers.split(",")]
    seeds = [int(s) for s in args.seeds.split(",")]
    scripts = pick_scripts(args.ids, args.all)
    load = os.getloadavg()
    print(
        f"machine: {platform.node()}, {os.cpu_count()} cores, python {platform.python_version()}; "
        f"load average at start {load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f}"
    )
    print(
        f"{len(scripts)} scripts x {len(samplers)} samplers x {args.trials} trials, "
        f"seeds {', '.join(map(str, seeds))}"
    )
    results: dict[SamplerKind, list[tuple[SearchResult, float]]] = {s: [] for s in samplers}
    started = time.perf_counter()
    with SearchStore(Path(args.out) / "search.sqlite") as store:
        for seed in seeds:
            for script in scripts:
                for sampler in samplers:
                    result, seconds = search(script, sampler, args, store, seed=seed)
                    results[sampler].append((result, seconds))
                    best = result.best
                    print(
                        f"{script.stem} seed {seed} {sampler.value}: best "
                        f"{'-' if best is None else best.outcome.value} at "
                        f"{'-' if best is None else best.index + 1}, first critical "
                        f"{result.first_critical or '-'}, {seconds:.0f} s"
                        + (f" ({result.resumed} resumed)" if result.resumed else ""),
                        flush=True,
                    )
    total = time.perf_counter() - started
    load = os.getloadavg()
    print(
        f"\nall searches: {total / 60:.1f} min; load average at end {load[0]:.1f} / {load[1]:.1f}"
    )
    print()
    print(sampler_table(results, args.trials))
    print()
    print(script_table(results))
    if args.timing and scripts:
        print()
        print(timing(scripts[0], args, seeds))


if __name__ == "__main__":
    main()
