"""The generator end to end: real KB, real validator, LLM answers replayed from cassettes
recorded from the embedded Qwen2.5-Coder-1.5B model (see tests/generate_cases.py)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from arise.generate.options import GenerateOptions
from arise.generate.pipeline import Generator
from arise.validate import CheckOptions, WorkerPool, check, check_text
from tests.conftest import DATA
from tests.generate_cases import CASES


def _run(name: str, out: Path, pool: WorkerPool):
    case = CASES[name]
    with Generator(case.options(replay=str(case.cassette)), pool=pool) as generator:
        return generator.generate(case.description, out)


def _report(out: Path) -> dict:
    return json.loads((out / "report.json").read_text())


@pytest.mark.slow
def test_first_try_success_writes_script_report_and_picture(tmp_path, validator_pool) -> None:
    run = _run("first_try", tmp_path, validator_pool)
    assert run.ok and run.first_pass_ok and run.repairs == 0
    report = _report(tmp_path)
    assert report["status"] == "executed" and report["spec"]["adversary_type"] == "bicycle"
    assert report["chosen"] and all(report["retrieved"].values())
    # the extraction only: the text states no number, so no tuning call
    assert report["llm"]["calls"] == 1 and report["llm"]["prompt_tokens"] > 0
    assert any("no tuning call" in note for note in report["retrieval_notes"])
    assert (tmp_path / "scene.png").read_bytes()[:4] == b"\x89PNG"
    script = (tmp_path / "scenario.scenic").read_text()
    assert "# BEGIN BEHAVIOR" in script and "ARISE: FAILED" not in script
    # The saved script really executes.
    assert check(tmp_path / "scenario.scenic", CheckOptions(seed=0), pool=validator_pool).ok
    # Every run says which confinement its script ran under.
    assert report["sandbox"]["active"] and not report["sandbox"]["missing"]
    assert all(a["sandbox"].startswith("landlock+seccomp") for a in report["attempts"])


@pytest.mark.slow
def test_success_after_a_rule_fix(tmp_path, validator_pool) -> None:
    run = _run("rule_fix", tmp_path, validator_pool)
    assert run.ok and not run.first_pass_ok
    kinds = [attempt.kind for attempt in run.attempts]
    assert kinds[0] == "initial" and kinds[-1] == "rule"
    attempts = _report(tmp_path)["attempts"]
    assert attempts[0]["diagnostic"]["error_type"] == "NameError"
    assert "SetWalkingSpeedAction" in run.attempts[-1].script
    assert attempts[-1]["diff"].startswith("--- before.scenic")
    assert len(list((tmp_path / "attempts").glob("*.scenic"))) == len(attempts)


@pytest.mark.slow
def test_success_after_an_llm_repair_of_the_failing_section(tmp_path, validator_pool) -> None:
    run = _run("llm_repair", tmp_path, validator_pool)
    assert run.ok
    first, last = run.attempts[0], run.attempts[-1]
    assert first.diagnostic is not None and first.diagnostic.error_type == "TypeError"
    assert first.diagnostic.section == "BEHAVIOR"
    assert last.kind == "llm" and last.ok and last.llm_usage.calls == 1
    # Only the failing section changed.
    changed = [
        line
        for line in last.diff.splitlines()
        if line.startswith(("+", "-")) and not line.startswith(("+++", "---"))
    ]
    assert changed and all(
        "SetWalking" in line
        or not line.strip("+- ")
        or "Action" in line
        or "behavior" in line
        or "while" in line
        or "take" in line
        for line in changed
    )


@pytest.mark.slow
def test_gives_up_after_the_budget_and_keeps_the_script(tmp_path, validator_pool) -> None:
    run = _run("give_up", tmp_path, validator_pool)
    assert run.status == "failed" and len(run.attempts) == 2  # initial + max_repairs=1
    assert "budget" in (run.message or "")
    script = (tmp_path / "scenario.scenic").read_text()
    assert script.startswith("# ARISE: FAILED")
    assert _report(tmp_path)["attempts"][-1]["diagnostic"]["stage"] == "simulate"


@pytest.mark.slow
def test_single_pass_and_chatscene_modes_do_not_repair(tmp_path, validator_pool) -> None:
    single = _run("single_pass", tmp_path / "single", validator_pool)
    assert single.ok and len(single.attempts) == 1
    baseline = _run("chatscene", tmp_path / "chatscene", validator_pool)
    assert baseline.usage.calls == 1, "ChatScene mode makes only the extraction call"
    assert len(baseline.attempts) == 1 and not baseline.ok
    assert _report(tmp_path / "chatscene")["mode"] == "chatscene"


@pytest.mark.slow  # the generator warms its validator pool on start
def test_bad_descriptions_are_refused_without_a_model(tmp_path) -> None:
    options = GenerateOptions(provider="replay", replay=str(tmp_path / "none.jsonl"))
    with Generator(options) as generator:
        for text in ("", "   ", "Bake a chocolate cake with three eggs."):
            run = generator.generate(text, tmp_path / "out")
            assert run.status == "refused" and run.message
    assert not (tmp_path / "out").exists(), "a refused description writes nothing"


@pytest.mark.slow
def test_rejected_simulations_are_resampled_within_the_spawn_budget(validator_pool) -> None:
    text = (
        (DATA / "base_crossing.scenic")
        .read_text()
        .replace(
            "terminate when (distance to EgoSpawnPt) > 60",
            "require always (distance from ego to EgoSpawnPt) < 10\n"
            "terminate when (distance to EgoSpawnPt) > 60",
        )
    )
    result = check_text(text, CheckOptions(seed=1, spawn_attempts=15), pool=validator_pool)
    assert result.ok and result.spawn_attempts_used > 1
    assert result.simulation_rejections and result.simulation_rejections[0].line == 30


@pytest.mark.slow
def test_a_reply_cut_off_at_the_token_limit_gives_way_to_the_rules_reading(
    tmp_path, validator_pool
) -> None:
    """Recorded: the model's extraction ran into its token limit inside a string. It is not
    re-asked (the same limit cuts it again), and the rules' reading makes the scenario."""
    run = _run("runaway_reply", tmp_path, validator_pool)
    assert run.ok, run.message
    report = _report(tmp_path)
    calls = report["llm_calls"]
    assert [c["label"] for c in calls] == ["extract"]
    assert calls[0]["usage"]["completion_tokens"] == 600  # the whole budget, cut off
    [note] = [n for n in report["spec_corrections"] if "the model's answer was unusable" in n]
    assert "after 1 attempt(s)" in note
    # the rules read the boy who runs out after the ball, and the cars parked on the nearside
    assert report["spec"]["adversary_type"] == "pedestrian"
    parked = report["spec"]["actors"][0]
    assert (parked["scenic_class"], parked["count"], parked["start"]) == ("Car", 3, "roadside_left")
