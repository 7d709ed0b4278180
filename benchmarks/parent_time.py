"""Parent time of `arise check` on adversarial scripts at the 256 KiB limit (issue 27).

Run:  .venv/bin/python benchmarks/parent_time.py [--kib 256] [--timeout 20]

The parent reads a script (its model line and map), resolves the map, hands the text to a
confined worker and validates what comes back. Only the worker may spend long on a script
(the static gate and Scenic's parser, bounded by --timeout); the parent must not. For each
script of `benchmarks/parent_parse.py`, this runs the real `check()` on one warm pool and
reports the parent's own CPU time (`time.process_time`: this process's threads, not the
worker's) beside the wall time of the whole check and how it ended. The done criterion is
a parent time under 5 s per script.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from parent_parse import scripts

from arise.validate import CheckOptions, WorkerPool, check


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kib", type=int, default=256, help="size of each script")
    parser.add_argument("--timeout", type=float, default=20.0, help="worker seconds per check")
    args = parser.parse_args()
    cases = scripts(args.kib * 1024)
    width = max(len(name) for name in cases)
    print(
        f"{'script (' + str(args.kib) + ' KiB)':<{width}}  {'parent CPU':>10}  {'wall':>7}  ended"
    )
    worst = 0.0
    with WorkerPool(size=1) as pool, tempfile.TemporaryDirectory() as folder:
        pool.warm()
        for name, text in cases.items():
            path = Path(folder) / "scenario.scenic"
            path.write_text(text, encoding="utf-8")
            cpu, wall = time.process_time(), time.perf_counter()
            result = check(path, CheckOptions(seed=0, steps=20, timeout=args.timeout), pool=pool)
            cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
            worst = max(worst, cpu)
            ended = (
                "OK" if result.ok else result.diagnostic.error_type if result.diagnostic else "?"
            )
            print(f"{name:<{width}}  {cpu:>9.2f}s  {wall:>6.1f}s  {ended}", flush=True)
    print(f"worst parent CPU time: {worst:.2f} s")


if __name__ == "__main__":
    main()
