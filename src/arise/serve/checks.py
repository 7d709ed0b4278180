"""Check a pasted or uploaded script, as `arise check` does: only in the confined
validator, never in the server's process. A script that runs also gets its replay."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from arise.errors import AriseError
from arise.present.files import write_text_atomic
from arise.present.replay import HTML_NAME, scene_for
from arise.present.source import from_check
from arise.render.html import replay_html
from arise.sections import find_sections
from arise.serve.errors import BadInput, InputTooLarge
from arise.validate import CheckOptions, WorkerPool, check
from arise.validate.types import CheckResult

SCRIPT_NAME = "scenario.scenic"
#: Seconds a pasted script may run in the validator (the server passes its own).
CHECK_TIMEOUT = 60.0


def check_options(map_dir: str | None, timeout: float, agent: str | None = None) -> CheckOptions:
    """What a pasted script is checked with (the server also holds a check's requests
    to these); `agent` drives the ego (a built-in, `serve.driving.admit_agent`)."""
    return CheckOptions(seed=0, map_dir=map_dir, timeout=timeout, agent=agent)


def admit_script(text: str, max_bytes: int) -> str:
    """The script as given, or a clear refusal (too large, empty, not text)."""
    size = len(text.encode("utf-8", errors="replace"))
    if size > max_bytes:
        raise InputTooLarge(
            f"the script is {size // 1024} KiB; the limit is {max_bytes // 1024} KiB"
        )
    if "\x00" in text:
        raise BadInput("the script is not text (it holds NUL bytes)")
    if not text.strip():
        raise BadInput("the script is empty: paste a Scenic 3 script or choose a .scenic file")
    return text


def result_view(result: CheckResult, script: str) -> dict[str, Any]:
    diagnostic = result.diagnostic
    simulation = result.simulation
    return {
        "ok": result.ok,
        "summary": result.summary(),
        "diagnostic": diagnostic.model_dump(mode="json") if diagnostic else None,
        "diagnostic_line": diagnostic.one_line() if diagnostic else None,
        "map": result.map.name if result.map else None,
        "map_note": (
            f"substitute for {result.map.requested}"
            if result.map and result.map.substituted and result.map.requested
            else None
        ),
        "sandbox": result.sandbox.label if result.sandbox else None,
        "warnings": list(result.warnings),
        "ego_pairs": (
            [pair.model_dump(mode="json") for pair in simulation.ego_pairs] if simulation else []
        ),
        "collisions": (
            [c.model_dump(mode="json") for c in simulation.collisions] if simulation else []
        ),
        "sections": [
            {"name": s.name, "first_line": s.first_line, "last_line": s.last_line}
            for s in find_sections(script)
        ],
        "lines": script.splitlines(),
    }


def check_script(
    text: str,
    folder: Path,
    pool: WorkerPool,
    map_dir: str | None = None,
    timeout: float = CHECK_TIMEOUT,
    agent: str | None = None,
) -> dict[str, Any]:
    """Check `text` (saved as folder/scenario.scenic) in the pool; a run adds replay.html,
    and with an agent its driving metrics. The server calls this in its check process
    (`checkproc`), never in its own."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / SCRIPT_NAME
    write_text_atomic(path, text)
    options = check_options(map_dir, timeout, agent)
    result = check(path, options, pool=pool)
    view = result_view(result, text)
    view["replay"] = None
    view["driving"] = None
    if result.ok and agent is not None:
        from arise.serve.driving import driving_view

        view["driving"] = driving_view(result, agent, options.steps)
    if result.ok:
        try:
            source = from_check(path, result, options)
            write_text_atomic(folder / HTML_NAME, replay_html(scene_for(source, map_dir)))
            view["replay"] = HTML_NAME
        except AriseError as error:
            view["warnings"].append(f"no replay: {error}")
    return view
