"""Resumable drive: scenarios x runs, each checked in the confined validator with the
agent in the ego's seat, measured, and its collision replayed.

Runs already in the database are skipped, so a killed drive resumes where it stopped.
The local executor shares one pool of confined workers between `workers` threads (the
simulation runs in the workers; a thread waits, measures and draws); the Ray executor
gives each actor a pool of its own. The parent alone writes the database.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from arise.agents import AgentError
from arise.drive.agent_names import agent_folder_part
from arise.drive.measure import measure
from arise.drive.records import DriveRecord, DriveStatus, DriveTask
from arise.drive.sources import Scenario, safe_part
from arise.drive.store import DriveStore
from arise.errors import AriseError
from arise.executors import Executor, ExecutorUnavailable
from arise.present.replay import write_replay
from arise.present.source import Origin, TraceSource
from arise.ray_session import start_ray
from arise.validate import CheckOptions, WorkerPool, check
from arise.validate.types import CheckResult

COLLISIONS = "collisions"
#: Simulated steps of a drive (as `arise check`): long enough for most routes.
DRIVE_STEPS = 300


OnRecord = Callable[[DriveRecord], None]


@dataclass
class DriveConfig:
    agent: str  # as `resolve_agent` gave it
    runs: int = 1
    seed: int = 0
    workers: int = 1
    executor: Executor = Executor.LOCAL
    map_dir: str | None = None
    steps: int = DRIVE_STEPS
    timeout: float = 60.0
    ray_address: str | None = None

    def check_options(self, seed: int | None) -> CheckOptions:
        return CheckOptions(
            seed=seed,
            map_dir=self.map_dir,
            steps=self.steps,
            timeout=self.timeout,
            agent=self.agent,
        )


def plan(scenarios: Sequence[Scenario], config: DriveConfig) -> list[DriveTask]:
    """Every run in a stable order: run by run, so an early stop covers every scenario."""
    return [
        DriveTask.of(scenario, config.agent, run, config.seed + run)
        for run in range(config.runs)
        for scenario in scenarios
    ]


def pending(tasks: Sequence[DriveTask], store: DriveStore) -> list[DriveTask]:
    done = store.done_keys()
    return [task for task in tasks if task.key not in done]


def replay_folder(task: DriveTask) -> str:
    """Where a run's collision replay goes, below the drive's folder."""
    scenario = "-".join(safe_part(part, "x") for part in task.scenario.split("/"))
    agent = agent_folder_part(task.agent)
    return f"{COLLISIONS}/{scenario}-{agent}-r{task.run_index}"


def raise_for_agent(result: CheckResult) -> None:
    """AgentError when the check failed because the agent itself cannot be made (no such
    class, an import that fails): every run would fail the same way, so the caller stops at
    once and saves nothing a fixed agent would find done."""
    if result.diagnostic is not None and result.diagnostic.error_type == AgentError.__name__:
        raise AgentError(result.diagnostic.message)


def drive_one(task: DriveTask, config: DriveConfig, pool: WorkerPool, out: Path) -> DriveRecord:
    """Check the task's script with the agent; a run that drove gets its metrics, and its
    replay when it collided. Never raises for a bad script; AgentError when the agent
    cannot be made."""
    started = time.perf_counter()
    options = config.check_options(task.seed)
    result = check(Path(task.script), options, pool=pool)
    record = DriveRecord(
        task=task,
        status=DriveStatus.FAILED,
        sandbox=result.sandbox.label if result.sandbox else None,
        map=result.map.name if result.map else None,
    )
    if not result.ok or result.simulation is None:
        raise_for_agent(result)
        record.message = result.diagnostic.one_line() if result.diagnostic else "did not run"
    else:
        timeout_s = options.steps * result.simulation.timestep
        record.timeout_s = round(timeout_s, 3)
        try:
            record.metrics = measure(result, timeout_s)
            record.status = DriveStatus.DRIVEN
        except AriseError as error:
            record.message = f"cannot measure: {error}"
        if record.collided:
            record.replay = _replay(task, result, options, out)
    record.seconds = round(time.perf_counter() - started, 3)
    return record


def _replay(task: DriveTask, result: CheckResult, options: CheckOptions, out: Path) -> str | None:
    """The collision's replay (the ego's whole path drawn), or None when it cannot be drawn."""
    assert result.simulation is not None
    folder = replay_folder(task)
    source = TraceSource(
        script=Path(task.script),
        simulation=result.simulation,
        map=result.map,
        origin=Origin.CHECKED,
        seed=options.seed,
        steps=options.steps,
    )
    try:
        files = write_replay(source, out / folder, map_dir=options.map_dir)
    except AriseError:
        return None
    return str(files.gif.relative_to(out))


# -- executors ------------------------------------------------------------------------------


def run_local(tasks: Sequence[DriveTask], config: DriveConfig, out: Path) -> Iterator[DriveRecord]:
    if not tasks:
        return
    workers = max(1, config.workers)
    with WorkerPool(size=workers, agent=config.agent) as pool:
        if workers == 1:
            for task in tasks:
                yield drive_one(task, config, pool, out)
            return
        with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="drive") as threads:
            futures = [threads.submit(drive_one, task, config, pool, out) for task in tasks]
            try:
                for future in as_completed(futures):
                    yield future.result()
            finally:
                for future in futures:
                    future.cancel()


class _RayActor:
    """drive_one inside a Ray actor, with a worker pool of its own."""

    def __init__(self, config_json: str, out: str):
        self.config = DriveConfig(**json.loads(config_json))
        self.out = Path(out)
        self.pool = WorkerPool(size=1, agent=self.config.agent)

    def run(self, task_json: str) -> str:
        task = DriveTask.model_validate_json(task_json)
        return drive_one(task, self.config, self.pool, self.out).model_dump_json()


def run_ray(tasks: Sequence[DriveTask], config: DriveConfig, out: Path) -> Iterator[DriveRecord]:
    try:
        import ray
        from ray.util import ActorPool
    except ImportError as error:
        raise ExecutorUnavailable("the Ray executor needs Ray: pip install 'arise[ray]'") from error
    if not tasks:
        return
    started_here = start_ray(ray, config.ray_address)
    try:
        actor_class = ray.remote(num_cpus=1)(_RayActor)
        config_json = json.dumps(config.__dict__)
        actors = [actor_class.remote(config_json, str(out)) for _ in range(max(1, config.workers))]
        pool = ActorPool(actors)
        payloads = [task.model_dump_json() for task in tasks]
        for result in pool.map_unordered(
            lambda actor, payload: actor.run.remote(payload), payloads
        ):
            yield DriveRecord.model_validate_json(result)
    finally:
        if started_here:
            ray.shutdown()


def run_drive(
    tasks: Sequence[DriveTask],
    config: DriveConfig,
    store: DriveStore,
    out: Path,
    on_record: OnRecord | None = None,
) -> list[DriveRecord]:
    """Run what the database does not hold yet; every finished run is saved at once."""
    store.set_meta(agent=config.agent, runs=config.runs, seed=config.seed, steps=config.steps)
    todo = pending(tasks, store)
    executor = run_ray if config.executor is Executor.RAY else run_local
    finished: list[DriveRecord] = []
    for record in executor(todo, config, out):
        store.save(record)
        finished.append(record)
        if on_record is not None:
            on_record(record)
    return finished


def planned_records(tasks: Sequence[DriveTask], store: DriveStore) -> list[DriveRecord]:
    """The database's runs of this plan, in plan order (runs of other agents, seeds or
    older scripts in the same database are left out)."""
    by_key: dict[Any, DriveRecord] = {r.task.key: r for r in store.records()}
    return [by_key[task.key] for task in tasks if task.key in by_key]
