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
from arise.generate.options import GenerateOptions
from arise.generate.retrieve import Retrieval
from arise.generate.spec import ScenarioSpec
from arise.llm.types import Usage
from arise.validate.types import CheckResult, Diagnostic


class RunStatus(StrEnum):
    RUNNING = "running"
    EXECUTED = "executed"  # the final script ran (and passed the semantic gate, if on)
    FAILED = "failed"  # no script ran within the repair budget (or the snippets did not fit)
    REFUSED = "refused"  # the description was refused before or by extraction
    PROVIDER_ERROR = "provider_error"  # the model could not be asked


class AttemptKind(StrEnum):
    """How the script of an attempt came to be."""

    INITIAL = "initial"  # assembled from the knowledge base
    RULE = "rule"  # a rule fixed a mechanical error
    LLM = "llm"  # the model rewrote the failing section
    SWAP = "swap"  # the next retrieved candidate replaced a section


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

    def as_dict(self) -> dict[str, Any]:
        return {
            "index": self.index,
            "kind": self.kind.value,
            "detail": self.detail,
            "ok": self.ok,
            "diagnostic": self.diagnostic.model_dump(mode="json") if self.diagnostic else None,
            "diff": self.diff,
            "check_seconds": round(self.check_seconds, 3),
            "sandbox": self.check.sandbox.label if self.check and self.check.sandbox else None,
            "llm": self.llm_usage.as_dict(),
        }


@dataclass(frozen=True)
class Outcome:
    """How a run ended: the one value `Generator.generate` turns into the run's status."""

    status: RunStatus
    message: str | None = None


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
    contradictions: list[str] = field(default_factory=list)
    retrieval: Retrieval | None = None
    draft: Draft | None = None
    attempts: list[Attempt] = field(default_factory=list)
    usage: Usage = field(default_factory=Usage)
    seconds: float = 0.0
    out_dir: Path | None = None
    # The deterministic conformity check of the script that ran (set when the run ends).
    conformity: dict[str, Any] | None = None

    @property
    def ok(self) -> bool:
        return self.status is RunStatus.EXECUTED

    @property
    def first_pass_ok(self) -> bool:
        return bool(self.attempts) and self.attempts[0].ok

    @property
    def repairs(self) -> int:
        return max(0, len(self.attempts) - 1)

    @property
    def final_check(self) -> CheckResult | None:
        """The validation of the last attempt (None before anything was validated)."""
        return self.attempts[-1].check if self.attempts else None

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
            "contradictions": self.contradictions,
            "retrieved": retrieval.ids() if retrieval else {},
            "chosen": [e.id for e in self.draft.entries] if self.draft else [],
            "retrieval_notes": retrieval.notes if retrieval else [],
            "map": self.draft.map_name if self.draft else None,
            "params": self.draft.params if self.draft else {},
            "first_pass_ok": self.first_pass_ok,
            "repairs": self.repairs,
            "attempts": [a.as_dict() for a in self.attempts],
            "llm": self.usage.as_dict(),
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
            how = "first try" if self.first_pass_ok else f"after {self.repairs} repair(s)"
            return (
                f"executed {how} in {self.seconds:.0f} s, {self.usage.calls} LLM call(s), "
                f"{self.usage.total_tokens} tokens"
            )
        return f"{self.status.value}: {self.message or ''}".strip()
