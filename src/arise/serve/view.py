"""What the page shows of a finished run, read from its folder (so it works after a
restart): the script with its sections and, for each line, the attempt that last changed
it; every attempt with its diagnostic; the spec's grounded facts; the conformity checks;
the files there are to see or download."""

from __future__ import annotations

import difflib
import json
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from arise.generate.facts import GroundedFact
from arise.generate.spec import Actor
from arise.present.source import FAILED_MARKER
from arise.sections import find_sections, section_of_line
from arise.serve.store import BUNDLE
from arise.validate.types import Diagnostic, SandboxReport

REPORT = "report.json"
SCRIPT = "scenario.scenic"
VIEWABLE = ("replay.html", "replay.gif", "scene.png")


def line_origins(scripts: list[str]) -> list[int]:
    """For each line of the last script, the index of the script that last wrote it
    (0: it was there from the first)."""
    if not scripts:
        return []
    origins = [0] * len(scripts[0].splitlines())
    for index in range(1, len(scripts)):
        before, after = scripts[index - 1].splitlines(), scripts[index].splitlines()
        moved: list[int] = []
        matcher = difflib.SequenceMatcher(a=before, b=after, autojunk=False)
        for tag, a0, a1, b0, b1 in matcher.get_opcodes():
            if tag == "equal":
                moved += origins[a0:a1]
            elif tag in ("replace", "insert"):
                moved += [index] * (b1 - b0)
        origins = moved
    return origins


def _attempt_scripts(folder: Path, last: int) -> list[str]:
    scripts = []
    for index in range(last + 1):
        path = folder / "attempts" / f"attempt-{index:02d}.scenic"
        scripts.append(path.read_text("utf-8") if path.is_file() else "")
    return scripts


def _final_script(folder: Path) -> str:
    path = folder / SCRIPT
    if not path.is_file():
        return ""
    text = path.read_text("utf-8")
    if text.startswith(FAILED_MARKER):
        text = text.split("\n", 1)[1] if "\n" in text else ""
    return text


def script_view(folder: Path, report: dict[str, Any]) -> dict[str, Any]:
    """The final script's lines, each with its section and the attempt that wrote it."""
    script = _final_script(folder)
    final = report.get("final_attempt")
    attempts = report.get("attempts") or []
    kinds = {a.get("index"): a.get("kind") for a in attempts if isinstance(a, dict)}
    origins: list[int] = []
    if isinstance(final, int) and final >= 0:
        scripts = _attempt_scripts(folder, final)
        if scripts[-1].splitlines() == script.splitlines():
            origins = line_origins(scripts)
    lines = []
    for number, text in enumerate(script.splitlines(), start=1):
        origin = origins[number - 1] if len(origins) >= number else 0
        lines.append(
            {
                "number": number,
                "text": text,
                "section": section_of_line(script, number),
                "attempt": origin,
                "kind": kinds.get(origin),
            }
        )
    sections = [
        {"name": s.name, "first_line": s.first_line, "last_line": s.last_line}
        for s in find_sections(script)
    ]
    return {"lines": lines, "sections": sections, "failed": report.get("status") != "executed"}


def _diagnostic_line(data: object) -> str | None:
    if not isinstance(data, dict):
        return None
    try:
        return Diagnostic.model_validate(data).one_line()
    except ValidationError:
        return str(data.get("message") or "")


def attempts_view(report: dict[str, Any]) -> list[dict[str, Any]]:
    found = []
    for attempt in report.get("attempts") or []:
        if not isinstance(attempt, dict):
            continue
        diagnostic = attempt.get("diagnostic")
        found.append(
            {
                "index": attempt.get("index"),
                "kind": attempt.get("kind"),
                "detail": attempt.get("detail"),
                "ok": attempt.get("ok"),
                "executed": attempt.get("executed"),
                "diagnostic": _diagnostic_line(diagnostic),
                "section": diagnostic.get("section") if isinstance(diagnostic, dict) else None,
                "hint": diagnostic.get("hint") if isinstance(diagnostic, dict) else None,
                "contradictions": attempt.get("contradictions") or [],
                "diff": attempt.get("diff") or "",
                "seconds": round(
                    float(attempt.get("check_seconds") or 0)
                    + float(attempt.get("repair_seconds") or 0),
                    2,
                ),
            }
        )
    return found


def spec_view(report: dict[str, Any]) -> dict[str, Any] | None:
    """Every fact with the words it rests on (or "not stated"), and the other actors."""
    spec = report.get("spec")
    if not isinstance(spec, dict):
        return None
    facts = []
    for raw in spec.get("grounding") or []:
        try:
            fact = GroundedFact.model_validate(raw)
        except ValidationError:
            continue
        facts.append(
            {
                "name": fact.name,
                "value": fact.value,
                "source": fact.source.value,
                "quote": fact.quote,
                "text": fact.describe(),
            }
        )
    actors = []
    for raw in spec.get("actors") or []:
        try:
            actors.append(Actor.model_validate(raw).describe())
        except ValidationError:
            continue
    return {
        "facts": facts,
        "actors": actors,
        "corrections": report.get("spec_corrections") or [],
        "ignored": report.get("ignored_text") or [],
        "contradictions": report.get("contradictions") or [],
        "fields": {k: v for k, v in spec.items() if k not in ("grounding", "actors")},
    }


def _sandbox_label(data: object) -> str | None:
    if not isinstance(data, dict):
        return None
    try:
        return SandboxReport.model_validate(data).label
    except ValidationError:
        return None


def run_view(folder: Path) -> dict[str, Any]:
    """Everything the page shows of a run; a run that never started has only `files`."""
    view: dict[str, Any] = {"report": None, "files": [], "viewable": []}
    view["files"] = [name for name in BUNDLE if (folder / name).is_file()]
    view["files"] += sorted(p.name for p in folder.glob("*.xodr"))
    view["viewable"] = [name for name in VIEWABLE if (folder / name).is_file()]
    path = folder / REPORT
    if not path.is_file():
        return view
    try:
        report = json.loads(path.read_text("utf-8"))
    except ValueError:
        return view
    if not isinstance(report, dict):
        return view
    view["report"] = {
        "status": report.get("status"),
        "message": report.get("message"),
        "map": report.get("map"),
        "chosen": report.get("chosen") or [],
        "repairs": report.get("repairs"),
        "seconds": report.get("seconds"),
        "llm": report.get("llm"),
        "sandbox": _sandbox_label(report.get("sandbox")),
        "semantic_gate": report.get("semantic_gate"),
    }
    view["script"] = script_view(folder, report)
    view["attempts"] = attempts_view(report)
    view["spec"] = spec_view(report)
    view["conformity"] = report.get("conformity")
    return view
