"""The search loop: VerifAI proposes, the confined pool checks, the trace scores, VerifAI
learns; every trial is saved as it finishes.

Trials run in batches of `workers`: the sampler proposes a whole batch, the batch runs in
parallel, then every score goes back to the sampler in trial order. The sampler's random
state is its own and seeded, so the same search proposes the same values again: resuming
re-proposes the saved trials (checking that they match), feeds their saved scores back
and runs only what is missing.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from arise.agents.types import BuiltinAgent
from arise.drive.agent_names import agent_folder_part, agent_label, resolve_agent
from arise.drive.runner import raise_for_agent
from arise.evaluate.search.errors import NoFreeParameters, SearchError, StoreMismatch
from arise.evaluate.search.executor import Executor, TrialJob, TrialRunner, make_runner
from arise.evaluate.search.expression import Expression
from arise.evaluate.search.objective import (
    CRITICAL_TTC,
    TTC_CAP,
    Objective,
    TrialOutcome,
    needs_metrics,
    outcome,
)
from arise.evaluate.search.sampler import ParamSampler, Proposal, SamplerKind
from arise.evaluate.search.space import FreeParam, ParamValue, find_free_params, fix_params
from arise.evaluate.search.store import SearchRow, SearchStore, TrialRecord
from arise.validate import CheckOptions
from arise.validate.script_info import read_script_info

#: Scenes a trial may try before its values count as failed: a value that makes every
#: simulation rejected would otherwise cost the validator's 15 tries (30-50 s) each time.
SEARCH_SPAWN_ATTEMPTS = 3

#: The score a failed trial is told to the sampler as, before any trial ran: as bad as
#: no conflict at all (then: the worst score seen).
FAILED_DISTANCE = 50.0

OnTrial = Callable[[TrialRecord, "SearchResult"], None]


@dataclass
class SearchConfig:
    script: Path
    objective: Objective = Objective.MIN_TTC
    sampler: SamplerKind = SamplerKind.CE
    trials: int = 30
    workers: int = 1
    executor: Executor = Executor.LOCAL
    seed: int = 0
    check: CheckOptions = field(
        default_factory=lambda: CheckOptions(spawn_attempts=SEARCH_SPAWN_ATTEMPTS)
    )
    ray_address: str | None = None
    #: the user's objective when ``objective`` is CUSTOM (checked by `parse_expression`)
    expression: Expression | None = None
    #: Stop after the batch in which a trial first found what the search looks for (the
    #: trials to a first failure are all a criticality table needs). Not part of the key: a
    #: search stopped early resumes into the full one.
    until_found: bool = False

    @property
    def agent(self) -> str | None:
        """Who drives the ego in every trial (`check.agent`); None: the script's own ego."""
        return self.check.agent

    @property
    def agent_label(self) -> str:
        return "scripted" if self.agent is None else agent_label(self.agent)

    @property
    def measures(self) -> bool:
        """Are the trials' driving metrics measured? With an agent (what it did is the
        point), or when the objective reads them."""
        return self.agent is not None or needs_metrics(self.objective, self.expression)


@dataclass
class SearchResult:
    key: str
    config: SearchConfig
    script_text: str
    params: list[FreeParam]
    trials: list[TrialRecord] = field(default_factory=list)
    resumed: int = 0  # trials read back from the database instead of run
    # Files the script reads beside itself (its own map), written beside each trial.
    files: dict[str, bytes] = field(default_factory=dict)

    @property
    def best(self) -> TrialRecord | None:
        ran = [t for t in self.trials if t.outcome.ok and t.outcome.value is not None]
        return min(ran, key=lambda t: (t.outcome.value, t.index), default=None)

    @property
    def first_found(self) -> int | None:
        """1-based number of the first trial that reached what the search looks for."""
        found = [t.index for t in self.trials if t.outcome.found(self.config.objective)]
        return min(found) + 1 if found else None

    @property
    def first_critical(self) -> int | None:
        """1-based number of the first trial with a collision or a TTC under 1 s."""
        found = [t.index for t in self.trials if t.outcome.critical]
        return min(found) + 1 if found else None

    @property
    def first_collision(self) -> int | None:
        """1-based number of the first trial in which ego and adversary touched."""
        found = [t.index for t in self.trials if t.outcome.ok and t.outcome.collision]
        return min(found) + 1 if found else None

    def best_so_far(self) -> list[float | None]:
        best: float | None = None
        curve: list[float | None] = []
        for trial in sorted(self.trials, key=lambda t: t.index):
            value = trial.outcome.value if trial.outcome.ok else None
            if value is not None and (best is None or value < best):
                best = value
            curve.append(best)
        return curve

    def concrete_script(self, values: dict[str, ParamValue]) -> str:
        """The script with these values fixed (the old ranges kept in comments)."""
        return fix_params(self.script_text, self.params, values)


def search_agent(name: str | None) -> str | None:
    """The agent as the workers are told it (`arise drive --agent`'s names), or None when
    the script drives: no name, or `scripted` (the same runs, so the same search).
    AgentError, one line, for a name that cannot be an agent."""
    if name is None:
        return None
    text = resolve_agent(name)
    return None if text == BuiltinAgent.SCRIPTED.value else text


def search_folder_name(agent: str | None) -> str:
    """The folder a run's search goes to: `search`, or `search-AGENT` for an agent, so the
    searches of several agents keep their own critical instance and files."""
    if agent is None:
        return "search"
    return "search-" + agent_folder_part(agent)


def resolve_script(target: Path) -> Path:
    """A script, or a run folder of `arise generate` (its scenario.scenic)."""
    path = target / "scenario.scenic" if target.is_dir() else target
    if not path.is_file():
        where = f"{target} has no scenario.scenic" if target.is_dir() else f"no such file: {target}"
        raise SearchError(where)
    return path


def _read(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise SearchError(f"cannot read {path} as UTF-8 text: {error}") from error


def search_key(text: str, config: SearchConfig) -> str:
    """Same script, sampler, objective, seed, check settings and agent: the same search."""
    identity = {
        "script": hashlib.sha256(text.encode()).hexdigest(),
        "sampler": config.sampler.value,
        "objective": config.objective.value,
        "seed": config.seed,
        "steps": config.check.steps,
        "spawn_attempts": config.check.spawn_attempts,
        "simulator": config.check.simulator.value,
        "map_dir": config.check.map_dir,
    }
    if config.expression is not None:  # only then: the keys of earlier searches stay
        identity["expression"] = config.expression.text
        if config.expression.needs_metrics:  # route_completion was once the trace's estimate
            identity["metrics"] = "drive"
    if config.agent is not None:  # likewise: a search without an agent keeps its key
        identity["agent"] = config.agent
    return hashlib.sha256(json.dumps(identity, sort_keys=True).encode()).hexdigest()[:16]


def _side_files(path: Path, text: str) -> dict[str, bytes]:
    """The map file a script names by a plain relative path in its own folder, if there."""
    requested = read_script_info(text).requested_map_file
    if not requested:
        return {}
    relative = Path(requested)
    if relative.is_absolute() or ".." in relative.parts:
        return {}
    candidate = path.resolve().parent / relative
    if candidate.is_symlink() or not candidate.is_file():
        return {}
    return {relative.as_posix(): candidate.read_bytes()}


def _critical_level(objective: Objective) -> float:
    return CRITICAL_TTC if objective is Objective.MIN_TTC else 0.0


def _failed_score(objective: Objective, trials: list[TrialRecord]) -> float:
    seen = [t.outcome.value for t in trials if t.outcome.ok and t.outcome.value is not None]
    if seen:
        return max(seen)
    if objective is Objective.SCORE:
        return 1.0  # a perfect drive: nothing found
    return TTC_CAP if objective is Objective.MIN_TTC else FAILED_DISTANCE


def prepare(config: SearchConfig, store: SearchStore) -> tuple[SearchResult, int]:
    """The search's identity, its free parameters and its batch size (from the database
    when the search is resumed)."""
    if config.trials < 1:
        raise SearchError("--trials must be at least 1")
    if config.workers < 1:
        raise SearchError("--workers must be at least 1")
    path = resolve_script(config.script)
    text = _read(path)
    params = find_free_params(text)
    if not params:
        raise NoFreeParameters(
            f"{path} has no free parameters to search: declare them as "
            "`param OPT_NAME = Range(low, high)` or with VerifaiRange, VerifaiDiscreteRange, "
            "VerifaiOptions (literal bounds)"
        )
    key = search_key(text, config)
    row = store.search(key)
    batch = row.batch if row is not None else config.workers
    if row is None:
        store.add_search(
            SearchRow(
                key=key,
                script=str(path),
                script_sha256=hashlib.sha256(text.encode()).hexdigest(),
                sampler=config.sampler.value,
                objective=config.objective.value,
                seed=config.seed,
                batch=batch,
                params=[
                    {"name": p.name, "kind": p.kind.value, "range": p.describe()} for p in params
                ],
                agent=config.agent,
            )
        )
    return SearchResult(key=key, config=config, script_text=text, params=params), batch


def run_search(
    config: SearchConfig,
    store: SearchStore,
    on_trial: OnTrial | None = None,
    runner: TrialRunner | None = None,
) -> SearchResult:
    """Run (or resume) one search; returns every trial, saved ones included."""
    result, batch = prepare(config, store)
    path = resolve_script(config.script)
    files = result.files = _side_files(path, result.script_text)
    saved = store.trials(result.key)
    sampler = ParamSampler(
        result.params, config.sampler, config.seed, _critical_level(config.objective)
    )
    options = config.check.model_copy(update={"seed": config.seed, "png": None})
    metrics_steps = options.steps if config.measures else None
    own_runner = runner is None
    active: TrialRunner | None = runner
    try:
        index = 0
        while index < config.trials:
            size = min(batch, config.trials - index)
            proposals: list[Proposal] = [sampler.propose() for _ in range(size)]
            outcomes: dict[int, TrialOutcome] = {}
            jobs = []
            for offset, proposal in enumerate(proposals):
                number = index + offset
                if number in saved:
                    if saved[number].values != proposal.values:
                        raise StoreMismatch(
                            f"{store.path}: trial {number + 1} was saved with other values "
                            "than this search proposes; use another --out (or delete the file)"
                        )
                    outcomes[number] = saved[number].outcome
                    result.trials.append(saved[number])
                    result.resumed += 1
                    if on_trial is not None:
                        on_trial(saved[number], result)
                    continue
                jobs.append(
                    TrialJob(
                        index=number,
                        text=result.concrete_script(proposal.values),
                        files=files,
                    )
                )
            if jobs:
                if active is None:
                    active = make_runner(
                        config.executor, config.workers, options, config.ray_address
                    )
                for job, check_result, seconds in active.run(jobs):
                    raise_for_agent(check_result)
                    verdict = outcome(
                        check_result,
                        config.objective,
                        seconds,
                        config.expression,
                        metrics_steps=metrics_steps,
                    )
                    record = TrialRecord(job.index, proposals[job.index - index].values, verdict)
                    store.save(result.key, record)
                    outcomes[job.index] = verdict
                    result.trials.append(record)
                    if on_trial is not None:
                        on_trial(record, result)
            for offset, proposal in enumerate(proposals):
                verdict = outcomes[index + offset]
                value = verdict.value if verdict.ok and verdict.value is not None else None
                sampler.tell(
                    proposal,
                    value if value is not None else _failed_score(config.objective, result.trials),
                )
            index += size
            if config.until_found and result.first_found is not None:
                break
    finally:
        if own_runner and active is not None:
            active.close()
    result.trials.sort(key=lambda t: t.index)
    return result
