"""Where a replay or an export gets its trace: a run folder or a script.

A run folder (scenario.scenic + report.json, as `arise generate` writes it) gives its
saved trace.json when that belongs to the script; otherwise the script is checked again
in the confined validator with the run's own seed and step count. A bare script is
always checked. Nothing here runs a script in this process.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path
from typing import Any

from arise.maps.registry import MapError, MapRegistry
from arise.present.errors import RunNotExecuted, RunNotFound, ScriptDidNotRun
from arise.present.tracefile import SavedTrace, read_trace, script_digest
from arise.validate import CheckOptions, WorkerPool, check
from arise.validate.types import CheckResult, MapChoice, SimulationFacts, Stage

RUN_SCRIPT = "scenario.scenic"
RUN_REPORT = "report.json"
FAILED_MARKER = "# ARISE: FAILED"
EXECUTED = "executed"  # report.json's status of a run whose final script ran
RECHECK_SAMPLE_ITERATIONS = 250  # as `arise generate` checks, so the same scene comes out


class Origin(StrEnum):
    """Where the trace came from."""

    SAVED = "saved"  # the run folder's trace.json
    CHECKED = "checked"  # a new check of the script in the confined validator


@dataclass
class TraceSource:
    """A trace, the map it ran on and the script it came from."""

    script: Path
    simulation: SimulationFacts
    map: MapChoice | None
    origin: Origin
    seed: int | None = None
    steps: int | None = None
    notes: list[str] = field(default_factory=list)

    @property
    def title(self) -> str:
        where = f" on {self.map.name}" if self.map else ""
        return f"{self.script.parent.name}/{self.script.name}{where}"

    def saved(self) -> SavedTrace:
        return SavedTrace(
            script_sha256=script_digest(self.script.read_text(encoding="utf-8")),
            map=self.map,
            simulation=self.simulation,
            seed=self.seed,
            steps=self.steps,
        )


def map_file(choice: MapChoice, map_dir: str | None = None) -> Path:
    """The map file a trace ran on: its recorded path, else the same map found by name
    (a trace saved on another machine records a cache path that is not here)."""
    path = Path(choice.path)
    if path.is_file():
        return path
    try:
        found = MapRegistry(map_dir).resolve(choice.name)
    except MapError as error:
        raise RunNotFound(
            f"the map {choice.name} of this trace is not available: {error}"
        ) from None
    if found.name != choice.name:
        raise RunNotFound(
            f"the map {choice.name} of this trace is not available here"
            " (give --map-dir with its .xodr)"
        )
    return Path(found.path)


def _report(folder: Path) -> dict[str, Any]:
    try:
        data = json.loads((folder / RUN_REPORT).read_text(encoding="utf-8"))
    except (OSError, ValueError) as error:
        raise RunNotFound(f"{folder / RUN_REPORT} cannot be read: {error}") from None
    if not isinstance(data, dict):
        raise RunNotFound(f"{folder / RUN_REPORT} is not a run report")
    return data


def run_check_options(report: dict[str, Any], map_dir: str | None) -> CheckOptions:
    """The check a run made of its script, so a new check gives the same scene."""
    options = report.get("options") if isinstance(report.get("options"), dict) else {}
    assert isinstance(options, dict)
    chosen: dict[str, Any] = {"sample_iterations": RECHECK_SAMPLE_ITERATIONS}
    for ours, theirs in (
        ("seed", "seed"),
        ("steps", "steps"),
        ("spawn_attempts", "spawn_attempts"),
        ("timeout", "check_timeout"),
        ("map_dir", "map_dir"),
    ):
        if options.get(theirs) is not None:
            chosen[ours] = options[theirs]
    if map_dir is not None:
        chosen["map_dir"] = map_dir
    return CheckOptions.model_validate(chosen)


def from_check(
    script: Path, result: CheckResult, options: CheckOptions, notes: list[str] | None = None
) -> TraceSource:
    """The trace of a check that ran (raises ScriptDidNotRun for one that did not). A script
    the semantic gate faulted still ran: its trace is what a user wants to see."""
    faulted_but_ran = result.diagnostic is not None and result.diagnostic.stage is Stage.SEMANTIC
    if (not result.ok and not faulted_but_ran) or result.simulation is None:
        reason = result.diagnostic.one_line() if result.diagnostic else "no simulation"
        raise ScriptDidNotRun(f"{script} did not run in the validator: {reason}")
    if result.simulation.agents and not any(a.trajectory for a in result.simulation.agents):
        raise ScriptDidNotRun(f"{script} ran but its trace holds no motion")
    return TraceSource(
        script=script,
        simulation=result.simulation,
        map=result.map,
        origin=Origin.CHECKED,
        seed=options.seed,
        steps=options.steps,
        notes=(notes or []) + result.warnings[:3],
    )


def _checked(
    script: Path, options: CheckOptions, pool: WorkerPool | None, notes: list[str]
) -> TraceSource:
    return from_check(script, check(script, options, pool=pool), options, notes)


def load_trace(
    target: str | Path,
    *,
    pool: WorkerPool | None = None,
    map_dir: str | None = None,
    options: CheckOptions | None = None,
) -> TraceSource:
    """The trace of a run folder or a script (see the module's docstring)."""
    path = Path(target)
    if path.is_dir():
        return _from_run(path, pool, map_dir)
    if path.is_file():
        if path.suffix != ".scenic":
            raise RunNotFound(f"{path} is not a Scenic script (.scenic) nor a run folder")
        chosen = options or CheckOptions(seed=0)
        if map_dir is not None:
            chosen = chosen.model_copy(update={"map_dir": map_dir})
        return _checked(path, chosen, pool, [])
    raise RunNotFound(f"{path} does not exist (give a run folder or a .scenic script)")


def _from_run(folder: Path, pool: WorkerPool | None, map_dir: str | None) -> TraceSource:
    script = folder / RUN_SCRIPT
    if not script.is_file() or not (folder / RUN_REPORT).is_file():
        raise RunNotFound(
            f"{folder} is not a run folder: it needs {RUN_SCRIPT} and {RUN_REPORT}"
            " (as `arise generate -o DIR` writes them)"
        )
    report = _report(folder)
    text = script.read_text(encoding="utf-8")
    status = report.get("status")
    if status != EXECUTED or text.startswith(FAILED_MARKER):
        raise RunNotExecuted(
            f"the run in {folder} never executed (status: {status}); there is no motion to "
            "show or export - see its report.json for the last diagnostic"
        )
    saved = read_trace(folder, text)
    if saved is not None:
        return TraceSource(
            script=script,
            simulation=saved.simulation,
            map=saved.map,
            origin=Origin.SAVED,
            seed=saved.seed,
            steps=saved.steps,
        )
    options = run_check_options(report, map_dir)
    notes = [
        "no saved trace: the script was checked again in the confined validator"
        + (f" with the run's seed {options.seed}" if options.seed is not None else "")
    ]
    if options.seed is None:
        notes.append("the run recorded no seed, so this scene may differ from the run's")
    return _checked(script, options, pool, notes)
