"""The semantic gate in milliseconds: on by default in arise mode, its checks on synthetic
traces, its repairs (a fitting swap first, then a model fix), and a run that keeps the
script that ran with the fewest contradictions when the budget is spent."""

from __future__ import annotations

import tempfile
from collections.abc import Iterable
from typing import Any

import pytest
from typer.testing import CliRunner

from arise.cli import app
from arise.generate.conformity import (
    Contradiction,
    actor_counts,
    check_conformity,
    contradictions,
)
from arise.generate.options import GenerateOptions, Mode
from arise.generate.repair import GatedValidate, repair_loop
from arise.generate.run import AttemptKind, GateVerdict, RunStatus
from arise.generate.spec import Actor, ScenarioSpec
from arise.kb.schema import Component
from arise.language.cast import read_cast
from arise.sections import section_body
from arise.validate.types import AgentTrace, CheckResult, SimulationFacts, Stage, TracePoint
from arise.vocabulary import ActorRole
from tests.fakes import FakeValidator, ScriptedProvider, failed, passed
from tests.generate.test_repair_loop import entry, kinds, setup, spawn

SIDE = Contradiction("spawn_position", "crossing_road_from_left", "20 m ahead, 3 m right", "SPAWN")
EXTRA = Contradiction("extra_actors", "no other object", "1: Car1", "MISC")
MISSING = Contradiction("participants", "at least 1 other object(s)", "0", "MISC")
WEATHER = Contradiction("weather", "ClearNoon", "MidRainyNoon", "WEATHER")


class FakeGate:
    """Contradictions from a queue, one list per script that ran."""

    def __init__(self, found: Iterable[list[Contradiction]]) -> None:
        self.found = list(found)

    def __call__(self, result: CheckResult) -> list[Contradiction]:
        assert self.found, "unexpected gate"
        return self.found.pop(0)


def gated(results: list[CheckResult], found: list[list[Contradiction]]) -> GatedValidate:
    return GatedValidate(FakeValidator(results), FakeGate(found))


# -- on by default in arise mode ------------------------------------------------------------


def test_the_gate_is_on_by_default_in_arise_mode_and_never_in_the_baselines() -> None:
    assert GenerateOptions().semantic_gate and GenerateOptions().gate_on
    assert not GenerateOptions(mode=Mode.SINGLE_PASS).gate_on
    assert not GenerateOptions(mode=Mode.CHATSCENE).gate_on
    assert not GenerateOptions(semantic_gate=False).gate_on


def _captured_options(monkeypatch: pytest.MonkeyPatch, module: str, name: str) -> list[Any]:
    """Replace `module.name` by a recorder that stops the command right after it (the
    stop reaches the CLI's crash handler: its report goes to a scratch cache folder)."""
    seen: list[Any] = []
    monkeypatch.setenv("ARISE_CACHE_DIR", tempfile.mkdtemp(prefix="arise-test-cache-"))

    class Stop(Exception):
        pass

    def record(*args: Any, **kwargs: Any) -> None:
        seen.append(args[0] if args else kwargs)
        raise Stop

    monkeypatch.setattr(f"{module}.{name}", record)
    return seen


@pytest.mark.parametrize(("flag", "expected"), [([], True), (["--no-semantic-gate"], False)])
def test_generate_turns_the_gate_off_with_no_semantic_gate(
    monkeypatch: pytest.MonkeyPatch, flag: list[str], expected: bool
) -> None:
    seen = _captured_options(monkeypatch, "arise.generate.batch", "Generator")
    CliRunner().invoke(app, ["generate", "A pedestrian crosses in front of the ego.", *flag])
    [options] = seen
    assert isinstance(options, GenerateOptions) and options.semantic_gate is expected


@pytest.mark.parametrize(
    ("flag", "expected"),
    [([], True), (["--no-semantic-gate"], False), (["--semantic-gate"], True)],
)
def test_bench_turns_the_gate_off_with_no_semantic_gate(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Any, flag: list[str], expected: bool
) -> None:
    prompts = tmp_path / "prompts.txt"
    prompts.write_text("A pedestrian crosses in front of the ego.\n")
    seen = _captured_options(monkeypatch, "arise.evaluate.cli", "BenchConfig")
    CliRunner().invoke(app, ["bench", str(prompts), "--out", str(tmp_path / "b"), *flag])
    [kwargs] = seen
    assert kwargs["base"].semantic_gate is expected


# -- the checks: missing and extra actors ---------------------------------------------------

SPEC = {
    "adversary_type": "pedestrian",
    "behavior": "crosses",
    "road_type": "straight_road",
    "ego_maneuver": "go_straight",
    "geometry": "a straight road",
    "spawn_position": "crossing_road_from_right",
    "spawn": "on the right sidewalk",
}


def _trace(name: str, kind: str, x: float, *, ego: bool = False, moves: bool = True) -> AgentTrace:
    """The ego drives 20 m up +y; others stand at y=10, and a mover walks 4 m towards -x."""
    points = [
        TracePoint(
            step=i,
            x=x - (i if moves and not ego else 0),
            y=5.0 * i if ego else 10.0,
            heading=0.0,
            speed=1.0,
        )
        for i in range(5)
    ]
    return AgentTrace(
        name=name,
        kind=kind,
        width=1.0,
        length=2.0,
        is_ego=ego,
        behavior=None if ego or not moves else "AdversaryBehavior",
        trajectory=points,
    )


def _facts(*others: AgentTrace) -> SimulationFacts:
    return SimulationFacts(
        steps=5,
        timestep=0.1,
        termination_type="time",
        termination_reason="done",
        params={"weather": "ClearNoon"},
        agents=[_trace("ego", "Car", 0.0, ego=True), _trace("adv", "Pedestrian", 4.0), *others],
    )


def actors_of(participants: list[str]) -> list[Actor]:
    """The actors the cast reads from each participant's words (the first thing named)."""
    found = []
    for words in participants:
        mention = read_cast(words).others[0]
        found.append(
            Actor(
                role=ActorRole.PARKED,
                scenic_class=mention.cls,
                count=mention.count,
                count_stated=mention.counted,
                quote=words,
            )
        )
    return found


def _found(participants: list[str], *others: AgentTrace) -> set[str]:
    spec = ScenarioSpec.model_validate(
        {**SPEC, "participants": participants, "actors": actors_of(participants)}
    )
    return {c.check for c in contradictions(check_conformity(spec, _facts(*others)))}


@pytest.mark.parametrize(
    ("words", "most"),
    [
        ("a parked car on the right", 1),
        ("two parked vans", 2),
        ("3 traffic cones", 3),
        ("parked cars along the street", None),
        ("a pedestrian waiting at the bus stop", 1),
        ("several cyclists", None),
    ],
)
def test_the_cast_says_how_many_objects_a_participant_stands_for(
    words: str, most: int | None
) -> None:
    assert actor_counts(actors_of([words])) == (1, most)


def test_actor_counts_add_up_and_a_group_has_no_upper_bound() -> None:
    assert actor_counts([]) == (0, 0)
    assert actor_counts(actors_of(["a bus", "parked cars"])) == (2, None)
    assert actor_counts(actors_of(["a bus", "two cones"])) == (2, 3)


def test_extra_actors_nobody_asked_for_are_a_contradiction() -> None:
    parked = [_trace(f"Car{i}", "Car", 6.0 + 3 * i, moves=False) for i in (1, 2)]
    assert _found([]) == set()
    assert _found([], *parked) == {"extra_actors"}
    assert _found(["a parked car"], *parked) == {"extra_actors"}
    assert _found(["parked cars"], *parked) == set(), "a plural stands for several"
    assert _found(["two parked cars"], *parked) == set()
    spec = ScenarioSpec.model_validate({**SPEC, "participants": []})
    [extra] = contradictions(check_conformity(spec, _facts(*parked)))
    assert extra.section == "MISC" and extra.observed == "2: Car1, Car2"
    assert extra.text() == "extra_actors: expected no other object, observed 2: Car1, Car2"


def test_missing_actors_are_a_contradiction() -> None:
    assert _found(["a parked car", "a cyclist"]) == {"participants"}
    one = _trace("Car1", "Car", 9.0, moves=False)
    assert _found(["a parked car", "a cyclist"], one) == {"participants"}
    two = _trace("Bicycle1", "Bicycle", 12.0, moves=False)
    assert _found(["a parked car", "a cyclist"], one, two) == set()


def test_an_adversary_that_never_nears_the_path_is_a_contradiction_unless_roadside() -> None:
    far = SimulationFacts(
        **{
            **_facts().model_dump(),
            "agents": [
                _trace("ego", "Car", 0.0, ego=True),
                _trace("adv", "Pedestrian", -30.0, moves=False),
            ],
        }
    )
    spec = ScenarioSpec.model_validate({**SPEC, "spawn_position": "crossing_road_from_left"})
    assert "reaches_ego_path" in {c.check for c in contradictions(check_conformity(spec, far))}
    roadside = ScenarioSpec.model_validate({**SPEC, "spawn_position": "roadside_left"})
    conformity = check_conformity(roadside, far)
    assert "reaches_ego_path" in [m.split(":")[0] for m in conformity.mismatches]
    assert "reaches_ego_path" not in {c.check for c in contradictions(conformity)}


# -- repairs --------------------------------------------------------------------------------


def test_a_gate_failure_is_repaired_by_a_swap_that_fits() -> None:
    model = ScriptedProvider()  # a candidate is left: the model is not asked
    run, draft, context = setup(provider=model)
    validate = gated([passed(), passed()], [[SIDE], []])
    outcome = repair_loop(run, draft.script, validate, context, max_repairs=3)
    run.end(outcome)
    assert outcome.status is RunStatus.EXECUTED and outcome.final is None and model.requests == []
    assert kinds(run) == [AttemptKind.INITIAL, AttemptKind.SWAP]
    assert run.attempts[1].detail == "spawn.s1 -> spawn.s2"
    first = run.attempts[0]
    assert not first.ok and first.executed and first.contradictions == [SIDE]
    assert first.diagnostic is not None and first.diagnostic.stage is Stage.SEMANTIC
    assert run.first_pass_ok, "ESR single counts a first script that ran"
    assert run.gate is GateVerdict.PASSED
    report = run.report()["semantic_gate"]
    assert report["on"] and report["passed"] and report["contradictions"] == []
    assert report["seconds"] == pytest.approx(run.attempts[1].seconds, abs=1e-3)
    assert run.gate_seconds > 0


def test_extra_actors_are_repaired_by_dropping_a_misc_entry() -> None:
    run, _, context = setup()
    misc = entry("misc.parked", "parked = new Car ahead of ego by 30", needs=["ego"])
    context.retrieval.candidates[Component.MISC] = [misc]
    context.retrieval.chosen[Component.MISC] = [misc]
    from arise.generate.assemble import assemble

    context.draft = assemble(context.retrieval, "Pedestrian", "x")
    run.use_draft(context.draft)
    validate = gated([passed(), passed()], [[EXTRA], []])
    outcome = repair_loop(run, context.draft.script, validate, context, max_repairs=3)
    assert outcome.status is RunStatus.EXECUTED
    assert run.attempts[1].detail == "dropped misc.parked"
    assert "parked" not in run.attempts[1].script


def test_a_gate_failure_goes_to_the_model_when_no_candidate_is_left() -> None:
    fixed = "adv = new Pedestrian left of ego by 5"
    model = ScriptedProvider([f"```scenic\n{fixed}\n```"])
    run, draft, context = setup(spawn(1), provider=model)  # no other spawn
    context.model_fixes_contradictions = True
    validate = gated([passed(), passed()], [[SIDE, WEATHER], []])
    outcome = repair_loop(run, draft.script, validate, context, max_repairs=3)
    assert outcome.status is RunStatus.EXECUTED
    assert kinds(run) == [AttemptKind.INITIAL, AttemptKind.LLM]
    assert section_body(run.attempts[1].script, "SPAWN") == fixed
    [request] = model.requests
    asked = request.messages[-1].content
    assert "Section SPAWN:" in asked
    assert "spawn_position: expected crossing_road_from_left, observed 20 m ahead" in asked
    assert "weather" not in asked.split("Section SPAWN:")[0], "only its own contradictions"


def test_the_gate_stops_when_the_model_fix_left_the_contradiction_and_no_candidate_is_left() -> (
    None
):
    first = "adv = new Pedestrian left of ego by 5"
    second = "adv = new Pedestrian left of ego by 9"
    model = ScriptedProvider([f"```scenic\n{first}\n```", f"```scenic\n{second}\n```"])
    run, draft, context = setup(spawn(1), provider=model)  # no other spawn
    context.model_fixes_contradictions = True
    validate = gated([passed(), passed()], [[SIDE], [SIDE]])
    outcome = repair_loop(run, draft.script, validate, context, max_repairs=8)
    assert kinds(run) == [AttemptKind.INITIAL, AttemptKind.LLM], "one model fix, not eight"
    assert len(model.requests) == 1
    assert outcome.status is RunStatus.EXECUTED
    assert (outcome.message or "").startswith("no repair left for")


def test_by_default_the_gate_stops_when_no_candidate_is_left_without_asking_the_model() -> None:
    model = ScriptedProvider(["```scenic\nadv = new Pedestrian left of ego by 5\n```"])
    run, draft, context = setup(spawn(1), provider=model)  # no other spawn
    assert not GenerateOptions().gate_model_fixes and not context.model_fixes_contradictions
    validate = gated([passed()], [[SIDE]])
    outcome = repair_loop(run, draft.script, validate, context, max_repairs=8)
    assert kinds(run) == [AttemptKind.INITIAL] and model.requests == []
    assert outcome.status is RunStatus.EXECUTED  # the script that ran, contradiction reported
    assert (outcome.message or "").startswith("no repair left for")


def test_missing_actors_are_not_fixed_by_dropping_one() -> None:
    model = ScriptedProvider(["```scenic\ncyclist = new Bicycle ahead of ego by 20\n```"])
    run, _, context = setup(provider=model)
    context.model_fixes_contradictions = True
    misc = entry("misc.cone", "cone = new Cone ahead of ego by 30", needs=["ego"])
    context.retrieval.candidates[Component.MISC] = [misc]
    context.retrieval.chosen[Component.MISC] = [misc]
    from arise.generate.assemble import assemble

    context.draft = assemble(context.retrieval, "Pedestrian", "x")
    run.use_draft(context.draft)
    validate = gated([passed(), passed()], [[MISSING], []])
    outcome = repair_loop(run, context.draft.script, validate, context, max_repairs=3)
    assert outcome.status is RunStatus.EXECUTED
    assert kinds(run) == [AttemptKind.INITIAL, AttemptKind.LLM]
    assert "Bicycle" in section_body(run.attempts[1].script, "MISC")


def test_budget_spent_keeps_the_script_that_ran_with_the_fewest_contradictions() -> None:
    run, draft, context = setup(spawn(1), spawn(2), spawn(3))
    crash = failed(Stage.SIMULATE, "TypeError", "bad", "SPAWN")
    validate = gated([passed(), passed(), crash], [[SIDE, WEATHER], [SIDE]])
    outcome = repair_loop(run, draft.script, validate, context, max_repairs=2)
    run.end(outcome)
    assert kinds(run) == [AttemptKind.INITIAL, AttemptKind.SWAP, AttemptKind.SWAP]
    assert outcome.status is RunStatus.EXECUTED and outcome.final == 1
    assert run.ok and run.final_attempt is run.attempts[1]
    assert run.final_check is run.attempts[1].check
    assert "repair budget spent" in (run.message or "")
    assert run.gate is GateVerdict.CONTRADICTS
    report = run.report()
    assert report["status"] == "executed" and report["final_attempt"] == 1
    gate = report["semantic_gate"]
    assert gate["on"] and gate["verdict"] == "contradicts" and gate["passed"] is False
    assert gate["contradictions"] == [SIDE.as_dict()]
    assert gate["seconds"] == pytest.approx(sum(a.seconds for a in run.attempts[1:]), abs=1e-3)
    assert report["attempts"][0]["executed"] and not report["attempts"][2]["executed"]
    assert run.summary().endswith(
        "1 contradiction with the description left (kept attempt 1): " + SIDE.text()
    )


def test_no_repair_left_also_keeps_a_script_that_ran() -> None:
    run, draft, context = setup(spawn(1))  # nothing to swap, no model
    validate = gated([passed()], [[WEATHER]])
    outcome = repair_loop(run, draft.script, validate, context, max_repairs=5)
    assert outcome.status is RunStatus.EXECUTED and outcome.final == 0
    assert (outcome.message or "").startswith("no repair left for: semantic [WEATHER]")
    # The search that found no repair is part of what the gate cost.
    assert run.gate_seconds == run.unused_repair_seconds > 0


def test_a_run_where_nothing_ran_still_fails() -> None:
    run, draft, context = setup(spawn(1))
    validate = gated([failed(Stage.COMPILE, "SyntaxError", "bad", "GEOMETRY")], [])
    outcome = repair_loop(run, draft.script, validate, context, max_repairs=0)
    run.end(outcome)
    assert outcome.status is RunStatus.FAILED and run.gate is GateVerdict.NOT_REACHED
    assert run.report()["semantic_gate"]["passed"] is None


def test_the_gate_is_off_in_the_report_of_a_baseline() -> None:
    run, draft, _ = setup()
    run.options = GenerateOptions(mode=Mode.SINGLE_PASS)
    run.end(repair_loop(run, draft.script, FakeValidator([passed()]), None, max_repairs=0))
    assert run.gate is GateVerdict.OFF
    assert run.report()["semantic_gate"] == {
        "on": False,
        "verdict": "off",
        "passed": None,
        "contradictions": [],
        "seconds": 0.0,
    }


def test_ahead_in_its_lane_holds_for_the_lane_a_turning_ego_enters() -> None:
    """The ego turns right (up +y, then along +x); the stalled car stands in the lane it
    turns into, far right of where the ego started: ahead on its route, not a contradiction."""
    turn = [(0.0, 0.0, 0.0), (0.0, 6.0, 0.0), (3.0, 10.0, -0.8), (8.0, 12.0, -1.57)]
    turn += [(8.0 + 5.0 * i, 12.0, -1.57) for i in range(1, 6)]
    ego = AgentTrace(
        name="ego",
        kind="Car",
        width=2.0,
        length=4.5,
        is_ego=True,
        trajectory=[
            TracePoint(step=i, x=x, y=y, heading=h, speed=5.0) for i, (x, y, h) in enumerate(turn)
        ],
    )
    stalled = AgentTrace(
        name="Motorcycle1",
        kind="Motorcycle",
        width=0.8,
        length=2.0,
        behavior="AdversaryBehavior",
        trajectory=[TracePoint(step=i, x=24.0, y=12.3, heading=-1.57, speed=0.0) for i in range(9)],
    )
    facts = SimulationFacts(
        steps=9,
        timestep=0.1,
        termination_type="time",
        termination_reason="done",
        params={"weather": "ClearNoon"},
        agents=[ego, stalled],
    )
    spec = ScenarioSpec.model_validate(
        {
            **SPEC,
            "adversary_type": "motorcycle",
            "ego_maneuver": "turn_right",
            "road_type": "intersection",
            "spawn_position": "ahead_same_lane",
        }
    )
    [check] = [c for c in check_conformity(spec, facts).checks if c.name == "spawn_position"]
    assert check.ok, check
    elsewhere = stalled.model_copy(
        update={"trajectory": [p.model_copy(update={"y": 20.0}) for p in stalled.trajectory]}
    )
    facts = facts.model_copy(update={"agents": [ego, elsewhere]})
    [check] = [c for c in check_conformity(spec, facts).checks if c.name == "spawn_position"]
    assert not check.ok, "8 m off the ego's path is not in its lane"


def test_a_foggy_spec_needs_the_fog_that_ran_not_only_its_preset() -> None:
    from arise.weather import Light, Visibility, weather_for

    fog = weather_for("ClearNoon", Visibility.FOG)
    spec = ScenarioSpec.model_validate(
        {**SPEC, "weather": fog.closest_preset(), "weather_parameters": fog.model_dump()}
    )

    def gate(seen: str) -> set[str]:
        facts = _facts().model_copy(update={"params": {"weather": seen}})
        return {c.check for c in contradictions(check_conformity(spec, facts))}

    assert gate(fog.param_text()) == set()
    assert gate("CloudyNoon") == {"weather"}, "the preset alone has no fog"
    dusk = weather_for("ClearNoon", Visibility.FOG, Light.DUSK)
    assert gate(dusk.param_text()) == {"weather"}
    assert "weather" not in gate("{not json"), "unreadable text is unknown, not contradicted"


LATE = Contradiction(
    "conflict", "within 6 m or TTC under 3 s", "closest 14.2 m, never closing", "BEHAVIOR"
)


def test_a_conflict_that_never_happens_is_repaired_by_another_behavior_never_by_the_model() -> None:
    model = ScriptedProvider()  # never asked: no model fix moves a trigger it cannot see run
    run, draft, context = setup(spawn(1), provider=model)
    timed = entry(
        "behavior.timed",
        "behavior AdversaryBehavior():\n    wait",
        defines=["AdversaryBehavior"],
    )
    context.retrieval.candidates[Component.BEHAVIOR].append(timed)
    validate = gated([passed(), passed()], [[LATE], [LATE]])
    outcome = repair_loop(run, draft.script, validate, context, max_repairs=5)
    assert kinds(run) == [AttemptKind.INITIAL, AttemptKind.SWAP]
    assert run.attempts[1].detail == "behavior.cross -> behavior.timed"
    assert model.requests == [], "no candidate left: the gate stops instead of asking"
    assert outcome.status is RunStatus.EXECUTED
    assert (outcome.message or "").startswith("no repair left for: ")
