"""One search of one script, with one or several samplers: what `arise search` does.

The command line parses its options into a `SearchRequest`, calls `search` and prints the
typed events it sends and the `SearchSession` it returns. Every trial is saved in
OUT/search.sqlite as it finishes, so an interrupted search resumes where it stopped.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from arise.errors import Interrupted
from arise.evaluate.search.errors import SearchError
from arise.evaluate.search.executor import Executor
from arise.evaluate.search.expression import parse_expression
from arise.evaluate.search.objective import Objective
from arise.evaluate.search.outputs import SearchFiles, write_outputs
from arise.evaluate.search.runner import (
    SearchConfig,
    SearchResult,
    resolve_script,
    run_search,
    search_agent,
    search_folder_name,
)
from arise.evaluate.search.sampler import SamplerKind
from arise.evaluate.search.store import SearchStore, TrialRecord
from arise.validate import CheckOptions


@dataclass(frozen=True)
class SearchRequest:
    """A script (or a run folder of `arise generate`) and how to search it; `out` defaults
    to RUN_DIR/search for a folder and out/search-NAME for a script."""

    target: Path
    samplers: list[SamplerKind]
    check: CheckOptions
    objective: Objective = Objective.MIN_TTC
    expression: str | None = None
    trials: int = 30
    workers: int = 1
    executor: Executor = Executor.LOCAL
    ray_address: str | None = None
    seed: int = 0
    out: Path | None = None
    #: Run the critical script again for its replay and .xosc.
    replay: bool = True
    #: Who drives the ego in every trial (as `arise drive --agent`); None: the script.
    agent: str | None = None
    #: Stop each sampler's search at its first failure (`SearchConfig.until_found`).
    until_found: bool = False


@dataclass(frozen=True)
class SamplerStarted:
    """One sampler's search begins (or resumes)."""

    config: SearchConfig


@dataclass(frozen=True)
class TrialDone:
    """A trial ran (or was read back from the database); `result` holds every trial so far."""

    config: SearchConfig
    record: TrialRecord
    result: SearchResult


@dataclass(frozen=True)
class SearchesDone:
    """Every sampler finished; the output files are written next."""

    results: list[SearchResult]


SearchEvent = SamplerStarted | TrialDone | SearchesDone
OnSearchEvent = Callable[[SearchEvent], None]


@dataclass(frozen=True)
class SearchSession:
    results: list[SearchResult]
    files: SearchFiles


def output_folder(target: Path, script: Path, out: Path | None, agent: str | None = None) -> Path:
    """OUT, else RUN_DIR/search (search-AGENT with an agent), else out/search-NAME(-AGENT)."""
    if out is not None:
        return out
    name = search_folder_name(agent)
    if target.is_dir():
        return target / name
    return Path("out") / (f"search-{script.stem}" + name.removeprefix("search"))


def search(request: SearchRequest, on_event: OnSearchEvent | None = None) -> SearchSession:
    """Search the script with each sampler in turn, then write the critical instance, the
    trials, the plot and the summary. SearchError for a bad target or objective, AgentError
    for a name that cannot be an agent, before any file is written; Ctrl-C raises Interrupted (the finished trials are saved)."""
    emit = on_event or (lambda event: None)
    script = resolve_script(request.target)
    check = request.check.model_copy(update={"agent": search_agent(request.agent)})
    custom = request.objective is Objective.CUSTOM
    if request.expression is not None and not custom:
        raise SearchError("--expression goes with --objective custom")
    goal = parse_expression(request.expression or "") if custom else None
    if not request.samplers:
        raise SearchError("--sampler needs at least one sampler")
    folder = output_folder(request.target, script, request.out, check.agent)
    results: list[SearchResult] = []
    with SearchStore(folder / "search.sqlite") as store:
        for kind in request.samplers:
            config = SearchConfig(
                script=script,
                objective=request.objective,
                expression=goal,
                sampler=kind,
                trials=request.trials,
                workers=request.workers,
                executor=request.executor,
                seed=request.seed,
                check=check,
                ray_address=request.ray_address,
                until_found=request.until_found,
            )
            emit(SamplerStarted(config))

            def on_trial(
                record: TrialRecord, result: SearchResult, config: SearchConfig = config
            ) -> None:
                emit(TrialDone(config, record, result))

            try:
                results.append(run_search(config, store, on_trial))
            except KeyboardInterrupt:
                raise Interrupted(
                    f"finished trials are in {store.path}; run the same command to resume"
                ) from None
    emit(SearchesDone(results))
    return SearchSession(results, write_outputs(results, folder, replay=request.replay))
