"""Checking several scripts with one pool of workers: what `arise check` does with its options.

The command line parses its options into `CheckOptions`, calls `check_scripts` and prints
the typed events it sends and the results it returns.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from arise.maps.registry import MapRegistry
from arise.validate.api import check
from arise.validate.pool import StageCallback, WorkerPool
from arise.validate.types import CheckOptions, CheckResult, Stage


@dataclass(frozen=True)
class ScriptStarted:
    """A script goes to a worker (one at a time only; parallel checks send no progress)."""

    script: Path


@dataclass(frozen=True)
class ScriptStage:
    """The worker checking `script` began a stage."""

    script: Path
    stage: Stage


@dataclass(frozen=True)
class ScriptChecked:
    """A script's verdict, in the order of the scripts given."""

    result: CheckResult


CheckEvent = ScriptStarted | ScriptStage | ScriptChecked
OnCheckEvent = Callable[[CheckEvent], None]


def png_target(png: str | None, script: Path, many: bool) -> str | None:
    """Where a script's picture goes: `png` itself, or for several scripts `png/STEM.png`."""
    if png is None:
        return None
    if many:
        folder = Path(png)
        folder.mkdir(parents=True, exist_ok=True)
        return str(folder / f"{script.stem}.png")
    return png


def check_scripts(
    scripts: Sequence[Path],
    options: CheckOptions,
    *,
    workers: int = 1,
    png: str | None = None,
    on_event: OnCheckEvent | None = None,
) -> list[CheckResult]:
    """Check every script (`workers` at a time) and return their results in order.

    Raises MapError for a bad map folder before a worker starts; a script that fails is a
    result, not an error (see `check`)."""
    registry = MapRegistry(options.map_dir)
    many = len(scripts) > 1
    emit = on_event or (lambda event: None)
    results: list[CheckResult] = []
    size = max(1, min(workers, len(scripts)))
    with WorkerPool(size=size, memory_mb=options.memory_mb) as pool:

        def run_one(script: Path, on_stage: StageCallback | None = None) -> CheckResult:
            per_script = options.model_copy(update={"png": png_target(png, script, many)})
            return check(script, per_script, pool=pool, registry=registry, on_stage=on_stage)

        if workers > 1 and many:
            with ThreadPoolExecutor(max_workers=pool.size) as executor:
                for result in executor.map(run_one, scripts):
                    results.append(result)
                    emit(ScriptChecked(result))
            return results
        for script in scripts:
            emit(ScriptStarted(script))

            def stage(name: Stage, script: Path = script) -> None:
                emit(ScriptStage(script, name))

            result = run_one(script, stage if on_event is not None else None)
            results.append(result)
            emit(ScriptChecked(result))
    return results
