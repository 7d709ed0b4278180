"""The SCS judge: arithmetic, weights, the prompt, a scripted fake model, replayed cassettes
recorded from the embedded Qwen2.5-Coder-1.5B model (tests/judge_cases.py), and the CLI."""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from arise.cli import app
from arise.evaluate import judge_pair
from arise.evaluate.judge import (
    CRITERIA,
    MAX_TOKENS,
    REASON_CHARS,
    JudgeInputError,
    Judgement,
    WeightsError,
    compact_script,
    compute_scs,
    consistency,
    input_problem,
    judge_messages,
    judge_script,
    parse_weights,
    resolve_weights,
    weights_problem,
)
from arise.llm.base import BaseProvider
from arise.llm.registry import get_provider
from arise.llm.types import (
    ProviderUnavailable,
    StructuredOutputFailed,
)
from tests.fakes import ScriptedProvider as Scripted
from tests.judge_cases import CASES, CHILD_DIR, PEDESTRIAN

SCORES = dict(zip(CRITERIA, (10, 8, 10, 10, 7, 10, 5), strict=True))  # sum 60


@pytest.fixture(autouse=True)
def hermetic_env(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    """No user config and a private response cache: the presets decide."""
    for name in list(os.environ):
        if name.startswith("ARISE_") and name != "ARISE_MODELS_DIR":
            monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("ARISE_CONFIG", str(tmp_path / "no-config.toml"))
    monkeypatch.setenv("ARISE_CACHE_DIR", str(tmp_path / "cache"))


# ------------------------------------------------------------------------------ arithmetic


def test_scs_with_equal_weights_is_the_papers_sum_over_70() -> None:
    assert compute_scs(SCORES) == pytest.approx(60 / 70)
    assert compute_scs(dict.fromkeys(CRITERIA, 10)) == 1.0
    assert compute_scs(dict.fromkeys(CRITERIA, 0)) == 0.0


def test_scs_with_custom_weights() -> None:
    # 2*10 + 1.5*8 + (10 + 10 + 7 + 10 + 5) = 74 over 10 * (2 + 1.5 + 5) = 85
    weights = {"adversary_type": 2, "behavior": 1.5}
    assert compute_scs(SCORES, weights) == pytest.approx(74 / 85)
    # a zero weight drops a criterion: (10 + 8 + 10 + 10 + 7 + 10) / 60
    assert compute_scs(SCORES, {"spawn": 0}) == pytest.approx(55 / 60)
    # only one criterion counts
    only = dict.fromkeys(CRITERIA, 0.0) | {"participants": 3.0}
    assert compute_scs(SCORES, only) == pytest.approx(0.7)


def test_judgement_scs_follows_its_weights_and_can_be_rescored() -> None:
    reasons = dict.fromkeys(CRITERIA, "ok")
    judgement = Judgement(scores=SCORES, reasons=reasons)
    assert judgement.scs == pytest.approx(60 / 70)
    heavier = judgement.rescored({"adversary_type": 2, "behavior": 1.5})
    assert heavier.scs == pytest.approx(74 / 85) and judgement.scs == pytest.approx(60 / 70)
    data = heavier.as_dict()
    assert [c["name"] for c in data["criteria"]] == list(CRITERIA)
    assert data["scs"] == pytest.approx(74 / 85) and data["criteria"][0]["weight"] == 2.0


# --------------------------------------------------------------------------------- weights


def test_weights_parse_and_default_to_one() -> None:
    assert parse_weights(None) == dict.fromkeys(CRITERIA, 1.0)
    parsed = parse_weights("adversary_type=2, behavior=1.5,")
    assert parsed["adversary_type"] == 2.0 and parsed["behavior"] == 1.5
    assert parsed["spawn"] == 1.0 and list(parsed) == list(CRITERIA)


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("speed=2", "unknown criterion 'speed'"),
        ("behavior=-1", "finite number >= 0"),
        ("behavior=nan", "finite number >= 0"),
        ("behavior=lots", "must be a number"),
        ("behavior", "NAME=NUMBER"),
        (",".join(f"{name}=0" for name in CRITERIA), "all zero"),
    ],
)
def test_bad_weights_are_one_clear_error(text: str, words: str) -> None:
    with pytest.raises(WeightsError, match=words) as caught:
        parse_weights(text)
    assert "\n" not in str(caught.value)


def test_weight_problems_are_also_available_as_values() -> None:
    assert weights_problem(None) is None and weights_problem({"weather": 0}) is None
    assert "unknown criterion" in (weights_problem({"colour": 1}) or "")
    assert "must be a number" in (weights_problem({"weather": "1"}) or "")
    assert "must be a number" in (weights_problem({"weather": True}) or "")
    with pytest.raises(WeightsError):
        resolve_weights({"weather": -2})
    with pytest.raises(WeightsError):
        compute_scs(SCORES, {"geometry": math.inf})


# ------------------------------------------------------------------------------- the prompt

SCRIPT = CASES["good"].script_text()


def test_compact_script_keeps_code_and_section_starts_only() -> None:
    compact = compact_script(SCRIPT)
    assert "steps off the right" not in compact, "the description in the header comment goes"
    assert "# kb:" not in compact and "# END" not in compact and "model scenic" not in compact
    assert "localPath" not in compact and "param carla_map = 'arise_straight'" in compact
    for section in ("HEADER", "WEATHER", "BEHAVIOR", "GEOMETRY", "SPAWN", "MISC", "REQUIREMENTS"):
        assert f"# BEGIN {section}" in compact
    assert "adversary = new Pedestrian" in compact and "\n\n" not in compact
    assert len(compact) < len(SCRIPT) * 0.8
    # inline comments without quotes go; a '#' inside a string stays
    assert compact_script("pass  # arise: dropped `require x`\nname = 'a # b'") == (
        "pass\nname = 'a # b'"
    )


def test_messages_put_the_shared_part_first_and_the_pair_last() -> None:
    messages = judge_messages(PEDESTRIAN, SCRIPT)
    assert messages[0].role == "system" and "adversary_type" in messages[0].content
    assert all(name in messages[0].content for name in CRITERIA)
    last = messages[-1]
    assert last.role == "user" and last.content.startswith("DESCRIPTION:\n" + PEDESTRIAN)
    assert compact_script(SCRIPT) in last.content
    for example in messages[1:-1]:  # few-shot answers, if any, are valid answers
        if example.role == "assistant":
            assert set(json.loads(example.content)) == set(CRITERIA)


def test_inputs_that_cannot_be_judged() -> None:
    assert input_problem(PEDESTRIAN, SCRIPT) is None
    assert "empty" in (input_problem("  ", SCRIPT) or "")
    assert "empty" in (input_problem(PEDESTRIAN, "# only a comment\n\n") or "")
    assert "characters" in (input_problem("x" * 2001, SCRIPT) or "")
    assert "characters" in (input_problem(PEDESTRIAN, "x = 1\n" * 3000) or "")


# --------------------------------------------------------------------- with a scripted model


def answer(scores: dict[str, int], reason: str = "matches") -> str:
    return json.dumps({name: {"reason": reason, "score": scores[name]} for name in CRITERIA})


def test_judge_script_turns_the_answer_into_a_judgement() -> None:
    model = Scripted([answer(SCORES, reason="x " * 200)])
    judgement = judge_script(
        PEDESTRIAN, SCRIPT, model, temperature=0.3, seed=5, weights={"adversary_type": 2}
    )
    assert judgement.scores == SCORES and judgement.model == "scripted-1"
    assert judgement.scs == pytest.approx(compute_scs(SCORES, {"adversary_type": 2}))
    assert all(len(r) <= REASON_CHARS for r in judgement.reasons.values()), "long reasons cut"
    request = model.requests[0]
    assert request.seed == 5 and request.temperature == 0.3 and request.max_tokens == MAX_TOKENS
    assert request.schema_name == "JudgeAnswer"
    props = request.json_schema["$defs"]["CriterionVerdict"]["properties"]
    assert props["score"]["enum"] == list(range(11)) and props["reason"]["maxLength"] > 0


def test_an_out_of_range_score_is_re_asked_then_fails_as_a_provider_error() -> None:
    bad = answer(SCORES | {"weather": 11})
    fixed = Scripted([bad, answer(SCORES)])
    assert judge_script(PEDESTRIAN, SCRIPT, fixed).scores == SCORES
    assert len(fixed.requests) == 2
    with pytest.raises(StructuredOutputFailed, match="JudgeAnswer"):
        judge_script(PEDESTRIAN, SCRIPT, Scripted([bad] * 3))


def test_judge_refuses_bad_input_and_bad_weights_before_calling_the_model() -> None:
    model = Scripted([])
    with pytest.raises(JudgeInputError, match="empty"):
        judge_script("", SCRIPT, model)
    with pytest.raises(WeightsError):
        judge_script(PEDESTRIAN, SCRIPT, model, weights={"weather": -1})
    assert model.requests == []


def test_consistency_varies_the_seed_and_reports_population_std() -> None:
    runs = [SCORES, SCORES | {"spawn": 9}, SCORES | {"spawn": 8, "behavior": 10}]
    model = Scripted([answer(s) for s in runs])
    result = consistency(PEDESTRIAN, SCRIPT, model, repeat=3, temperature=0.7, seed=10)
    assert [r.seed for r in model.requests] == [10, 11, 12]
    assert len({r.key() for r in model.requests}) == 3, "each repeat is its own request"
    scs = [60 / 70, 64 / 70, 65 / 70]
    assert result.scs.min == pytest.approx(min(scs)) and result.scs.max == pytest.approx(max(scs))
    assert result.scs.mean == pytest.approx(sum(scs) / 3)
    mean = sum(scs) / 3
    assert result.scs.std == pytest.approx(math.sqrt(sum((v - mean) ** 2 for v in scs) / 3))
    spawn = result.criteria["spawn"]
    assert (spawn.min, spawn.max, spawn.mean) == (5, 9, pytest.approx(22 / 3))
    assert result.criteria["weather"].std == 0
    data = result.as_dict()
    assert data["std"] == "population" and data["judged"] == 3 and len(data["runs"]) == 3
    assert data["usage"]["calls"] == 3


def test_consistency_leaves_out_failed_repeats_and_raises_when_all_fail() -> None:
    bad = "not json"
    model = Scripted([bad, bad, bad, answer(SCORES)])  # repeat 1: 3 tries; repeat 2 fine
    result = consistency(PEDESTRIAN, SCRIPT, model, repeat=2)
    assert len(result.runs) == 1 and len(result.failures) == 1
    assert result.failures[0].startswith("seed 0:")
    with pytest.raises(StructuredOutputFailed):
        consistency(PEDESTRIAN, SCRIPT, Scripted([bad] * 6), repeat=2)
    with pytest.raises(ValueError):
        consistency(PEDESTRIAN, SCRIPT, Scripted([]), repeat=0)


# ---------------------------------------------- replayed from the real local model's cassettes


def replayed(name: str) -> list[Judgement]:
    case = CASES[name]
    with get_provider(replay=case.cassette) as llm:
        result = consistency(
            case.description,
            case.script_text(),
            llm,
            repeat=case.repeat,
            temperature=case.temperature,
            seed=case.seed,
        )
    assert not result.failures
    return result.runs


@pytest.mark.parametrize("name", ["good", "mismatch", "child"])
def test_recorded_judgements_parse_into_seven_scores(name: str) -> None:
    (judgement,) = replayed(name)
    assert list(judgement.scores) == list(CRITERIA)
    assert all(0 <= score <= 10 for score in judgement.scores.values())
    assert all(judgement.reasons[c].strip() for c in CRITERIA)
    assert judgement.scs == pytest.approx(sum(judgement.scores.values()) / 70)
    assert judgement.model.startswith("qwen2.5-coder-1.5b")


def test_what_the_small_local_model_really_answered() -> None:
    # Recorded from Qwen2.5-Coder-1.5B-Instruct Q4_K_M (llama.cpp, temperature 0, seed 0).
    # It gives one score to all seven criteria, and that score does not follow the pair: the
    # car-in-hard-rain script gets 10/10 for the clear-noon pedestrian description, like the
    # matching script, and the real generator output with real flaws gets 1s. These asserts pin
    # what the cassettes hold so docs/judge.md cannot drift from them; a better judge model
    # will fail them (then re-record and rewrite the docs).
    (good,) = replayed("good")
    (bad,) = replayed("mismatch")
    (child,) = replayed("child")
    assert set(good.scores.values()) == {10} and set(bad.scores.values()) == {10}
    assert bad.scores["adversary_type"] == good.scores["adversary_type"] == 10
    assert set(child.scores.values()) == {1} and child.scs == pytest.approx(0.1)


def test_recorded_consistency_of_three_sampled_repeats() -> None:
    # Same model, temperature 0.7, seeds 0, 1, 2: again one score per answer, spread widely.
    runs = replayed("repeat")
    assert [run.seed for run in runs] == [0, 1, 2]
    assert [round(run.scs, 2) for run in runs] == [1.0, 0.7, 0.2]
    assert all(len(set(run.scores.values())) == 1 for run in runs)


# ------------------------------------------------------------------------------------ CLI

runner = CliRunner()


def invoke(*args: str):
    return runner.invoke(app, ["judge", *args])


def test_cli_help_has_examples() -> None:
    result = invoke("--help")
    assert result.exit_code == 0
    assert "Examples" in result.output and "--repeat" in result.output
    assert "report.json" in result.output


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["x", "missing.scenic"], "no such script"),
        (["", str(CASES["good"].script)], "description is empty"),
        (["-", str(CASES["good"].script)], "only a folder"),
        ([PEDESTRIAN, str(CASES["good"].script), "--weights", "speed=2"], "unknown criterion"),
        ([PEDESTRIAN, str(CASES["good"].script), "--repeat", "0"], "at least 1"),
        (["-", str(CHILD_DIR.parent)], "without scenario.scenic"),
    ],
)
def test_cli_user_mistakes_exit_2_with_one_line(args: list[str], words: str) -> None:
    result = invoke(*args)
    assert result.exit_code == 2, result.output
    assert words in result.output and "Traceback" not in result.output
    assert len(result.output.strip().splitlines()) == 1


def test_cli_provider_failures_exit_1(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    script = str(CASES["good"].script)
    missing = invoke(PEDESTRIAN, script, "--replay", str(tmp_path / "none.jsonl"))
    assert missing.exit_code == 1 and "does not exist" in missing.output
    other = invoke("A car cuts in.", script, "--replay", str(CASES["good"].cassette))
    assert other.exit_code == 1 and "no recording" in other.output

    def down(*args: object, **kwargs: object) -> BaseProvider:
        raise ProviderUnavailable("llamacpp: cannot reach http://127.0.0.1:8080/v1; start it")

    monkeypatch.setattr(judge_pair, "get_provider", down)
    result = invoke(PEDESTRIAN, script, "--provider", "llamacpp")
    assert result.exit_code == 1 and "cannot reach" in result.output
    assert "Traceback" not in result.output


def test_cli_prints_the_table_and_json_from_a_recorded_judgement() -> None:
    case = CASES["good"]
    table = invoke(case.description, str(case.script), "--replay", str(case.cassette))
    assert table.exit_code == 0, table.output
    assert "SCS" in table.output and "%" in table.output
    assert all(name in table.output for name in CRITERIA)
    as_json = invoke(
        case.description,
        str(case.script),
        "--replay",
        str(case.cassette),
        "--json",
        "--weights",
        "adversary_type=2",
    )
    assert as_json.exit_code == 0, as_json.output
    data = json.loads(as_json.output)
    scores = {c["name"]: c["score"] for c in data["criteria"]}
    assert data["scs"] == pytest.approx(compute_scs(scores, {"adversary_type": 2}))
    assert data["description"] == case.description


def test_cli_reads_a_generation_folder_and_its_description() -> None:
    result = invoke("-", str(CHILD_DIR), "--replay", str(CASES["child"].cassette), "--json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["description"].startswith("On a straight urban street, a child")
    assert data["script"].endswith("scenario.scenic")


def test_cli_repeat_shows_the_spread() -> None:
    case = CASES["repeat"]
    args = [
        case.description,
        str(case.script),
        "--replay",
        str(case.cassette),
        "--repeat",
        "3",
        "--temperature",
        "0.7",
    ]
    result = invoke(*args)
    assert result.exit_code == 0, result.output
    assert "population std" in result.output and "pp" in result.output
    data = json.loads(invoke(*args, "--json").output)
    assert data["judged"] == 3 and set(data["scs"]) == {"min", "max", "mean", "std"}
    assert set(data["criteria"]) == set(CRITERIA)
