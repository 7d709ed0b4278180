"""The state of one generation run: its status, its attempts, and their one serialisation.

`Generation.report()` is the only serialisation of a run: report.json is written from it,
and the benchmark's rows and attempt rows are read from it (evaluate/records.py), so the
two can never disagree.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path
from typing import Any

from arise.generate.assemble import Draft
from arise.generate.conformity import Contradiction
from arise.generate.options import GenerateOptions
from arise.generate.retrieve import Retrieval
from arise.generate.spec import ScenarioSpec
from arise.llm.types import Usage
from arise.validate.types import CheckResult, Diagnostic


class RunStatus(StrEnum):
    RUNNING = "running"
    # The final script ran; whether it also agrees with the description is the run's
    # `gate` verdict (a run is never FAILED only because the semantic gate stayed unmet).
    EXECUTED = "executed"
    FAILED = "failed"  # no script ran within the repair budget (or the snippets did not fit)
    REFUSED = "refused"  # the description was refused before or by extraction
    PROVIDER_ERROR = "provider_error"  # the model could not be asked


class AttemptKind(StrEnum):
    """How the script of an attempt came to be."""

    INITIAL = "initial"  # assembled from the knowledge base
    RULE = "rule"  # a rule fixed a mechanical error
    LLM = "llm"  # the model rewrote the failing section
    SWAP = "swap"  # the next retrieved candidate replaced a section


class GateVerdict(StrEnum):
    """What the semantic gate says about a run's final script."""

    OFF = "off"  # the gate was not on (baseline modes, or --no-semantic-gate)
    PASSED = "passed"  # the final script runs and contradicts none of the gated facts
    CONTRADICTS = "contradicts"  # it runs, but contradictions were left when repair ended
    NOT_REACHED = "not_reached"  # no script ran, so the gate judged none


def unified_diff(before: str, after: str) -> str:
    return "".join(
        difflib.unified_diff(
            before.splitlines(True), after.splitlines(True), "before.scenic", "after.scenic", n=1
        )
    )


@dataclass
class Attempt:
    """One validated version of the script and how it came to be."""

    index: int
    kind: AttemptKind
    detail: str
    script: str
    ok: bool
    diagnostic: Diagnostic | None
    diff: str
    check_seconds: float
    llm_usage: Usage = field(default_factory=Usage)
    # The validator's whole answer (None when nothing was validated, e.g. a compose error).
    check: CheckResult | None = None
    # What the semantic gate found wrong with a script that ran (empty: none, or no gate).
    contradictions: list[Contradiction] = field(default_factory=list)
    # Time spent making this script (a rule, a swap or a model call) before its check.
    repair_seconds: float = 0.0

    @property
    def executed(self) -> bool:
        """The script ran without error, whether or not it passed the semantic gate."""
        return self.ok or bool(self.contradictions)

    @property
    def seconds(self) -> float:
        return self.repair_seconds + self.check_seconds

    def as_dict(self) -> dict[str, Any]:
        return {
            "index": self.index,
            "kind": self.kind.value,
            "detail": self.detail,
            "ok": self.ok,
            "diagnostic": self.diagnostic.model_dump(mode="json") if self.diagnostic else None,
            "diff": self.diff,
            "check_seconds": round(self.check_seconds, 3),
            "repair_seconds": round(self.repair_seconds, 3),
            "executed": self.executed,
            "contradictions": [c.as_dict() for c in self.contradictions],
            "sandbox": self.check.sandbox.label if self.check and self.check.sandbox else None,
            "llm": self.llm_usage.as_dict(),
        }


@dataclass(frozen=True)
class Outcome:
    """How a run ended: the one value `Generator.generate` turns into the run's status."""

    status: RunStatus
    message: str | None = None
    # The attempt whose script is the run's result (None: the last one).
    final: int | None = None


@dataclass
class Generation:
    """Everything one generation did. Filled in stage by stage by `Generator.generate`
    (spec, retrieval, draft) and the repair loop (attempts, draft after a swap); its status
    is set once, when the run ends."""

    description: str
    options: GenerateOptions
    status: RunStatus = RunStatus.RUNNING
    message: str | None = None
    spec: ScenarioSpec | None = None
    hint_notes: list[str] = field(default_factory=list)
    ignored_text: list[str] = field(default_factory=list)  # input that is not the scenario
    # Time of the last repair search, when it found no repair (no attempt holds it).
    unused_repair_seconds: float = 0.0
    contradictions: list[str] = field(default_factory=list)
    retrieval: Retrieval | None = None
    draft: Draft | None = None
    attempts: list[Attempt] = field(default_factory=list)
    usage: Usage = field(default_factory=Usage)
    #: one entry per model call: what it was for, its tokens and how its prefix was met
    llm_calls: list[dict[str, Any]] = field(default_factory=list)
    seconds: float = 0.0
    out_dir: Path | None = None
    # The deterministic conformity check of the script that ran (set when the run ends).
    conformity: dict[str, Any] | None = None
    # Index of the attempt that is the result, when it is not the last (see Outcome.final).
    final_index: int | None = None

    @property
    def ok(self) -> bool:
        return self.status is RunStatus.EXECUTED

    @property
    def first_pass_ok(self) -> bool:
        """The first assembled script ran (ESR single); the gate's verdict is separate."""
        return bool(self.attempts) and self.attempts[0].executed

    @property
    def repairs(self) -> int:
        return max(0, len(self.attempts) - 1)

    @property
    def final_attempt(self) -> Attempt | None:
        """The attempt whose script is the result: the last, unless the run kept an earlier
        one that ran (the one with the fewest contradictions when the gate stayed unmet)."""
        if not self.attempts:
            return None
        return self.attempts[-1 if self.final_index is None else self.final_index]

    @property
    def final_check(self) -> CheckResult | None:
        """The validation of the final attempt (None before anything was validated)."""
        final = self.final_attempt
        return final.check if final else None

    @property
    def gate_on(self) -> bool:
        return self.options.gate_on

    @property
    def gate(self) -> GateVerdict:
        final = self.final_attempt
        if not self.gate_on:
            return GateVerdict.OFF
        if final is None or not final.executed or not self.ok:
            return GateVerdict.NOT_REACHED
        return GateVerdict.CONTRADICTS if final.contradictions else GateVerdict.PASSED

    @property
    def contradictions_left(self) -> list[Contradiction]:
        final = self.final_attempt
        return list(final.contradictions) if final and self.ok else []

    @property
    def gate_seconds(self) -> float:
        """Time spent only because of the gate: every attempt after the first script that
        ran, when that script failed the gate."""
        first = next((a for a in self.attempts if a.executed), None)
        if first is None or first.ok:
            return 0.0
        tried = sum(a.seconds for a in self.attempts[first.index + 1 :])
        return tried + self.unused_repair_seconds

    def gate_report(self) -> dict[str, Any]:
        verdict = self.gate
        return {
            "on": self.gate_on,
            "verdict": verdict.value,
            "passed": None
            if verdict in (GateVerdict.OFF, GateVerdict.NOT_REACHED)
            else verdict is GateVerdict.PASSED,
            "contradictions": [c.as_dict() for c in self.contradictions_left],
            "seconds": round(self.gate_seconds, 3),
        }

    def add_attempt(self, attempt: Attempt) -> None:
        """The one way an attempt joins the run (its index is its place in the list)."""
        assert attempt.index == len(self.attempts), "attempts are numbered in order"
        self.attempts.append(attempt)

    def use_draft(self, draft: Draft) -> None:
        """The script's entries changed (assembly, or a swap during repair)."""
        self.draft = draft

    def end(self, outcome: Outcome) -> None:
        """The one transition out of RUNNING."""
        assert self.status is RunStatus.RUNNING, f"run already ended as {self.status}"
        self.status, self.message = outcome.status, outcome.message
        if outcome.final is not None:
            assert 0 <= outcome.final < len(self.attempts), "the final attempt is one of them"
            self.final_index = outcome.final

    def report(self) -> dict[str, Any]:
        """What report.json holds; the bench rows are read from this too."""
        retrieval = self.retrieval
        final = self.final_check
        return {
            "description": self.description,
            "status": self.status.value,
            "message": self.message,
            "mode": self.options.mode.value,
            "options": self.options.model_dump(mode="json"),
            "spec": self.spec.model_dump(mode="json") if self.spec else None,
            "spec_corrections": self.hint_notes,
            "ignored_text": self.ignored_text,
            "contradictions": self.contradictions,
            "retrieved": retrieval.ids() if retrieval else {},
            "chosen": [e.label for e in self.draft.entries] if self.draft else [],
            "retrieval_notes": retrieval.notes if retrieval else [],
            # The other road users placed by spawns of their own ("chosen" says which of
            # them the final draft still has: a repair may leave one out).
            "placed_actors": [
                {
                    "name": placed.name,
                    "class": placed.actor.scenic_class,
                    "role": placed.actor.role.value,
                    "quote": placed.actor.quote,
                    "spawn": placed.spawn.id,
                    "behavior": placed.behavior.id,
                }
                for placed in (retrieval.actors if retrieval else [])
            ],
            "map": self.draft.map_name if self.draft else None,
            "params": self.draft.params if self.draft else {},
            "first_pass_ok": self.first_pass_ok,
            "repairs": self.repairs,
            "final_attempt": self.final_attempt.index if self.final_attempt else None,
            "semantic_gate": self.gate_report(),
            "attempts": [a.as_dict() for a in self.attempts],
            "llm": self.usage.as_dict(),
            "llm_calls": self.llm_calls,
            "seconds": round(self.seconds, 3),
            "simulation": (
                final.simulation.model_dump(mode="json", exclude={"agents"})
                if final and final.simulation
                else None
            ),
            "conformity": self.conformity,
            # The confinement the final script ran under (every attempt has its label).
            "sandbox": (final.sandbox.model_dump(mode="json") if final and final.sandbox else None),
        }

    def summary(self) -> str:
        if self.ok:
            how = "first try" if self.repairs == 0 else f"after {self.repairs} repair(s)"
            return (
                f"executed {how} in {self.seconds:.0f} s, {self.usage.calls} LLM call(s), "
                f"{self.usage.total_tokens} tokens" + self.gate_summary()
            )
        return f"{self.status.value}: {self.message or ''}".strip()

    def gate_summary(self) -> str:
        """What the gate says, for the one-line summary ('' when it is off or passed)."""
        left = self.contradictions_left
        if self.gate is not GateVerdict.CONTRADICTS or not left:
            return ""
        final = self.final_attempt
        kept = f" (kept attempt {final.index})" if final and final.index != self.repairs else ""
        count = f"{len(left)} contradiction{'s' if len(left) > 1 else ''}"
        return f"; {count} with the description left{kept}: " + "; ".join(c.text() for c in left)
