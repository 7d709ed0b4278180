"""`check()`: the library call behind `arise check`.

The worker's result is untrusted (the script runs in the process that writes it and may
forge it): the parent keeps only the facts, validated by a strict schema
(`WorkerResult`), and says itself which script, map and world model the check ran on and
where the picture went. A result that breaks the schema is a `ProtocolViolation`.
"""

from __future__ import annotations

import base64
import binascii
import os
import tempfile
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from arise.agents.loader import AgentError, check_agent_spec
from arise.atomic import write_bytes_atomic
from arise.limits import MAX_AGENTS, MAX_NAME, MAX_STEPS
from arise.maps.registry import MapError, MapRegistry
from arise.validate.carla_server import unreachable_reason
from arise.validate.map_cache import MapPreparationError, prepare_map
from arise.validate.pool import SandboxRequired, StageCallback, WorkerDied, WorkerPool
from arise.validate.sandbox import required_by_settings
from arise.validate.script_info import read_script_info
from arise.validate.types import (
    PARENT_FIELDS,
    CheckOptions,
    CheckResult,
    Diagnostic,
    MapChoice,
    Simulator,
    Stage,
    WorkerResult,
)

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def _failure(
    script: str, stage: Stage, error_type: str, message: str, hint: str | None = None
) -> CheckResult:
    return CheckResult(
        ok=False,
        script=script,
        diagnostic=Diagnostic(stage=stage, error_type=error_type, message=message, hint=hint),
    )


def check(
    script: str | os.PathLike[str],
    options: CheckOptions | None = None,
    *,
    pool: WorkerPool | None = None,
    registry: MapRegistry | None = None,
    on_stage: StageCallback | None = None,
    **overrides: Any,
) -> CheckResult:
    """Gate, compile, sample and simulate one Scenic file in a confined worker.

    Never raises for a bad script: every failure is in `result.diagnostic`, and
    `result.sandbox` says which confinement the script ran under. Raises OutputError
    only when the picture asked for (`png`) cannot be written where it was asked, and
    AgentError (before any worker starts) for an agent name that cannot be one.
    """
    options = (options or CheckOptions()).model_copy(update=overrides)
    asked_agent = options.agent
    options = options.model_copy(update={"agent": _checked_agent(options)})
    if not options.require_sandbox and required_by_settings():
        options = options.model_copy(update={"require_sandbox": True})
    path = Path(script)
    name = str(path)
    if not path.is_file():
        return _failure(name, Stage.GATE, "FileNotFoundError", f"no such file: {path}")
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        return _failure(
            name, Stage.GATE, type(error).__name__, f"cannot read {path} as UTF-8 text: {error}"
        )
    if not text.strip():
        return _failure(
            name,
            Stage.PARSE,
            "EmptyScript",
            "the script is empty",
            "write at least a `model` line, a map and an `ego = new Car`",
        )
    info = read_script_info(text)
    try:
        registry = registry or MapRegistry(options.map_dir)
        choice = registry.resolve(
            info.requested_map,
            _trusted_map_file(info.requested_map_file, path),
            path.resolve().parent,
        )
        prepare_map(Path(choice.path))
    except (MapError, MapPreparationError) as error:
        return _failure(name, Stage.COMPILE, "MapError", str(error))
    if options.simulator == Simulator.CARLA:
        reason = unreachable_reason(
            options.carla_host, options.carla_port, min(options.carla_timeout, 5.0)
        )
        if reason:
            return _failure(name, Stage.SIMULATE, "CarlaUnreachable", reason)
    request = {
        "text": text,
        "name": path.name,
        "options": options.model_dump(mode="json"),
        "map": choice.model_dump(mode="json"),
    }
    own_pool = pool is None
    active = pool or WorkerPool(size=1, memory_mb=options.memory_mb)
    try:
        raw = active.run(request, options.timeout, on_stage)
    except WorkerDied as death:
        return CheckResult(
            ok=False,
            script=name,
            diagnostic=death.diagnostic,
            map=choice,
            model=info.model,
            sandbox=death.sandbox,
        )
    except SandboxRequired as refusal:
        result = _failure(
            name,
            Stage.GATE,
            "SandboxUnavailable",
            str(refusal),
            "run on Linux >= 6.7 with Landlock enabled and libseccomp installed, "
            "or in a container or VM (see docs/security.md)",
        )
        result.sandbox = refusal.sandbox
        return result
    finally:
        if own_pool:
            active.close()
    result = _accepted(raw, name, choice, info.model, options.png)
    if result.simulation is not None:  # who drove is the parent's to say, not the worker's
        # As the user named it; a path past the trace's bound keeps its end (file, class).
        label = (asked_agent or "").strip()[-MAX_NAME:]
        result.simulation.agent = label if options.agent is not None else None
    return result


def _checked_agent(options: CheckOptions) -> str | None:
    """The agent's canonical name for the worker (None: the script drives); AgentError for
    a name that cannot be an agent, or for an agent CARLA cannot run."""
    spec = check_agent_spec(options.agent)
    if spec.scripted:
        return None
    if options.simulator == Simulator.CARLA:
        raise AgentError(carla_agents_problem(spec.text))
    return spec.text


def carla_agents_problem(name: str) -> str:
    """Why `--agent` cannot drive in CARLA here."""
    import importlib.util

    try:
        found = importlib.util.find_spec("agents.navigation.basic_agent") is not None
    except (ImportError, ValueError):
        found = False
    if not found:
        return (
            f"agent '{name}' in CARLA needs CARLA's own agents (BasicAgent, BehaviorAgent from "
            "the `agents.navigation` package of CARLA's PythonAPI), which cannot be imported "
            "here; put CARLA's PythonAPI/carla folder on PYTHONPATH, or drop --simulator carla"
        )
    return (
        f"agent '{name}' in CARLA: arise does not yet seat CARLA's BasicAgent or "
        "BehaviorAgent in the ego; run the agent on the offline world model instead"
    )


def _accepted(
    raw: dict[str, Any], name: str, choice: MapChoice, model: str | None, png: str | None
) -> CheckResult:
    """The check's result from the worker's answer: the facts after the strict schema, the
    rest from the parent's own request."""
    png_data = raw.get("png_data")
    try:
        facts = WorkerResult.model_validate(
            {key: value for key, value in raw.items() if key not in PARENT_FIELDS}
        )
    except ValidationError as error:
        return _violation(name, choice, model, raw, _first_problem(error))
    result = CheckResult(
        ok=False,
        script=name,
        map=choice,
        model=model,
        diagnostic=facts.diagnostic,
        warnings=facts.warnings,
        timings=facts.timings,
        spawn_attempts_used=facts.spawn_attempts_used,
        sample_iterations_used=facts.sample_iterations_used,
        simulation=facts.simulation,
        simulation_rejections=facts.simulation_rejections,
        sandbox=facts.sandbox,
    )
    # The verdict follows from the facts, not from a flag the script's process may forge.
    result.ok = result.diagnostic is None and result.simulation is not None
    if not result.ok and result.diagnostic is None:
        result.diagnostic = Diagnostic(
            stage=Stage.SIMULATE,
            error_type="ProtocolViolation",
            message="the check reported success without a simulation (a forged result?)",
            hint="the script wrote on the validator's result channel; remove that code.",
        )
    picture = _png_bytes(png_data) if png else None
    if png and png_data is not None and picture is None:
        result.warnings.append("the worker's picture was not a PNG image; none was written")
    result.png = _write_png(png, picture)
    return result


def _first_problem(error: ValidationError) -> str:
    """The first schema violation, in one short line (never the offending data)."""
    first = error.errors(include_url=False, include_input=False)[0]
    where = ".".join(str(part) for part in first["loc"][:6]) or "result"
    return f"{where}: {first['msg']}"[:300]


def _violation(
    name: str, choice: MapChoice, model: str | None, raw: dict[str, Any], problem: str
) -> CheckResult:
    result = _failure(
        name,
        Stage.SIMULATE,
        "ProtocolViolation",
        f"the worker's result broke the result schema ({problem})",
        "either the script wrote a result of its own on the validator's channel, or its "
        f"run exceeded the bounds every result is held to (at most {MAX_AGENTS} agents and "
        f"{MAX_STEPS} steps; arise/limits.py)",
    )
    result.map, result.model = choice, model
    try:  # the pool's own stamp, from before the script ran
        result.sandbox = WorkerResult.model_validate({"sandbox": raw.get("sandbox")}).sandbox
    except ValidationError:
        result.sandbox = None
    return result


def _png_bytes(data: object) -> bytes | None:
    """The picture the worker drew, when it is a PNG image at all."""
    if not isinstance(data, str):
        return None
    try:
        decoded = base64.b64decode(data, validate=True)
    except (binascii.Error, ValueError):
        return None
    return decoded if decoded.startswith(PNG_SIGNATURE) else None


def _trusted_map_file(requested: str | None, script: Path) -> str | None:
    """A map file a script names is read only when it is a plain .xodr file in the
    script's own folder tree; anything else (absolute paths, `..`, symlinks) is looked up
    by name among the known maps instead, so a script cannot make us read other files."""
    if not requested or not requested.endswith(".xodr"):
        return None
    relative = Path(requested)
    if relative.is_absolute() or ".." in relative.parts:
        return None
    folder = script.resolve().parent
    candidate = folder / relative
    if candidate.is_symlink() or not candidate.is_file():
        return None
    if not candidate.resolve().is_relative_to(folder):
        return None
    return str(candidate)


def _write_png(target: str | None, data: bytes | None) -> str | None:
    """Write the picture the worker drew into the place the caller asked for, whole
    (OutputError, naming the folder, when it cannot be written there)."""
    if not target or not data:
        return None
    return str(write_bytes_atomic(Path(target), data))


def check_text(text: str, options: CheckOptions | None = None, **kwargs: Any) -> CheckResult:
    """Check a script held in memory (written to a private temporary file first)."""
    with tempfile.TemporaryDirectory(prefix="arise-check-") as folder:
        path = Path(folder) / "scenario.scenic"
        path.write_text(text, encoding="utf-8")
        result = check(path, options, **kwargs)
    return result
