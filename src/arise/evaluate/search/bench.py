"""The bench's criticality after a search: each executed run's script searched for N trials
(VerifAI's cross-entropy sampler, smallest TTC), with an agent in the ego's seat if one is
given, the outcome kept in the run's record.

`arise report DB --search-trials N` runs it before writing the report, whose criticality
table then has "critical after search": per category, the share of executed scripts whose
search reached a collision or a TTC under 1 s within N trials. Each search is saved in the
run's folder (`search/`, `search-AGENT/` with an agent: search.sqlite, the critical script
without a replay, trials.csv, objective.png, search.json), so a killed pass resumes.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from arise.evaluate.records import RunRecord
from arise.evaluate.search.objective import Objective
from arise.evaluate.search.outputs import write_outputs
from arise.evaluate.search.runner import (
    SEARCH_SPAWN_ATTEMPTS,
    SearchConfig,
    run_search,
    search_agent,
    search_folder_name,
)
from arise.evaluate.search.sampler import SamplerKind
from arise.evaluate.search.store import SearchStore
from arise.evaluate.store import BenchStore
from arise.validate import CheckOptions


def search_runs(
    store: BenchStore,
    trials: int,
    *,
    seed: int = 0,
    map_dir: str | None = None,
    agent: str | None = None,
    on_record: Callable[[RunRecord], None] | None = None,
) -> int:
    """Search every executed run whose folder still holds its script, with `agent` (as
    `arise drive --agent` names it) driving the ego; returns how many. AgentError for a
    name that cannot be an agent, before any search."""
    driver = search_agent(agent)
    count = 0
    for record in store.runs():
        script = Path(record.out_dir or "") / "scenario.scenic"
        if not record.ok or not script.is_file():
            continue
        config = SearchConfig(
            script=script,
            objective=Objective.MIN_TTC,
            sampler=SamplerKind.CE,
            trials=trials,
            seed=seed,
            check=CheckOptions(map_dir=map_dir, spawn_attempts=SEARCH_SPAWN_ATTEMPTS, agent=driver),
        )
        folder = script.parent / search_folder_name(driver)
        with SearchStore(folder / "search.sqlite") as searches:
            result = run_search(config, searches)
        write_outputs([result], folder, replay=False)
        best = result.best
        record.criticality = dict(record.criticality or {})
        record.criticality["search"] = {
            "sampler": config.sampler.value,
            "agent": config.agent_label,
            "trials": trials,
            "critical": result.first_critical is not None,
            "first_critical": result.first_critical,
            "first_collision": result.first_collision,
            "best_ttc": None if best is None else best.outcome.value,
        }
        store.save(record)
        count += 1
        if on_record:
            on_record(record)
    return count
