"""Proving the knowledge base: lint every entry, then run the covering scripts for real.

Every script goes through the same validator as `arise check` (compile, sample, simulate,
offline). A failure is reported against the entry whose snippet holds the failing line
(each snippet is preceded by a `# kb: <id>` mark), and against the whole script otherwise.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

from arise.kb.compose import entry_at_line
from arise.kb.lints import LintProblem, lint_all
from arise.kb.loader import KBError, KnowledgeBase
from arise.kb.plan import Composition, plan_validation
from arise.validate import CheckOptions, CheckResult, WorkerPool, check_text

DEFAULT_OPTIONS = CheckOptions(seed=1, steps=200, timeout=90)


@dataclass
class ScriptOutcome:
    composition: Composition
    result: CheckResult
    seconds: float

    @property
    def ok(self) -> bool:
        return self.result.ok

    @property
    def culprit(self) -> str | None:
        """The entry whose snippet holds the failing line, when the line is known."""
        if self.ok or self.result.diagnostic is None:
            return None
        return entry_at_line(self.composition.script(), self.result.diagnostic.line)

    def describe(self) -> str:
        c = self.composition
        head = f"{c.name} [{c.adversary_class} on {c.map_name}] ({', '.join(c.ids)})"
        if self.ok:
            return f"{head}: OK"
        blame = f" -> entry {self.culprit}" if self.culprit else ""
        return f"{head}: {self.result.summary()}{blame}"


@dataclass
class KBReport:
    """What passed, what failed and why, for the whole knowledge base or a part of it."""

    checked: list[str]
    outcomes: list[ScriptOutcome] = field(default_factory=list)
    lint_problems: list[LintProblem] = field(default_factory=list)
    load_problems: list[KBError] = field(default_factory=list)
    uncovered: dict[str, str] = field(default_factory=dict)
    seconds: float = 0.0

    def failures(self) -> dict[str, list[str]]:
        """Entry id -> why it is not proven (lint, no fitting script, or a failed run)."""
        found: dict[str, list[str]] = {}
        for problem in self.lint_problems:
            found.setdefault(problem.entry, []).append(f"lint: {problem.message}")
        for entry_id, why in self.uncovered.items():
            found.setdefault(entry_id, []).append(why)
        passed = self.passed_ids()
        for outcome in self.outcomes:
            if outcome.ok:
                continue
            culprit = outcome.culprit
            for entry_id in outcome.composition.ids:
                if entry_id not in self.checked:
                    continue
                if entry_id == culprit or (culprit is None and entry_id not in passed):
                    found.setdefault(entry_id, []).append(outcome.describe())
        return found

    def passed_ids(self) -> set[str]:
        ran_ok = {i for o in self.outcomes if o.ok for i in o.composition.ids}
        ran_bad = {
            i for o in self.outcomes if not o.ok for i in o.composition.ids if i == o.culprit
        }
        return (ran_ok - ran_bad) & set(self.checked)

    @property
    def ok(self) -> bool:
        return not self.failures() and not self.load_problems and all(o.ok for o in self.outcomes)

    def pass_rate(self) -> float:
        if not self.checked:
            return 1.0
        failed = set(self.failures())
        return sum(1 for i in self.checked if i not in failed) / len(self.checked)

    def summary(self) -> str:
        scripts_ok = sum(1 for o in self.outcomes if o.ok)
        failed = self.failures()
        lines = [
            f"{len(self.checked) - len(failed)}/{len(self.checked)} entries proven "
            f"({100 * self.pass_rate():.1f}%), {scripts_ok}/{len(self.outcomes)} scripts "
            f"ran, {self.seconds:.0f}s"
        ]
        lines += [f"load problem: {problem}" for problem in self.load_problems]
        for entry_id in sorted(failed):
            for why in failed[entry_id]:
                lines.append(f"FAILED {entry_id}: {why}")
        for outcome in self.outcomes:
            if not outcome.ok and outcome.culprit is None:
                lines.append(f"FAILED script {outcome.describe()}")
        return "\n".join(lines)


def builtin_maps() -> dict[str, frozenset[str]]:
    """Our shipped maps and their features: what a fresh machine can run."""
    from arise.maps.registry import MapRegistry

    registry = MapRegistry(map_dir=None)
    return {
        name: entry.features
        for name, entry in registry.entries.items()
        if entry.source == "builtin"
    }


def validate_kb(
    kb: KnowledgeBase,
    *,
    only: Iterable[str] | None = None,
    options: CheckOptions | None = None,
    pool: WorkerPool | None = None,
    workers: int = 2,
    maps: dict[str, frozenset[str]] | None = None,
    on_outcome: Callable[[ScriptOutcome], None] | None = None,
) -> KBReport:
    """Lint the entries, plan covering scripts and run each through the validator.

    only: the entry ids to prove (default: all); partners may be any entry of `kb`.
    """
    started = time.monotonic()
    entries = list(kb)
    checked = [e.id for e in entries if only is None or e.id in set(only)]
    lint_problems = [p for p in lint_all(entries) if p.entry in checked]
    plan = plan_validation(entries, maps or builtin_maps(), only=checked)
    report = KBReport(
        checked=checked,
        lint_problems=lint_problems,
        load_problems=list(kb.problems),
        uncovered=plan.uncovered,
    )
    options = options or DEFAULT_OPTIONS

    def run(composition: Composition, active: WorkerPool) -> ScriptOutcome:
        begin = time.monotonic()
        result = check_text(composition.script(), options, pool=active)
        outcome = ScriptOutcome(composition, result, time.monotonic() - begin)
        if on_outcome is not None:
            on_outcome(outcome)
        return outcome

    own = pool is None
    active = pool or WorkerPool(size=workers, memory_mb=options.memory_mb)
    try:
        with ThreadPoolExecutor(max_workers=active.size) as executor:
            report.outcomes = list(executor.map(lambda c: run(c, active), plan.compositions))
    finally:
        if own:
            active.close()
    report.seconds = time.monotonic() - started
    return report
