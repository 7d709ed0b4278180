"""How long Scenic takes to parse each of our generated maps, and how big they are.

Run:  PYTHONPATH=src .venv/bin/python benchmarks/map_parse.py [--runs 3]
Each map is copied to a temporary folder and parsed with no .snet cache (the first parse a
fresh machine pays), `--runs` times; prints a markdown table (median and worst of the runs).
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

from arise.maps.features import load_network
from arise.maps.generate import MAPS

DATA = Path(__file__).resolve().parents[1] / "src" / "arise" / "maps" / "data"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args(argv)
    print("| map | size (KB) | roads (incl. connecting) | parse median (s) | worst (s) |")
    print("|---|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory(prefix="arise-map-parse-") as tmp:
        for spec in MAPS.values():
            copy = Path(tmp) / spec.file
            shutil.copyfile(DATA / spec.file, copy)
            times = []
            for _ in range(args.runs):
                started = time.perf_counter()
                network = load_network(copy)
                times.append(time.perf_counter() - started)
            roads = len(network.roads) + len(network.connectingRoads)
            print(
                f"| {spec.name} | {copy.stat().st_size / 1024:.1f} | {roads} | "
                f"{statistics.median(times):.2f} | {max(times):.2f} |"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
