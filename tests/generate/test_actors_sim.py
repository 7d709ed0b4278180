"""Several actors, proven on the real Scenic compiler and simulator on our shipped maps.

The description is grounded with a scripted model answer, retrieved, assembled with the
entries' default parameters and run; the trace is scored against truth written by hand:
every actor the text names is there, as many as it says, on its side, going its way, and
nothing else is.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from arise.evaluate.fidelity import (
    Direction,
    FactKind,
    LabeledActor,
    Start,
    Truth,
    score_fidelity,
)
from arise.generate.assemble import assemble
from arise.generate.conformity import check_conformity, contradictions
from arise.generate.grounding import ground
from arise.generate.options import GenerateOptions
from arise.generate.repair import RepairContext, repair_loop
from arise.generate.retrieve import retrieve
from arise.generate.rules import RuleContext
from arise.generate.run import Generation, RunStatus
from arise.generate.spec import ExtractionAnswer
from arise.kb.loader import KnowledgeBase, load_kb
from arise.kb.retrieval import BM25Retriever
from arise.maps.registry import MapRegistry
from arise.validate import CheckOptions, CheckResult, WorkerPool, check_text

SEEDS = (0, 1)
ACTOR_FACTS = {FactKind.ACTOR, FactKind.NO_EXTRA_ACTORS, FactKind.START, FactKind.DIRECTION}
# (description, the model's words for the adversary and its side, the truth)
CASES = [
    (
        "Two slow trucks drive ahead in the ego's lane and a car overtakes the ego from "
        "behind on the left.",
        "a car",
        "adjacent_lane_left",
        Truth(
            actors=(
                LabeledActor("Truck", 2, start=Start.AHEAD, direction=Direction.SAME),
                LabeledActor("Car", 1, start=Start.LEFT_REAR, direction=Direction.SAME),
            )
        ),
    ),
    (
        "A stalled car blocks the ego's lane ahead while an oncoming bus approaches.",
        "A stalled car",
        "ahead_same_lane",
        Truth(
            actors=(
                LabeledActor("Car", 1, start=Start.AHEAD, direction=Direction.STATIONARY),
                LabeledActor("Bus", 1, start=Start.ONCOMING, direction=Direction.OPPOSITE),
            )
        ),
    ),
    (
        "Three cyclists ride ahead of the ego in its lane.",
        "Three cyclists",
        "ahead_same_lane",
        Truth(actors=(LabeledActor("Bicycle", 3, start=Start.AHEAD, direction=Direction.SAME),)),
    ),
    (
        "The ego follows a slow car while a motorcycle comes up behind it.",
        "a motorcycle",
        "behind_same_lane",
        Truth(
            actors=(
                LabeledActor("Car", 1, start=Start.AHEAD, direction=Direction.SAME),
                LabeledActor("Motorcycle", 1, start=Start.BEHIND, direction=Direction.SAME),
            )
        ),
    ),
    (
        # a second road user from the other side of the junction: the cross street's far
        # approach, not a car pulling out from the kerb
        "At a crossroads with no signals the ego goes straight on. A motorcycle comes from "
        "the left and a van comes from the right at the same moment.",
        "A motorcycle",
        "crossing_road_from_left",
        Truth(
            actors=(
                LabeledActor(
                    "Motorcycle", 1, start=Start.LEFT, direction=Direction.CROSSING_LEFT_TO_RIGHT
                ),
                LabeledActor(
                    "Van", 1, start=Start.RIGHT, direction=Direction.CROSSING_RIGHT_TO_LEFT
                ),
            )
        ),
    ),
]


@pytest.fixture(scope="module")
def kb() -> KnowledgeBase:
    return load_kb(builtin=True)


@pytest.fixture(scope="module")
def maps() -> dict[str, frozenset[str]]:
    return {name: entry.features for name, entry in MapRegistry().entries.items()}


@pytest.mark.slow
@pytest.mark.parametrize(("text", "adversary", "position", "truth"), CASES)
def test_every_named_actor_runs_on_its_side(
    kb: KnowledgeBase,
    maps: dict[str, frozenset[str]],
    validator_pool: WorkerPool,
    text: str,
    adversary: str,
    position: str,
    truth: Truth,
) -> None:
    answer = ExtractionAnswer.model_validate(
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
    spec = ground(text, answer).spec
    found = retrieve(spec, kb, BM25Retriever(kb), maps, text)
    chosen = [e.label for e in found.chosen_entries()]
    assert found.actors, chosen
    draft = assemble(found, spec.scenic_class, text, params={})
    for seed in SEEDS:
        result = check_text(draft.script, CheckOptions(seed=seed, timeout=60), pool=validator_pool)
        assert result.ok and result.simulation is not None, (chosen, result.diagnostic)
        fidelity = score_fidelity(truth, result, maps[draft.map_name])
        wrong = [
            f"{v.name}: expected {v.expected}, observed {v.observed}"
            for v in fidelity.verdicts
            if v.fact in ACTOR_FACTS and v.match is False
        ]
        assert not wrong, (chosen, seed, wrong)
        behaviors = sorted(a.behavior or "" for a in result.simulation.agents if not a.is_ego)
        assert behaviors.count("AdversaryBehavior") == 1, behaviors
        # The conformity check against the spec sees each actor too (not gated).
        conformity = check_conformity(spec, result.simulation)
        checks = [c for c in conformity.checks if c.name.startswith("actor ")]
        assert len(checks) == len(spec.actors) and all(c.ok for c in checks), checks
        assert not [c for c in contradictions(conformity) if c.check.startswith("actor")]


@pytest.mark.slow
def test_an_actor_that_cannot_be_placed_is_left_out_by_the_repair_loop(
    kb: KnowledgeBase, maps: dict[str, frozenset[str]], validator_pool: WorkerPool
) -> None:
    """A bus put 'ahead' of the ego far beyond the end of the road does not fit on it
    (every sample is rejected, and the rejection names no line, only the class): the loop
    leaves the bus out and the scene with the adversary runs. (The gap is set out of reach
    by hand: on our maps the KB's own gaps now always fit.)"""
    text = (
        "The ego waits behind a stopped bus at a T-junction when a motorcycle comes from the right."
    )
    answer = ExtractionAnswer.model_validate(
        {
            "adversary": "a motorcycle",
            "adversary_type": "motorcycle",
            "behavior": "",
            "road_type": "t_junction",
            "ego_maneuver": "go_straight",
            "geometry": "",
            "spawn_position": "crossing_road_from_right",
            "spawn": "",
        }
    )
    spec = ground(text, answer).spec
    found = retrieve(spec, kb, BM25Retriever(kb), maps, text)
    [bus] = found.actors
    assert bus.actor.scenic_class == "Bus"
    draft = assemble(found, spec.scenic_class, text, params={})
    gap = "param OPT_ACTOR2_SPAWN_GAP = Range(15, 25)"
    assert gap in draft.script
    draft = replace(draft, script=draft.script.replace(gap, "param OPT_ACTOR2_SPAWN_GAP = 900"))
    context = RepairContext(
        description=text,
        retrieval=found,
        draft=draft,
        provider=None,
        rules=RuleContext(adversary_class=spec.scenic_class),
        maps=maps,
    )
    run = Generation(description=text, options=GenerateOptions(), spec=spec, retrieval=found)
    run.use_draft(draft)

    def validate(script: str) -> CheckResult:
        return check_text(script, CheckOptions(seed=0, timeout=60), pool=validator_pool)

    outcome = repair_loop(run, draft.script, validate, context, max_repairs=2)
    assert outcome.status is RunStatus.EXECUTED, [a.detail for a in run.attempts]
    first, *_, last = run.attempts
    assert not first.ok and first.diagnostic is not None
    assert "unnamed Bus" in first.diagnostic.rejections[0].reason
    assert last.ok and last.detail.startswith("dropped actor2 (")
    assert "actor2" not in last.script
