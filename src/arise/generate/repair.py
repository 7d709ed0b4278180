"""Module D: the Test-and-Repair Loop.

Each failed check is routed by its diagnostic: first a rule for mechanical errors, then a
model repair of the failing section (the section back, never the whole script), and as a
last resort the next retrieved candidate for that section. A script that runs but fails
the semantic gate goes the other way round: first a candidate that fits, then a model fix.
Every attempt is kept; when the gate is never met, the run keeps the script that ran with
the fewest contradictions.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from arise.generate.assemble import Draft, apply_params
from arise.generate.conformity import Contradiction, gate_result
from arise.generate.events import AttemptChecked, Progress, RunStage, StageStarted, ignore
from arise.generate.retrieve import Retrieval
from arise.generate.rules import RuleContext, apply_rules
from arise.generate.run import Attempt, AttemptKind, Generation, Outcome, RunStatus, unified_diff
from arise.generate.timing import timed_params
from arise.kb.compose import (
    ComposeError,
    actor_at_line,
    compose,
    composition_problems,
    pick_map,
)
from arise.kb.schema import Component, Entry
from arise.llm.base import BaseProvider
from arise.llm.types import Message, Usage
from arise.prompts import load
from arise.sections import replace_section, section_body
from arise.validate.types import CheckResult, Diagnostic, Stage
from arise.vocabulary import Timing

SECTION_COMPONENT = {c.section: c for c in Component}
_UNNAMED = re.compile(r"\bunnamed (\w+)")
_CODE_BLOCK = re.compile(r"```(?:scenic|python)?\s*\n(.*?)```", re.S)
#: Contradictions a model fix cannot be told how to remove: a conflict that came too late or
#: too far is the timing of the behavior's entry, which only another entry changes.
SWAP_ONLY_CHECKS = frozenset({"conflict"})
#: A section's model repairs that may fail before only swaps are tried for it.
MODEL_TRIES_PER_SECTION = 2

Validate = Callable[[str], CheckResult]
Gate = Callable[[CheckResult], list[Contradiction]]
OnAttempt = Callable[[Attempt], None]


@dataclass(frozen=True)
class GatedValidate:
    """A validator with the semantic gate: `check` runs a script, `gate` lists what a script
    that ran contradicts. Called, it gives the gated result; the loop calls the two parts
    itself to keep the contradictions as data on the attempt."""

    check: Validate
    gate: Gate

    def validate(self, script: str) -> tuple[CheckResult, list[Contradiction]]:
        result = self.check(script)
        found = self.gate(result) if result.ok else []
        return gate_result(result, found), found

    def __call__(self, script: str) -> CheckResult:
        return self.validate(script)[0]


@dataclass(frozen=True)
class RepairStep:
    """The one result of a repair step: a new script (None: nothing left to try), how it
    was made, what the model cost, and the new draft when a candidate was swapped in."""

    script: str | None
    kind: AttemptKind
    detail: str
    usage: Usage = field(default_factory=Usage)
    draft: Draft | None = None
    # A section the model was asked to rewrite and answered nothing usable for.
    model_failed_on: str | None = None


def extract_code(reply: str) -> str | None:
    """The code a model returned: its first fenced block, or the whole reply if it has none."""
    match = _CODE_BLOCK.search(reply)
    code = match.group(1) if match else reply
    code = code.strip("\n")
    return code if code.strip() else None


def guilty_actor(script: str, diagnostic: Diagnostic, entries: Sequence[Entry] = ()) -> str | None:
    """The other actor ('actor2') whose snippet the diagnostic's line (or its first rejection
    with a line) is in; None when it is about the adversary or the scene. A rejection
    without a line that names an object's class ("unnamed Bus is not contained") is about
    the last of the other actors of that class in `entries`, if there is one."""
    lines = [diagnostic.line] + [r.line for r in diagnostic.rejections]
    line = next((n for n in lines if n is not None), None)
    if line is not None:
        return actor_at_line(script, line)
    for rejection in diagnostic.rejections:
        named = _UNNAMED.search(rejection.reason)
        if named is not None:
            mine = [e.actor for e in entries if e.actor and e.actor_class == named.group(1)]
            if mine:
                return mine[-1]
    return None


def guilty_section(diagnostic: Diagnostic) -> str | None:
    if diagnostic.section in SECTION_COMPONENT:
        return diagnostic.section
    for rejection in diagnostic.rejections:
        if rejection.section in SECTION_COMPONENT:
            return rejection.section
    return None


@dataclass
class RepairContext:
    """What repairs need beyond the script, and what they remember between steps."""

    description: str
    retrieval: Retrieval
    draft: Draft
    provider: BaseProvider | None
    rules: RuleContext
    temperature: float = 0.0
    seed: int | None = None
    llm_failures: dict[str, int] = field(default_factory=dict)
    tried: dict[str, set[str]] = field(default_factory=dict)  # section -> entry ids swapped in
    # (section, check, expected) a model fix of that section was already asked to remove:
    # asking again gives the same answer, so the gate stops instead.
    model_asked: set[tuple[str, str, str]] = field(default_factory=set)
    maps: dict[str, frozenset[str]] = field(default_factory=dict)  # map name -> features
    timing: Timing | None = None  # when the text says the adversary moves (`generate.timing`)
    # whether the semantic gate may ask the model to fix a contradiction (`gate_model_fixes`)
    model_fixes_contradictions: bool = False

    def count_model_failure(self, section: str) -> None:
        self.llm_failures[section] = self.llm_failures.get(section, 0) + 1

    def model_may_repair(self, section: str | None, diagnostic: Diagnostic) -> bool:
        return (
            self.provider is not None
            and section is not None
            and section != "HEADER"
            and self.llm_failures.get(section, 0) < MODEL_TRIES_PER_SECTION
            and diagnostic.stage is not Stage.GATE
        )


def repair_messages(request: str) -> list[Message]:
    """The repair call: fixed system prompt, then the scenario, error and section."""
    return [Message("system", load("repair_system.md")), Message("user", request)]


def llm_repair(
    context: RepairContext, script: str, diagnostic: Diagnostic, section: str
) -> RepairStep:
    """Ask the model for the failing section back; no script when its answer is unusable."""
    assert context.provider is not None
    component = SECTION_COMPONENT[section]
    examples = [
        e
        for e in context.retrieval.candidates.get(component, [])[:3]
        if e not in context.draft.entries
    ][:2]
    example_text = "\n\n".join(
        f"Example ({e.descriptions[0]}):\n```scenic\n{e.snippet}```" for e in examples
    )
    problem = diagnostic.one_line() + (f"\nHint: {diagnostic.hint}" if diagnostic.hint else "")
    if diagnostic.excerpt:
        problem += f"\n{diagnostic.excerpt}"
    user = (
        f"Scenario: {context.description.strip()}\n\nError:\n{problem}\n\n"
        f"Section {section}:\n```scenic\n{section_body(script, section)}\n```\n\n"
        + (f"Working examples of this kind of section:\n{example_text}\n\n" if example_text else "")
        + f"Return the corrected {section} section."
    )
    completion = context.provider.complete(
        repair_messages(user),
        temperature=context.temperature,
        max_tokens=700,
        seed=context.seed,
    )
    code = extract_code(completion.text)
    if code is None:
        return RepairStep(
            None,
            AttemptKind.LLM,
            "the model returned no code",
            completion.usage,
            model_failed_on=section,
        )
    repaired = replace_section(script, section, code)
    if repaired is None or repaired == script:
        return RepairStep(
            None,
            AttemptKind.LLM,
            "the model returned the section unchanged",
            completion.usage,
            model_failed_on=section,
        )
    return RepairStep(repaired, AttemptKind.LLM, f"model rewrote {section}", completion.usage)


def swap_candidate(context: RepairContext, section: str | None) -> RepairStep:
    """Replace the entry of the failing section by the next compatible candidate (or,
    when none is left, another section's)."""
    order = [section] if section else []
    order += [
        s for s in ("SPAWN", "BEHAVIOR", "GEOMETRY", "MISC", "REQUIREMENTS") if s not in order
    ]
    for name in order:
        step = swap_section(context, name)
        if step is not None:
            return step
    return RepairStep(None, AttemptKind.SWAP, "no other candidate fits")


def swap_section(context: RepairContext, name: str) -> RepairStep | None:
    """The next compatible candidate for one section (MISC and REQUIREMENTS: drop their
    last entry); None when nothing is left for it."""
    component = SECTION_COMPONENT.get(name)
    if component is None or component is Component.WEATHER:
        return None
    draft = context.draft
    # The adversary's (or the scene's) entries: the other actors' copies are not swapped.
    current = [e for e in draft.entries if e.component is component and e.actor is None]
    if component in (Component.MISC, Component.REQUIREMENTS):
        if not current:
            return None
        entries = [e for e in draft.entries if e is not current[-1]]
        note = f"dropped {current[-1].id}"
    else:
        tried = context.tried.setdefault(name, {e.id for e in current})
        others = [e for e in draft.entries if e not in current]
        candidates = [
            c for c in context.retrieval.candidates.get(component, []) if c.id not in tried
        ]
        replacement: Entry | None = None
        # With the other actors if a candidate fits them, else without them (a geometry
        # without an oncoming lane has no room for an oncoming bus): the adversary first.
        for keep in (others, [e for e in others if e.actor is None]):
            replacement = next(
                (
                    c
                    for c in candidates
                    if not composition_problems([*keep, c], draft.adversary_class)
                ),
                None,
            )
            if replacement is not None:
                break
        if replacement is None:
            return None
        tried.add(replacement.id)
        entries = [
            replacement if e in current else e for e in draft.entries if e in keep or e in current
        ]
        note = f"{current[0].id if current else '-'} -> {replacement.id}"
        left_out = sorted({e.actor for e in others if e.actor and e not in keep})
        if left_out:
            note += f" (without {', '.join(left_out)})"
    return _recomposed(context, entries, note)


def _recomposed(context: RepairContext, entries: list[Entry], note: str) -> RepairStep | None:
    """The draft of these entries as one swap step; None when they do not compose."""
    draft = context.draft
    map_name = pick_map(entries, context.maps) if context.maps else draft.map_name
    if map_name is None:
        return None
    try:
        script = compose(entries, draft.adversary_class, map_name, description=context.description)
    except ComposeError:
        return None
    # A swapped-in entry's triggers have ranges of their own: the timing words narrow those.
    params = {**draft.params, **timed_params(context.timing, (e for e in entries if not e.actor))}
    new_draft = Draft(
        script=apply_params(script, params),
        entries=entries,
        map_name=map_name,
        adversary_class=draft.adversary_class,
        params=params,
    )
    return RepairStep(new_draft.script, AttemptKind.SWAP, note, draft=new_draft)


def drop_actor(context: RepairContext, actor: str) -> RepairStep | None:
    """Leave out one other actor (its spawn and behavior copies): a diagnostic about it
    should not cost the adversary's scene. None when it is not in the draft."""
    mine = [e for e in context.draft.entries if e.actor == actor]
    if not mine:
        return None
    entries = [e for e in context.draft.entries if e.actor != actor]
    return _recomposed(context, entries, f"dropped {actor} ({', '.join(e.id for e in mine)})")


def semantic_repair(
    context: RepairContext, script: str, diagnostic: Diagnostic, found: list[Contradiction]
) -> RepairStep:
    """A script that runs but contradicts the description: first a candidate that fits for a
    section a contradiction names, and only when none is left (and the run allows it,
    `model_fixes_contradictions`), a model fix of that section told what the trace showed,
    once per contradiction: when no candidate is left and the model was already asked or
    may not be, nothing can remove it and the gate stops. Missing actors are never fixed by
    dropping one."""
    named = [c.section for c in found] or [diagnostic.section or ""]
    sections = [s for s in dict.fromkeys(named) if s in SECTION_COMPONENT]
    for section in sections:
        checks = {c.check for c in found if c.section == section}
        if checks == {"participants"}:
            continue  # a swap of MISC drops an object: it cannot add the missing one
        step = swap_section(context, section)
        if step is not None:
            return step
    usage = Usage()
    if not context.model_fixes_contradictions:
        return RepairStep(None, AttemptKind.SWAP, "no other candidate fits", usage)
    for section in sections:
        own = [c for c in found if c.section == section and c.check not in SWAP_ONLY_CHECKS]
        if found and not own:
            continue
        keys = {(section, c.check, c.expected) for c in own}
        if keys and keys <= context.model_asked:
            continue  # a model fix of this section already failed to remove these
        context.model_asked |= keys
        told = diagnostic.model_copy(
            update={
                "section": section,
                "message": "; ".join(c.text() for c in own) or diagnostic.message,
            }
        )
        while context.model_may_repair(section, told):
            step = llm_repair(context, script, told, section)
            usage = usage + step.usage
            if step.script is not None:
                return RepairStep(step.script, AttemptKind.LLM, step.detail, usage)
            context.count_model_failure(section)
    return RepairStep(None, AttemptKind.SWAP, "no other candidate fits", usage)


def repair_once(
    context: RepairContext,
    script: str,
    diagnostic: Diagnostic,
    contradictions: list[Contradiction] | None = None,
) -> RepairStep:
    """One repair step, routed by the diagnostic: rule, else model, else swap; for a script
    that runs but fails the semantic gate, swap, else model."""
    if diagnostic.stage is Stage.SEMANTIC:
        return semantic_repair(context, script, diagnostic, contradictions or [])
    fix = apply_rules(diagnostic, script, context.rules)
    if fix is not None:
        return RepairStep(fix.text, AttemptKind.RULE, f"{fix.rule}: {fix.note}")
    actor = guilty_actor(script, diagnostic, context.draft.entries)
    if actor is not None:
        dropped = drop_actor(context, actor)
        if dropped is not None:
            return dropped
    section = guilty_section(diagnostic)
    if context.model_may_repair(section, diagnostic):
        assert section is not None
        step = llm_repair(context, script, diagnostic, section)
        if step.script is not None:
            return step
        swap = swap_candidate(context, section)
        return RepairStep(
            swap.script,
            AttemptKind.SWAP,
            f"{step.detail}; {swap.detail}",
            step.usage,
            swap.draft,
            model_failed_on=section,
        )
    return swap_candidate(context, section)


def run_attempt(
    index: int,
    kind: AttemptKind,
    detail: str,
    before: str,
    script: str,
    validate: Validate,
    usage: Usage,
    repair_seconds: float = 0.0,
) -> Attempt:
    started = time.perf_counter()
    if isinstance(validate, GatedValidate):
        result, found = validate.validate(script)
    else:
        result, found = validate(script), []
    return Attempt(
        index=index,
        kind=kind,
        detail=detail,
        script=script,
        ok=result.ok,
        diagnostic=result.diagnostic,
        diff=unified_diff(before, script),
        check_seconds=time.perf_counter() - started,
        llm_usage=usage,
        check=result,
        contradictions=found,
        repair_seconds=repair_seconds,
    )


def best_executed(attempts: list[Attempt]) -> Attempt | None:
    """The attempt that ran with the fewest contradictions (the earliest of equals)."""
    ran = [a for a in attempts if a.executed]
    return min(ran, key=lambda a: (len(a.contradictions), a.index)) if ran else None


def settle(run: Generation, reason: str | None) -> Outcome:
    """How a run ends when its last attempt did not pass: EXECUTED with the best script that
    ran when one did (the gate was not met), else FAILED."""
    best = best_executed(run.attempts)
    if best is None:
        return Outcome(RunStatus.FAILED, reason)
    left = len(best.contradictions)
    note = f"the semantic gate was not met: kept attempt {best.index}, {left} contradiction(s)"
    return Outcome(RunStatus.EXECUTED, f"{reason}; {note}" if reason else note, final=best.index)


def repair_loop(
    run: Generation,
    script: str,
    validate: Validate,
    context: RepairContext | None,
    *,
    max_repairs: int,
    emit: Progress = ignore,
    on_attempt: OnAttempt | None = None,
) -> Outcome:
    """Module D: validate the assembled script, then repair it until it runs or
    `max_repairs` repairs are spent (no repairs at all when `context` is None).

    This loop is the only place that adds attempts to `run` and swaps its draft. Provider
    errors propagate (the caller ends the run with them); every attempt made before stays.
    """

    def add(attempt: Attempt) -> Attempt:
        run.add_attempt(attempt)
        emit(
            AttemptChecked(
                attempt.index,
                attempt.kind,
                attempt.ok,
                attempt.detail,
                attempt.diagnostic.one_line() if attempt.diagnostic else None,
            )
        )
        if on_attempt is not None:
            on_attempt(attempt)
        return attempt

    emit(StageStarted(RunStage.VALIDATE, attempt=len(run.attempts)))
    attempt = add(
        run_attempt(
            len(run.attempts),
            AttemptKind.INITIAL,
            "assembled from the knowledge base",
            "",
            script,
            validate,
            Usage(),
        )
    )
    if context is None:
        return Outcome(RunStatus.EXECUTED) if attempt.ok else settle(run, None)
    while not attempt.ok and len(run.attempts) <= max_repairs:
        diagnostic = attempt.diagnostic
        assert diagnostic is not None
        emit(StageStarted(RunStage.REPAIR, attempt=len(run.attempts), error=diagnostic.one_line()))
        started = time.perf_counter()
        step = repair_once(context, attempt.script, diagnostic, attempt.contradictions)
        repair_seconds = time.perf_counter() - started
        if step.model_failed_on is not None:
            context.count_model_failure(step.model_failed_on)
        if step.script is None:
            # The search for a repair that found none (model fixes that came back unusable
            # included) took time too: the gate's cost counts it.
            run.unused_repair_seconds += repair_seconds
            return settle(run, f"no repair left for: {diagnostic.one_line()}")
        if step.draft is not None:
            context.draft = step.draft
            run.use_draft(step.draft)
        attempt = run_attempt(
            len(run.attempts),
            step.kind,
            step.detail,
            attempt.script,
            step.script,
            validate,
            step.usage,
            repair_seconds,
        )
        if step.kind is AttemptKind.LLM and not attempt.ok and attempt.diagnostic is not None:
            # A model repair that did not run counts against the section now failing.
            failing = guilty_section(attempt.diagnostic)
            if failing:
                context.count_model_failure(failing)
        add(attempt)
    if attempt.ok:
        return Outcome(RunStatus.EXECUTED)
    last = attempt.diagnostic
    return settle(run, f"repair budget spent; last error: {last.one_line()}" if last else None)
