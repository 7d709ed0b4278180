"""A real search: VerifAI proposes, the confined worker runs each trial, the trace scores
it, SQLite keeps it; a second run resumes; the outputs hold the critical instance."""

from __future__ import annotations

import csv
import sqlite3
from pathlib import Path

import pytest

from arise.evaluate.search import (
    Executor,
    NoFreeParameters,
    Objective,
    SamplerKind,
    SearchConfig,
    SearchStore,
    StoreMismatch,
    find_free_params,
    run_search,
    write_outputs,
)
from arise.evaluate.search.executor import LocalRunner
from arise.evaluate.search.runner import SEARCH_SPAWN_ATTEMPTS
from arise.validate import CheckOptions, WorkerPool, check
from tests.conftest import DATA

pytest.importorskip("verifai", reason="the verifai extra is not installed (docs/search.md)")

SCRIPT = DATA / "base_crossing.scenic"


class PoolRunner(LocalRunner):
    """The local executor on the session's warm pool (closing it is the fixture's job)."""

    def __init__(self, pool: WorkerPool, options: CheckOptions):
        super().__init__(1, options)
        self.pool.close()
        self.pool = pool

    def close(self) -> None:
        self.threads.shutdown(wait=True)


def _config(trials: int, sampler: SamplerKind = SamplerKind.CE) -> SearchConfig:
    return SearchConfig(
        script=SCRIPT,
        objective=Objective.MIN_TTC,
        sampler=sampler,
        trials=trials,
        seed=3,
        check=CheckOptions(spawn_attempts=SEARCH_SPAWN_ATTEMPTS, timeout=60),
    )


def _runner(pool: WorkerPool) -> PoolRunner:
    return PoolRunner(pool, _config(1).check.model_copy(update={"seed": 3}))


@pytest.mark.slow
def test_search_saves_every_trial_and_resumes(validator_pool: WorkerPool, tmp_path: Path) -> None:
    database = tmp_path / "search.sqlite"
    seen = []
    with SearchStore(database) as store:
        first = run_search(
            _config(3), store, lambda r, _: seen.append(r.index), _runner(validator_pool)
        )
    assert sorted(seen) == [0, 1, 2] and first.resumed == 0
    params = {p.name: p for p in find_free_params(SCRIPT.read_text(encoding="utf-8"))}
    for trial in first.trials:
        assert trial.outcome.ok, trial.outcome.message
        assert trial.outcome.value is not None and 0 <= trial.outcome.value <= 10
        for name, value in trial.values.items():
            assert params[name].low <= float(value) <= params[name].high
    with sqlite3.connect(database) as db:
        assert db.execute("SELECT count(*) FROM trials").fetchone() == (3,)

    with SearchStore(database) as store:
        second = run_search(_config(5), store, None, _runner(validator_pool))
    assert second.resumed == 3 and len(second.trials) == 5
    assert [t.values for t in second.trials[:3]] == [t.values for t in first.trials]

    with sqlite3.connect(database) as db:
        db.execute("UPDATE trials SET params = '{\"OPT_TRIGGER\": 1}' WHERE idx = 0")
    with SearchStore(database) as store, pytest.raises(StoreMismatch):
        run_search(_config(5), store, None, _runner(validator_pool))


@pytest.mark.slow
def test_the_surrogate_sampler_runs_real_trials_and_resumes(
    validator_pool: WorkerPool, tmp_path: Path
) -> None:
    """Past its uniform start the surrogate proposes from its model: those trials compile
    and run like any other (a numpy scalar once reached the script and failed to compile),
    and a resumed search proposes the same values again."""
    database = tmp_path / "search.sqlite"
    config = _config(6, SamplerKind.SURROGATE)
    with SearchStore(database) as store:
        first = run_search(config, store, None, _runner(validator_pool))
    assert len(first.trials) == 6
    for trial in first.trials:
        assert trial.outcome.ok, trial.outcome.message
    with SearchStore(database) as store:
        again = run_search(_config(7, SamplerKind.SURROGATE), store, None, _runner(validator_pool))
    assert again.resumed == 6 and len(again.trials) == 7
    assert [t.values for t in again.trials[:6]] == [t.values for t in first.trials]


@pytest.mark.slow
def test_outputs_hold_the_critical_instance_and_it_scores_the_same_again(
    validator_pool: WorkerPool, tmp_path: Path
) -> None:
    with SearchStore(tmp_path / "search.sqlite") as store:
        result = run_search(_config(4, SamplerKind.HALTON), store, None, _runner(validator_pool))
    files = write_outputs([result], tmp_path, replay=True, pool=validator_pool)
    best = result.best
    assert best is not None and files.critical_script is not None
    text = files.critical_script.read_text(encoding="utf-8")
    assert text.startswith("# arise search: the most critical instance")
    for name, value in best.values.items():
        assert f"param {name} = {value}  # searched in Range(" in text
    again = check(
        files.critical_script, CheckOptions(seed=3, spawn_attempts=3), pool=validator_pool
    )
    assert again.ok, again.diagnostic
    assert not [n for n in files.notes if "when run again" in n], files.notes
    names = {p.name for p in files.replay}
    assert {"trace.json", "replay.html", "replay.gif", "scenario.xosc"} <= names
    with files.trials_csv.open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert [int(r["trial"]) for r in rows] == [1, 2, 3, 4]
    assert all(r["sampler"] == "halton" for r in rows)
    assert files.plot.stat().st_size > 5_000


def test_a_script_without_free_parameters_is_refused(tmp_path: Path) -> None:
    script = tmp_path / "fixed.scenic"
    script.write_text(
        "param map = localPath('maps/arise_straight.xodr')\n"
        "model scenic.simulators.carla.model\nparam OPT_SPEED = 5\nego = new Car\n",
        encoding="utf-8",
    )
    config = _config(2)
    config.script = script
    with (
        SearchStore(tmp_path / "search.sqlite") as store,
        pytest.raises(NoFreeParameters, match="no free parameters"),
    ):
        run_search(config, store)


@pytest.mark.slow
def test_ray_executor_proposes_and_scores_as_the_local_one(tmp_path: Path) -> None:
    """Same seed and batch size: the same values, and the same scenes, so the same scores;
    the trials ran in confined workers inside Ray actors."""
    pytest.importorskip("ray")
    results = {}
    for executor in (Executor.LOCAL, Executor.RAY):
        config = _config(4, SamplerKind.HALTON)
        config.workers, config.executor = 2, executor
        with SearchStore(tmp_path / f"{executor.value}.sqlite") as store:
            results[executor] = run_search(config, store)
    local, ray = results[Executor.LOCAL], results[Executor.RAY]
    assert [t.values for t in ray.trials] == [t.values for t in local.trials]
    assert [t.outcome.value for t in ray.trials] == [t.outcome.value for t in local.trials]
    assert all(t.outcome.ok for t in ray.trials)
