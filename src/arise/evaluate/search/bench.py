"""The bench's criticality after a search: each executed run's script searched for N trials
(VerifAI's cross-entropy sampler, smallest TTC), the outcome kept in the run's record.

`arise report DB --search-trials N` runs it before writing the report, whose criticality
table then has "critical after search": per category, the share of executed scripts whose
search reached a collision or a TTC under 1 s within N trials. Each search is saved in the
run's folder (`search/`: search.sqlite, the critical script without a replay, trials.csv,
objective.png, search.json), so a killed pass resumes.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from arise.evaluate.records import RunRecord
from arise.evaluate.search.objective import Objective
from arise.evaluate.search.outputs import write_outputs
from arise.evaluate.search.runner import SEARCH_SPAWN_ATTEMPTS, SearchConfig, run_search
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
    on_record: Callable[[RunRecord], None] | None = None,
) -> int:
    """Search every executed run whose folder still holds its script; returns how many."""
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
            check=CheckOptions(map_dir=map_dir, spawn_attempts=SEARCH_SPAWN_ATTEMPTS),
        )
        with SearchStore(script.parent / "search" / "search.sqlite") as searches:
            result = run_search(config, searches)
        write_outputs([result], script.parent / "search", replay=False)
        best = result.best
        record.criticality = dict(record.criticality or {})
        record.criticality["search"] = {
            "sampler": config.sampler.value,
            "trials": trials,
            "critical": result.first_critical is not None,
            "first_critical": result.first_critical,
            "best_ttc": None if best is None else best.outcome.value,
        }
        store.save(record)
        count += 1
        if on_record:
            on_record(record)
    return count
