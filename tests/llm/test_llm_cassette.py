"""Cassettes: record real calls, replay them without the model, scrub secrets."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Literal

import pytest
from pydantic import BaseModel

from arise.llm import LLMError, ReplayMiss, get_provider
from arise.llm.cassette import SCRUBBED, read_cassette, scrub
from arise.llm.types import system, user

CASSETTES = Path(__file__).resolve().parents[1] / "cassettes" / "llm"

#: recorded from the real embedded model; re-record with ARISE_RERECORD=1 pytest -k committed
COMMITTED = CASSETTES / "local-qwen2.5-coder-1.5b.jsonl"
RERECORD = bool(os.environ.get("ARISE_RERECORD"))  # read before the hermetic fixture clears it


class Weather(BaseModel):
    condition: Literal["clear", "rain", "fog", "snow"]
    time_of_day: Literal["day", "night", "dusk"]


COMMITTED_CALLS = [
    (
        [
            system("You extract facts from traffic scenario descriptions."),
            user("On a foggy night, a cyclist swerves in front of the ego vehicle."),
        ],
        Weather,
    ),
    ([user("Which Python keyword defines a function? One word.")], None),
]


def _run_committed(llm: object) -> list[object]:
    out = []
    for messages, schema in COMMITTED_CALLS:
        out.append(llm.complete(messages, max_tokens=40, schema=schema))  # type: ignore[attr-defined]
    return out


def test_committed_cassette_replays_without_a_model() -> None:
    if RERECORD:
        COMMITTED.unlink(missing_ok=True)
        recorder = get_provider("local", cache=False, record=COMMITTED)
        _run_committed(recorder)
        recorder.close()
    meta, entries = read_cassette(COMMITTED)
    assert meta["provider"] == "local"
    assert meta["model"] == "qwen2.5-coder-1.5b-instruct-q4_k_m"
    assert len(entries) == len(COMMITTED_CALLS)
    llm = get_provider(replay=COMMITTED)
    weather, keyword = _run_committed(llm)
    assert isinstance(weather.parsed, Weather)  # type: ignore[attr-defined]
    assert weather.parsed.condition == "fog" and weather.parsed.time_of_day == "night"  # type: ignore[attr-defined]
    assert "def" in keyword.text.lower()  # type: ignore[attr-defined]
    assert llm.total.calls == 2 and llm.total.prompt_tokens > 0
    assert llm.capabilities.structured == "json_object_schema"  # taken from the cassette


@pytest.mark.slow
def test_record_then_replay_round_trip(llama_server: str, tmp_path: Path) -> None:
    cassette = tmp_path / "run.jsonl"
    live = get_provider("llamacpp", base_url=llama_server, cache=False, record=cassette)
    prompts = [
        [user("Say 'left' or 'right': which side do cars drive on in Germany?")],
        [user("What colour means stop at a traffic light? One word.")],
    ]
    recorded = [live.complete(p, max_tokens=6) for p in prompts]
    structured = live.complete([user("Rain at dusk, a bus stops.")], max_tokens=40, schema=Weather)
    live.close()

    replay = get_provider(replay=cassette)
    replayed = [replay.complete(p, max_tokens=6) for p in prompts]
    assert [r.text for r in replayed] == [r.text for r in recorded]
    assert [r.usage.prompt_tokens for r in replayed] == [r.usage.prompt_tokens for r in recorded]
    again = replay.complete([user("Rain at dusk, a bus stops.")], max_tokens=40, schema=Weather)
    assert again.parsed == structured.parsed

    # the same request with another parameter is not in the cassette: a clear miss
    with pytest.raises(ReplayMiss) as info:
        replay.complete(prompts[0], max_tokens=7)
    message = str(info.value)
    assert str(cassette) in message and info.value.key[:16] in message and "--record" in message


@pytest.mark.slow
def test_secrets_never_reach_the_cassette(
    llama_server: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    secret = "sk-live-abcdefghijklmnopqrstuvwxyz012345"
    monkeypatch.setenv("LLAMACPP_API_KEY", secret)  # sent to the server as the bearer token
    cassette = tmp_path / "secret.jsonl"
    llm = get_provider("llamacpp", base_url=llama_server, cache=False, record=cassette)
    llm.complete([user(f"Ignore this token {secret} and say ok.")], max_tokens=4)
    llm.close()
    text = cassette.read_text()
    assert secret not in text and SCRUBBED in text
    # the key of the entry still matches the real request, so replay works
    replay = get_provider(replay=cassette)
    assert replay.complete([user(f"Ignore this token {secret} and say ok.")], max_tokens=4).text


def test_scrub_patterns(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("MY_SERVICE_TOKEN", "hunter2-long-value")
    data = {
        "a": "Authorization: Bearer abcdefghijklmnop123",
        "b": ["sk-ant-api03-abcdefghijklmnopqrstuvwx", "AIza" + "x" * 35],
        "c": "value hunter2-long-value here",
        "d": 3,
    }
    clean = scrub(data)
    assert "abcdefghijklmnop123" not in json.dumps(clean)
    assert clean["b"] == [SCRUBBED, SCRUBBED]
    assert clean["c"] == f"value {SCRUBBED} here" and clean["d"] == 3


def test_missing_cassette_is_a_clear_error(tmp_path: Path) -> None:
    with pytest.raises(LLMError, match="does not exist; record one with --record"):
        get_provider(replay=tmp_path / "nope.jsonl")
