"""Module D: the Test-and-Repair Loop.

Each failed check is routed by its diagnostic: first a rule for mechanical errors, then a
model repair of the failing section (the section back, never the whole script), and as a
last resort the next retrieved candidate for that section. Every attempt is kept.
"""

from __future__ import annotations

import difflib
import re
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from arise.generate.assemble import Draft, apply_params
from arise.generate.retrieve import Retrieval
from arise.generate.rules import RuleContext, apply_rules
from arise.kb.compose import ComposeError, compose, composition_problems, pick_map
from arise.kb.schema import Component, Entry
from arise.llm.base import BaseProvider
from arise.llm.types import Message, Usage
from arise.prompts import load
from arise.validate.types import CheckResult, Diagnostic, Stage

SECTION_COMPONENT = {c.section: c for c in Component}
_CODE_BLOCK = re.compile(r"```(?:scenic|python)?\s*\n(.*?)```", re.S)


@dataclass
class Attempt:
    """One validated version of the script and how it came to be."""

    index: int
    kind: str  # initial | rule | llm | swap
    detail: str
    script: str
    ok: bool
    diagnostic: Diagnostic | None
    diff: str
    check_seconds: float
    llm_usage: Usage = field(default_factory=Usage)

    def as_dict(self) -> dict[str, Any]:
        return {
            "index": self.index, "kind": self.kind, "detail": self.detail, "ok": self.ok,
            "diagnostic": self.diagnostic.model_dump(mode="json") if self.diagnostic else None,
            "diff": self.diff, "check_seconds": round(self.check_seconds, 3),
            "llm": self.llm_usage.as_dict(),
        }


def unified_diff(before: str, after: str) -> str:
    return "".join(difflib.unified_diff(before.splitlines(True), after.splitlines(True),
                                        "before.scenic", "after.scenic", n=1))


def section_span(script: str, name: str) -> tuple[int, int] | None:
    """0-based line indexes of the BEGIN and END markers of a section."""
    lines = script.split("\n")
    begin = next((i for i, line in enumerate(lines) if line.strip() == f"# BEGIN {name}"), None)
    if begin is None:
        return None
    end = next((i for i in range(begin + 1, len(lines)) if lines[i].strip() == f"# END {name}"),
               None)
    return None if end is None else (begin, end)


def replace_section(script: str, name: str, body: str) -> str | None:
    span = section_span(script, name)
    if span is None:
        return None
    lines = script.split("\n")
    body_lines = [line for line in body.strip("\n").split("\n")
                  if line.strip() not in (f"# BEGIN {name}", f"# END {name}")]
    return "\n".join(lines[: span[0] + 1] + body_lines + lines[span[1]:])


def section_body(script: str, name: str) -> str:
    span = section_span(script, name)
    if span is None:
        return ""
    return "\n".join(script.split("\n")[span[0] + 1: span[1]])


def extract_code(reply: str) -> str | None:
    """The code a model returned: its first fenced block, or the whole reply if it has none."""
    match = _CODE_BLOCK.search(reply)
    code = match.group(1) if match else reply
    code = code.strip("\n")
    return code if code.strip() else None


def guilty_section(diagnostic: Diagnostic) -> str | None:
    if diagnostic.section in SECTION_COMPONENT:
        return diagnostic.section
    for rejection in diagnostic.rejections:
        if rejection.section in SECTION_COMPONENT:
            return rejection.section
    return None


@dataclass
class RepairContext:
    description: str
    retrieval: Retrieval
    draft: Draft
    provider: BaseProvider | None
    rules: RuleContext
    temperature: float = 0.0
    seed: int | None = None
    llm_failures: dict[str, int] = field(default_factory=dict)
    tried: dict[str, set[str]] = field(default_factory=dict)  # section -> entry ids swapped in
    maps: dict[str, frozenset[str]] = field(default_factory=dict)  # map name -> features


def llm_repair(context: RepairContext, script: str, diagnostic: Diagnostic, section: str
               ) -> tuple[str | None, Usage, str]:
    """Ask the model for the failing section back; None when its answer is unusable."""
    assert context.provider is not None
    component = SECTION_COMPONENT[section]
    examples = [e for e in context.retrieval.candidates.get(component, [])[:3]
                if e not in context.draft.entries][:2]
    example_text = "\n\n".join(f"Example ({e.descriptions[0]}):\n```scenic\n{e.snippet}```"
                               for e in examples)
    problem = diagnostic.one_line() + (f"\nHint: {diagnostic.hint}" if diagnostic.hint else "")
    if diagnostic.excerpt:
        problem += f"\n{diagnostic.excerpt}"
    user = (f"Scenario: {context.description.strip()}\n\nError:\n{problem}\n\n"
            f"Section {section}:\n```scenic\n{section_body(script, section)}\n```\n\n"
            + (f"Working examples of this kind of section:\n{example_text}\n\n"
               if example_text else "")
            + f"Return the corrected {section} section.")
    completion = context.provider.complete(
        [Message("system", load("repair_system.md")), Message("user", user)],
        temperature=context.temperature, max_tokens=700, seed=context.seed)
    code = extract_code(completion.text)
    if code is None:
        return None, completion.usage, "the model returned no code"
    repaired = replace_section(script, section, code)
    if repaired is None or repaired == script:
        return None, completion.usage, "the model returned the section unchanged"
    return repaired, completion.usage, f"model rewrote {section}"


def swap_candidate(context: RepairContext, section: str | None) -> tuple[str | None, str]:
    """Replace the entry of the failing section by the next compatible candidate."""
    order = [section] if section else []
    order += [s for s in ("SPAWN", "BEHAVIOR", "GEOMETRY", "MISC", "REQUIREMENTS")
              if s not in order]
    draft = context.draft
    for name in order:
        component = SECTION_COMPONENT.get(name)
        if component is None or component is Component.WEATHER:
            continue
        current = [e for e in draft.entries if e.component is component]
        if component in (Component.MISC, Component.REQUIREMENTS):
            if not current:
                continue
            entries = [e for e in draft.entries if e is not current[-1]]
            note = f"dropped {current[-1].id}"
            replacement: Entry | None = None
        else:
            tried = context.tried.setdefault(name, {e.id for e in current})
            others = [e for e in draft.entries if e.component is not component]
            replacement = next(
                (c for c in context.retrieval.candidates.get(component, [])
                 if c.id not in tried
                 and not composition_problems([*others, c], draft.adversary_class)), None)
            if replacement is None:
                continue
            tried.add(replacement.id)
            entries = [replacement if e.component is component else e for e in draft.entries]
            note = f"{current[0].id if current else '-'} -> {replacement.id}"
        map_name = pick_map(entries, context.maps) if context.maps else draft.map_name
        if map_name is None:
            continue
        try:
            script = compose(entries, draft.adversary_class, map_name,
                             description=context.description)
        except ComposeError:
            continue
        context.draft = Draft(script=apply_params(script, draft.params), entries=entries,
                              map_name=map_name, adversary_class=draft.adversary_class,
                              params=draft.params)
        return context.draft.script, note
    return None, "no other candidate fits"


Validate = Callable[[str], CheckResult]


def repair_once(context: RepairContext, script: str, diagnostic: Diagnostic
                ) -> tuple[str | None, str, str, Usage]:
    """One repair step: (new script or None, kind, detail, model usage)."""
    if diagnostic.stage is Stage.SEMANTIC:
        # The script runs: editing numbers will not change who or where; another entry will.
        swapped, note = swap_candidate(context, guilty_section(diagnostic))
        return swapped, "swap", note, Usage()
    fix = apply_rules(diagnostic, script, context.rules)
    if fix is not None:
        return fix.text, "rule", f"{fix.rule}: {fix.note}", Usage()
    section = guilty_section(diagnostic)
    if context.provider is not None and section is not None and section != "HEADER" \
            and context.llm_failures.get(section, 0) < 2 and diagnostic.stage is not Stage.GATE:
        repaired, usage, note = llm_repair(context, script, diagnostic, section)
        if repaired is not None:
            return repaired, "llm", note, usage
        context.llm_failures[section] = context.llm_failures.get(section, 0) + 1
        swapped, swap_note = swap_candidate(context, section)
        return swapped, "swap", f"{note}; {swap_note}", usage
    swapped, note = swap_candidate(context, section)
    return swapped, "swap", note, Usage()


def note_llm_failure(context: RepairContext, attempt: Attempt) -> None:
    """An LLM repair that did not run counts against its section (then we swap)."""
    if attempt.kind == "llm" and not attempt.ok and attempt.diagnostic is not None:
        section = guilty_section(attempt.diagnostic)
        if section:
            context.llm_failures[section] = context.llm_failures.get(section, 0) + 1


def run_attempt(index: int, kind: str, detail: str, before: str, script: str,
                validate: Validate, usage: Usage) -> Attempt:
    started = time.perf_counter()
    result = validate(script)
    return Attempt(index=index, kind=kind, detail=detail, script=script, ok=result.ok,
                   diagnostic=result.diagnostic, diff=unified_diff(before, script),
                   check_seconds=time.perf_counter() - started, llm_usage=usage)
