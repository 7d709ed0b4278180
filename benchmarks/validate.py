"""Validator speed and memory: wall time per check (compile + sample + 300 simulated steps)
for a fresh worker process and for the warm pool, and peak worker RSS.

Run:  .venv/bin/python benchmarks/validate.py [--rounds 2] [--map-dir DIR]
Prints a Markdown table; copy it into docs/benchmarks.md with the machine and date.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import platform
import re
import statistics
import tempfile
import threading
import time
from pathlib import Path

import psutil

from arise.validate import CheckOptions, WorkerPool, check

REPO = Path(__file__).resolve().parents[1]
SCRIPTS = sorted((REPO / "examples" / "categories").glob("*.scenic")) + [
    REPO / "examples" / "pedestrian_crossing.scenic",
    REPO / "tests" / "data" / "base_crossing.scenic",
    *sorted((REPO / "tests" / "data" / "foreign").glob("[amp]*.scenic")),
    REPO / "tests" / "data" / "foreign" / "traffic_lights.scenic",
]


class PeakRss:
    """Samples the RSS of this process's children (the workers) every 50 ms."""

    def __init__(self) -> None:
        self.peak = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        me = psutil.Process()
        while not self._stop.is_set():
            for child in me.children(recursive=True):
                with contextlib.suppress(psutil.Error):
                    self.peak = max(self.peak, child.memory_info().rss)
            time.sleep(0.05)

    def __enter__(self) -> PeakRss:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()


def without_termination(script: Path, folder: Path) -> Path:
    """A copy that runs the full step budget: `terminate` lines removed."""
    text = re.sub(r"^\s*terminate .*$", "", script.read_text(), flags=re.M)
    copy = folder / script.name
    # Keep relative map paths meaningful: they are resolved by name through the registry.
    copy.write_text(text)
    return copy


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=2, help="warm rounds over all scripts")
    parser.add_argument("--map-dir", default=None, help="extra maps (e.g. CARLA towns)")
    parser.add_argument("--fresh", type=int, default=len(SCRIPTS),
                        help="how many scripts to time with a fresh process each")
    args = parser.parse_args()
    options = CheckOptions(seed=1, steps=300, map_dir=args.map_dir, timeout=120)

    with tempfile.TemporaryDirectory() as tmp:
        scripts = [without_termination(s, Path(tmp)) for s in SCRIPTS]
        fresh: list[float] = []
        warm: list[float] = []
        steps: list[int] = []
        failures: list[str] = []
        with PeakRss() as fresh_rss:
            for script in scripts[: args.fresh]:
                started = time.perf_counter()
                result = check(script, options)  # a new worker process for this one check
                fresh.append(time.perf_counter() - started)
                if not result.ok:
                    failures.append(f"{script.name}: {result.summary()}")
        with PeakRss() as warm_rss, WorkerPool(size=1) as pool:
            pool.warm()
            check(scripts[0], options, pool=pool)  # first map parse is not a steady-state cost
            for _ in range(args.rounds):
                for script in scripts:
                    started = time.perf_counter()
                    result = check(script, options, pool=pool)
                    warm.append(time.perf_counter() - started)
                    if result.simulation is not None:
                        steps.append(result.simulation.steps)
                    elif not result.ok:
                        failures.append(f"{script.name}: {result.summary()}")

    load = os.getloadavg()[0]
    print(f"machine: {platform.machine()}, {psutil.cpu_count()} cores, "
          f"{psutil.virtual_memory().total / 2**30:.0f} GiB; load average at end {load:.2f}")
    print(f"scripts: {len(scripts)}, warm rounds: {args.rounds}, "
          f"median steps simulated: {statistics.median(steps) if steps else 0:g}\n")
    print("| mode | checks | median s | p90 s | max s | peak worker RSS MB |")
    print("|---|---|---|---|---|---|")
    for name, times, rss in (("fresh process", fresh, fresh_rss.peak),
                             ("warm pool", warm, warm_rss.peak)):
        ordered = sorted(times)
        p90 = ordered[int(0.9 * (len(ordered) - 1))] if ordered else 0
        print(f"| {name} | {len(times)} | {statistics.median(times):.2f} | {p90:.2f} | "
              f"{max(times):.2f} | {rss / 2**20:.0f} |")
    if failures:
        print("\nfailures:\n" + "\n".join(sorted(set(failures))))


if __name__ == "__main__":
    main()
