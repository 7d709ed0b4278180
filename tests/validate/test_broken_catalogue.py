"""Deliberately broken scripts: each must fail at the right stage, with type, line, section.

Runs the real validator (Scenic compiler + offline simulator) in an isolated worker.
"""

from __future__ import annotations

import pytest

from arise.validate import CheckOptions, Stage, WorkerPool, check
from tests.conftest import DATA

BROKEN = DATA / "broken"

# name: (stage, error type, acceptable lines, section, words the message or hint must hold)
CATALOGUE: dict[str, tuple[Stage, str, tuple[int, ...], str, str]] = {
    "scenic2_no_new": (Stage.PARSE, "ScenicParseError", (20,), "GEOMETRY", "new"),
    "indentation": (Stage.PARSE, "ScenicParseError", (14,), "BEHAVIOR", "indented"),
    "unclosed_paren": (Stage.PARSE, "ScenicParseError", (28, 29), "REQUIREMENTS", "syntax"),
    "undefined_name_top": (Stage.COMPILE, "NameError", (25,), "SPAWN", "AdversaryBehaviour"),
    "undefined_name_behavior": (
        Stage.SIMULATE,
        "NameError",
        (12,),
        "BEHAVIOR",
        "SetWalkingSpeedAction",
    ),
    "wrong_specifier": (Stage.COMPILE, "SpecifierError", (20,), "GEOMETRY", "position"),
    "type_error_top": (Stage.COMPILE, "TypeError", (18,), "GEOMETRY", "unsupported"),
    "wrong_model": (Stage.COMPILE, "ModuleNotFoundError", (5,), "HEADER", "carla.model"),
    "unknown_blueprint": (
        Stage.SIMULATE,
        "UnknownBlueprintError",
        (17,),
        "GEOMETRY",
        "vehicle.lincoln.mkz_2017",
    ),
    "bad_weather": (Stage.SIMULATE, "WeatherError", (6,), "HEADER", "SunnyNoon"),
    "no_ego": (Stage.SAMPLE, "InvalidScenarioError", (28,), "REQUIREMENTS", "ego"),
    "unsatisfiable_requirement": (
        Stage.SAMPLE,
        "RejectionException",
        (28,),
        "REQUIREMENTS",
        "line 28",
    ),
    "overlapping_spawn": (Stage.SAMPLE, "RejectionException", (25, 28), "", "intersects"),
    "violated_in_simulation": (
        Stage.SIMULATE,
        "RejectionException",
        (30,),
        "REQUIREMENTS",
        "line 30",
    ),
    "attribute_error_behavior": (Stage.SIMULATE, "AttributeError", (12,), "BEHAVIOR", "velocityy"),
    "infinite_loop_behavior": (
        Stage.SIMULATE,
        "StuckBehaviorWarning",
        (12, 13),
        "BEHAVIOR",
        "wait",
    ),
    "infinite_loop_top": (Stage.COMPILE, "CheckTimeout", (18, 19), "GEOMETRY", "longer than"),
    "memory_bomb": (Stage.COMPILE, "MemoryError", (18,), "GEOMETRY", "memory limit"),
    "forbidden_import": (Stage.GATE, "ForbiddenConstruct", (6,), "HEADER", "'os'"),
    "file_write": (Stage.GATE, "ForbiddenConstruct", (18,), "GEOMETRY", "open"),
    "dunder_escape": (Stage.GATE, "ForbiddenConstruct", (18,), "GEOMETRY", "starts with '_'"),
}

OPTIONS = CheckOptions(seed=3, timeout=12, spawn_attempts=4, sample_iterations=300)


def test_catalogue_covers_every_broken_file() -> None:
    assert {p.stem for p in BROKEN.glob("*.scenic")} == set(CATALOGUE)
    assert len(CATALOGUE) >= 15


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_broken_script_is_diagnosed(name: str, validator_pool: WorkerPool) -> None:
    stage, error_type, lines, section, words = CATALOGUE[name]
    result = check(BROKEN / f"{name}.scenic", OPTIONS, pool=validator_pool)
    assert not result.ok
    diagnostic = result.diagnostic
    assert diagnostic is not None
    if name == "infinite_loop_top" and diagnostic.error_type == "Timeout":
        # Now and then, late in a long test run, the parent's hard deadline (12 s + 3 s)
        # comes before the worker's own watchdog answers: the loop is still caught, in the
        # compile stage, and the worker killed, only without the line of the loop.
        assert diagnostic.stage is Stage.COMPILE, diagnostic
        assert "did not finish within 12 s" in diagnostic.message
        return
    assert (diagnostic.stage, diagnostic.error_type) == (stage, error_type), diagnostic
    text = " ".join(
        [diagnostic.message, diagnostic.hint or ""] + [r.reason for r in diagnostic.rejections]
    )
    assert words in text, text
    if name == "overlapping_spawn":
        # The overlap is named, with the line that creates the overlapping object.
        overlap = [r for r in diagnostic.rejections if "intersects" in r.reason]
        assert overlap and overlap[0].line == 25 and overlap[0].section == "SPAWN"
        return
    assert diagnostic.line in lines, diagnostic
    assert diagnostic.section == section
    marked = [row for row in (diagnostic.excerpt or "").splitlines() if row.startswith(">")]
    assert marked and f" {diagnostic.line} |" in marked[0]


@pytest.mark.slow
def test_a_script_that_swallows_the_interrupt_is_killed(tmp_path, validator_pool) -> None:
    script = tmp_path / "stubborn.scenic"
    script.write_text(
        (BROKEN.parent / "base_crossing.scenic")
        .read_text()
        .replace(
            'EGO_MODEL = "vehicle.lincoln.mkz_2017"',
            'EGO_MODEL = "vehicle.lincoln.mkz_2017"\n'
            "while True:\n    try:\n        while True:\n            pass\n"
            "    except BaseException:\n        pass",
        )
    )
    result = check(script, OPTIONS.model_copy(update={"timeout": 5}), pool=validator_pool)
    assert result.diagnostic is not None
    assert result.diagnostic.error_type == "Timeout"
    assert result.diagnostic.stage is Stage.COMPILE
    # The pool replaced the killed worker and still answers.
    good = check(BROKEN.parent / "base_crossing.scenic", OPTIONS, pool=validator_pool)
    assert good.ok, good.diagnostic
