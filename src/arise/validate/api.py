"""`check()`: the library call behind `arise check`."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

from arise.maps.registry import MapError, MapRegistry
from arise.validate.carla_server import unreachable_reason
from arise.validate.pool import WorkerDied, WorkerPool
from arise.validate.script_info import read_script_info
from arise.validate.types import CheckOptions, CheckResult, Diagnostic, Stage


def _failure(script: str, stage: Stage, error_type: str, message: str,
             hint: str | None = None) -> CheckResult:
    return CheckResult(ok=False, script=script, diagnostic=Diagnostic(
        stage=stage, error_type=error_type, message=message, hint=hint))


def check(
    script: str | os.PathLike[str],
    options: CheckOptions | None = None,
    *,
    pool: WorkerPool | None = None,
    registry: MapRegistry | None = None,
    on_stage: Callable[[str], None] | None = None,
    **overrides: Any,
) -> CheckResult:
    """Gate, compile, sample and simulate one Scenic file in an isolated worker.

    Never raises for a bad script: every failure is in `result.diagnostic`.
    """
    options = (options or CheckOptions()).model_copy(update=overrides)
    path = Path(script)
    name = str(path)
    if not path.is_file():
        return _failure(name, Stage.GATE, "FileNotFoundError", f"no such file: {path}")
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        return _failure(name, Stage.GATE, type(error).__name__,
                        f"cannot read {path} as UTF-8 text: {error}")
    if not text.strip():
        return _failure(name, Stage.PARSE, "EmptyScript", "the script is empty",
                        "write at least a `model` line, a map and an `ego = new Car`")
    info = read_script_info(text)
    try:
        registry = registry or MapRegistry(options.map_dir)
        choice = registry.resolve(info.requested_map, info.requested_map_file,
                                  path.resolve().parent)
    except MapError as error:
        return _failure(name, Stage.COMPILE, "MapError", str(error))
    if options.simulator == "carla":
        reason = unreachable_reason(options.carla_host, options.carla_port,
                                    min(options.carla_timeout, 5.0))
        if reason:
            return _failure(name, Stage.SIMULATE, "CarlaUnreachable", reason)
    request = {"script": str(path.resolve()), "options": options.model_dump(mode="json"),
               "map": choice.model_dump(mode="json")}
    own_pool = pool is None
    active = pool or WorkerPool(size=1, memory_mb=options.memory_mb)
    try:
        raw = active.run(request, options.timeout, on_stage)
    except WorkerDied as death:
        result = CheckResult(ok=False, script=name, diagnostic=death.diagnostic, map=choice,
                             model=info.model)
        return result
    finally:
        if own_pool:
            active.close()
    result = CheckResult.model_validate(raw)
    result.script = name
    return result


def check_text(text: str, options: CheckOptions | None = None, **kwargs: Any) -> CheckResult:
    """Check a script held in memory (written to a private temporary file first)."""
    with tempfile.TemporaryDirectory(prefix="arise-check-") as folder:
        path = Path(folder) / "scenario.scenic"
        path.write_text(text, encoding="utf-8")
        result = check(path, options, **kwargs)
    return result
