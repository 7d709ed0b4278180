"""Do the generated scripts of the labeled dev sets meet the ego when an agent drives it?

Run:  .venv/bin/python benchmarks/devset_reach.py out/final-short out/final-nhtsa ...
      [--agent blind] [--seed 0] [--workers 2]
Each argument is the output folder of `arise bench` on a dev set (its `runs/ID/*/` hold
the final scripts). Every run whose description's hand-written truth has an adversary is
checked again in the confined validator with the agent in the ego's seat (300 steps, as
`arise drive`). A run reaches the conflict when the adversary's box comes within 6 m of
the ego's, or their time-to-collision drops under 3 s (issue 31); a description the truth
labels `must_come_close` also counts whether the two touched or came under 1.5 s TTC.
The truth comes from the dev-set files, never from the pipeline's own reading.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from conflict_reach import box_gap

from arise.drive.metrics_encounters import min_ttc
from arise.drive.metrics_track import Track
from arise.evaluate.fidelity import LabeledDescription, load_devsets
from arise.generate.conflict import ConflictLevel, conflict_met
from arise.generate.conformity import find_adversary
from arise.validate import CheckOptions, WorkerPool, check

STEPS = 300


@dataclass(frozen=True)
class Run:
    item: LabeledDescription
    script: Path


@dataclass(frozen=True)
class Met:
    run: Run
    gap_m: float | None
    ttc_s: float | None
    error: str | None = None

    @property
    def reached(self) -> bool:
        return conflict_met(self.gap_m, self.ttc_s, ConflictLevel.REACH)

    @property
    def close(self) -> bool:
        return conflict_met(self.gap_m, self.ttc_s, ConflictLevel.CLOSE)


def runs_of(bench_out: Path, items: dict[str, LabeledDescription]) -> list[Run]:
    """The final script of each run whose truth names an adversary."""
    found = []
    for script in sorted(bench_out.glob("runs/*/*/scenario.scenic")):
        item = items.get(script.parent.parent.name)
        if item is not None and any(
            a.role is not None and a.role.value == "adversary" for a in item.truth.actors
        ):
            found.append(Run(item, script))
    return found


def drive(run: Run, agent: str, pool: WorkerPool, seed: int) -> Met:
    options = CheckOptions(seed=seed, steps=STEPS, timeout=120, agent=agent)
    result = check(run.script, options, pool=pool)
    facts = result.simulation
    if not result.ok or facts is None:
        message = result.diagnostic.one_line() if result.diagnostic else "did not run"
        return Met(run, None, None, error=message)
    ego = next(a for a in facts.agents if a.is_ego)
    adversary = find_adversary(facts.agents)
    if adversary is None:
        return Met(run, None, None, error="no adversary in the trace")
    ego_track, other = Track.of(ego, facts.timestep), Track.of(adversary, facts.timestep)
    return Met(run, box_gap(ego_track, other), min_ttc(ego_track, [other]))


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bench_out", nargs="+", type=Path)
    parser.add_argument("--agent", default="blind")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args(argv)
    items = {item.id: item for items in load_devsets().values() for item in items}
    every: list[Met] = []
    for folder in args.bench_out:
        runs = runs_of(folder, items)
        with WorkerPool(size=args.workers) as pool, ThreadPoolExecutor(args.workers) as threads:
            mets = list(threads.map(lambda r: drive(r, args.agent, pool, args.seed), runs))
        every += mets
        for met in mets:
            if not met.reached or (met.run.item.truth.must_come_close and not met.close):
                gap = "-" if met.gap_m is None else f"{met.gap_m:.1f} m"
                ttc = "-" if met.ttc_s is None else f"{met.ttc_s:.1f} s"
                print(f"  {met.run.item.id}: {gap}, TTC {ttc} {met.error or ''}")
        _summary(folder.name, mets)
    _summary("all", every)
    return 0


def _summary(name: str, mets: list[Met]) -> None:
    close = [m for m in mets if m.run.item.truth.must_come_close]
    print(
        f"| {name} | {sum(m.reached for m in mets)}/{len(mets)} "
        f"| {sum(m.close for m in close)}/{len(close)} |",
        flush=True,
    )


if __name__ == "__main__":
    sys.exit(main())
