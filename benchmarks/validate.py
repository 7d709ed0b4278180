"""Validator speed and memory: wall time per check (compile + sample + 300 simulated steps)
for a fresh worker process and for the warm pool, and peak worker RSS; and what the
OS-level confinement costs: the same checks on a confined and an unconfined warm pool,
interleaved script by script so both see the same load.

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
from arise.validate.pool import Worker

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
    parser.add_argument(
        "--fresh",
        type=int,
        default=len(SCRIPTS),
        help="how many scripts to time with a fresh process each",
    )
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
        unconfined: list[float] = []
        # Worker start (Python, Scenic, world model, and confinement or not), alternated.
        starts: dict[bool, list[float]] = {True: [], False: []}
        for _ in range(3):
            for confine in (True, False):
                started = time.perf_counter()
                Worker(options.memory_mb, (), confine).kill()
                starts[confine].append(time.perf_counter() - started)
        with (
            PeakRss() as warm_rss,
            WorkerPool(size=1) as pool,
            WorkerPool(size=1, confine=False) as open_pool,
        ):
            for each in (pool, open_pool):
                each.warm()
                check(scripts[0], options, pool=each)  # first map parse: not steady state
            for _ in range(args.rounds):
                for script in scripts:
                    for each, times in ((pool, warm), (open_pool, unconfined)):
                        started = time.perf_counter()
                        result = check(script, options, pool=each)
                        times.append(time.perf_counter() - started)
                        if each is pool and result.simulation is not None:
                            steps.append(result.simulation.steps)
                        elif not result.ok:
                            failures.append(f"{script.name}: {result.summary()}")
                        if each is pool and not (result.sandbox and result.sandbox.full):
                            failures.append(f"{script.name}: confinement incomplete")

    load = os.getloadavg()[0]
    print(
        f"machine: {platform.machine()}, {psutil.cpu_count()} cores, "
        f"{psutil.virtual_memory().total / 2**30:.0f} GiB; load average at end {load:.2f}"
    )
    print(
        f"scripts: {len(scripts)}, warm rounds: {args.rounds}, "
        f"median steps simulated: {statistics.median(steps) if steps else 0:g}\n"
    )
    print("| mode | checks | median s | p90 s | max s | peak worker RSS MB |")
    print("|---|---|---|---|---|---|")
    for name, times, rss in (
        ("fresh process (confined)", fresh, fresh_rss.peak),
        ("warm pool (confined)", warm, warm_rss.peak),
        ("warm pool, unconfined (benchmark only)", unconfined, warm_rss.peak),
    ):
        ordered = sorted(times)
        p90 = ordered[int(0.9 * (len(ordered) - 1))] if ordered else 0
        print(
            f"| {name} | {len(times)} | {statistics.median(times):.2f} | {p90:.2f} | "
            f"{max(times):.2f} | {rss / 2**20:.0f} |"
        )
    ratio = statistics.median(warm) / statistics.median(unconfined)
    print(
        f"\nconfined / unconfined warm median: {ratio:.3f}; worker start (median of 3) "
        f"{statistics.median(starts[True]):.2f} s confined vs "
        f"{statistics.median(starts[False]):.2f} s unconfined"
    )
    if failures:
        print("\nfailures:\n" + "\n".join(sorted(set(failures))))


if __name__ == "__main__":
    main()
