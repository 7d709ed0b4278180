"""The semantic gate with the real Scenic simulator: knowledge-base entries picked by id (so
the test does not hang on extraction or retrieval), the generator's own gated validator,
and a scripted model. Not replayed from cassettes: the gate's repairs of these drafts need
no model call that could be recorded, and the one that does gets unusable answers."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from arise.generate.assemble import assemble
from arise.generate.options import GenerateOptions
from arise.generate.pipeline import Generator
from arise.generate.repair import GatedValidate, RepairContext, repair_loop
from arise.generate.retrieve import Retrieval
from arise.generate.rules import RuleContext
from arise.generate.run import AttemptKind, GateVerdict, Generation, RunStatus
from arise.generate.spec import ScenarioSpec
from arise.kb.compose import pick_map
from arise.kb.schema import Component, Entry
from arise.validate import WorkerPool
from tests.fakes import ScriptedProvider
from tests.generate.test_semantic_gate import actors_of

DESCRIPTION = "A pedestrian steps off the right sidewalk in front of the ego car."
SPEC = {
    "adversary_type": "pedestrian",
    "behavior": "steps off the sidewalk and crosses",
    "road_type": "straight_road",
    "ego_maneuver": "go_straight",
    "geometry": "a straight road",
    "spawn_position": "crossing_road_from_right",
    "spawn": "on the right sidewalk ahead",
    "weather": "ClearNoon",
}
CHOSEN = {
    Component.GEOMETRY: "geometry.straight_road",
    Component.SPAWN: "spawn.roadside_right_near",
    Component.BEHAVIOR: "behavior.cross_and_stop",
    Component.MISC: "misc.parked_car_ahead",  # a parked car nobody may have asked for
}


@pytest.fixture(scope="module")
def generator(validator_pool: WorkerPool) -> Iterator[Generator]:
    with Generator(GenerateOptions(retrieval="bm25"), pool=validator_pool) as built:
        yield built


def _run(
    generator: Generator,
    participants: list[str],
    model: ScriptedProvider,
    model_fixes: bool = False,
) -> tuple[Generation, RunStatus]:
    kb = {e.id: e for e in generator.kb}
    weather = [
        e for e in generator.kb if e.component is Component.WEATHER and "ClearNoon" in e.snippet
    ][:1]
    chosen: dict[Component, list[Entry]] = {c: [kb[i]] for c, i in CHOSEN.items()}
    chosen[Component.WEATHER] = weather
    retrieval = Retrieval(candidates={c: list(v) for c, v in chosen.items()}, chosen=chosen)
    retrieval.map_name = pick_map(retrieval.chosen_entries(), generator.maps)
    draft = assemble(retrieval, "Pedestrian", DESCRIPTION)
    spec = ScenarioSpec.model_validate(
        {**SPEC, "participants": participants, "actors": actors_of(participants)}
    )
    run = Generation(
        description=DESCRIPTION,
        options=generator.options,
        spec=spec,
        retrieval=retrieval,
        draft=draft,
    )
    context = RepairContext(
        description=DESCRIPTION,
        retrieval=retrieval,
        draft=draft,
        provider=model,
        rules=RuleContext(adversary_class="Pedestrian"),
        maps=generator.maps,
        model_fixes_contradictions=model_fixes,
    )
    validate = generator.validator(None, spec)
    assert isinstance(validate, GatedValidate), "the gate is on by default in arise mode"
    outcome = repair_loop(run, draft.script, validate, context, max_repairs=3)
    run.end(outcome)
    return run, outcome.status


@pytest.mark.slow
def test_an_extra_parked_car_is_dropped_and_the_gate_passes(generator: Generator) -> None:
    model = ScriptedProvider()  # a swap is left: the model is not asked
    run, status = _run(generator, [], model)
    assert status is RunStatus.EXECUTED and model.requests == []
    first, last = run.attempts[0], run.attempts[-1]
    assert first.executed and not first.ok
    assert [c.check for c in first.contradictions] == ["extra_actors"]
    assert last.kind is AttemptKind.SWAP and last.detail == "dropped misc.parked_car_ahead"
    assert last.ok and last.check is not None and last.check.simulation is not None
    assert run.gate is GateVerdict.PASSED and run.gate_seconds > 0
    assert run.report()["semantic_gate"]["passed"] is True


@pytest.mark.slow
def test_a_missing_actor_the_model_cannot_add_leaves_the_run_executed(
    generator: Generator,
) -> None:
    model = ScriptedProvider(["```scenic\n```", "```scenic\n```"])  # unusable answers
    # with --model-fixes: by default the gate would stop after the swap, asking no one
    run, status = _run(generator, ["a parked van on the left", "a cyclist"], model, True)
    assert status is RunStatus.EXECUTED, "never FAILED only because of the gate"
    assert len(model.requests) == 2, "no swap adds an actor: the model was asked for MISC"
    assert "Section MISC:" in model.requests[0].messages[-1].content
    # The parked car is of a class the text never names: extra, so the swap drops it first;
    # what is left is the van and the cyclist nobody can add.
    assert [a.kind for a in run.attempts] == [AttemptKind.INITIAL, AttemptKind.SWAP]
    assert run.final_attempt is run.attempts[1] and run.final_check is not None
    assert run.final_check.simulation is not None, "the kept script really ran"
    assert run.gate is GateVerdict.CONTRADICTS
    gate = run.report()["semantic_gate"]
    assert gate["passed"] is False
    assert [c["check"] for c in gate["contradictions"]] == ["participants"]
    assert "1 contradiction with the description left" in run.summary()
