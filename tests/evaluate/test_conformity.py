"""The deterministic conformity check on real simulations, with planted mismatches."""

from __future__ import annotations

from pathlib import Path

import pytest

from arise.evaluate.criticality import criticality
from arise.generate.conformity import check_conformity, semantic_gate
from arise.generate.options import GenerateOptions
from arise.generate.pipeline import Generator
from arise.generate.spec import ScenarioSpec
from arise.validate import CheckOptions, CheckResult, Stage, check

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "pedestrian_crossing.scenic"

TRUE_SPEC = dict(
    adversary_type="pedestrian",
    behavior="crosses the road in front of the ego",
    road_type="straight_road",
    ego_maneuver="go_straight",
    geometry="straight road",
    spawn_position="crossing_road_from_right",
    spawn="on the right sidewalk ahead",
    participants=[],
    weather="ClearNoon",
    requirements=[],
)


@pytest.fixture(scope="module")
def example_run(validator_pool) -> CheckResult:
    result = check(EXAMPLE, CheckOptions(seed=0), pool=validator_pool)
    assert result.ok and result.simulation is not None
    return result


def _spec(**changes: object) -> ScenarioSpec:
    return ScenarioSpec.model_validate({**TRUE_SPEC, **changes})


@pytest.mark.slow
def test_the_true_spec_conforms(example_run: CheckResult) -> None:
    conformity = check_conformity(_spec(), example_run.simulation)
    assert conformity.mismatches == [] and conformity.score == 1.0
    names = {c.name for c in conformity.checks}
    assert {
        "adversary_type",
        "ego_maneuver",
        "road_type",
        "spawn_position",
        "reaches_ego_path",
        "weather",
        "participants",
    } <= names


@pytest.mark.slow
@pytest.mark.parametrize(
    ("changes", "wrong"),
    [
        ({"adversary_type": "car"}, "adversary_type"),
        ({"spawn_position": "crossing_road_from_left"}, "spawn_position"),
        ({"weather": "HardRainNight"}, "weather"),
        ({"ego_maneuver": "turn_left", "road_type": "intersection"}, "ego_maneuver"),
        (
            {
                "participants": ["parked van on the right"],
                "actors": [
                    {"role": "parked", "scenic_class": "Van", "quote": "parked van on the right"}
                ],
            },
            "participants",
        ),
    ],
)
def test_planted_mismatches_are_caught(
    example_run: CheckResult, changes: dict[str, object], wrong: str
) -> None:
    conformity = check_conformity(_spec(**changes), example_run.simulation)
    assert [m.split(":")[0] for m in conformity.mismatches][:1] == [wrong] or wrong in [
        m.split(":")[0] for m in conformity.mismatches
    ]
    assert conformity.score is not None and conformity.score < 1.0


@pytest.mark.slow
def test_a_weaving_ego_fails_the_ego_maneuver_check(example_run: CheckResult) -> None:
    assert example_run.simulation is not None
    agents = [
        a.model_copy(update={"weaving": True}) if a.is_ego else a
        for a in example_run.simulation.agents
    ]
    facts = example_run.simulation.model_copy(update={"agents": agents})
    conformity = check_conformity(_spec(), facts)
    check = next(c for c in conformity.checks if c.name == "ego_maneuver")
    assert check.observed == "weaving" and check.ok is False


@pytest.mark.slow
def test_criticality_reads_the_adversary_pair(example_run: CheckResult) -> None:
    crit = criticality(example_run.simulation)
    assert crit is not None and crit.min_distance is not None and crit.min_distance >= 0
    assert crit.route_completion is not None and 0 < crit.route_completion <= 1


@pytest.mark.slow
def test_semantic_gate_fails_a_running_script_that_says_something_else(
    example_run: CheckResult, validator_pool
) -> None:
    with Generator(GenerateOptions(semantic_gate=True), pool=validator_pool) as generator:
        passed = semantic_gate(example_run, generator.conformity_of(_spec(), example_run))
        failed = semantic_gate(
            example_run,
            generator.conformity_of(
                _spec(adversary_type="truck", weather="ClearNight"), example_run
            ),
        )
    assert passed.ok
    assert not failed.ok and failed.diagnostic is not None
    assert failed.diagnostic.stage is Stage.SEMANTIC
    assert failed.diagnostic.section == "SPAWN"
    assert "adversary_type" in failed.diagnostic.message and "weather" in failed.diagnostic.message


@pytest.mark.slow
def test_every_run_reports_its_conflict_and_the_gate_holds_a_stated_contact(
    example_run: CheckResult,
) -> None:
    conformity = check_conformity(_spec(), example_run.simulation)
    conflict = conformity.as_dict()["conflict"]
    assert conflict is not None and conflict["asked"] == "reach"
    pair = next(
        c for c in conformity.checks if c.name == "conflict"
    )  # the crossing pedestrian meets the ego
    assert pair.ok is True and conflict["met"] is True
    assert conflict["closest_m"] is not None and conflict["closest_m"] < 6
    # Told that the two touched, the same run must show contact or a TTC under 1.5 s.
    touched = check_conformity(_spec(contact_stated=True), example_run.simulation)
    close = next(c for c in touched.checks if c.name == "conflict")
    assert close.expected == "contact or TTC under 1.5 s"
    assert close.ok is (conflict["contact"] or (conflict["min_ttc_s"] or 99) < 1.5)
    # A parked adversary is asked for no conflict at all.
    parked = check_conformity(_spec(adversary_stationary=True), example_run.simulation)
    assert "conflict" not in {c.name for c in parked.checks}
    assert parked.conflict is not None and parked.conflict["asked"] == "none"
