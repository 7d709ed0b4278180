"""`arise serve` under load on loopback: N jobs submitted at once to a model replayed from
a cassette (the real validator runs every script), each followed over its SSE stream to
its end. Measures how many were lost or failed, the time to the last one, and the
server's memory (RSS of the server process, and of its validator workers) before and
after each round.

Run:  .venv/bin/python benchmarks/serve_load.py [--jobs 20] [--rounds 3]
Prints a Markdown table; copy it into docs/benchmarks.md with the machine and date.
The slow test tests/serve/test_load.py runs one round of 20 with the same driver.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import socket
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import httpx
import psutil

REPO = Path(__file__).resolve().parents[1]
CASSETTE = REPO / "tests" / "cassettes" / "generate" / "first_try.jsonl"
DESCRIPTION = "A cyclist riding ahead in the ego's lane suddenly brakes to a full stop."
FINISHED = {"done", "failed", "cancelled"}


@dataclass
class JobOutcome:
    status_code: int
    job_id: str | None = None
    state: str | None = None
    events: int = 0
    seconds: float = 0.0
    error: str | None = None


@dataclass
class Round:
    jobs: int
    outcomes: list[JobOutcome] = field(default_factory=list)
    seconds: float = 0.0
    server_mb_before: float = 0.0
    server_mb_after: float = 0.0
    workers_mb_after: float = 0.0

    @property
    def accepted(self) -> int:
        return sum(o.status_code == 201 for o in self.outcomes)

    @property
    def done(self) -> int:
        return sum(o.state == "done" for o in self.outcomes)

    @property
    def lost(self) -> int:
        """Submitted but never seen to finish (no end on its stream)."""
        return sum(o.status_code == 201 and o.state not in FINISHED for o in self.outcomes)


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def start_server(runs_dir: Path, port: int, cassette: Path = CASSETTE) -> subprocess.Popen[bytes]:
    """`arise serve` in its own process, answering from the cassette."""
    command = [sys.executable, "-m", "arise", "serve", "--port", str(port)]
    command += ["--runs-dir", str(runs_dir), "--replay", str(cassette)]
    return subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)


def wait_ready(url: str, process: subprocess.Popen[bytes], timeout: float = 120) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if process.poll() is not None:
            raise RuntimeError(
                f"the server exited: {process.stderr.read().decode() if process.stderr else ''}"
            )
        try:
            if httpx.get(f"{url}/api/health", timeout=2).status_code == 200:
                return
        except httpx.HTTPError:
            pass
        time.sleep(0.2)
    raise RuntimeError("the server did not answer in time")


def rss_mb(pid: int) -> tuple[float, float]:
    """RSS of the process and of all its descendants (the validator workers), in MB."""
    process = psutil.Process(pid)
    children = 0.0
    for child in process.children(recursive=True):
        try:
            children += child.memory_info().rss
        except psutil.Error:
            continue
    return process.memory_info().rss / 1e6, children / 1e6


def one_job(url: str, description: str, timeout: float) -> JobOutcome:
    """Submit one job and follow its stream to the end."""
    started = time.perf_counter()
    with httpx.Client(base_url=url, timeout=timeout) as client:
        response = client.post("/api/jobs", json={"description": description})
        outcome = JobOutcome(response.status_code)
        if response.status_code != 201:
            outcome.error = response.text
            return outcome
        outcome.job_id = response.json()["id"]
        with client.stream("GET", f"/api/jobs/{outcome.job_id}/events") as stream:
            for line in stream.iter_lines():
                if not line.startswith("data:"):
                    continue
                outcome.events += 1
                event = json.loads(line[5:])
                if event.get("event") == "state" and event.get("state") in FINISHED:
                    outcome.state = event["state"]
        outcome.seconds = time.perf_counter() - started
    return outcome


def run_round(url: str, pid: int, jobs: int, timeout: float = 900) -> Round:
    """`jobs` submissions at once, each followed to its end; memory before and after."""
    result = Round(jobs)
    result.server_mb_before, _ = rss_mb(pid)
    started = time.perf_counter()
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = [pool.submit(one_job, url, DESCRIPTION, timeout) for _ in range(jobs)]
        for future in futures:
            try:
                result.outcomes.append(future.result())
            except httpx.HTTPError as error:
                result.outcomes.append(JobOutcome(0, error=f"{type(error).__name__}: {error}"))
    result.seconds = time.perf_counter() - started
    result.server_mb_after, result.workers_mb_after = rss_mb(pid)
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--jobs", type=int, default=20)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="arise-serve-load-") as folder:
        port = free_port()
        url = f"http://127.0.0.1:{port}"
        process = start_server(Path(folder), port)
        try:
            wait_ready(url, process)
            warm = run_round(url, process.pid, 1)  # loads the KB and warms the worker
            rounds = [run_round(url, process.pid, args.jobs) for _ in range(args.rounds)]
            alive = process.poll() is None and httpx.get(f"{url}/api/health").status_code == 200
        finally:
            process.terminate()
            process.wait(timeout=30)
    print(f"machine: {platform.node()}, {os.cpu_count()} cores, Python {platform.python_version()}")
    print(f"warm-up job: {warm.seconds:.1f} s; server alive after all rounds: {alive}\n")
    print(
        "| round | jobs | accepted | done | lost | wall s | s/job | server MB before -> after | workers MB |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for index, r in enumerate(rounds, 1):
        print(
            f"| {index} | {r.jobs} | {r.accepted} | {r.done} | {r.lost} | {r.seconds:.1f} | "
            f"{r.seconds / r.jobs:.2f} | {r.server_mb_before:.0f} -> {r.server_mb_after:.0f} | "
            f"{r.workers_mb_after:.0f} |"
        )


if __name__ == "__main__":
    main()
