"""What the page shows of a finished run, read from its folder (so it works after a
restart): the script with its sections and, for each line, the attempt that last changed
it; every attempt with its diagnostic; the spec's grounded facts; the conformity checks;
the files there are to see or download.

The folder is untrusted input (see `store`): every file is read through `safefs` (no
links, bounded sizes), the report's numbers are bounded before they drive a loop, and the
per-line work is linear, so a crafted folder can neither leak a file nor stall the view."""

from __future__ import annotations

import difflib
import math
from typing import Any

from pydantic import ValidationError

from arise.generate.spec import Actor
from arise.language.facts import GroundedFact
from arise.present.source import FAILED_MARKER
from arise.sections import find_sections, sections_by_line
from arise.serve.safefs import EntryKind, Folder, Refused, parse_json
from arise.serve.store import bundle_of
from arise.validate.types import Diagnostic, SandboxReport

REPORT = "report.json"
SCRIPT = "scenario.scenic"
VIEWABLE = ("replay.html", "replay.gif", "scene.png")
ATTEMPTS = "attempts"
MAX_REPORT_BYTES = 8 * 1024 * 1024
MAX_SCRIPT_BYTES = 1024 * 1024
#: Attempts read back for line origins (a run has max_repairs + 1; the default is 11).
MAX_ATTEMPTS = 64
#: Facts and actors shown of a spec (a real one has a few dozen).
MAX_ITEMS = 1000
#: Beyond this many lines a script gets no sections and no line origins (both grow
#: faster than the text; a generated script has a few hundred lines).
MAX_DIFF_LINES = 5000


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


def _attempt_scripts(folder: Folder, last: int) -> list[str]:
    try:
        attempts = folder.folder(ATTEMPTS)
    except Refused:
        return []
    with attempts:
        return [
            attempts.read_text(f"attempt-{index:02d}.scenic", MAX_SCRIPT_BYTES) or ""
            for index in range(last + 1)
        ]


def _final_script(folder: Folder) -> str:
    text = folder.read_text(SCRIPT, MAX_SCRIPT_BYTES) or ""
    if text.startswith(FAILED_MARKER):
        text = text.split("\n", 1)[1] if "\n" in text else ""
    return text


def script_view(folder: Folder, report: dict[str, Any]) -> dict[str, Any]:
    """The final script's lines, each with its section and the attempt that wrote it."""
    script = _final_script(folder)
    final = report.get("final_attempt")
    kinds = {
        a.get("index"): a.get("kind")
        for a in _list(report.get("attempts"))
        if isinstance(a, dict) and isinstance(a.get("index"), int)
    }
    origins: list[int] = []
    lines_of_script = script.splitlines()
    if (
        isinstance(final, int)
        and 0 <= final < MAX_ATTEMPTS
        and len(lines_of_script) <= MAX_DIFF_LINES
    ):
        scripts = _attempt_scripts(folder, final)
        if (
            scripts
            and scripts[-1].splitlines() == lines_of_script
            and all(s.count("\n") <= MAX_DIFF_LINES for s in scripts)
        ):
            origins = line_origins(scripts)
    small = len(lines_of_script) <= MAX_DIFF_LINES
    found = find_sections(script) if small else []
    sections_of = sections_by_line(script) if small else [None] * len(lines_of_script)
    lines = []
    for number, text in enumerate(lines_of_script, start=1):
        origin = origins[number - 1] if len(origins) >= number else 0
        lines.append(
            {
                "number": number,
                "text": text,
                "section": sections_of[number - 1],
                "attempt": origin,
                "kind": kinds.get(origin),
            }
        )
    sections = [
        {"name": s.name, "first_line": s.first_line, "last_line": s.last_line} for s in found
    ]
    return {"lines": lines, "sections": sections, "failed": report.get("status") != "executed"}


def _diagnostic_line(data: object) -> str | None:
    if not isinstance(data, dict):
        return None
    try:
        return Diagnostic.model_validate(data).one_line()
    except ValidationError:
        return str(data.get("message") or "")


def _seconds(*values: object) -> float:
    """The sum of the numbers among `values` (anything else counts as 0)."""
    total = sum(float(v) for v in values if isinstance(v, int | float) and not isinstance(v, bool))
    return round(total, 2) if math.isfinite(total) else 0.0


def _list(value: object, limit: int = MAX_ATTEMPTS) -> list[Any]:
    return value[:limit] if isinstance(value, list) else []


def attempts_view(report: dict[str, Any]) -> list[dict[str, Any]]:
    found = []
    for attempt in _list(report.get("attempts")):
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
                "seconds": _seconds(attempt.get("check_seconds"), attempt.get("repair_seconds")),
            }
        )
    return found


def spec_view(report: dict[str, Any]) -> dict[str, Any] | None:
    """Every fact with the words it rests on (or "not stated"), and the other actors."""
    spec = report.get("spec")
    if not isinstance(spec, dict):
        return None
    facts = []
    for raw in _list(spec.get("grounding"), MAX_ITEMS):
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
    for raw in _list(spec.get("actors"), MAX_ITEMS):
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


def run_view(folder: Folder) -> dict[str, Any]:
    """Everything the page shows of a run; a run that never started has only `files`.
    Entries that are links or special files are neither listed nor read (`skipped`)."""
    bundle = bundle_of(folder)
    view: dict[str, Any] = {"report": None, "files": bundle.names, "skipped": bundle.skipped}
    view["viewable"] = [name for name in VIEWABLE if folder.kind(name) is EntryKind.REGULAR]
    text = folder.read_text(REPORT, MAX_REPORT_BYTES)
    if text is None:
        return view
    try:
        report = parse_json(text)
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
