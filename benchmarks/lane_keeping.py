"""How often the offline ego leaves its lane when it should keep it, per geometry and speed.

Run:  .venv/bin/python benchmarks/lane_keeping.py [--carla-maps DIR] [--seeds N]
Each geometry entry of the knowledge base drives the ego alone at the top of its speed
range (highway entries also at 35 m/s) for 20 s; the trace is read lane by lane with
Scenic's road network (the validator's `lane_changes`). Prints one markdown row per case:
lane changes per seed. To compare with an older world model, run it from a worktree of
that commit (PYTHONPATH=<worktree>/src).
"""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Sequence

from arise.kb.compose import compose, pick_map
from arise.kb.loader import load_kb
from arise.kb.schema import Component
from arise.maps.registry import MapRegistry
from arise.validate import CheckOptions, WorkerPool, check_text

SPEED = re.compile(r"param OPT_EGO_SPEED = Range\(([\d.]+), ([\d.]+)\)")


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--carla-maps", help="folder of CARLA town maps (else our maps)")
    parser.add_argument("--seeds", type=int, default=2)
    args = parser.parse_args(argv)
    registry = MapRegistry(args.carla_maps) if args.carla_maps else MapRegistry()
    maps = {
        name: entry.features
        for name, entry in registry.entries.items()
        if entry.features and (not args.carla_maps or entry.source == "map-dir")
    }
    print("| geometry | map | speed (m/s) | lane changes per seed |\n|---|---|---|---|")
    with WorkerPool(size=1) as pool:
        for entry in load_kb().of(Component.GEOMETRY):
            found = SPEED.search(entry.snippet)
            map_name = pick_map([entry], maps)
            if found is None or map_name is None:
                continue
            speeds = [float(found.group(2))]
            if "highway" in entry.map_features:
                speeds.append(35.0)
            for speed in speeds:
                script = compose([entry], None, map_name).replace(
                    found.group(0), f"param OPT_EGO_SPEED = {speed:g}"
                )
                changes = []
                for seed in range(args.seeds):
                    options = CheckOptions(
                        seed=seed, steps=200, timeout=120, map_dir=args.carla_maps
                    )
                    result = check_text(script, options, pool=pool)
                    if not result.ok or result.simulation is None:
                        changes.append("failed")
                        continue
                    ego = next(a for a in result.simulation.agents if a.is_ego)
                    changes.append(str(ego.lane_changes))
                print(f"| {entry.id} | {map_name} | {speed:g} | {', '.join(changes)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
