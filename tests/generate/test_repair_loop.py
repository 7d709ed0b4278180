"""The test-and-repair loop in milliseconds: a scripted model and a fake validator.

Each test plans the model's answers and the validator's results, runs `repair_loop`, and
checks the attempts it kept, the outcome, and what the model was asked.
"""

from __future__ import annotations

import pytest

from arise.generate.assemble import Draft, assemble
from arise.generate.conformity import Conformity, ConformityCheck, semantic_gate
from arise.generate.events import (
    AttemptChecked,
    ProgressEvent,
    RunFinished,
    RunStage,
    StageStarted,
    event_dict,
)
from arise.generate.options import GenerateOptions
from arise.generate.repair import RepairContext, RepairStep, repair_loop, repair_once
from arise.generate.retrieve import Retrieval
from arise.generate.rules import RuleContext
from arise.generate.run import AttemptKind, Generation, RunStatus
from arise.kb.schema import Component, Entry
from arise.llm.types import ProviderUnavailable
from arise.sections import section_body
from arise.validate.types import Rejection, Stage
from arise.vocabulary import ActorClass
from tests.fakes import FakeValidator, ScriptedProvider, failed, passed

DESCRIPTION = "A pedestrian crosses in front of the ego."
MAPS = {"plain": frozenset[str]()}


def entry(entry_id: str, snippet: str, **fields: object) -> Entry:
    component = Component(entry_id.split(".")[0])
    return Entry(
        id=entry_id, component=component, descriptions=[entry_id], snippet=snippet, **fields
    )  # type: ignore[arg-type]


GEOMETRY = entry("geometry.road", "ego = new Car", defines=["ego"])
BEHAVIOR = entry(
    "behavior.cross", "behavior AdversaryBehavior():\n    wait", defines=["AdversaryBehavior"]
)


def spawn(number: int, snippet: str | None = None) -> Entry:
    return entry(
        f"spawn.s{number}",
        snippet or f"adv = new Pedestrian ahead of ego by {10 * number}",
        needs=["ego"],
        defines=["adv"],
    )


def setup(
    *spawns: Entry, provider: ScriptedProvider | None = None
) -> tuple[Generation, Draft, RepairContext]:
    spawns = spawns or (spawn(1), spawn(2))
    retrieval = Retrieval(
        candidates={
            Component.GEOMETRY: [GEOMETRY],
            Component.SPAWN: list(spawns),
            Component.BEHAVIOR: [BEHAVIOR],
        },
        chosen={
            Component.GEOMETRY: [GEOMETRY],
            Component.SPAWN: [spawns[0]],
            Component.BEHAVIOR: [BEHAVIOR],
        },
        map_name="plain",
    )
    draft = assemble(retrieval, "Pedestrian", DESCRIPTION)
    run = Generation(
        description=DESCRIPTION, options=GenerateOptions(), retrieval=retrieval, draft=draft
    )
    context = RepairContext(
        description=DESCRIPTION,
        retrieval=retrieval,
        draft=draft,
        provider=provider,
        rules=RuleContext(adversary_class=ActorClass.PEDESTRIAN),
        maps=MAPS,
    )
    return run, draft, context


def kinds(run: Generation) -> list[AttemptKind]:
    return [attempt.kind for attempt in run.attempts]


def test_first_try_needs_no_repair() -> None:
    run, draft, context = setup()
    events: list[ProgressEvent] = []
    outcome = repair_loop(
        run, draft.script, FakeValidator([passed()]), context, max_repairs=3, emit=events.append
    )
    assert outcome.status is RunStatus.EXECUTED and outcome.message is None
    assert kinds(run) == [AttemptKind.INITIAL] and run.first_pass_ok
    assert [event_dict(e) for e in events] == [
        {"event": "stage", "stage": "validate", "attempt": 0},
        {
            "event": "attempt",
            "index": 0,
            "kind": "initial",
            "ok": True,
            "detail": "assembled from the knowledge base",
        },
    ]


def test_a_rule_fixes_a_mechanical_error_without_the_model() -> None:
    model = ScriptedProvider()  # any call fails the test
    run, draft, context = setup(
        spawn(1, "adv = new Pedestrain ahead of ego by 10"), spawn(2), provider=model
    )
    typo = failed(
        Stage.COMPILE,
        "NameError",
        "name 'Pedestrain' is not defined",
        "SPAWN",
        line=9,
        hint="'Pedestrain' is not defined; did you mean Pedestrian?",
    )
    validator = FakeValidator([typo, passed()])
    outcome = repair_loop(run, draft.script, validator, context, max_repairs=3)
    assert outcome.status is RunStatus.EXECUTED
    assert kinds(run) == [AttemptKind.INITIAL, AttemptKind.RULE]
    assert run.attempts[1].detail == "close_name: Pedestrain -> Pedestrian"
    assert "new Pedestrian ahead" in validator.scripts[1] and model.requests == []
    assert run.attempts[1].diff.startswith("--- before.scenic")


def test_the_model_rewrites_only_the_failing_section() -> None:
    fixed = "behavior AdversaryBehavior():\n    take SetWalkingSpeedAction(1)"
    model = ScriptedProvider([f"Here it is:\n```scenic\n{fixed}\n```"])
    run, draft, context = setup(provider=model)
    crash = failed(Stage.SIMULATE, "TypeError", "wait() takes no arguments", "BEHAVIOR", line=6)
    validator = FakeValidator([crash, passed()])
    outcome = repair_loop(run, draft.script, validator, context, max_repairs=3)
    assert outcome.status is RunStatus.EXECUTED
    assert kinds(run) == [AttemptKind.INITIAL, AttemptKind.LLM]
    last = run.attempts[-1]
    assert last.detail == "model rewrote BEHAVIOR" and last.llm_usage.calls == 1
    assert section_body(last.script, "BEHAVIOR") == fixed
    assert section_body(last.script, "SPAWN") == section_body(draft.script, "SPAWN")
    [request] = model.requests
    asked = request.messages[-1].content
    assert "Section BEHAVIOR:" in asked and "wait() takes no arguments" in asked
    assert request.max_tokens == 700


def test_an_unusable_answer_counts_against_the_section_and_swaps_in_the_next_candidate() -> None:
    model = ScriptedProvider(["```scenic\n```"])  # no code
    run, draft, context = setup(provider=model)
    stuck = failed(Stage.SAMPLE, "RejectionException", "no sample satisfied", "SPAWN")
    validator = FakeValidator([stuck, passed()])
    outcome = repair_loop(run, draft.script, validator, context, max_repairs=3)
    assert outcome.status is RunStatus.EXECUTED
    assert kinds(run) == [AttemptKind.INITIAL, AttemptKind.SWAP]
    assert run.attempts[1].detail == "the model returned no code; spawn.s1 -> spawn.s2"
    assert run.attempts[1].llm_usage.calls == 1, "the failed model call is paid for"
    assert context.llm_failures == {"SPAWN": 1}
    assert [e.id for e in run.draft.entries if e.component is Component.SPAWN] == ["spawn.s2"]
    assert context.draft is run.draft and "by 20" in validator.scripts[1]


def test_a_model_repair_that_does_not_run_counts_and_two_failures_stop_asking() -> None:
    answer = "```scenic\nbehavior AdversaryBehavior():\n    take SetWalkingSpeedAction({})\n```"
    model = ScriptedProvider([answer.format(1), answer.format(2)])
    run, draft, context = setup(spawn(1), provider=model)  # no spawn to swap to
    crash = failed(Stage.SIMULATE, "TypeError", "bad behavior", "BEHAVIOR", line=6)
    validator = FakeValidator([crash, crash, crash])
    outcome = repair_loop(run, draft.script, validator, context, max_repairs=5)
    assert kinds(run) == [AttemptKind.INITIAL, AttemptKind.LLM, AttemptKind.LLM]
    assert context.llm_failures == {"BEHAVIOR": 2} and len(model.requests) == 2
    assert outcome.status is RunStatus.FAILED
    assert outcome.message == (
        "no repair left for: simulate line 6 [BEHAVIOR]: TypeError: bad behavior"
    )


def test_a_semantic_mismatch_goes_straight_to_a_swap() -> None:
    model = ScriptedProvider()  # the model is not asked: numbers will not change who or where
    run, draft, context = setup(provider=model)
    conformity = Conformity(
        [
            ConformityCheck(
                "spawn_position",
                "crossing_road_from_left",
                "20 m ahead, 0.0 m left, moving same",
                False,
            ),
            ConformityCheck("weather", "ClearNoon", "ClearNoon", True),
        ]
    )
    gated = semantic_gate(passed(), conformity)
    assert not gated.ok and gated.diagnostic is not None
    assert gated.diagnostic.stage is Stage.SEMANTIC and gated.diagnostic.section == "SPAWN"
    assert semantic_gate(passed(), Conformity([conformity.checks[1]])).ok
    validator = FakeValidator([gated, passed()])
    outcome = repair_loop(run, draft.script, validator, context, max_repairs=3)
    assert outcome.status is RunStatus.EXECUTED and model.requests == []
    assert kinds(run) == [AttemptKind.INITIAL, AttemptKind.SWAP]
    assert run.attempts[1].detail == "spawn.s1 -> spawn.s2"


def test_the_budget_is_spent_and_the_run_fails_with_the_last_error() -> None:
    run, draft, context = setup(spawn(1), spawn(2), spawn(3), spawn(4))
    overlap = failed(Stage.SAMPLE, "RejectionException", "too many rejections", "SPAWN")
    validator = FakeValidator([overlap] * 3)
    events: list[ProgressEvent] = []
    outcome = repair_loop(run, draft.script, validator, context, max_repairs=2, emit=events.append)
    assert kinds(run) == [AttemptKind.INITIAL, AttemptKind.SWAP, AttemptKind.SWAP]
    assert outcome.status is RunStatus.FAILED
    assert outcome.message == (
        "repair budget spent; last error: sample [SPAWN]: RejectionException: too many rejections"
    )
    repairs = [e for e in events if isinstance(e, StageStarted) and e.stage is RunStage.REPAIR]
    assert [e.attempt for e in repairs] == [1, 2]
    assert all(e.error for e in repairs)
    assert [e.index for e in events if isinstance(e, AttemptChecked)] == [0, 1, 2]


def test_no_repairs_without_a_context() -> None:
    run, draft, _ = setup()
    outcome = repair_loop(run, draft.script, FakeValidator([failed()]), None, max_repairs=10)
    assert outcome.status is RunStatus.FAILED and outcome.message is None
    assert kinds(run) == [AttemptKind.INITIAL]


def test_a_provider_error_mid_loop_propagates_and_keeps_the_attempts() -> None:
    model = ScriptedProvider([ProviderUnavailable("llamacpp: the server went away")])
    run, draft, context = setup(provider=model)
    validator = FakeValidator([failed(Stage.SIMULATE, "TypeError", "bad", "BEHAVIOR")])
    saved: list[int] = []
    with pytest.raises(ProviderUnavailable, match="went away"):
        repair_loop(
            run,
            draft.script,
            validator,
            context,
            max_repairs=3,
            on_attempt=lambda attempt: saved.append(attempt.index),
        )
    assert kinds(run) == [AttemptKind.INITIAL] and saved == [0]
    assert run.status is RunStatus.RUNNING, "the loop never sets the status"


def test_gate_refusals_and_the_header_are_never_sent_to_the_model() -> None:
    model = ScriptedProvider()
    _, draft, context = setup(spawn(1), provider=model)
    refused = failed(Stage.GATE, "ForbiddenImport", "import of os refused", "BEHAVIOR").diagnostic
    header = failed(Stage.COMPILE, "MapError", "no map", "HEADER").diagnostic
    assert refused is not None and header is not None
    for diagnostic in (refused, header):
        step = repair_once(context, draft.script, diagnostic)
        assert step == RepairStep(None, AttemptKind.SWAP, "no other candidate fits")
    assert model.requests == []


def test_a_rejection_names_the_section_when_the_diagnostic_does_not() -> None:
    run, draft, context = setup()
    rejected = failed(
        Stage.SAMPLE,
        "RejectionException",
        "rejected",
        None,
        rejections=[Rejection(reason="requirement on line 3", count=9, section="SPAWN")],
    )
    outcome = repair_loop(
        run, draft.script, FakeValidator([rejected, passed()]), context, max_repairs=1
    )
    assert outcome.status is RunStatus.EXECUTED
    assert run.attempts[1].detail == "spawn.s1 -> spawn.s2"


def test_events_serialise_to_the_dicts_a_page_streams() -> None:
    assert event_dict(StageStarted(RunStage.REPAIR, attempt=2, error="x")) == {
        "event": "stage",
        "stage": "repair",
        "attempt": 2,
        "error": "x",
    }
    assert event_dict(RunFinished(RunStatus.FAILED, "failed: x")) == {
        "event": "done",
        "status": "failed",
        "summary": "failed: x",
    }
