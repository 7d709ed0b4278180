"""The knowledge base covers what the issue asks for: categories, road users, behaviors."""

from __future__ import annotations

from arise.kb.loader import load_kb
from arise.kb.plan import plan_validation
from arise.kb.runner import builtin_maps
from arise.vocabulary import PAPER_CATEGORIES

KB = load_kb(strict=True)

REQUIRED_BEHAVIORS = [
    "behavior.cross_and_stop",
    "behavior.cross_diagonally",
    "behavior.dash_from_occluder",
    "behavior.sudden_brake",
    "behavior.emergency_stop",
    "behavior.slow_to_block",
    "behavior.accelerate",
    "behavior.cut_in",
    "behavior.weave_between_lanes",
    "behavior.turn_left_across_path",
    "behavior.turn_right_across_path",
    "behavior.run_red_light",
    "behavior.reverse",
    "behavior.swerve",
    "behavior.block_lanes_slowly",
    "behavior.dismount_in_intersection",
    "behavior.stop_in_intersection",
]

# The paper's eight categories and the extra situations, each as tags some entry carries.
REQUIRED_TAGS = [
    *PAPER_CATEGORIES,
    "highway",
    "cyclist",
    "motorcycle",
    "truck",
    "roadside_parked",
    "bus_stop",
    "vending_machine",
    "parked_car",
    "background_traffic",
]


def test_required_behaviors_exist() -> None:
    missing = [i for i in REQUIRED_BEHAVIORS if i not in KB]
    assert not missing


def test_categories_and_situations_are_covered() -> None:
    tags = {tag for entry in KB for tag in entry.tags}
    assert not [t for t in REQUIRED_TAGS if t not in tags]


def test_every_adversary_class_has_behaviors_and_spawns() -> None:
    for adversary in ("Car", "Truck", "Motorcycle", "Bicycle", "Pedestrian"):
        assert sum(e.suits(adversary) for e in KB.of("behavior")) >= 3, adversary
        assert sum(e.suits(adversary) for e in KB.of("spawn")) >= 3, adversary


def test_every_entry_has_a_script_in_the_plan() -> None:
    plan = plan_validation(list(KB), builtin_maps())
    assert not plan.uncovered
    covered = {i for c in plan.compositions for i in c.ids}
    assert covered == set(KB.entries)
    # Compact enough for CI: a few entries per script.
    assert len(plan.compositions) <= 75
