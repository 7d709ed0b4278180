"""A description that names no road user causing the danger (debris, cones, a slippery
road) becomes a scene with no adversary: a geometry, the named objects and the weather.

Real knowledge base, real Scenic compiler and simulator; the model's answer is scripted
(it names an adversary anyway, as the small model does)."""

from __future__ import annotations

import pytest

from arise.generate.assemble import assemble
from arise.generate.conformity import check_conformity
from arise.generate.grounding import ground
from arise.generate.retrieve import retrieve
from arise.generate.spec import ExtractionAnswer
from arise.kb.compose import composition_problems
from arise.kb.loader import load_kb
from arise.kb.retrieval import BM25Retriever
from arise.kb.schema import Component
from arise.maps.registry import MapRegistry
from arise.validate import CheckOptions, WorkerPool, check_text

ANSWER = ExtractionAnswer.model_validate(
    {
        "adversary": "a car",
        "adversary_type": "car",
        "behavior": "",
        "road_type": "straight_road",
        "ego_maneuver": "go_straight",
        "geometry": "",
        "spawn_position": "ahead_same_lane",
        "spawn": "",
    }
)


def test_a_text_without_road_users_has_no_adversary() -> None:
    spec = ground("Four cones narrow the ego's lane on a quiet road.", ANSWER).spec
    assert spec.no_adversary
    assert [p.split()[:2] for p in spec.participants] == [["Four", "cones"]]
    assert not ground("A cyclist swerves in front of the ego.", ANSWER).spec.no_adversary


def test_a_scene_without_an_adversary_has_no_spawn_or_behavior() -> None:
    kb = load_kb()
    geometry = kb.get("geometry.straight_road")
    spawn = kb.get("spawn.lead_same_lane")
    assert composition_problems([geometry], None) == []
    assert composition_problems([geometry, spawn], None) == [
        "spawn.lead_same_lane: a scene without an adversary has no spawn"
    ]


@pytest.mark.slow
def test_debris_alone_runs_with_the_debris_and_nothing_else(
    validator_pool: WorkerPool,
) -> None:
    text = "On a straight road the ego drives toward some debris lying in its lane."
    spec = ground(text, ANSWER).spec
    kb = load_kb()
    maps = {name: entry.features for name, entry in MapRegistry().entries.items()}
    found = retrieve(spec, kb, BM25Retriever(kb), maps, text)
    assert not found.chosen.get(Component.SPAWN) and not found.chosen.get(Component.BEHAVIOR)
    [misc] = found.chosen[Component.MISC]
    draft = assemble(found, None, text)
    result = check_text(draft.script, CheckOptions(seed=0, timeout=60), pool=validator_pool)
    assert result.ok, result.diagnostic
    assert result.simulation is not None
    kinds = sorted({a.kind for a in result.simulation.agents if not a.is_ego})
    assert kinds == ["Debris"], misc.id
    conformity = check_conformity(spec, result.simulation)
    [adversary] = [c for c in conformity.checks if c.name == "adversary_type"]
    assert adversary.ok and adversary.expected == "no adversary"
