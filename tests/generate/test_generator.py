"""The Generator around the loop, with a scripted model and a fake validator (no worker, no
model file): how a run ends, the semantic gate's wiring, and what reconfigure does."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path

import pytest

from arise.generate.events import ProgressEvent, RunFinished, StageStarted, event_dict
from arise.generate.options import GenerateOptions, ModelExtraction
from arise.generate.pipeline import Generator, ReconfigureError
from arise.generate.run import RunStatus
from arise.generate.spec import ExtractionAnswer, ScenarioSpec
from arise.llm.accounting import UsageLedger
from arise.validate.types import AgentTrace, CheckResult, SimulationFacts, Stage, TracePoint
from tests.fakes import FakeValidator, ScriptedProvider, passed
from tests.generate_cases import FAULTY_KB

DESCRIPTION = "A pedestrian steps off the right sidewalk in front of the ego car."
# The same with a time the rules do not place: its scripts' numbers are tuned by the model.
MEASURED_DESCRIPTION = (
    "A pedestrian steps off the right sidewalk in front of the ego car, 2 seconds before it "
    "arrives."
)
SPEC = ScenarioSpec.model_validate(
    {
        "adversary_type": "pedestrian",
        "behavior": "steps off the right sidewalk",
        "road_type": "straight_road",
        "ego_maneuver": "go_straight",
        "geometry": "",
        "spawn_position": "roadside_right",
        "spawn": "the right sidewalk",
    }
)
#: The model's answer for DESCRIPTION (what extraction asks the model for).
ANSWER = ExtractionAnswer.model_validate(
    {
        "adversary": "A pedestrian",
        **SPEC.model_dump(include={"adversary_type", "behavior", "road_type", "ego_maneuver"}),
        **SPEC.model_dump(include={"geometry", "spawn_position", "spawn"}),
    }
)


@pytest.fixture(scope="module")
def generator() -> Iterator[Generator]:
    model = UsageLedger(ScriptedProvider())
    # The model reads every description here (the tests are about its answers).
    options = GenerateOptions(retrieval="bm25", model_extraction=ModelExtraction.ALWAYS)
    with Generator(options, provider=model, checker=FakeValidator()) as built:
        yield built


def _script(
    generator: Generator, *replies: str, results: list[CheckResult] | None = None
) -> ScriptedProvider:
    """Give the generator's model these replies and its validator these results."""
    model = generator.provider.unwrap()
    assert isinstance(model, ScriptedProvider)
    model.replies, model.requests = list(replies), []
    generator._checker = FakeValidator(results or [])
    return model


def test_a_model_that_fails_mid_run_ends_it_as_a_provider_error(
    generator: Generator, tmp_path: Path
) -> None:
    # Extraction answers; the parameter tuning gets three replies that never fit its schema.
    model = _script(generator, ANSWER.model_dump_json(), "{}", "{}", "{}")
    events: list[ProgressEvent] = []
    run = generator.generate(MEASURED_DESCRIPTION, tmp_path, events.append)
    assert run.status is RunStatus.PROVIDER_ERROR and "TunedParams" in (run.message or "")
    assert run.spec is not None and run.retrieval is not None and not run.attempts
    assert run.usage.calls == 4 and len(model.requests) == 4
    report = json.loads((tmp_path / "report.json").read_text())
    assert report["status"] == "provider_error" and report["spec"]["adversary_type"] == "pedestrian"
    assert [e.stage.value for e in events if isinstance(e, StageStarted)] == [
        "extract",
        "retrieve",
        "assemble",
    ]
    assert isinstance(events[-1], RunFinished)
    assert event_dict(events[-1])["status"] == "provider_error"


def test_a_refused_description_asks_no_one(generator: Generator, tmp_path: Path) -> None:
    model = _script(generator)
    run = generator.generate("Bake a cake with three eggs.", tmp_path / "out")
    assert run.status is RunStatus.REFUSED and model.requests == []
    assert not (tmp_path / "out").exists()


def _facts(adversary_kind: str) -> SimulationFacts:
    def trace(name: str, kind: str, x: float, ego: bool = False) -> AgentTrace:
        points = [TracePoint(step=i, x=x, y=float(i), heading=0.0, speed=1.0) for i in range(3)]
        return AgentTrace(
            name=name,
            kind=kind,
            width=1.0,
            length=2.0,
            is_ego=ego,
            behavior=None if ego else "AdversaryBehavior",
            trajectory=points,
        )

    return SimulationFacts(
        steps=3,
        timestep=0.1,
        termination_type="time",
        termination_reason="done",
        params={"weather": "ClearNoon"},
        agents=[trace("ego", "Car", 0.0, ego=True), trace("adv", adversary_kind, -4.0)],
    )


def test_the_semantic_gate_fails_a_script_that_contradicts_the_spec(generator: Generator) -> None:
    wrong = passed().model_copy(update={"simulation": _facts("Car")})
    right = passed().model_copy(update={"simulation": _facts("Pedestrian")})
    _script(generator, results=[wrong, wrong, right])
    generator.reconfigure(generator.options.model_copy(update={"semantic_gate": True}))
    try:
        gated = generator.validator(None, SPEC)("script")
        assert not gated.ok and gated.diagnostic is not None
        assert gated.diagnostic.stage is Stage.SEMANTIC and gated.diagnostic.section == "SPAWN"
        assert "adversary_type: expected Pedestrian, observed Car" in gated.diagnostic.message
        generator.reconfigure(generator.options.model_copy(update={"semantic_gate": False}))
        assert generator.validator(None, SPEC)("script").ok, "no gate: a run is a pass"
        assert generator.validator(None, SPEC)("script").ok
    finally:
        generator.reconfigure(generator.options.model_copy(update={"semantic_gate": False}))


def test_reconfigure_refuses_another_model_for_a_given_provider(generator: Generator) -> None:
    before = generator.options
    with pytest.raises(ReconfigureError, match="model"):
        generator.reconfigure(before.model_copy(update={"model": "other"}))
    assert generator.options is before
    generator.reconfigure(before.model_copy(update={"temperature": 0.7, "seed": 3}))
    assert generator.options.temperature == 0.7
    generator.reconfigure(before)


def test_reconfigure_loads_another_kb_and_rebuilds_its_own_provider(tmp_path: Path) -> None:
    cassette = tmp_path / "none.jsonl"
    cassette.write_text("")
    options = GenerateOptions(retrieval="bm25", provider="replay", replay=str(cassette))
    with Generator(options, checker=FakeValidator()) as own:
        first = own.provider
        own.reconfigure(options.model_copy(update={"temperature": 0.5}))
        assert own.provider is first, "per-run options keep the model"
        own.reconfigure(options.model_copy(update={"run_index": 1}))
        assert own.provider is not first, "a replayed run index reads its own cassette"
        size = len(own.kb)
        own.reconfigure(own.options.model_copy(update={"kb_dirs": [str(FAULTY_KB)]}))
        assert len(own.kb) > size and own.options.kb_dirs == [str(FAULTY_KB)]


def test_topk_is_the_number_of_candidates_kept(generator: Generator, tmp_path: Path) -> None:
    _script(generator, ANSWER.model_dump_json(), "{}", "{}", "{}")
    generator.reconfigure(generator.options.model_copy(update={"topk": 2}))
    try:
        run = generator.generate(MEASURED_DESCRIPTION)
    finally:
        generator.reconfigure(generator.options.model_copy(update={"topk": 10}))
    assert run.retrieval is not None
    kept = {
        component.value: len(entries) for component, entries in run.retrieval.candidates.items()
    }
    assert kept["geometry"] <= 2 and kept["spawn"] <= 2 and kept["behavior"] <= 2
    assert max(kept["geometry"], kept["spawn"], kept["behavior"]) == 2


def test_a_description_with_no_speed_distance_or_moment_keeps_the_defaults_without_asking(
    generator: Generator, tmp_path: Path
) -> None:
    # A tuning call would take the "{}" replies, which never fit its schema.
    model = _script(generator, ANSWER.model_dump_json(), "{}", "{}", "{}", results=[passed()])
    run = generator.generate(DESCRIPTION, tmp_path)
    assert run.spec is not None and not run.spec.quantities_stated
    assert run.retrieval is not None and any("no tuning call" in n for n in run.retrieval.notes)
    assert len(model.requests) == 1 and run.status is not RunStatus.PROVIDER_ERROR


def test_a_description_the_rules_read_whole_asks_the_model_nothing(tmp_path: Path) -> None:
    """The default: no extraction call when the rules read the adversary and its start,
    and no tuning call without words of speed, distance or time."""
    model = ScriptedProvider([])  # any call would fail the run: there is no reply
    checker = FakeValidator([passed()])
    with Generator(
        GenerateOptions(retrieval="bm25"), provider=UsageLedger(model), checker=checker
    ) as generator:
        run = generator.generate(DESCRIPTION, tmp_path)
    assert run.status is RunStatus.EXECUTED, run.message
    assert model.requests == [] and run.usage.calls == 0
    assert run.spec is not None and run.spec.adversary_type.value == "pedestrian"
    assert run.spec.spawn_position.value == "roadside_right"
    assert any("no model call" in note for note in run.hint_notes)
