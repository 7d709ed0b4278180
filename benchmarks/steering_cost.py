"""What the steering feed-forward costs the simulator: simulate seconds per check, before
and after, on two warm workers whose code differs, script by script in turn.

Run:  .venv/bin/python benchmarks/steering_cost.py --before <worktree>/src [--rounds 3]
The "before" worker runs the code on `--before` (a worktree of an older commit, on its
PYTHONPATH); the "after" worker runs this checkout's. Each script runs 300 steps (its
`terminate` lines removed) with the same seed on both, alternately, so both see the same
load; the scripts are the validator benchmark's (benchmarks/validate.py) plus the KB's
highway and junction geometry entries composed alone. Prints a Markdown table of medians.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
from pathlib import Path

from arise.kb.compose import compose, pick_map
from arise.kb.loader import load_kb
from arise.maps.registry import MapRegistry
from arise.validate import CheckOptions, WorkerPool, check

sys.path.insert(0, str(Path(__file__).resolve().parent))
from validate import SCRIPTS, without_termination  # noqa: E402

ENTRIES = (
    "geometry.highway_cruise",
    "geometry.curved_road",
    "geometry.signalized_left_turn_on_green",
)


def _scripts(folder: Path) -> list[Path]:
    scripts = [without_termination(s, folder) for s in SCRIPTS]
    kb = load_kb()
    maps = {name: entry.features for name, entry in MapRegistry().entries.items()}
    for ident in ENTRIES:
        entry = kb.get(ident)
        chosen = pick_map([entry], maps)
        assert chosen is not None, ident
        path = folder / f"{ident}.scenic"
        path.write_text(compose([entry], None, chosen), encoding="utf-8")
        scripts.append(without_termination(path, folder))
    return scripts


def _pool_with(pythonpath: str | None) -> WorkerPool:
    """A warm one-worker pool whose worker imports arise from `pythonpath` (None: ours)."""
    saved = os.environ.get("PYTHONPATH")
    if pythonpath is None:
        os.environ.pop("PYTHONPATH", None)
    else:
        os.environ["PYTHONPATH"] = pythonpath
    try:
        pool = WorkerPool(size=1, recycle_after=10_000)
        pool.warm()
    finally:
        if saved is None:
            os.environ.pop("PYTHONPATH", None)
        else:
            os.environ["PYTHONPATH"] = saved
    return pool


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", required=True, help="src folder of the older commit")
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    options = CheckOptions(seed=1, steps=300, timeout=120)
    simulate: dict[str, list[float]] = {"before": [], "after": []}
    total: dict[str, list[float]] = {"before": [], "after": []}
    with tempfile.TemporaryDirectory() as tmp:
        scripts = _scripts(Path(tmp))
        pools = {"before": _pool_with(args.before), "after": _pool_with(None)}
        try:
            for _ in range(args.rounds):
                for script in scripts:
                    for name, pool in pools.items():
                        result = check(script, options, pool=pool)
                        if not result.ok:
                            print(f"{name}: {script.name}: {result.summary()}", file=sys.stderr)
                            continue
                        simulate[name].append(result.timings.get("simulate", 0.0))
                        total[name].append(sum(result.timings.values()))
        finally:
            for pool in pools.values():
                pool.close()
    print("| code | checks | median simulate s (300 steps) | mean simulate s | median check s |")
    print("|---|---|---|---|---|")
    for name in ("before", "after"):
        print(
            f"| {name} | {len(simulate[name])} | {statistics.median(simulate[name]):.2f} | "
            f"{statistics.mean(simulate[name]):.2f} | {statistics.median(total[name]):.2f} |"
        )
    ratio = statistics.mean(simulate["after"]) / statistics.mean(simulate["before"])
    print(f"\nmean simulate time, after / before: {ratio:.2f}")


if __name__ == "__main__":
    main()
