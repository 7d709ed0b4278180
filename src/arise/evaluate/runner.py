"""Resumable benchmark: prompts x modes x temperatures x runs through the generator.

Tasks already in the database are skipped, so a killed benchmark resumes where it stopped.
Each executor process (or Ray actor) keeps one Generator, i.e. one model and one validator,
for all its tasks; the parent alone writes the database.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from arise.atomic import write_text_atomic
from arise.errors import AriseError
from arise.evaluate.criticality import criticality
from arise.evaluate.prompt_file import BenchPrompt
from arise.evaluate.records import BenchTask, RunRecord
from arise.evaluate.store import BenchStore
from arise.executors import Executor, ExecutorUnavailable
from arise.generate.options import GenerateOptions, Mode
from arise.generate.pipeline import Generator
from arise.generate.run import Generation
from arise.llm.accounting import UsageLedger
from arise.ray_session import start_ray
from arise.validate import CheckResult

OnRecord = Callable[[RunRecord], None]


@dataclass
class BenchConfig:
    prompts: list[BenchPrompt]
    base: GenerateOptions = field(default_factory=GenerateOptions)
    modes: list[Mode] = field(default_factory=lambda: [Mode.ARISE])
    temperatures: list[float] = field(default_factory=lambda: [0.0])
    runs: int = 1
    workers: int = 1
    executor: Executor = Executor.LOCAL
    judge: bool = False
    # The judge's own model (the paper judges with another model than it generates with).
    judge_provider: str | None = None
    judge_model: str | None = None
    ray_address: str | None = None
    # A driving agent (`arise drive --agent`'s names, resolved): every executed script is
    # also driven by it and the run gets SafeBench's metrics.
    agent: str | None = None


def plan(config: BenchConfig) -> list[BenchTask]:
    """Every task in a stable order: run by run, so an early stop covers all prompts."""
    return [
        BenchTask(
            prompt_id=p.id,
            category=p.category,
            description=p.description,
            mode=mode,
            temperature=temperature,
            run_index=run,
            truth=p.truth,
        )
        for run in range(config.runs)
        for temperature in config.temperatures
        for mode in config.modes
        for p in config.prompts
    ]


def pending(config: BenchConfig, store: BenchStore) -> list[BenchTask]:
    done = store.done_keys()
    return [task for task in plan(config) if task.key not in done]


def task_options(base: GenerateOptions, task: BenchTask) -> GenerateOptions:
    seed = None if base.seed is None else base.seed + task.run_index
    return base.model_copy(
        update={
            "mode": task.mode,
            "temperature": task.temperature,
            "run_index": task.run_index,
            "seed": seed,
        }
    )


def task_dir(out_root: Path, task: BenchTask) -> Path:
    return (
        out_root
        / "runs"
        / task.prompt_id
        / (f"{task.mode}-t{task.temperature:g}-r{task.run_index}")
    )


def record_of(task: BenchTask, run: Generation, out_dir: Path | None) -> RunRecord:
    """The database row of a generation: its report (the one serialisation of a run) plus
    the criticality of the script that ran."""
    final = run.final_check
    crit = criticality(final.simulation if final is not None and run.ok else None)
    return RunRecord.from_report(
        task,
        run.report(),
        out_dir=str(out_dir) if out_dir else None,
        criticality=crit.as_dict() if crit else None,
    )


def fidelity_of(
    generator: Generator, task: BenchTask, check: CheckResult | None
) -> dict[str, Any] | None:
    """The run's trace against the prompt's hand-written truth (never against its spec)."""
    if task.truth is None:
        return None
    from arise.evaluate.fidelity import Fidelity, parse_truth, score_fidelity

    if check is None:
        return Fidelity(executed=False).as_dict()
    entry = generator.registry.entries.get(check.map.name) if check.map else None
    truth = parse_truth(json.loads(task.truth), task.prompt_id)
    return score_fidelity(truth, check, entry.features if entry else None).as_dict()


def add_to_report(path: Path, key: str, value: Any) -> None:
    """Add one entry to a run's report.json, whole or not at all."""
    if not path.is_file():
        return
    report = json.loads(path.read_text(encoding="utf-8"))
    report[key] = value
    write_text_atomic(path, json.dumps(report, indent=2, default=str))


class TaskRunner:
    """Runs tasks one after another with one Generator; lives in whichever process runs it."""

    def __init__(
        self,
        base: GenerateOptions,
        out_root: Path,
        judge: bool = False,
        judge_provider: str | None = None,
        judge_model: str | None = None,
        agent: str | None = None,
    ):
        self.base = base
        self.out_root = out_root
        self.agent = agent
        self.judging = judge
        self.judge_provider = judge_provider
        self.judge_model = judge_model
        self._generator: Generator | None = None
        self._judge_llm: UsageLedger | None = None

    def judge_llm(self, generator: Generator) -> UsageLedger:
        """The generator's model, unless the benchmark names a judge of its own."""
        if not (self.judge_provider or self.judge_model):
            return generator.provider
        if self._judge_llm is None:
            from arise.llm.registry import get_provider

            overrides: dict[str, Any] = {"model": self.judge_model} if self.judge_model else {}
            self._judge_llm = get_provider(self.judge_provider, cache=self.base.cache, **overrides)
        return self._judge_llm

    def generator_for(self, task: BenchTask) -> Generator:
        """The runner's one Generator, set to the task's mode, temperature and seed."""
        options = task_options(self.base, task)
        if self._generator is None:
            self._generator = Generator(options)
        self._generator.reconfigure(options)
        return self._generator

    def run(self, task: BenchTask) -> RunRecord:
        generator = self.generator_for(task)
        out_dir = task_dir(self.out_root, task)
        generation = generator.generate(task.description, out_dir)
        record = record_of(task, generation, out_dir)
        if task.truth is not None:
            record.fidelity = fidelity_of(generator, task, generation.final_check)
            add_to_report(out_dir / "report.json", "fidelity", record.fidelity)
        if self.judging and generation.ok:
            record.judge = judge_run(
                self.judge_llm(generator), task, out_dir, generator.options.seed
            )
        if self.agent and generation.ok:
            record.driving = self.drive(record)
        return record

    def drive(self, record: RunRecord) -> dict[str, Any] | None:
        """The run's executed script driven by the agent (the run's seed): its DriveRecord."""
        from arise.evaluate.driving import drive_run

        assert self.agent is not None
        generator = self.generator_for(record.task)
        return drive_run(record, self.agent, generator.options, generator.pool)

    def judge(self, record: RunRecord) -> dict[str, Any]:
        """Judge a run finished earlier (a benchmark first run without --judge)."""
        generator = self.generator_for(record.task)
        return judge_run(
            self.judge_llm(generator),
            record.task,
            Path(record.out_dir or "."),
            generator.options.seed,
        )

    def close(self) -> None:
        if self._generator is not None:
            self._generator.close()
            self._generator = None
        if self._judge_llm is not None:
            self._judge_llm.close()
            self._judge_llm = None


def judge_run(
    judge: UsageLedger, task: BenchTask, out_dir: Path, seed: int | None
) -> dict[str, Any]:
    """SCS of the executed script, or why it could not be judged."""
    from arise.evaluate.judge import judge_script

    try:
        script = (out_dir / "scenario.scenic").read_text(encoding="utf-8")
    except OSError as error:
        return {"scs": None, "error": f"no script to judge: {error}"}
    try:
        judgement = judge_script(task.description, script, judge, temperature=0.0, seed=seed)
    except AriseError as error:  # the model failed, or the pair cannot be judged
        return {"scs": None, "error": str(error)}
    return judgement.as_dict()


# -- executors ------------------------------------------------------------------------------


def run_local(
    tasks: Sequence[BenchTask], config: BenchConfig, out_root: Path
) -> Iterator[RunRecord]:
    if config.workers <= 1:
        runner = TaskRunner(
            config.base,
            out_root,
            config.judge,
            config.judge_provider,
            config.judge_model,
            config.agent,
        )
        try:
            for task in tasks:
                yield runner.run(task)
        finally:
            runner.close()
        return
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed

    context = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(
        max_workers=config.workers,
        mp_context=context,
        initializer=_init_process,
        initargs=(
            config.base.model_dump_json(),
            str(out_root),
            config.judge,
            config.judge_provider,
            config.judge_model,
            config.agent,
        ),
    ) as pool:
        futures = [pool.submit(_run_in_process, json.dumps(task.__dict__)) for task in tasks]
        for future in as_completed(futures):
            yield RunRecord.from_dict(future.result())


_PROCESS_RUNNER: TaskRunner | None = None


def _init_process(
    base_json: str,
    out_root: str,
    judge: bool,
    judge_provider: str | None,
    judge_model: str | None,
    agent: str | None = None,
) -> None:
    global _PROCESS_RUNNER
    _PROCESS_RUNNER = TaskRunner(
        GenerateOptions.model_validate_json(base_json),
        Path(out_root),
        judge,
        judge_provider,
        judge_model,
        agent,
    )


def _run_in_process(task_json: str) -> dict[str, Any]:
    assert _PROCESS_RUNNER is not None
    return _PROCESS_RUNNER.run(BenchTask(**json.loads(task_json))).as_dict()


class _RayActor:
    """A TaskRunner inside a Ray actor (created through `ray.remote` at run time)."""

    def __init__(
        self,
        base_json: str,
        out_root: str,
        judge: bool,
        judge_provider: str | None,
        judge_model: str | None,
        agent: str | None = None,
    ):
        self.runner = TaskRunner(
            GenerateOptions.model_validate_json(base_json),
            Path(out_root),
            judge,
            judge_provider,
            judge_model,
            agent,
        )

    def run(self, task_json: str) -> dict[str, Any]:
        return self.runner.run(BenchTask(**json.loads(task_json))).as_dict()


def run_ray(tasks: Sequence[BenchTask], config: BenchConfig, out_root: Path) -> Iterator[RunRecord]:
    try:
        import ray
        from ray.util import ActorPool
    except ImportError as error:
        raise ExecutorUnavailable("the Ray executor needs Ray: pip install 'arise[ray]'") from error
    started_here = start_ray(ray, config.ray_address)
    try:
        actor_class = ray.remote(num_cpus=1)(_RayActor)
        actors = [
            actor_class.remote(
                config.base.model_dump_json(),
                str(out_root),
                config.judge,
                config.judge_provider,
                config.judge_model,
                config.agent,
            )
            for _ in range(max(1, config.workers))
        ]
        pool = ActorPool(actors)
        payloads = [json.dumps(task.__dict__) for task in tasks]
        for result in pool.map_unordered(
            lambda actor, payload: actor.run.remote(payload), payloads
        ):
            yield RunRecord.from_dict(result)
    finally:
        if started_here:
            ray.shutdown()


def run_bench(
    config: BenchConfig, store: BenchStore, out_root: Path, on_record: OnRecord | None = None
) -> list[RunRecord]:
    """Run what the database does not hold yet; every finished run is saved at once."""
    store.set_meta(
        options=config.base.model_dump(mode="json"),
        modes=[m.value for m in config.modes],
        temperatures=config.temperatures,
        runs=config.runs,
        prompts=len(config.prompts),
        **({"agent": config.agent} if config.agent else {}),
    )
    tasks = pending(config, store)
    executor = run_ray if config.executor is Executor.RAY else run_local
    finished = []
    for record in executor(tasks, config, out_root):
        store.save(record)
        finished.append(record)
        if on_record:
            on_record(record)
    if config.judge:
        judge_missing(config, store, out_root, on_record)
    if config.agent:
        drive_missing(config, store, out_root, on_record)
    return finished


def undriven(config: BenchConfig, store: BenchStore) -> list[RunRecord]:
    """Executed runs of the plan not yet driven by the config's agent."""
    planned = {task.key for task in plan(config)}
    return [
        r
        for r in store.runs()
        if r.ok
        and r.task.key in planned
        and (r.driving or {}).get("task", {}).get("agent") != config.agent
    ]


def drive_missing(
    config: BenchConfig, store: BenchStore, out_root: Path, on_driven: OnRecord | None = None
) -> int:
    """Drive executed runs that the agent has not driven yet (a benchmark first run
    without --agent, or with another one), in this process on a pool of its own (nothing
    is generated); each is saved at once."""
    from arise.evaluate.driving import drive_run
    from arise.validate import WorkerPool

    todo = undriven(config, store)
    if not todo or config.agent is None:
        return 0
    with WorkerPool(size=1, agent=config.agent) as pool:
        for record in todo:
            options = task_options(config.base, record.task)
            record.driving = drive_run(record, config.agent, options, pool)
            store.save(record)
            if on_driven:
                on_driven(record)
    return len(todo)


def unjudged(config: BenchConfig, store: BenchStore) -> list[RunRecord]:
    planned = {task.key for task in plan(config)}
    return [r for r in store.runs() if r.ok and r.judge is None and r.task.key in planned]


def judge_missing(
    config: BenchConfig, store: BenchStore, out_root: Path, on_judged: OnRecord | None = None
) -> int:
    """Score executed runs that have no SCS yet, in this process; each is saved at once."""
    todo = unjudged(config, store)
    if not todo:
        return 0
    runner = TaskRunner(config.base, out_root, True, config.judge_provider, config.judge_model)
    try:
        for record in todo:
            record.judge = runner.judge(record)
            store.save(record)
            if on_judged:
                on_judged(record)
    finally:
        runner.close()
    return len(todo)


#: Options of a bench database that name files this process would read: a database (and
#: its run folders) may come from anyone, so a re-check takes these from the caller only.
UNTRUSTED_FILE_OPTIONS = ("map_dir", "kb_dirs", "record", "replay")


def recheck(
    store: BenchStore, on_record: OnRecord | None = None, map_dir: str | None = None
) -> int:
    """Validate each executed run's saved script again (same seed, so the same scene) and
    refresh its conformity and criticality: old runs get the current checks without
    generating anything again. The maps are the caller's (`map_dir`), not the store's."""
    from arise.generate.spec import ScenarioSpec
    from arise.validate import check

    meta_options = store.meta().get("options")
    stored = meta_options if isinstance(meta_options, dict) else {}
    trusted = {k: v for k, v in stored.items() if k not in UNTRUSTED_FILE_OPTIONS}
    base = GenerateOptions.model_validate({**trusted, "map_dir": map_dir})
    runner = TaskRunner(base, Path("."))
    count = 0
    try:
        for record in store.runs():
            script = Path(record.out_dir or "") / "scenario.scenic"
            if not record.ok or record.spec is None or not script.is_file():
                continue
            generator = runner.generator_for(record.task)
            result = check(
                script, generator.check_options(), pool=generator.pool, registry=generator.registry
            )
            record.conformity = generator.conformity_of(
                ScenarioSpec.model_validate(record.spec), result
            ).as_dict()
            crit = criticality(result.simulation if result.ok else None)
            record.criticality = crit.as_dict() if crit else None
            record.fidelity = fidelity_of(generator, record.task, result)
            record.sandbox = result.sandbox.label if result.sandbox else None
            store.save(record)
            count += 1
            if on_record:
                on_record(record)
    finally:
        runner.close()
    return count
