"""The default extraction path end to end: descriptions the fixed rules read whole become
scripts that run, with the real validator and no model call at all (the scripted model has
no reply, so any call would fail the run)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from arise.generate.options import GenerateOptions
from arise.generate.pipeline import Generator
from arise.generate.run import RunStatus
from arise.llm.accounting import UsageLedger
from arise.validate import WorkerPool
from tests.fakes import ScriptedProvider

# Written for this test; none of them comes from a labeled set or the held-apart set.
DESCRIPTIONS = [
    (
        "A delivery van parked on the right pulls out into the ego's lane.",
        ("car", "roadside_right"),
    ),
    (
        "ego RT at the lights, jogger on the right sidewalk steps into the crosswalk",
        ("pedestrian", "roadside_right"),
    ),
    (
        "V1 (the AV) was northbound in the #1 lane; V2, a pickup in the #2 lane, "
        "changed lanes into V1.",
        ("truck", "adjacent_lane_right"),
    ),
]


@pytest.mark.slow
@pytest.mark.parametrize(("description", "expected"), DESCRIPTIONS)
def test_a_description_the_rules_read_runs_without_the_model(
    description: str, expected: tuple[str, str], validator_pool: WorkerPool, tmp_path: Path
) -> None:
    model = ScriptedProvider([])
    options = GenerateOptions(retrieval="bm25")
    with Generator(options, provider=UsageLedger(model), pool=validator_pool) as generator:
        run = generator.generate(description, tmp_path)
    assert model.requests == [], [r.messages[-1].content[:60] for r in model.requests]
    assert run.status is RunStatus.EXECUTED, run.message
    assert run.spec is not None
    assert (run.spec.adversary_type.value, run.spec.spawn_position.value) == expected
    report = json.loads((tmp_path / "report.json").read_text())
    assert report["llm"]["calls"] == 0 and report["llm_calls"] == []
    assert any("no model call" in note for note in report["spec_corrections"])
