"""Where a replay or an export gets its trace: a run folder or a script.

A run folder (scenario.scenic + report.json, as `arise generate` writes it) gives its
saved trace.json when that belongs to the script; otherwise the script is checked again
in the confined validator with the run's own seed and step count. A bare script is
always checked. Nothing here runs a script in this process.

A run folder is untrusted (anyone may hand one over): its files are read only when they
are regular files within size limits and validated strictly; no path in them is used
(the map of a saved trace is found again by name, in the registry or as `NAME.xodr` in
the run folder itself), and report.json may choose the seed, steps and time limit of a
new check but not the maps it sees.
"""

from __future__ import annotations

import stat
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path
from typing import Annotated

from pydantic import BaseModel, Field, StringConstraints, ValidationError

from arise.limits import (
    MAX_RECHECK_TIMEOUT,
    MAX_REPORT_FILE_BYTES,
    MAX_RUN_SCRIPT_BYTES,
    MAX_SPAWN_ATTEMPTS,
    MAX_STEPS,
)
from arise.maps.cache import cached_copy, trusted_entry
from arise.maps.registry import MapError, MapRegistry
from arise.present.errors import RunNotExecuted, RunNotFound, ScriptDidNotRun
from arise.present.tracefile import SavedTrace, load_trace_file, script_digest
from arise.present.untrusted import UntrustedFileError, read_json, read_text
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
    """A trace, the map it ran on and the script it came from. `map` is always a choice
    the parent made (a check's, or a saved trace's map found again by name)."""

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
    """The map file a trace ran on: the parent's own cached copy when the choice's path is
    one (`trusted_entry`), else the same map found by name in the registry."""
    entry = trusted_entry(choice.path)
    if entry is None or entry.stem != choice.name:
        try:
            found = MapRegistry(map_dir).exact(choice.name)
        except MapError as error:
            raise RunNotFound(
                f"the map {choice.name} of this trace is not available: {error}"
            ) from None
        if found is None:
            raise RunNotFound(
                f"the map {choice.name} of this trace is not available here"
                " (give --map-dir with its .xodr)"
            )
        entry = Path(found.path)
    return entry


def saved_map(choice: MapChoice, map_dir: str | None, folder: Path) -> MapChoice:
    """The map a saved trace names, found again by its name alone: in the registry, else
    as a regular `NAME.xodr` in the run folder itself (never the path the trace records)."""
    try:
        found = MapRegistry(map_dir).exact(choice.name)
        if found is None:
            local = folder / f"{choice.name}.xodr"  # a safe file stem, by the schema
            if not _is_plain_file(local):
                raise RunNotFound(
                    f"the map {choice.name} of this trace is not available here (give "
                    f"--map-dir with its .xodr, or put {choice.name}.xodr in {folder})"
                )
            found = MapChoice(requested=choice.name, name=choice.name, path=str(cached_copy(local)))
    except MapError as error:
        raise RunNotFound(
            f"the map {choice.name} of this trace is not available: {error}"
        ) from None
    return found.model_copy(
        update={
            "requested": choice.requested,
            "substituted": choice.substituted,
            "reason": choice.reason,
        }
    )


def _is_plain_file(path: Path) -> bool:
    try:
        return stat.S_ISREG(path.lstat().st_mode)
    except OSError:
        return False


class _RunOptions(BaseModel):
    """The options of report.json a new check of the run's script takes (others, such as
    `map_dir`, are ignored: a run folder must not point this process at other files)."""

    seed: Annotated[int, Field(ge=-(2**63), le=2**64)] | None = None
    steps: Annotated[int, Field(ge=1, le=MAX_STEPS)] | None = None
    spawn_attempts: Annotated[int, Field(ge=1, le=MAX_SPAWN_ATTEMPTS)] | None = None
    check_timeout: (
        Annotated[float, Field(allow_inf_nan=False, gt=0, le=MAX_RECHECK_TIMEOUT)] | None
    ) = None


class RunReport(BaseModel):
    """What this module reads of a run's report.json."""

    status: Annotated[str, StringConstraints(max_length=64)] | None = None
    options: _RunOptions = Field(default_factory=_RunOptions)


def _report(folder: Path) -> RunReport:
    path = folder / RUN_REPORT
    try:
        data = read_json(path, MAX_REPORT_FILE_BYTES)
    except (OSError, UntrustedFileError) as error:
        raise RunNotFound(f"{path} cannot be read: {_reason(error)}") from None
    if not isinstance(data, dict):
        raise RunNotFound(f"{path} is not a run report")
    try:
        return RunReport.model_validate(data)
    except ValidationError as error:
        first = error.errors(include_url=False, include_input=False)[0]
        where = ".".join(str(part) for part in first["loc"][:4])
        raise RunNotFound(f"{path} is not a valid run report ({where}: {first['msg']})") from None


def _reason(error: Exception) -> str:
    return (error.strerror if isinstance(error, OSError) else None) or str(error)


def run_check_options(report: RunReport, map_dir: str | None) -> CheckOptions:
    """The check a run made of its script, so a new check gives the same scene. The maps
    are the caller's (`map_dir`), never the report's."""
    options = report.options
    chosen = {
        "sample_iterations": RECHECK_SAMPLE_ITERATIONS,
        "seed": options.seed,
        "steps": options.steps,
        "spawn_attempts": options.spawn_attempts,
        "timeout": options.check_timeout,
        "map_dir": map_dir,
    }
    return CheckOptions.model_validate({k: v for k, v in chosen.items() if v is not None})


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
    if not _is_plain_file(script) or not _is_plain_file(folder / RUN_REPORT):
        raise RunNotFound(
            f"{folder} is not a run folder: it needs {RUN_SCRIPT} and {RUN_REPORT}"
            " (as `arise generate -o DIR` writes them, regular files)"
        )
    report = _report(folder)
    try:
        text = read_text(script, MAX_RUN_SCRIPT_BYTES)
    except (OSError, UntrustedFileError) as error:
        raise RunNotFound(f"{script} cannot be read: {_reason(error)}") from None
    status = report.status
    if status != EXECUTED or text.startswith(FAILED_MARKER):
        raise RunNotExecuted(
            f"the run in {folder} never executed (status: {status}); there is no motion to "
            "show or export - see its report.json for the last diagnostic"
        )
    saved = load_trace_file(folder, text)
    if saved is not None:
        return TraceSource(
            script=script,
            simulation=saved.simulation,
            map=saved_map(saved.map, map_dir, folder) if saved.map is not None else None,
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
