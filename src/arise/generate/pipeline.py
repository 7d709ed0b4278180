"""`generate()`: one description through modules A-D, with outputs and progress."""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from arise.evaluate.conformity import GATED_CHECKS, Conformity, check_conformity
from arise.generate.assemble import Draft, assemble, declared_params, tune_params
from arise.generate.extract import check_description, extract_spec
from arise.generate.hints import apply_hints, keep_stated_requirements
from arise.generate.options import GenerateOptions, Mode
from arise.generate.outputs import write_attempt, write_report, write_script
from arise.generate.repair import (
    Attempt,
    RepairContext,
    note_llm_failure,
    repair_once,
    run_attempt,
)
from arise.generate.retrieve import Retrieval, retrieve
from arise.generate.rules import RuleContext
from arise.generate.spec import ScenarioSpec
from arise.kb.compose import ComposeError
from arise.kb.loader import KnowledgeBase
from arise.kb.retrieval.base import Retriever
from arise.kb.schema import Component
from arise.llm.accounting import UsageLedger
from arise.llm.types import LLMError, Usage
from arise.validate import CheckOptions, CheckResult, Diagnostic, Stage, WorkerPool, check_text

Progress = Callable[[dict[str, Any]], None]
# Rejection-sampling budget per check: enough for entries that run, and a failing
# requirement is named within seconds instead of tens of seconds.
SAMPLE_ITERATIONS = 250


@dataclass
class Generation:
    """Everything one generation did; `report()` is what report.json holds."""

    description: str
    options: GenerateOptions
    status: str = "running"  # executed | failed | refused | provider_error
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
    final_check: CheckResult | None = None
    # The deterministic conformity check of the script that ran (set when the run ends).
    conformity: dict[str, Any] | None = None

    @property
    def ok(self) -> bool:
        return self.status == "executed"

    @property
    def first_pass_ok(self) -> bool:
        return bool(self.attempts) and self.attempts[0].ok

    @property
    def repairs(self) -> int:
        return max(0, len(self.attempts) - 1)

    def report(self) -> dict[str, Any]:
        retrieval = self.retrieval
        return {
            "description": self.description,
            "status": self.status,
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
            "seconds": round(self.seconds, 2),
            "simulation": (self.final_check.simulation.model_dump(mode="json", exclude={"agents"})
                           if self.final_check and self.final_check.simulation else None),
            "conformity": self.conformity,
        }

    def summary(self) -> str:
        if self.status == "executed":
            how = "first try" if self.first_pass_ok else f"after {self.repairs} repair(s)"
            return (f"executed {how} in {self.seconds:.0f} s, {self.usage.calls} LLM call(s), "
                    f"{self.usage.total_tokens} tokens")
        return f"{self.status}: {self.message or ''}".strip()


def slug(text: str) -> str:
    words = re.findall(r"[a-z0-9]+", text.lower())[:6]
    return "-".join(words) or "scenario"


def chatscene_retrieval(spec: ScenarioSpec, kb: KnowledgeBase, retriever: Retriever,
                        maps: dict[str, frozenset[str]]) -> Retrieval:
    """The baseline: top-1 per component by text alone, no filters, no compatibility check."""
    from arise.kb.compose import pick_map

    result = Retrieval()
    for component, text in ((Component.GEOMETRY, spec.geometry), (Component.SPAWN, spec.spawn),
                            (Component.BEHAVIOR, spec.behavior),
                            (Component.WEATHER, spec.weather)):
        hits = retriever.search(text, component, k=1)
        result.candidates[component] = [h.entry for h in hits]
        result.chosen[component] = [h.entry for h in hits][:1]
    result.map_name = pick_map(result.chosen_entries(), maps)
    return result


class Generator:
    """Holds what is expensive to build once: the KB, the retriever, the model, the pool."""

    def __init__(self, options: GenerateOptions, *, pool: WorkerPool | None = None,
                 provider: UsageLedger | None = None):
        from arise.kb.loader import load_kb
        from arise.kb.retrieval import make_retriever
        from arise.maps.registry import MapRegistry

        self.options = options
        self.kb = load_kb(options.kb_dirs)
        self.retriever = make_retriever(self.kb, options.retrieval)
        self.registry = MapRegistry(options.map_dir)
        self.maps = {name: entry.features for name, entry in self.registry.entries.items()}
        self._own_pool = pool is None
        self.pool = pool or WorkerPool(size=1)
        self._own_provider = provider is None
        self._provider = provider

    def reconfigure(self, options: GenerateOptions) -> None:
        """Use other per-run options (mode, temperature, seed, run) with the same KB, maps,
        validator and model; a replayed run index needs its own cassette reader."""
        if (self._provider is not None and self._own_provider and options.replay
                and options.run_index != self.options.run_index):
            self._provider.close()
            self._provider = None
        self.options = options

    @property
    def provider(self) -> UsageLedger:
        if self._provider is None:
            from arise.llm.registry import get_provider

            overrides: dict[str, Any] = {}
            if self.options.model:
                overrides["model"] = self.options.model
            if self.options.threads:
                overrides["threads"] = self.options.threads
            self._provider = get_provider(self.options.provider, cache=self.options.cache,
                                          record=self.options.record,
                                          replay=self.options.replay,
                                          run_index=self.options.run_index, **overrides)
        return self._provider

    def close(self) -> None:
        if self._own_pool:
            self.pool.close()
        if self._provider is not None and self._own_provider:
            self._provider.close()

    def __enter__(self) -> Generator:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- one description -------------------------------------------------------------------
    def generate(self, description: str, out_dir: Path | None = None,
                 progress: Progress | None = None) -> Generation:
        options = self.options
        run = Generation(description=description, options=options, out_dir=out_dir)
        started = time.perf_counter()
        emit = progress or (lambda event: None)
        refusal = check_description(description)
        if refusal:
            run.status, run.message = "refused", refusal
            return run
        usage_before = self._provider.total if self._provider is not None else Usage()
        try:
            self._run(run, emit)
        except LLMError as error:
            run.status, run.message = "provider_error", str(error)
        finally:
            run.seconds = time.perf_counter() - started
            if self._provider is not None:
                run.usage = self._provider.total - usage_before
            if run.ok and run.spec is not None and run.final_check is not None:
                run.conformity = self.conformity_of(run.spec, run.final_check).as_dict()
            self._save(run, final=True)
        emit({"event": "done", "status": run.status, "summary": run.summary()})
        return run

    def check_options(self, png: str | None = None) -> CheckOptions:
        """How this generator validates a script (also used to re-check saved scripts)."""
        options = self.options
        return CheckOptions(
            simulator=options.simulator, map_dir=options.map_dir, steps=options.steps,
            spawn_attempts=options.spawn_attempts, seed=options.seed,
            sample_iterations=SAMPLE_ITERATIONS, timeout=options.check_timeout, png=png)

    def conformity_of(self, spec: ScenarioSpec, result: CheckResult) -> Conformity:
        """The conformity check of a validation, with the features of the map it ran on."""
        features = self.maps.get(result.map.name, frozenset()) if result.map else frozenset()
        return check_conformity(spec, result.simulation, features)

    def _validate(self, script: str, run: Generation) -> CheckResult:
        png = str(run.out_dir / "scene.png") if run.out_dir else None
        result = check_text(script, self.check_options(png), pool=self.pool,
                            registry=self.registry)
        if result.ok and self.options.semantic_gate and run.spec is not None:
            result = self._semantic_gate(result, run.spec)
        run.final_check = result
        return result

    def _semantic_gate(self, result: CheckResult, spec: ScenarioSpec) -> CheckResult:
        """A script that runs but contradicts the spec fails, naming the section to change."""
        conformity = self.conformity_of(spec, result)
        wrong = [c for c in conformity.checks if c.ok is False and c.name in GATED_CHECKS]
        if not wrong:
            return result
        diagnostic = Diagnostic(
            stage=Stage.SEMANTIC, error_type="ConformityMismatch",
            message="; ".join(f"{c.name}: expected {c.expected}, observed {c.observed}"
                              for c in wrong),
            section=GATED_CHECKS[wrong[0].name],
            hint="the script runs but does not do what the description says")
        return result.model_copy(update={"ok": False, "diagnostic": diagnostic})

    def _run(self, run: Generation, emit: Progress) -> None:
        options = self.options
        emit({"event": "stage", "stage": "extract"})
        extraction = extract_spec(run.description, self.provider,
                                  temperature=options.temperature, seed=options.seed)
        if extraction.spec is None:
            run.status, run.message = "refused", extraction.error
            return
        hinted, run.hint_notes = apply_hints(run.description, extraction.spec)
        run.spec, dropped = keep_stated_requirements(run.description, hinted)
        run.hint_notes += dropped
        run.contradictions = extraction.contradictions
        spec = run.spec
        emit({"event": "stage", "stage": "retrieve"})
        if options.mode is Mode.CHATSCENE:
            run.retrieval = chatscene_retrieval(spec, self.kb, self.retriever, self.maps)
        else:
            run.retrieval = retrieve(spec, self.kb, self.retriever, self.maps, run.description)
            for component, entries in run.retrieval.candidates.items():
                if component in (Component.MISC, Component.REQUIREMENTS):
                    continue
                run.retrieval.candidates[component] = entries[: max(options.topk, 1) + 8]
        emit({"event": "stage", "stage": "assemble"})
        adversary = spec.adversary_type.scenic_class
        try:
            params: dict[str, str] = {}
            if options.mode is not Mode.CHATSCENE and run.retrieval.chosen:
                params, notes = tune_params(run.description, run.retrieval.chosen_entries(),
                                            self.provider, temperature=options.temperature,
                                            seed=options.seed)
                run.retrieval.notes += notes
            run.draft = assemble(run.retrieval, adversary, run.description, params)
        except ComposeError as error:
            run.status, run.message = "failed", f"the retrieved snippets do not fit: {error}"
            run.attempts.append(Attempt(
                index=0, kind="initial", detail="compose", script="", ok=False,
                diagnostic=Diagnostic(stage=Stage.COMPILE, error_type="ComposeError",
                                      message=str(error)),
                diff="", check_seconds=0.0))
            return
        script = run.draft.script
        emit({"event": "stage", "stage": "validate", "attempt": 0})
        attempt = run_attempt(0, "initial", "assembled from the knowledge base", "", script,
                              lambda text: self._validate(text, run), Usage())
        self._record(run, attempt, emit)
        if options.mode is not Mode.ARISE:
            run.status = "executed" if attempt.ok else "failed"
            return
        context = RepairContext(
            description=run.description, retrieval=run.retrieval, draft=run.draft,
            provider=self.provider, maps=self.maps, temperature=options.temperature,
            seed=options.seed,
            rules=RuleContext(adversary_class=adversary,
                              param_defaults={name: default for name, (default, _) in
                                              declared_params(list(self.kb)).items()}))
        while not attempt.ok and len(run.attempts) <= options.max_repairs:
            assert attempt.diagnostic is not None
            emit({"event": "stage", "stage": "repair", "attempt": len(run.attempts),
                  "error": attempt.diagnostic.one_line()})
            repaired, kind, detail, usage = repair_once(context, attempt.script,
                                                        attempt.diagnostic)
            if repaired is None:
                run.message = f"no repair left for: {attempt.diagnostic.one_line()}"
                break
            attempt = run_attempt(len(run.attempts), kind, detail, attempt.script, repaired,
                                  lambda text: self._validate(text, run), usage)
            note_llm_failure(context, attempt)
            run.draft = context.draft if kind == "swap" else run.draft
            self._record(run, attempt, emit)
        run.status = "executed" if attempt.ok else "failed"
        if not attempt.ok and run.message is None and attempt.diagnostic is not None:
            run.message = f"repair budget spent; last error: {attempt.diagnostic.one_line()}"

    def _record(self, run: Generation, attempt: Attempt, emit: Progress) -> None:
        run.attempts.append(attempt)
        emit({"event": "attempt", "index": attempt.index, "kind": attempt.kind,
              "ok": attempt.ok, "detail": attempt.detail,
              "error": attempt.diagnostic.one_line() if attempt.diagnostic else None})
        self._save(run, final=False)

    def _save(self, run: Generation, final: bool) -> None:
        if run.out_dir is None or run.status == "refused":
            return
        if run.attempts:
            last = run.attempts[-1]
            if last.script:
                write_attempt(run.out_dir, last.index, last.script)
            if final and last.script:
                write_script(run.out_dir, last.script, last.ok)
        write_report(run.out_dir, run.report())


def generate(description: str, options: GenerateOptions | None = None,
             out_dir: str | Path | None = None, progress: Progress | None = None) -> Generation:
    """Library call behind `arise generate` for one description."""
    with Generator(options or GenerateOptions()) as generator:
        return generator.generate(description, Path(out_dir) if out_dir else None, progress)

