"""Where the trials of a search run: threads over a local pool of confined workers, or
Ray actors that each keep one confined worker (on this machine or a cluster).

Either way every trial's script runs only in a validator worker (`arise.validate`), is
written first into a private temporary folder (with the map file it names beside it, if
any), and comes back as the validator's `CheckResult`.
"""

from __future__ import annotations

import os
import tempfile
import time
from collections.abc import Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Protocol

from arise.evaluate.search.errors import SearchError
from arise.executors import Executor
from arise.validate import CheckOptions, CheckResult, WorkerPool, check


@dataclass(frozen=True)
class TrialJob:
    index: int
    text: str
    # Files the script reads beside itself (relative path -> bytes): its own map.
    files: dict[str, bytes] = field(default_factory=dict)


Finished = tuple[TrialJob, CheckResult, float]


class TrialRunner(Protocol):
    def run(self, jobs: Sequence[TrialJob]) -> Iterator[Finished]:
        """Check every job; yields each as it finishes, with its wall-clock seconds."""
        ...

    def close(self) -> None: ...


def check_job(job: TrialJob, options: CheckOptions, pool: WorkerPool) -> tuple[CheckResult, float]:
    """Check one trial's script from a private temporary folder."""
    with tempfile.TemporaryDirectory(prefix="arise-search-") as folder:
        root = Path(folder)
        for relative, data in job.files.items():
            target = root / relative
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
        path = root / "scenario.scenic"
        path.write_text(job.text, encoding="utf-8")
        started = time.perf_counter()
        result = check(path, options, pool=pool)
        return result, time.perf_counter() - started


class LocalRunner:
    """`workers` threads, each check in one of `workers` warm confined processes."""

    def __init__(self, workers: int, options: CheckOptions):
        self.options = options
        # A user's agent (options.agent) is imported by each worker before confinement.
        self.pool = WorkerPool(
            size=max(1, workers), memory_mb=options.memory_mb, agent=options.agent
        )
        self.threads = ThreadPoolExecutor(max_workers=max(1, workers))

    def run(self, jobs: Sequence[TrialJob]) -> Iterator[Finished]:
        futures = {
            self.threads.submit(check_job, job, self.options, self.pool): job for job in jobs
        }
        for future in as_completed(futures):
            result, seconds = future.result()
            yield futures[future], result, seconds

    def close(self) -> None:
        self.threads.shutdown(wait=True, cancel_futures=True)
        self.pool.close()


class _RayTrialActor:
    """One confined worker inside a Ray actor (made remote by `ray.remote` at run time)."""

    def __init__(self, options_json: str):
        self.options = CheckOptions.model_validate_json(options_json)
        self.pool = WorkerPool(size=1, memory_mb=self.options.memory_mb, agent=self.options.agent)

    def run(self, job: dict[str, Any]) -> dict[str, Any]:
        result, seconds = check_job(TrialJob(**job), self.options, self.pool)
        return {"index": job["index"], "result": result.model_dump(mode="json"), "seconds": seconds}


class RayRunner:
    """`workers` Ray actors (one CPU each); Ray places them on the cluster's nodes."""

    def __init__(self, workers: int, options: CheckOptions, address: str | None = None):
        try:
            import ray
            from ray.util import ActorPool
        except ImportError as error:
            raise SearchError("the Ray executor needs Ray: pip install 'arise[ray]'") from error
        self._ray = ray
        self._started_here = not ray.is_initialized()
        if self._started_here:
            ray.init(
                address=address,
                include_dashboard=False,
                log_to_driver=False,
                ignore_reinit_error=True,
                runtime_env={
                    "env_vars": {k: v for k, v in os.environ.items() if k.startswith("ARISE_")}
                },
            )
        actor_class = ray.remote(num_cpus=1)(_RayTrialActor)
        options_json = options.model_dump_json()
        self.actors: list[Any] = [actor_class.remote(options_json) for _ in range(max(1, workers))]
        self._pool = ActorPool(self.actors)

    def run(self, jobs: Sequence[TrialJob]) -> Iterator[Finished]:
        by_index = {job.index: job for job in jobs}
        for answer in self._pool.map_unordered(
            lambda actor, job: actor.run.remote(asdict(job)), list(jobs)
        ):
            yield (
                by_index[answer["index"]],
                CheckResult.model_validate(answer["result"]),
                float(answer["seconds"]),
            )

    def close(self) -> None:
        for actor in self.actors:
            self._ray.kill(actor)
        if self._started_here:
            self._ray.shutdown()


def make_runner(
    executor: Executor, workers: int, options: CheckOptions, ray_address: str | None = None
) -> TrialRunner:
    if executor is Executor.RAY:
        return RayRunner(workers, options, ray_address)
    return LocalRunner(workers, options)
