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

Against an agent (issue 31): `--agents blind,cautious,idm` puts each agent in the ego's seat
of every trial (default: none, the scripts' own ego), and `--scripts DIR...` takes the run
folders of `arise bench` (or `arise generate`) found under each DIR instead: every
RUN/scenario.scenic whose report.json says it executed. A run's category is its
report.json's `category`, else the bench database's (DIR/bench.sqlite, by the run's
folder), else its prompt folder's name (`runs/<prompt>/<mode>`) without its number. Then,
per agent and category: the share of scripts where the search found a failure (a collision
or a TTC under 1 s) within the trials, and the median trials to the first failure (over the
scripts where it found one), per sampler; and the driving metrics of the critical instances.

Run:  .venv/bin/python benchmarks/search.py [--trials 30] [--samplers random,halton,ce]
          [--seeds 0,1] [--workers 2] [--out out/bench-search] [--ids so-4,lc-1] [--timing]
          [--agents blind,cautious,idm] [--scripts out/bench-dev ...] [--objective score]
Trials go to OUT/search.sqlite: a killed run resumes. Prints Markdown tables; copy them
into docs/benchmarks.md with the machine, the date and the load.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import re
import sqlite3
import statistics
import time
from dataclasses import dataclass
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
from arise.evaluate.search.critical import executed_runs
from arise.evaluate.search.runner import SEARCH_SPAWN_ATTEMPTS, search_agent
from arise.validate import CheckOptions

REPO = Path(__file__).resolve().parents[1]
SCRIPTS = REPO / "benchmarks" / "data" / "search_dev"
DEV_BENCH = REPO / "benchmarks" / "data" / "runs" / "eval-dev" / "bench.sqlite"
DEV_PROMPTS = REPO / "benchmarks" / "data" / "dev_prompts.jsonl"
#: The driving metrics shown for the critical instances (docs/agents.md#metrics).
METRIC_COLUMNS = (
    ("CR", "collision"),
    ("RR", "red_lights_run"),
    ("SS", "stop_signs_run"),
    ("OR (m)", "out_of_road_m"),
    ("Comp", "route_completion"),
    ("ACC", "mean_acceleration"),
    ("LI", "lane_invasions"),
    ("OS", "overall_score"),
)


@dataclass(frozen=True)
class Script:
    path: Path
    name: str
    category: str


def dev_categories() -> dict[str, str]:
    categories = {}
    for line in DEV_PROMPTS.read_text(encoding="utf-8").splitlines():
        if line.strip():
            prompt = json.loads(line)
            categories[prompt["id"]] = prompt["category"]
    return categories


def _bench_categories(root: Path) -> dict[str, str]:
    """Run folder (resolved) -> category, from the bench database at the root, if any."""
    database = root / "bench.sqlite"
    if not database.is_file():
        return {}
    with sqlite3.connect(database) as db:
        rows = db.execute("SELECT out_dir, category FROM runs WHERE out_dir IS NOT NULL")
        return {str(Path(out).resolve()): category for out, category in rows}


def run_scripts(roots: list[Path]) -> list[Script]:
    """Every executed run folder under the roots, with its name and category."""
    found: list[Script] = []
    for root in roots:
        bench = _bench_categories(root)
        for run in executed_runs(root):
            report = json.loads((run / "report.json").read_text(encoding="utf-8"))
            in_bench = run.parent.parent.name == "runs"  # runs/<prompt>/<mode>
            prompt = run.parent.name if in_bench else run.name
            category = (
                report.get("category")
                or bench.get(str(run.resolve()))
                or re.sub(r"[-_]?\d+$", "", prompt)
                or "uncategorised"
            )
            name = str(run.relative_to(root)) if run != root else run.name
            found.append(Script(run / "scenario.scenic", f"{root.name}/{name}", category))
    return found


def not_critical_at_dev_run() -> set[str]:
    """Prompt ids whose dev-run scene had no collision and a TTC of at least 1 s."""
    with sqlite3.connect(DEV_BENCH) as db:
        rows = db.execute(
            "SELECT prompt_id FROM runs WHERE status = 'executed' AND collision = 0 "
            "AND (min_ttc IS NULL OR min_ttc >= 1.0)"
        ).fetchall()
    return {r[0] for r in rows}


def pick_scripts(ids: str | None, take_all: bool) -> list[Script]:
    categories = dev_categories()
    scripts = [
        Script(p, p.stem, categories.get(p.stem, "uncategorised"))
        for p in sorted(SCRIPTS.glob("*.scenic"))
    ]
    if ids:
        wanted = {i.strip() for i in ids.split(",")}
        return [s for s in scripts if s.name in wanted]
    if take_all:
        return scripts
    calm = not_critical_at_dev_run()
    return [s for s in scripts if s.name in calm]


def search(
    script: Path,
    sampler: SamplerKind,
    args: argparse.Namespace,
    store: SearchStore,
    executor: Executor = Executor.LOCAL,
    workers: int | None = None,
    seed: int = 0,
    agent: str | None = None,
) -> tuple[SearchResult, float]:
    config = SearchConfig(
        script=script,
        objective=Objective(args.objective),
        sampler=sampler,
        trials=args.trials,
        workers=workers or args.workers,
        executor=executor,
        seed=seed,
        check=CheckOptions(timeout=60, spawn_attempts=SEARCH_SPAWN_ATTEMPTS, agent=agent),
        until_found=args.until_found,
    )
    started = time.perf_counter()
    result = run_search(config, store)
    return result, time.perf_counter() - started


def _mean(values: list[float], digits: int = 1) -> str:
    return f"{statistics.mean(values):.{digits}f}" if values else "-"


def _best_label(results: dict[SamplerKind, list[tuple[SearchResult, float]]]) -> str:
    """What the best score is: TTC (s), as the tables always said, or the objective."""
    objective = next((r.config.objective for runs in results.values() for r, _ in runs), None)
    if objective is None or objective is Objective.MIN_TTC:
        return "TTC (s)"
    return objective.label


def sampler_table(results: dict[SamplerKind, list[tuple[SearchResult, float]]], budget: int) -> str:
    lines = [
        "| sampler | scripts made critical | trials to first critical (mean over found; "
        "median) | critical trials (mean share) | scripts with a collision | trials to first "
        f"collision (mean over found) | collision trials (mean share) | mean best "
        f"{_best_label(results)} | wall time of one search (mean s; fresh ones) |",
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


def script_table(
    results: dict[SamplerKind, list[tuple[SearchResult, float]]], scripts: list[str]
) -> str:
    samplers = list(results)
    label = _best_label(results)
    header = "| script | " + " | ".join(
        f"{s.value}: best {label} (first critical)" for s in samplers
    )
    lines = [header + " |", "|---" * (len(samplers) + 1) + "|"]
    names = [
        f"{name} (seed {r.config.seed})"
        for name, (r, _) in zip(scripts, results[samplers[0]], strict=True)
    ]
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


Found = dict[tuple[str, SamplerKind], list[tuple[Script, SearchResult]]]


def _median(values: list[int]) -> str:
    return f"{statistics.median(values):g}" if values else "-"


def criticality_table(found: Found, agents: list[str], samplers: list[SamplerKind]) -> str:
    """Per agent and category: scripts where the search found a failure (what the objective
    looks for: a collision, or for the others a collision or a TTC under 1 s) within the
    budget, and the median trials to the first one, per sampler."""
    head = ["agent", "category", "searches"]
    for sampler in samplers:
        head += [f"{sampler.value}: failure found", f"{sampler.value}: median trials to first"]
    lines = ["| " + " | ".join(head) + " |", "|---" * len(head) + "|"]
    for agent in agents:
        runs = {sampler: found.get((agent, sampler), []) for sampler in samplers}
        categories = sorted({script.category for rows in runs.values() for script, _ in rows})
        for category in [*categories, "all"]:
            cells = [agent, category]
            count = None
            for sampler in samplers:
                rows = [r for s, r in runs[sampler] if category in ("all", s.category)]
                firsts = [r.first_found for r in rows if r.first_found is not None]
                count = len(rows)
                share = f"{len(firsts)}/{len(rows)} ({len(firsts) / max(1, len(rows)):.0%})"
                cells += [share, _median(firsts)]
            lines.append("| " + " | ".join([*cells[:2], str(count), *cells[2:]]) + " |")
    return "\n".join(lines)


def sign_test(wins: int, losses: int) -> float:
    """Two-sided exact sign test: the chance of a split at least this uneven between wins
    and losses if either sampler were as likely to be sooner (ties left out)."""
    n = wins + losses
    if n == 0:
        return 1.0
    tail = sum(math.comb(n, k) for k in range(min(wins, losses) + 1)) / 2**n
    return min(1.0, 2 * tail)


def active_versus_random(found: Found, agents: list[str]) -> str:
    """Each active sampler against random, script by script: which found the first failure
    sooner (a search that found none counts as budget + 1), the mean trials to the first
    failure on that count, and the failures found within the budget."""
    lines = []
    for agent in agents:
        rand = found.get((agent, SamplerKind.RANDOM), [])
        for kind in SamplerKind:
            active = found.get((agent, kind), [])
            if not kind.active or not active or not rand:
                continue
            sooner = later = same = 0
            counts: tuple[list[int], list[int]] = ([], [])
            for (_, a), (_, b) in zip(active, rand, strict=True):
                budget = a.config.trials + 1
                x, y = a.first_found or budget, b.first_found or budget
                sooner, later, same = sooner + (x < y), later + (x > y), same + (x == y)
                counts[0].append(x)
                counts[1].append(y)
            found_active = sum(a.first_found is not None for _, a in active)
            found_random = sum(b.first_found is not None for _, b in rand)
            lines.append(
                f"{agent}: {kind.value} found the first failure sooner than random in "
                f"{sooner} searches, later in {later}, at the same trial in {same} (of "
                f"{len(active)}; sign test p = {sign_test(sooner, later):.3f}); mean trials "
                f"to the first (none = budget + 1) {statistics.mean(counts[0]):.1f} against "
                f"{statistics.mean(counts[1]):.1f}; failures found {found_active} against "
                f"{found_random}"
            )
    return "\n".join(lines)


def metrics_table(found: Found, agents: list[str], sampler: SamplerKind) -> str:
    """The driving metrics (docs/agents.md) of each search's critical instance (its best
    trial), means per agent and category; min TTC is the median."""
    head = ["agent", "category", "instances", *[name for name, _ in METRIC_COLUMNS], "min TTC (s)"]
    lines = ["| " + " | ".join(head) + " |", "|---" * len(head) + "|"]
    for agent in agents:
        rows = found.get((agent, sampler), [])
        for category in [*sorted({s.category for s, _ in rows}), "all"]:
            metrics = [
                r.best.outcome.metrics
                for s, r in rows
                if category in ("all", s.category) and r.best and r.best.outcome.metrics
            ]
            if not metrics:
                continue
            cells = [agent, category, str(len(metrics))]
            for _, key in METRIC_COLUMNS:
                values = [float(v) for m in metrics if (v := m.get(key)) is not None]
                cells.append(_mean(values, 2))
            ttc = [float(v) for m in metrics if (v := m.get("min_ttc_s")) is not None]
            cells.append(f"{statistics.median(ttc):.2f}" if ttc else "-")
            lines.append("| " + " | ".join(cells) + " |")
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
    parser.add_argument(
        "--until-found",
        action="store_true",
        help="stop each search at its first failure (trials to the first failure, found or "
        "not within --trials, are all the criticality tables need)",
    )
    parser.add_argument(
        "--objective",
        default=Objective.MIN_TTC.value,
        choices=[o.value for o in Objective if o is not Objective.CUSTOM],
        help="what the samplers minimise; a failure is what it looks for (a collision for "
        "'collision', else a collision or a TTC under 1 s)",
    )
    parser.add_argument(
        "--agents",
        default=None,
        help="comma-separated agents in the ego's seat (e.g. blind,cautious,idm); "
        "default: the scripts' own ego",
    )
    parser.add_argument(
        "--scripts",
        nargs="+",
        type=Path,
        default=None,
        metavar="DIR",
        help="search the executed run folders under these folders (arise bench / generate "
        "output) instead of the dev set's scripts",
    )
    args = parser.parse_args()

    samplers = [SamplerKind(s.strip()) for s in args.samplers.split(",")]
    seeds = [int(s) for s in args.seeds.split(",")]
    names = [a.strip() for a in (args.agents or "").split(",") if a.strip()] or ["scripted"]
    agents = {name: search_agent(name) for name in names}  # a bad name stops here
    scripts = run_scripts(args.scripts) if args.scripts else pick_scripts(args.ids, args.all)
    if args.scripts and args.ids:
        wanted = {i.strip() for i in args.ids.split(",")}
        scripts = [s for s in scripts if any(part in wanted for part in Path(s.name).parts)]
    load = os.getloadavg()
    print(
        f"machine: {platform.node()}, {os.cpu_count()} cores, python {platform.python_version()}; "
        f"load average at start {load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f}"
    )
    print(
        f"{len(scripts)} scripts x {len(samplers)} samplers x {args.trials} trials x "
        f"{len(agents)} agents ({', '.join(agents)}), seeds {', '.join(map(str, seeds))}"
    )
    found: Found = {}
    started = time.perf_counter()
    with SearchStore(Path(args.out) / "search.sqlite") as store:
        for name, agent in agents.items():
            results: dict[SamplerKind, list[tuple[SearchResult, float]]] = {s: [] for s in samplers}
            labels: list[str] = []
            for seed in seeds:
                for script in scripts:
                    labels.append(script.name)
                    for sampler in samplers:
                        result, seconds = search(
                            script.path, sampler, args, store, seed=seed, agent=agent
                        )
                        results[sampler].append((result, seconds))
                        found.setdefault((name, sampler), []).append((script, result))
                        best = result.best
                        print(
                            f"{name} {script.name} seed {seed} {sampler.value}: best "
                            f"{'-' if best is None else best.outcome.value} at "
                            f"{'-' if best is None else best.index + 1}, first critical "
                            f"{result.first_critical or '-'}, first found "
                            f"{result.first_found or '-'}, {seconds:.0f} s"
                            + (f" ({result.resumed} resumed)" if result.resumed else ""),
                            flush=True,
                        )
            print(f"\n### agent: {name}\n")
            print(sampler_table(results, args.trials))
            print()
            print(script_table(results, labels))
    total = time.perf_counter() - started
    load = os.getloadavg()
    print(
        f"\nall searches: {total / 60:.1f} min; load average at end {load[0]:.1f} / {load[1]:.1f}"
    )
    print(f"\n### failures found within {args.trials} trials, per agent and category\n")
    print(criticality_table(found, list(agents), samplers))
    comparison = active_versus_random(found, list(agents))
    if comparison:
        print()
        print(comparison)
    metric_sampler = next((s for s in samplers if s.active), samplers[0])
    metrics = metrics_table(found, list(agents), metric_sampler)
    if metrics.count("\n") > 1:
        print(f"\n### driving metrics of the critical instances ({metric_sampler.value})\n")
        print(metrics)
    if args.timing and scripts:
        print()
        print(timing(scripts[0].path, args, seeds))


if __name__ == "__main__":
    main()
