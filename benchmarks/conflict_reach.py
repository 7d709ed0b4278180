"""Does each adversary behavior of the knowledge base meet the ego, whoever drives it?

Run:  .venv/bin/python benchmarks/conflict_reach.py [--agents blind,cautious] [--seed N]
      [--only behavior.cut_in,...] [--all]
Each behavior entry (but those declared as no conflict by nature, `NO_CONFLICT_TAGS`) is
composed with its companions as the KB validator plans it, the ego's `OPT_EGO_SPEED` is
fixed at a slow and a fast value (0.6 and 1.4 times the middle of its geometry's range),
and the script runs in the validator with a built-in agent in the ego's seat. A run
reaches the conflict when the adversary's box comes within 6 m of the ego's, or the
time-to-collision of the two boxes (constant velocity) drops under 3 s. One markdown row
per entry: per agent and speed, `yes`/`no` (with the gap and TTC), then the share;
`--all` measures the declared exceptions too.
To measure an older knowledge base, run it from a copy of that commit's src
(PYTHONPATH=<copy>/src); tests/kb/test_conflict_timing.py asserts the same on this one.
"""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Iterable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

from arise.drive.metrics_encounters import min_gap, min_ttc
from arise.drive.metrics_track import Track
from arise.generate.conflict import ConflictLevel, conflict_met
from arise.kb.loader import load_kb
from arise.kb.plan import Composition, plan_validation
from arise.kb.runner import builtin_maps
from arise.kb.schema import Component, Entry
from arise.validate import CheckOptions, WorkerPool, check_text

AGENTS = ("blind", "cautious")
#: The ego's target speed, as a share of the middle of its geometry's OPT_EGO_SPEED range.
SPEED_FACTORS = (0.6, 1.4)
#: Tags of behaviors that have no conflict with the ego by nature (they stand still, or
#: only block or cruise): declared on the entry, never listed by id here.
NO_CONFLICT_TAGS = frozenset({"static", "no_conflict"})
EGO_SPEED = re.compile(r"^param OPT_EGO_SPEED = (?:Range\(([\d.]+), ([\d.]+)\)|([\d.]+))$", re.M)
STEPS = 200


@dataclass(frozen=True)
class Case:
    behavior: str
    composition: Composition
    agent: str
    factor: float

    @property
    def label(self) -> str:
        return f"{self.agent}@{self.factor:g}"


@dataclass(frozen=True)
class Reach:
    """What one run measured: the closest the boxes came and the smallest TTC."""

    case: Case
    gap_m: float | None  # None: the run failed or had no adversary
    ttc_s: float | None
    error: str | None = None

    @property
    def met(self) -> bool:
        return conflict_met(self.gap_m, self.ttc_s, ConflictLevel.REACH)

    def cell(self) -> str:
        if self.error:
            return "error"
        gap = "-" if self.gap_m is None else f"{self.gap_m:.1f}"
        ttc = "-" if self.ttc_s is None else f"{self.ttc_s:.1f}"
        return f"{'yes' if self.met else 'no'} ({gap} m, {ttc} s)"


def adversary_behaviors(entries: Iterable[Entry], *, every: bool = False) -> list[Entry]:
    """The behavior entries that must meet the ego (all but the declared exceptions, unless
    `every`)."""
    return [
        e
        for e in entries
        if e.component is Component.BEHAVIOR and (every or not set(e.tags) & NO_CONFLICT_TAGS)
    ]


def composition_for(behavior: Entry, entries: Sequence[Entry]) -> Composition | None:
    """The behavior with the core (and misc companions) the KB validator would prove it in."""
    misc = [e.id for e in entries if e.component is Component.MISC and e.id in behavior.companions]
    plan = plan_validation(entries, builtin_maps(), only=[behavior.id, *misc])
    found = plan.covering(behavior.id)
    return found[0] if found else None


def with_ego_speed(script: str, factor: float) -> str:
    """The script with its ego's target speed fixed at `factor` x its range's middle."""

    def fixed(match: re.Match[str]) -> str:
        if match.group(3) is not None:
            middle = float(match.group(3))
        else:
            middle = (float(match.group(1)) + float(match.group(2))) / 2
        return f"param OPT_EGO_SPEED = {middle * factor:.1f}"

    return EGO_SPEED.sub(fixed, script)


def box_gap(a: Track, b: Track) -> float:
    """The smallest distance between the two boxes over their common steps (0: contact;
    inf: no common step)."""
    gap = min_gap(a, [b])
    return float("inf") if gap is None else gap


def run_case(case: Case, pool: WorkerPool, seed: int) -> Reach:
    script = with_ego_speed(case.composition.script(), case.factor)
    options = CheckOptions(seed=seed, steps=STEPS, timeout=120, agent=case.agent)
    result = check_text(script, options, pool=pool)
    facts = result.simulation
    if not result.ok or facts is None:
        message = result.diagnostic.one_line() if result.diagnostic else "did not run"
        return Reach(case, None, None, error=message)
    ego = next(a for a in facts.agents if a.is_ego)
    adversary = next((a for a in facts.agents if a.behavior == "AdversaryBehavior"), None)
    if adversary is None:
        return Reach(case, None, None, error="no adversary in the trace")
    ego_track = Track.of(ego, facts.timestep)
    adversary_track = Track.of(adversary, facts.timestep)
    return Reach(case, box_gap(ego_track, adversary_track), min_ttc(ego_track, [adversary_track]))


def cases(
    entries: Sequence[Entry], only: set[str] | None, agents: Sequence[str], *, every: bool = False
) -> tuple[list[Case], list[str]]:
    found: list[Case] = []
    missing: list[str] = []
    for behavior in adversary_behaviors(entries, every=every):
        if only and behavior.id not in only:
            continue
        composition = composition_for(behavior, entries)
        if composition is None:
            missing.append(behavior.id)
            continue
        found += [
            Case(behavior.id, composition, agent, factor)
            for agent in agents
            for factor in SPEED_FACTORS
        ]
    return found, missing


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--agents", default=",".join(AGENTS))
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--only", default="", help="comma-separated behavior ids")
    parser.add_argument("--all", action="store_true", help="the declared exceptions too")
    args = parser.parse_args(argv)
    agents = [a for a in args.agents.split(",") if a]
    only = {i for i in args.only.split(",") if i} or None
    entries = list(load_kb(builtin=True))
    todo, missing = cases(entries, only, agents, every=args.all)
    labels = [f"{agent}@{factor:g}" for agent in agents for factor in SPEED_FACTORS]
    print(f"| behavior | {' | '.join(labels)} |")
    print(f"|---|{'---|' * len(labels)}")
    rows: dict[str, dict[str, Reach]] = {}
    with WorkerPool(size=args.workers) as pool, ThreadPoolExecutor(args.workers) as executor:
        for reach in executor.map(lambda c: run_case(c, pool, args.seed), todo):
            row = rows.setdefault(reach.case.behavior, {})
            row[reach.case.label] = reach
            if len(row) == len(labels):
                cells = [row[label].cell() for label in labels]
                print(f"| {reach.case.behavior} | {' | '.join(cells)} |", flush=True)
    for behavior in missing:
        print(f"| {behavior} | no composition |")
    every = [reach for row in rows.values() for reach in row.values()]
    for label in labels:
        mine = [r for r in every if r.case.label == label]
        print(f"{label}: {sum(r.met for r in mine)}/{len(mine)} met the ego")
    print(f"all: {sum(r.met for r in every)}/{len(every)} met the ego")
    return 0


if __name__ == "__main__":
    sys.exit(main())
