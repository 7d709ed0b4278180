"""The other actors of a description: read into the spec, placed by spawns of their own, and
known to the repair loop. Fast: the real knowledge base, no simulator, no model."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from arise.generate.assemble import assemble, declared_params
from arise.generate.conformity import check_conformity, contradictions
from arise.generate.grounding import ground
from arise.generate.options import GenerateOptions, ModelExtraction
from arise.generate.pipeline import Generator
from arise.generate.repair import RepairContext, guilty_actor, repair_once
from arise.generate.retrieve import Retrieval, retrieve
from arise.generate.rules import RuleContext
from arise.generate.run import AttemptKind, RunStatus
from arise.generate.spec import Actor, ExtractionAnswer, ScenarioSpec
from arise.kb.compose import composition_problems
from arise.kb.loader import KnowledgeBase, load_kb
from arise.kb.retrieval import BM25Retriever
from arise.kb.schema import Component
from arise.llm.accounting import UsageLedger
from arise.maps.registry import MapRegistry
from arise.validate.types import (
    AgentTrace,
    Diagnostic,
    Rejection,
    SimulationFacts,
    Stage,
    TracePoint,
)
from arise.vocabulary import ActorRole, EgoPlan, RelativePosition, StartDetail
from tests.fakes import FakeValidator, ScriptedProvider, failed, passed

TRUCKS = (
    "Two slow trucks drive ahead in the ego's lane and a car overtakes the ego from behind "
    "on the left."
)
BUS = "A stalled car blocks the ego's lane ahead while an oncoming bus approaches."
VAN = "A pedestrian steps out from behind a parked van on the right."
CONES = "The ego passes three cones and a parked car on the right when a cyclist swerves."


def answer(adversary: str, position: str = "ahead_same_lane") -> ExtractionAnswer:
    return ExtractionAnswer.model_validate(
        {
            "adversary": adversary,
            "adversary_type": "car",
            "behavior": "",
            "road_type": "straight_road",
            "ego_maneuver": "go_straight",
            "geometry": "",
            "spawn_position": position,
            "spawn": "",
        }
    )


@pytest.fixture(scope="module")
def kb() -> KnowledgeBase:
    return load_kb()


@pytest.fixture(scope="module")
def maps() -> dict[str, frozenset[str]]:
    return {name: entry.features for name, entry in MapRegistry().entries.items()}


def spec_of(text: str, adversary: str) -> ScenarioSpec:
    return ground(text, answer(adversary)).spec


def retrieved(kb: KnowledgeBase, maps: dict[str, frozenset[str]], text: str, adversary: str):
    spec = spec_of(text, adversary)
    return spec, retrieve(spec, kb, BM25Retriever(kb), maps, text)


# -- the spec -------------------------------------------------------------------------------


def test_each_other_road_user_is_an_actor_with_its_count_and_side() -> None:
    spec = spec_of(TRUCKS, "a car")
    assert spec.scenic_class == "Car"
    assert spec.actors == [
        Actor(
            role=ActorRole.SLOW,
            scenic_class="Truck",
            count=2,
            start=RelativePosition.AHEAD_SAME_LANE,
            quote="Two slow trucks",
        )
    ]
    assert len(spec.participants) == len(spec.actors)  # the words are still there


def test_roles_come_from_each_actors_own_words() -> None:
    [bus] = spec_of(BUS, "A stalled car").actors
    assert (bus.role, bus.scenic_class, bus.start) == (
        ActorRole.ONCOMING,
        "Bus",
        RelativePosition.ONCOMING,
    )
    [van] = spec_of(VAN, "A pedestrian").actors
    assert (van.role, van.scenic_class, van.stationary) == (ActorRole.OCCLUDER, "Van", True)
    cones, car = spec_of(CONES, "a cyclist").actors
    assert (cones.role, cones.count, cones.road_user) == (ActorRole.OBSTACLE, 3, False)
    assert (car.role, car.start, car.stationary) == (
        ActorRole.PARKED,
        RelativePosition.ROADSIDE_RIGHT,
        True,
    )


def test_a_stalled_vehicle_is_stopped_and_a_follower_follows() -> None:
    [stalled] = spec_of("A cyclist swerves around a stalled truck ahead.", "A cyclist").actors
    assert (stalled.role, stalled.stationary) == (ActorRole.STOPPED, True)
    [follower] = spec_of(
        "A car brakes hard ahead of the ego while a van follows the ego closely.", "A car"
    ).actors
    assert follower.scenic_class == "Van" and follower.role is ActorRole.FOLLOWING


# -- retrieval and composition --------------------------------------------------------------


def test_two_slow_trucks_get_two_spawns_of_their_own_and_no_misc_entry(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    spec, found = retrieved(kb, maps, TRUCKS, "a car")
    assert [placed.name for placed in found.actors] == ["actor2", "actor3"]
    assert {placed.spawn.id for placed in found.actors} == {"spawn.lead_same_lane"}
    assert {placed.behavior.id for placed in found.actors} == {"behavior.slow_to_block"}
    assert {placed.spawn.actor_class for placed in found.actors} == {"Truck"}
    assert found.chosen[Component.MISC] == []  # no double placement
    [adversary_spawn] = found.chosen[Component.SPAWN]
    assert adversary_spawn.actor is None
    entries = found.chosen_entries()
    assert composition_problems(entries, spec.scenic_class) == []
    draft = assemble(found, spec.scenic_class, TRUCKS, params={})
    assert draft.script.count("= new Truck at actor") == 2
    assert "# kb: behavior.slow_to_block as actor3" in draft.script
    assert "param OPT_ACTOR3_SPAWN_GAP = Range(37, 47)" in draft.script  # behind actor2


def test_an_oncoming_bus_gets_a_geometry_with_an_oncoming_lane(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    spec, found = retrieved(kb, maps, BUS, "A stalled car")
    [geometry] = found.chosen[Component.GEOMETRY]
    assert "oncomingSection" in geometry.defines
    [bus] = found.actors
    assert bus.spawn.id == "spawn.oncoming_lane_ahead"
    assert bus.behavior.id == "behavior.cruise_constant"
    assert [e.id for e in found.chosen[Component.BEHAVIOR]] == ["behavior.stalled"]
    assert found.chosen[Component.MISC] == []


@pytest.mark.parametrize(
    ("text", "adversary", "read"),
    [
        (
            "A car pulls out in front of the ego while a truck is parked on the right.",
            "A car",
            RelativePosition.ROADSIDE_RIGHT,
        ),
        # parked "in the lane" beside the ego: no spawn parks a car in a lane of traffic
        (
            "A moped comes the other way while a box van is parked in the lane to the ego's"
            " right, half on the pavement.",
            "A moped",
            RelativePosition.ADJACENT_LANE_RIGHT,
        ),
    ],
)
def test_a_parked_actor_stays_put_at_the_kerb_of_its_side(
    kb: KnowledgeBase,
    maps: dict[str, frozenset[str]],
    text: str,
    adversary: str,
    read: RelativePosition,
) -> None:
    _, found = retrieved(kb, maps, text, adversary)
    [parked] = found.actors
    assert parked.actor.role is ActorRole.PARKED
    assert parked.actor.start is read
    assert parked.spawn.approach is not None and parked.spawn.approach.value == "roadside_right"
    assert set(parked.behavior.tags) & {"static", "stalled"}


def test_occluders_and_props_are_still_misc_entries(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    _, found = retrieved(kb, maps, VAN, "A pedestrian")
    assert found.actors == []
    assert [e.id for e in found.chosen[Component.MISC]] == ["misc.occluder_parked_van"]


def test_an_occluder_at_the_kerb_across_from_the_adversary_stands_where_the_text_puts_it(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    # the occluder entries stand by the adversary; a cyclist coming the other way is on
    # the far side, and the van is at the right kerb: it gets a parked spawn of its own
    text = (
        "A cyclist comes the other way while a girl steps out from behind a van parked at "
        "the right kerb."
    )
    spec, found = retrieved(kb, maps, text, "A cyclist")
    assert spec.spawn_position is RelativePosition.ONCOMING
    [van] = [a for a in spec.actors if a.scenic_class.value == "Van"]
    assert van.start is RelativePosition.ROADSIDE_RIGHT
    [placed] = [p for p in found.actors if p.actor is van]
    assert placed.spawn.approach is not None and placed.spawn.approach.value == "roadside_right"
    assert set(placed.behavior.tags) & {"static", "stalled"}
    assert not any("occluder" in e.tags for e in found.chosen[Component.MISC])


def test_an_occluder_the_text_puts_in_the_oncoming_lane_drives_there(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    text = (
        "On a two-way street an oncoming lorry hides a boy who runs out from the left in"
        " front of the ego."
    )
    spec, found = retrieved(kb, maps, text, "a boy")
    [lorry] = [a for a in spec.actors if a.role is ActorRole.OCCLUDER]
    assert lorry.start is RelativePosition.ONCOMING
    [placed] = found.actors
    assert placed.spawn.id == "spawn.oncoming_lane_ahead"
    assert not set(placed.behavior.tags) & {"static", "stalled"}
    assert not any("occluder" in e.tags for e in found.chosen[Component.MISC])


def test_oncoming_traffic_at_a_junction_gets_the_far_approach_not_the_adversarys_route(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    text = (
        "At the crossroads the ego turns left on green. A pickup coming the other way goes"
        " straight on, and an oncoming taxi waits behind it."
    )
    _, found = retrieved(kb, maps, text, "A pickup")
    [adversary_spawn] = found.chosen[Component.SPAWN]
    assert adversary_spawn.id == "spawn.junction_conflict_route"
    [taxi] = found.actors
    assert taxi.spawn.id == "spawn.junction_oncoming_approach"
    assert taxi.spawn.actor == "actor2"


@pytest.mark.parametrize(
    ("text", "entry"),
    [
        (
            "Three cardboard boxes lie across the ego's lane as a van comes the other way.",
            "misc.boxes_across_lane_ahead",
        ),
        (
            "A cardboard box lies in the ego's lane as a van comes the other way.",
            "misc.box_in_lane_ahead",
        ),
    ],
)
def test_a_counted_prop_is_placed_as_many_times_as_the_text_counts(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], text: str, entry: str
) -> None:
    _, found = retrieved(kb, maps, text, "a van")
    assert [e.id for e in found.chosen[Component.MISC]] == [entry]


@pytest.mark.parametrize(
    ("text", "entry"),
    [
        (
            "A steel plate lies in the ego's lane as a van comes the other way.",
            "misc.plate_in_lane_ahead",
        ),
        (
            "Turning left, the ego meets a road plate just past the corner as a van comes the "
            "other way.",
            "misc.plate_in_exit_lane",
        ),
    ],
)
def test_a_road_plate_is_placed_where_the_text_puts_it(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], text: str, entry: str
) -> None:
    spec, found = retrieved(kb, maps, text, "a van")
    assert [a.scenic_class.value for a in spec.actors] == ["IronPlate"]
    assert [e.id for e in found.chosen[Component.MISC]] == [entry]


def test_no_misc_entry_puts_an_actor_where_the_text_does_not(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    text = (
        "At a T-junction the ego turns left out of the side road; a van comes from the right,"
        " and a cyclist rides toward the ego on the main road."
    )
    spec, found = retrieved(kb, maps, text, "a van")
    [cyclist] = spec.actors
    assert cyclist.start is RelativePosition.ONCOMING
    # no spawn fits at a T-junction's stem, and the only misc cyclist rides ahead the same way
    assert found.actors == []
    assert "misc.cyclist_riding_ahead" not in [e.id for e in found.chosen[Component.MISC]]
    assert any("left out" in note for note in found.notes)


def test_a_walker_said_to_cross_from_a_corner_does_not_walk_along_first(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    text = (
        "The ego turns right onto Kiln Lane on a green arrow; a woman steps off the far corner"
        " and walks across Kiln Lane."
    )
    spec, found = retrieved(kb, maps, text, "a woman")
    assert spec.start_detail is not None
    [behavior] = found.chosen[Component.BEHAVIOR]
    assert "sudden_turn" not in behavior.tags


def test_a_spec_without_actors_retrieves_as_before(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    spec = spec_of(TRUCKS, "a car").model_copy(update={"actors": []})
    found = retrieve(spec, kb, BM25Retriever(kb), maps, TRUCKS)
    assert found.actors == []
    assert all(e.actor is None for e in found.chosen_entries())


# -- repair ---------------------------------------------------------------------------------


def context_for(found: Retrieval, spec: ScenarioSpec, maps: dict[str, frozenset[str]]):
    draft = assemble(found, spec.scenic_class, TRUCKS, params={})
    return RepairContext(
        description=TRUCKS,
        retrieval=found,
        draft=draft,
        provider=None,
        rules=RuleContext(adversary_class=spec.scenic_class),
        maps=maps,
    )


def test_a_diagnostic_about_an_actor_drops_that_actor(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    spec, found = retrieved(kb, maps, TRUCKS, "a car")
    context = context_for(found, spec, maps)
    script = context.draft.script
    line = next(
        n for n, text in enumerate(script.splitlines(), 1) if text.startswith("actor3 = new")
    )
    diagnostic = Diagnostic(
        stage=Stage.SAMPLE,
        error_type="RejectionException",
        message="failed to generate a scenario",
        rejections=[Rejection(reason="object intersects", count=200, line=line)],
    )
    assert guilty_actor(script, diagnostic) == "actor3"
    step = repair_once(context, script, diagnostic)
    assert step.kind is AttemptKind.SWAP and step.draft is not None
    assert step.detail == "dropped actor3 (behavior.slow_to_block, spawn.lead_same_lane)"
    assert step.script is not None and "actor3" not in step.script
    assert "actor2 = new Truck" in step.script
    adversary = next(
        n for n, text in enumerate(script.splitlines(), 1) if text.startswith("adversary = ")
    )
    assert (
        guilty_actor(script, diagnostic.model_copy(update={"rejections": [], "line": adversary}))
        is None
    )


def test_a_swap_replaces_the_adversarys_spawn_and_keeps_the_actors(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    from arise.generate.repair import swap_section

    spec, found = retrieved(kb, maps, TRUCKS, "a car")
    context = context_for(found, spec, maps)
    step = swap_section(context, "SPAWN")
    assert step is not None and step.draft is not None
    spawns = [e for e in step.draft.entries if e.component is Component.SPAWN]
    assert [e.actor for e in spawns].count(None) == 1
    assert sorted(e.actor for e in spawns if e.actor) == ["actor2", "actor3"]
    assert spawns[0].id != found.chosen[Component.SPAWN][0].id


def test_a_truck_the_adversary_walks_out_from_in_front_of_hides_it() -> None:
    text = "The ego passes a truck double-parked on the right; a man walks out from in front of the truck."
    [truck] = spec_of(text, "a man").actors
    assert truck.role is ActorRole.OCCLUDER


def test_an_actor_says_what_it_rests_on() -> None:
    [trucks] = spec_of(TRUCKS, "a car").actors
    assert trucks.describe() == "actor: 2 Truck, slow, ahead same lane ('Two slow trucks')"


# -- the generator ----------------------------------------------------------------------------


def test_a_run_places_the_actors_tunes_only_the_adversary_and_drops_a_failing_actor(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], tmp_path: Path
) -> None:
    # a time the rules leave to the model's tuning
    trucks = TRUCKS + " The trucks keep 2 seconds apart."
    extraction = answer("a car", "adjacent_lane_left")
    spec = ground(trucks, extraction).spec
    found = retrieve(spec, kb, BM25Retriever(kb), maps, trucks, topk=10)
    own = [e for e in found.chosen_entries() if e.actor is None]
    defaults = {name: value for name, (value, _) in declared_params(own).items()}
    script = assemble(found, spec.scenic_class, trucks, params={}).script
    line = next(
        n for n, text in enumerate(script.splitlines(), 1) if text.startswith("actor3 = new")
    )
    overlap = failed(
        Stage.SAMPLE,
        "RejectionException",
        "failed to generate a scenario",
        rejections=[Rejection(reason="object intersects", count=250, line=line)],
    )
    model = ScriptedProvider([extraction.model_dump_json(), json.dumps(defaults)])
    checker = FakeValidator([overlap, passed()])
    options = GenerateOptions(
        retrieval="bm25", semantic_gate=False, model_extraction=ModelExtraction.ALWAYS
    )
    with Generator(options, provider=UsageLedger(model), checker=checker) as generator:
        run = generator.generate(trucks, tmp_path)
    assert run.status is RunStatus.EXECUTED, run.message
    tune = model.requests[1].messages[-1].content
    assert "OPT_SPAWN_BEHIND" in tune and "OPT_ACTOR" not in tune
    assert checker.scripts[0] == script
    assert "actor3" not in checker.scripts[1] and "actor2 = new Truck" in checker.scripts[1]
    assert run.attempts[1].detail == "dropped actor3 (behavior.slow_to_block, spawn.lead_same_lane)"
    report = json.loads((tmp_path / "report.json").read_text())
    assert [a["name"] for a in report["placed_actors"]] == ["actor2", "actor3"]
    assert "spawn.lead_same_lane as actor2" in report["chosen"]
    assert "spawn.lead_same_lane as actor3" not in report["chosen"]


def test_a_rejection_without_a_line_that_names_an_actors_class_is_about_that_actor(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    spec, found = retrieved(kb, maps, TRUCKS, "a car")
    context = context_for(found, spec, maps)
    reason = "Containment violation: unnamed Truck is not contained in its container"
    diagnostic = Diagnostic(
        stage=Stage.SAMPLE,
        error_type="RejectionException",
        message="no scene satisfied the requirements",
        rejections=[Rejection(reason=reason, count=500)],
    )
    script, entries = context.draft.script, context.draft.entries
    assert guilty_actor(script, diagnostic, entries) == "actor3"
    assert guilty_actor(script, diagnostic) is None  # no entries: no actor to blame
    car = diagnostic.model_copy(
        update={"rejections": [Rejection(reason=reason.replace("Truck", "Car"), count=500)]}
    )
    assert guilty_actor(script, car, entries) is None  # the adversary's class


def test_waiting_behind_a_vehicle_does_not_make_it_an_occluder() -> None:
    text = (
        "The ego waits behind a stopped bus at a T-junction when a motorcycle comes from the right."
    )
    [bus] = spec_of(text, "a motorcycle").actors
    assert (bus.role, bus.stationary) == (ActorRole.STOPPED, True)
    text = "The ego turns left while an oncoming car goes straight and a pedestrian waits on the right sidewalk."
    [walker] = spec_of(text, "an oncoming car").actors
    assert walker.stationary and walker.start is RelativePosition.ROADSIDE_RIGHT


# -- conformity -----------------------------------------------------------------------------


def _trace(name: str, kind: str, x: float, y: float, **fields: object) -> AgentTrace:
    """An agent standing at (x, y) facing +y (the ego's heading at the origin)."""
    point = TracePoint(step=0, x=x, y=y, heading=0.0, speed=0.0)
    return AgentTrace(name=name, kind=kind, width=2.0, length=5.0, trajectory=[point], **fields)


def _facts(agents: list[AgentTrace]) -> SimulationFacts:
    return SimulationFacts(
        agents=agents, steps=1, timestep=0.1, termination_type="steps", termination_reason=""
    )


def test_conformity_sees_each_actor_on_its_side_without_gating_it() -> None:
    spec = spec_of(TRUCKS, "a car")
    agents = [
        _trace("ego", "Car", 0, 0, is_ego=True),
        _trace("Car2", "Car", -3.5, -12, behavior="AdversaryBehavior"),
        _trace("Truck1", "Truck", 0, 20, behavior="Actor2Behavior"),
        _trace("Truck2", "Truck", -3.5, 40, behavior="Actor3Behavior"),  # in the left lane
    ]
    conformity = check_conformity(spec, _facts(agents))
    [check] = [c for c in conformity.checks if c.name == "actor 1"]
    assert (check.expected, check.observed, check.ok) == (
        "2 Truck ahead_same_lane",
        "2 Truck, 1 there",
        False,
    )
    assert all(not c.check.startswith("actor") for c in contradictions(conformity))
    agents[-1] = _trace("Truck2", "Truck", 0, 40, behavior="Actor3Behavior")
    [check] = [c for c in check_conformity(spec, _facts(agents)).checks if c.name == "actor 1"]
    assert check.ok


def test_the_others_of_a_counted_adversary_are_copies_of_its_entries(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    text = "Three cyclists ride ahead of the ego in its lane."
    spec, found = retrieved(kb, maps, text, "Three cyclists")
    assert spec.scenic_class == "Bicycle" and spec.participants == []
    assert spec.actors == [
        Actor(role=ActorRole.ADVERSARY, scenic_class="Bicycle", count=2, quote="Three cyclists")
    ]
    [spawn] = found.chosen[Component.SPAWN]
    [behavior] = found.chosen[Component.BEHAVIOR]
    assert [p.name for p in found.actors] == ["actor2", "actor3"]
    assert {p.spawn.id for p in found.actors} == {spawn.id}
    assert {p.behavior.id for p in found.actors} == {behavior.id}
    draft = assemble(found, spec.scenic_class, text, params={})
    gaps = [
        line
        for line in draft.script.splitlines()
        if line.startswith("param OPT_") and "GAP" in line
    ]
    assert len(gaps) == 3 and len(set(gaps)) == 3  # each further out than the one before
    # Neither missing nor extra for the conformity check: the text names three.
    agents = [
        _trace("ego", "Car", 0, 0, is_ego=True),
        _trace("Bicycle1", "Bicycle", 0, 20, behavior="AdversaryBehavior"),
        _trace("Bicycle2", "Bicycle", 0, 35, behavior="Actor2Behavior"),
        _trace("Bicycle3", "Bicycle", 0, 50, behavior="Actor3Behavior"),
    ]
    conformity = check_conformity(spec, _facts(agents))
    assert {
        c.name: c.ok for c in conformity.checks if c.name in ("participants", "extra_actors")
    } == {
        "participants": True,
        "extra_actors": True,
    }


def test_a_geometry_swap_leaves_out_an_actor_the_new_road_has_no_room_for(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    from arise.generate.repair import swap_section

    spec, found = retrieved(kb, maps, BUS, "A stalled car")
    [geometry] = found.chosen[Component.GEOMETRY]
    found.candidates[Component.GEOMETRY] = [geometry, kb.get("geometry.straight_road")]
    context = RepairContext(
        description=BUS,
        retrieval=found,
        draft=assemble(found, spec.scenic_class, BUS, params={}),
        provider=None,
        rules=RuleContext(adversary_class=spec.scenic_class),
        maps=maps,
    )
    step = swap_section(context, "GEOMETRY")
    assert step is not None and step.draft is not None
    assert step.detail == f"{geometry.id} -> geometry.straight_road (without actor2)"
    assert all(e.actor is None for e in step.draft.entries)
    assert "geometry.straight_road" in [e.id for e in step.draft.entries]


def test_an_actors_undeclared_parameter_gets_the_entrys_default() -> None:
    from arise.generate.rules import fix_undeclared_param

    text = "actor2Start = new OrientedPoint ahead of egoStart by globalParameters.OPT_ACTOR2_SPAWN_GAP\n"
    diagnostic = Diagnostic(
        stage=Stage.COMPILE,
        error_type="AttributeError",
        message="'Params' has no attribute 'OPT_ACTOR2_SPAWN_GAP'",
    )
    context = RuleContext(param_defaults={"OPT_SPAWN_GAP": "Range(15, 25)"})
    fix = fix_undeclared_param(diagnostic, text, context)
    assert fix is not None
    assert fix.text.splitlines()[0] == "param OPT_ACTOR2_SPAWN_GAP = Range(15, 25)"


def test_a_road_user_stopped_in_the_road_a_turning_ego_enters_is_placed_in_that_lane(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    text = (
        "The ego turns left at the crossroads. A removal lorry is stopped just past the"
        " corner, and an oncoming moped comes straight on."
    )
    spec, found = retrieved(kb, maps, text, "an oncoming moped")
    [lorry] = spec.actors
    assert lorry.start is RelativePosition.AHEAD_SAME_LANE
    assert lorry.start_detail is StartDetail.EXIT_LANE
    [placed] = found.actors
    assert placed.spawn.id == "spawn.junction_exit_lane_ahead"


@pytest.mark.parametrize(
    ("text", "adversary", "exit_lane"),
    [
        (
            "Turning right at the lights, the AV finds a tractor stopped in the lane it is"
            " entering.",
            "a tractor",
            True,
        ),
        # the words the model quotes no longer decide: "enters" here is the junction
        (
            "The ego turns left as a hatchback enters the junction from the left.",
            "a hatchback",
            False,
        ),
    ],
)
def test_only_a_start_read_in_the_exit_lane_takes_the_exit_lanes_spawn(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], text: str, adversary: str, exit_lane: bool
) -> None:
    # the model quotes the words that once sent it to the exit lane ("enters")
    quoted = answer(adversary).model_copy(update={"behavior": text.split(", ")[-1]})
    spec = ground(text, quoted).spec
    assert "enter" in spec.behavior
    found = retrieve(spec, kb, BM25Retriever(kb), maps, text)
    assert (spec.start_detail is StartDetail.EXIT_LANE) is exit_lane
    [spawn] = found.chosen[Component.SPAWN]
    assert ("exit_lane" in spawn.tags) is exit_lane, spawn.id


def test_a_parked_van_on_the_street_the_ego_turns_onto_is_placed_on_that_street(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    text = (
        "The AV was turning left onto Marlow Street. A delivery van was parked on Marlow"
        " Street, and a scooter came the other way."
    )
    spec, found = retrieved(kb, maps, text, "a scooter")
    [van] = spec.actors
    assert van.role is ActorRole.PARKED
    assert van.start_detail is StartDetail.EXIT_LANE
    [placed] = found.actors
    assert placed.spawn.id == "spawn.junction_exit_lane_ahead"


def test_a_parked_truck_the_ego_goes_round_through_the_oncoming_lane_stays_in_its_lane(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]]
) -> None:
    text = (
        "A removal lorry is parked ahead in the ego's lane; the ego pulls out to pass it"
        " while a moped comes the other way."
    )
    spec, found = retrieved(kb, maps, text, "a moped")
    assert spec.ego_plan is EgoPlan.BYPASS
    [lorry] = spec.actors
    assert lorry.role is ActorRole.PARKED
    [placed] = found.actors
    assert "curb" not in placed.spawn.id and "roadside" not in placed.spawn.id, placed.spawn.id
