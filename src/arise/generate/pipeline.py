"""`generate()`: one description through modules A-D, with outputs and progress."""

from __future__ import annotations

import re
import time
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

from arise.errors import AriseError
from arise.generate.assemble import assemble, declared_params, tune_params
from arise.generate.conformity import (
    Conformity,
    Contradiction,
    check_conformity,
    contradictions,
)
from arise.generate.events import Progress, RunFinished, RunStage, StageStarted, ignore
from arise.generate.extract import check_description, extract_spec
from arise.generate.options import GenerateOptions, Mode, ModelExtraction
from arise.generate.outputs import (
    attempt_png,
    write_attempt,
    write_report,
    write_scene_picture,
    write_script,
)
from arise.generate.repair import GatedValidate, RepairContext, Validate, repair_loop
from arise.generate.retrieve import EGO_STOPPED_TAG, Retrieval, retrieve
from arise.generate.rules import RuleContext
from arise.generate.run import Attempt, AttemptKind, Generation, Outcome, RunStatus
from arise.generate.spec import ScenarioSpec
from arise.generate.speeds import stated_speeds
from arise.generate.timing import timed_params
from arise.kb.compose import ComposeError
from arise.kb.loader import KnowledgeBase
from arise.kb.retrieval.base import Retriever
from arise.kb.schema import Component
from arise.llm.accounting import UsageLedger
from arise.llm.types import LLMError, Usage
from arise.present.outputs import write_run_files
from arise.present.source import from_check
from arise.validate import CheckOptions, CheckResult, Diagnostic, Stage, WorkerPool, check_text

__all__ = ["Generation", "Generator", "ReconfigureError", "generate", "slug"]

# Rejection-sampling budget per check: enough for entries that run, and a failing
# requirement is named within seconds instead of tens of seconds.
SAMPLE_ITERATIONS = 250


#: Gated checks about one fact of the spec: the gate holds a script to that fact only when
#: the description states it (a model's guess or an unstated maneuver is no contradiction;
#: the neutral weather is, since weather nobody asked for is a fault).
GROUNDED_CHECKS = frozenset(
    {"adversary_type", "spawn_position", "ego_maneuver", "ego_stopped", "road_type"}
)


class ReconfigureError(AriseError):
    """A change `Generator.reconfigure` cannot honour (another model for a provider the
    caller gave): build another Generator."""


def _holdable(spec: ScenarioSpec, retrieval: Retrieval) -> ScenarioSpec:
    """The spec the gate holds a script to: a stopped ego only when some geometry candidate
    can keep it still (else retrieval already said it drives, and no swap would help)."""
    geometries = retrieval.candidates.get(Component.GEOMETRY, [])
    if spec.ego_stopped and not any(EGO_STOPPED_TAG in e.tags for e in geometries):
        return spec.model_copy(update={"ego_stopped": False})
    return spec


def slug(text: str) -> str:
    words = re.findall(r"[a-z0-9]+", text.lower())[:6]
    return "-".join(words) or "scenario"


def chatscene_retrieval(
    spec: ScenarioSpec, kb: KnowledgeBase, retriever: Retriever, maps: dict[str, frozenset[str]]
) -> Retrieval:
    """The baseline: top-1 per component by text alone, no filters, no compatibility check."""
    from arise.kb.compose import pick_map

    result = Retrieval()
    for component, text in (
        (Component.GEOMETRY, spec.geometry),
        (Component.SPAWN, spec.spawn),
        (Component.BEHAVIOR, spec.behavior),
        (Component.WEATHER, spec.weather),
    ):
        hits = retriever.search(text, component, k=1)
        result.candidates[component] = [h.entry for h in hits]
        result.chosen[component] = [h.entry for h in hits][:1]
    result.map_name = pick_map(result.chosen_entries(), maps)
    return result


Checker = Callable[[str, CheckOptions], CheckResult]


class Generator:
    """Holds what is expensive to build once: the KB, the retriever, the model, the pool.

    `checker` replaces the validator (tests give a fake with a queue of results); by
    default a script is checked by `check_text` in this generator's worker pool.
    """

    def __init__(
        self,
        options: GenerateOptions,
        *,
        pool: WorkerPool | None = None,
        provider: UsageLedger | None = None,
        checker: Checker | None = None,
    ):
        self.options = options
        self._own_pool = pool is None
        self.pool = pool or WorkerPool(size=1)
        if checker is None and self._own_pool:
            # overlaps the KB's and the model's loading; niced, so that on 2 cores it takes
            # only what the model's two threads leave (its checks run while the model waits)
            self.pool.warm_in_background(nice=10)
        self._load_kb(options)
        self._load_maps(options)
        self._own_provider = provider is None
        self._provider = provider
        self._checker = checker

    def _load_kb(self, options: GenerateOptions) -> None:
        from arise.kb.loader import load_kb
        from arise.kb.retrieval import make_retriever

        self.kb = load_kb(options.kb_dirs)
        self.retriever = make_retriever(self.kb, options.retrieval)

    def _load_maps(self, options: GenerateOptions) -> None:
        from arise.maps.registry import MapRegistry

        self.registry = MapRegistry(options.map_dir)
        self.maps = {name: entry.features for name, entry in self.registry.entries.items()}

    @staticmethod
    def _provider_key(options: GenerateOptions) -> tuple[object, ...]:
        """What the provider is built from; a replayed run index has its own cassette reader."""
        return (
            options.provider,
            options.model,
            options.threads,
            options.cache,
            options.record,
            options.replay,
            options.run_index if options.replay else None,
        )

    def reconfigure(self, options: GenerateOptions) -> None:
        """Use other options for the next runs. Per-run options (mode, temperature, seed,
        budgets, simulator) just change; another KB or map folder is loaded; another model
        gets a new provider, unless the caller gave this generator its provider: then
        ReconfigureError, and nothing changes."""
        new_provider = self._provider_key(options) != self._provider_key(self.options)
        if new_provider and not self._own_provider:
            changed = [
                name
                for name in (
                    "provider",
                    "model",
                    "threads",
                    "cache",
                    "record",
                    "replay",
                    "run_index",
                )
                if getattr(options, name) != getattr(self.options, name)
            ]
            raise ReconfigureError(
                f"this generator was given its model; it cannot change "
                f"{', '.join(changed)}: build a new Generator"
            )
        if new_provider and self._provider is not None:
            self._provider.close()
            self._provider = None
        if (options.kb_dirs, options.retrieval) != (self.options.kb_dirs, self.options.retrieval):
            self._load_kb(options)
        if options.map_dir != self.options.map_dir:
            self._load_maps(options)
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
            self._provider = get_provider(
                self.options.provider,
                cache=self.options.cache,
                record=self.options.record,
                replay=self.options.replay,
                run_index=self.options.run_index,
                **overrides,
            )
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
    def generate(
        self, description: str, out_dir: Path | None = None, progress: Progress | None = None
    ) -> Generation:
        """One description through modules A-D. Never raises for a bad description or a
        failing model: the run's status and message say what happened."""
        run = Generation(description=description, options=self.options, out_dir=out_dir)
        started = time.perf_counter()
        emit = progress or ignore
        refusal = check_description(description)
        if refusal:
            run.end(Outcome(RunStatus.REFUSED, refusal))
            return run
        usage_before = self._provider.total if self._provider is not None else Usage()
        calls_before = len(self._provider.calls) if self._provider is not None else 0
        outcome: Outcome | None = None
        try:
            outcome = self._run(run, emit)
        except LLMError as error:
            outcome = Outcome(RunStatus.PROVIDER_ERROR, str(error))
        finally:  # also when a bug escapes: what was done so far is saved
            run.seconds = time.perf_counter() - started
            if self._provider is not None:
                run.usage = self._provider.total - usage_before
                run.llm_calls = [c.as_dict() for c in self._provider.calls[calls_before:]]
            if outcome is not None:
                run.end(outcome)
            if run.ok and run.spec is not None and run.final_check is not None:
                run.conformity = self.conformity_of(run.spec, run.final_check).as_dict()
            self._save(run, final=True)
        emit(RunFinished(run.status, run.summary()))
        return run

    def check_options(self, png: str | None = None) -> CheckOptions:
        """How this generator validates a script (also used to re-check saved scripts)."""
        options = self.options
        return CheckOptions(
            simulator=options.simulator,
            map_dir=options.map_dir,
            steps=options.steps,
            spawn_attempts=options.spawn_attempts,
            seed=options.seed,
            sample_iterations=SAMPLE_ITERATIONS,
            timeout=options.check_timeout,
            png=png,
        )

    def conformity_of(self, spec: ScenarioSpec, result: CheckResult) -> Conformity:
        """The conformity check of a validation, with the features of the map it ran on."""
        features = self.maps.get(result.map.name, frozenset()) if result.map else frozenset()
        return check_conformity(spec, result.simulation, features)

    def validator(self, out_dir: Path | None, spec: ScenarioSpec | None) -> Validate:
        """How the repair loop validates a script of this run: the check, then the semantic
        gate when it is on (arise mode, unless --no-semantic-gate)."""
        checks = 0

        def validate(script: str) -> CheckResult:
            # Each attempt's picture is kept (attempts/attempt-NN.png): the final script may
            # be an earlier attempt than the last one checked, and scene.png must show it.
            nonlocal checks
            png = attempt_png(out_dir, checks) if out_dir else None
            checks += 1
            options = self.check_options(str(png) if png else None)
            if self._checker is not None:
                return self._checker(script, options)
            return check_text(script, options, pool=self.pool, registry=self.registry)

        if not self.options.gate_on or spec is None:
            return validate
        gated_spec = spec

        def gate(result: CheckResult) -> list[Contradiction]:
            return [
                found
                for found in contradictions(self.conformity_of(gated_spec, result))
                if found.check not in GROUNDED_CHECKS or gated_spec.rests_on_words(found.check)
            ]

        return GatedValidate(validate, gate)

    def _run(self, run: Generation, emit: Progress) -> Outcome:
        """Modules A-C fill in the run's spec, retrieval and draft; the repair loop adds
        the attempts. Returns how the run ended."""
        options = self.options
        emit(StageStarted(RunStage.EXTRACT))
        self.provider.label = "extract"
        extraction = extract_spec(
            run.description,
            self.provider,
            temperature=options.temperature,
            seed=options.seed,
            ask_model=options.model_extraction is ModelExtraction.ALWAYS
            or options.mode is not Mode.ARISE,
        )
        if extraction.spec is None:
            return Outcome(RunStatus.REFUSED, extraction.error)
        run.spec = extraction.spec
        run.hint_notes = extraction.notes
        run.ignored_text = extraction.ignored
        run.contradictions = extraction.contradictions
        spec = run.spec
        emit(StageStarted(RunStage.RETRIEVE))
        if options.mode is Mode.CHATSCENE:
            run.retrieval = chatscene_retrieval(spec, self.kb, self.retriever, self.maps)
        else:
            run.retrieval = retrieve(
                spec, self.kb, self.retriever, self.maps, run.description, topk=options.topk
            )
        emit(StageStarted(RunStage.ASSEMBLE))
        adversary = None if spec.no_adversary else spec.scenic_class
        try:
            params: dict[str, str] = {}
            # The adversary's scene: the other actors' copies keep their defaults.
            own = [e for e in run.retrieval.chosen_entries() if e.actor is None]
            tunes = options.mode is not Mode.CHATSCENE and bool(run.retrieval.chosen)
            if tunes and not spec.quantities_stated:
                run.retrieval.notes.append(
                    "parameters: the description states no number the rules leave "
                    "unplaced; the defaults, stated speeds and timing words stand (no "
                    "tuning call)"
                )
            elif tunes:
                self.provider.label = "adapt"
                params, notes = tune_params(
                    run.description,
                    own,
                    self.provider,
                    temperature=options.temperature,
                    seed=options.seed,
                )
                run.retrieval.notes += notes
            timed = timed_params(spec.timing, own)
            if timed:
                run.retrieval.notes.append(
                    f"timing: the text says the adversary moves {spec.timing}: "
                    + ", ".join(f"{name} = {value}" for name, value in timed.items())
                )
            speeds = stated_speeds(spec, own) if options.mode is not Mode.CHATSCENE else {}
            if speeds:
                run.retrieval.notes.append(
                    "speeds stated in the text: "
                    + ", ".join(f"{name} = {value}" for name, value in speeds.items())
                )
            # stated numbers, which the model read, win over timing words; speeds the rules
            # read win over the model's
            params = {**timed, **params, **speeds}
            draft = assemble(run.retrieval, adversary, run.description, params)
        except ComposeError as error:
            run.add_attempt(compose_failure(error))
            return Outcome(RunStatus.FAILED, f"the retrieved snippets do not fit: {error}")
        run.use_draft(draft)
        context = (
            None
            if options.mode is not Mode.ARISE
            else RepairContext(
                description=run.description,
                retrieval=run.retrieval,
                draft=draft,
                provider=self.provider,
                maps=self.maps,
                timing=spec.timing,
                model_fixes_contradictions=options.gate_model_fixes,
                temperature=options.temperature,
                seed=options.seed,
                rules=RuleContext(
                    adversary_class=adversary or spec.scenic_class,
                    param_defaults={
                        name: default
                        for name, (default, _) in declared_params(list(self.kb)).items()
                    },
                ),
            )
        )
        self.provider.label = "repair"
        return repair_loop(
            run,
            draft.script,
            self.validator(run.out_dir, _holdable(spec, run.retrieval)),
            context,
            max_repairs=options.max_repairs,
            emit=emit,
            on_attempt=lambda attempt: self._save(run, final=False),
        )

    def _save(self, run: Generation, final: bool) -> None:
        if run.out_dir is None or run.status is RunStatus.REFUSED:
            return
        if run.attempts:
            last = run.attempts[-1]
            if last.script:
                write_attempt(run.out_dir, last.index, last.script)
            result = run.final_attempt  # the last, or the kept one that ran (semantic gate)
            if final and result is not None and result.script:
                write_script(run.out_dir, result.script, result.executed)
                write_scene_picture(run.out_dir, attempt_png(run.out_dir, result.index))
                check = result.check
                if result.executed and check is not None and check.simulation is not None:
                    self._present(run.out_dir, check)
        write_report(run.out_dir, run.report())

    def _present(self, folder: Path, result: CheckResult) -> None:
        """trace.json, replay.gif, replay.html, scenario.xosc and the map's .xodr of the
        script that ran; a run never fails for want of them."""
        try:
            source = from_check(folder / "scenario.scenic", result, self.check_options())
            write_run_files(source, folder, map_dir=self.options.map_dir)
        except AriseError as error:
            warnings.warn(f"replay and export not written: {error}", stacklevel=2)


def compose_failure(error: ComposeError) -> Attempt:
    """The attempt that records snippets that did not fit together (nothing was run)."""
    return Attempt(
        index=0,
        kind=AttemptKind.INITIAL,
        detail="compose",
        script="",
        ok=False,
        diagnostic=Diagnostic(stage=Stage.COMPILE, error_type="ComposeError", message=str(error)),
        diff="",
        check_seconds=0.0,
    )


def generate(
    description: str,
    options: GenerateOptions | None = None,
    out_dir: str | Path | None = None,
    progress: Progress | None = None,
) -> Generation:
    """Library call behind `arise generate` for one description."""
    with Generator(options or GenerateOptions()) as generator:
        return generator.generate(description, Path(out_dir) if out_dir else None, progress)
