"""Would a prior learned from other scenes' searches find the agent's first failure sooner?

Issue 31 asks for an active sampler that beats random on trials to the first failure. Three
that learn within one search (`ce`, a local search, a Gaussian process) did not: most scenes
fail at one of the first trials or need a narrow window. This asks, offline and without a
simulation, whether knowledge carried over from *other* scenes could: the same parameter
names (`OPT_ADV_SPEED`, `OPT_EGO_TO_JUNCTION`, ...) recur across scripts.

For each scene, a naive-Bayes score of collision by parameter name and value (five bins of
the normalised range) is fitted on every other scene's trials (leave one scene out), then

- its AUC ranks that scene's `random` trials (within-scene, what a sampler could use);
- a replay draws trials from the scene's own pool in random order, or takes the best-scored
  of k, and counts trials to the first collision (none in 30 counts 31).

The pools come from searches that stop at the first failure, so they over-represent the
trials around failures; the replay is an optimistic estimate, not a measurement.

    .venv/bin/python benchmarks/transfer_prior.py out/s39-search-coll-s0 \\
        out/s39-search-coll-s1 out/s40-coll-s2
"""

from __future__ import annotations

import argparse
import json
import math
import random
import sqlite3
import statistics
from collections import defaultdict
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

BINS = 5
SMOOTHING = 20  # pseudo-trials at the overall rate in each bin
REPLAYS = 200


@dataclass(frozen=True)
class Trial:
    scene: str
    sampler: str
    values: dict[str, float]  # parameter -> value normalised to its range
    collision: bool


def load(folders: list[Path]) -> list[Trial]:
    """The trials of every search database, with values normalised to their ranges."""
    trials = []
    for folder in folders:
        with sqlite3.connect(folder / "search.sqlite") as db:
            searches = db.execute("select key, script, sampler, params from searches").fetchall()
            for key, script, sampler, params in searches:
                ranges = {
                    p["name"]: json.loads(p["range"])
                    for p in json.loads(params)
                    if p["kind"] == "range"
                }
                scene = script.split("/runs/")[1].split("/")[0]
                rows = db.execute(
                    "select params, collision from trials where search = ? and ok = 1", (key,)
                )
                for values, collision in rows:
                    drawn = json.loads(values)
                    normalised = {
                        name: (drawn[name] - lo) / (hi - lo) if hi > lo else 0.5
                        for name, (lo, hi) in ranges.items()
                        if name in drawn
                    }
                    trials.append(Trial(scene, sampler, normalised, bool(collision)))
    return trials


def fit(trials: list[Trial]) -> Callable[[dict[str, float]], float]:
    """A score that grows with the odds of a collision, by parameter name and bin."""
    overall = sum(t.collision for t in trials) / len(trials)
    counts: dict[tuple[str, int], list[int]] = defaultdict(lambda: [0, 0])
    for trial in trials:
        for name, value in trial.values.items():
            cell = counts[(name, min(int(value * BINS), BINS - 1))]
            cell[0] += trial.collision
            cell[1] += 1

    def score(values: dict[str, float]) -> float:
        total = 0.0
        for name, value in values.items():
            hits, seen = counts.get((name, min(int(value * BINS), BINS - 1)), (0, 0))
            rate = (hits + overall * SMOOTHING) / (seen + SMOOTHING)
            total += math.log(rate / overall)
        return total

    return score


def auc(scores: list[float], labels: list[bool]) -> float | None:
    positive = [s for s, hit in zip(scores, labels, strict=True) if hit]
    negative = [s for s, hit in zip(scores, labels, strict=True) if not hit]
    if not positive or not negative:
        return None
    wins = sum((p > n) + 0.5 * (p == n) for p in positive for n in negative)
    return wins / len(positive) / len(negative)


def replay(pool: list[tuple[float, bool]], best_of: int, rng: random.Random) -> float:
    """Mean trials to the first collision, drawing from the pool (best-scored of k)."""
    firsts = []
    for _ in range(REPLAYS):
        left = pool[:]
        rng.shuffle(left)
        for trial in range(1, 31):
            chosen = max(left[:best_of], key=lambda item: item[0])
            left.remove(chosen)
            if chosen[1]:
                firsts.append(trial)
                break
        else:
            firsts.append(31)
    return statistics.mean(firsts)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folders", nargs="+", type=Path, help="search output folders")
    args = parser.parse_args()
    trials = load(args.folders)
    scenes = sorted({t.scene for t in trials})
    print(
        f"{len(trials)} trials, {sum(t.collision for t in trials)} collisions, {len(scenes)} scenes"
    )
    rng = random.Random(0)
    within: list[float] = []
    means: dict[int, list[float]] = {1: [], 4: [], 8: []}
    for scene in scenes:
        score = fit([t for t in trials if t.scene != scene])
        own = [t for t in trials if t.scene == scene]
        uniform = [t for t in own if t.sampler == "random"]
        found = auc([score(t.values) for t in uniform], [t.collision for t in uniform])
        if found is not None:
            within.append(found)
        if any(t.collision for t in own):
            pool = [(score(t.values), t.collision) for t in own]
            for best_of, values in means.items():
                values.append(replay(pool, best_of, rng))
    print(
        f"within-scene AUC of the prior (leave one scene out): {statistics.mean(within):.2f} "
        f"over {len(within)} scenes"
    )
    for best_of, values in means.items():
        label = "random order" if best_of == 1 else f"best of {best_of} by the prior"
        print(
            f"mean trials to the first collision, {label}: {statistics.mean(values):.2f} "
            f"({len(values)} scenes with a collision in their pool)"
        )


if __name__ == "__main__":
    main()
