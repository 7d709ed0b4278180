"""The embedded model (the offline default), end to end in this process."""

from __future__ import annotations

from pathlib import Path
from typing import Literal

import pytest
from pydantic import BaseModel
from typer.testing import CliRunner

from arise.llm import ModelNotInstalled, get_provider, local
from arise.llm.cli import app
from arise.llm.local import LocalProvider
from arise.llm.types import Request, system, user

pytestmark = pytest.mark.slow


class Actor(BaseModel):
    kind: Literal["pedestrian", "cyclist", "car", "truck"]
    side: Literal["left", "right"]


def test_default_provider_end_to_end(model_path: Path) -> None:
    llm = get_provider(cache=False)  # no name: the settings' default, the embedded model
    assert llm.name == "local" and llm.capabilities.local
    reply = llm.complete(
        [
            system("You read traffic scenarios and name the other road user."),
            user("A pedestrian steps onto the road from the left."),
        ],
        max_tokens=40,
        schema=Actor,
    )
    assert isinstance(reply.parsed, Actor)
    # the grammar guarantees the shape; only a working model gets the content right
    assert reply.parsed.kind == "pedestrian" and reply.parsed.side == "left"
    assert reply.model == "qwen2.5-coder-1.5b-instruct-q4_k_m"
    assert reply.usage.calls == 1 and reply.usage.prompt_tokens > 20
    assert reply.first_token_latency is not None and 0 < reply.first_token_latency < reply.latency
    assert llm.total.completion_tokens == reply.usage.completion_tokens


def test_shared_prefix_is_evaluated_once(model_path: Path) -> None:
    # one thread: its speed holds when another process shares the 2 cores (2 threads collapse)
    provider = LocalProvider(model_path=model_path, threads=1)
    rules = "\n".join(
        f"Rule {i}: a {kind} that appears on the {side} must be named with its side."
        for i, (kind, side) in enumerate(
            [("pedestrian", "left"), ("cyclist", "right"), ("car", "left"), ("truck", "right")] * 6
        )
    )
    first = provider.send(
        Request.build([system(rules), user("A cyclist on the left. Who?")], max_tokens=8)
    )
    second = provider.send(
        Request.build([system(rules), user("A truck on the right. Who?")], max_tokens=8)
    )
    assert first.usage.prompt_tokens > 300
    evaluated_first = first.details["prompt_tokens_evaluated"]
    evaluated_second = second.details["prompt_tokens_evaluated"]
    assert evaluated_first > 300
    assert evaluated_second < 40, "the shared prefix was evaluated again"
    assert second.first_token_latency is not None and first.first_token_latency is not None
    assert second.first_token_latency < first.first_token_latency / 3


def test_threads_change_without_reloading(model_path: Path) -> None:
    provider = LocalProvider(model_path=model_path, threads=2)
    provider.send(Request.build([user("Say ok.")], max_tokens=2))
    loaded = local.loaded_model()
    provider.set_threads(1)
    reply = provider.send(Request.build([user("Say yes.")], max_tokens=2))
    assert reply.details["threads"] == 1 and "load_seconds" not in reply.details
    assert local.loaded_model() is loaded
    provider.set_threads(2)


def test_cli_ping_local(model_path: Path) -> None:
    result = CliRunner().invoke(app, ["ping", "--provider", "local", "--threads", "2"])
    assert result.exit_code == 0, result.output
    assert "local (qwen2.5-coder-1.5b-instruct-q4_k_m) answered" in result.output
    assert "tok/s" in result.output


def test_missing_model_says_how_to_get_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ARISE_MODELS_DIR", str(tmp_path / "models"))
    with pytest.raises(ModelNotInstalled) as info:
        get_provider("local", cache=False)
    message = str(info.value)
    assert "arise llm install-model" in message and "ARISE_MODEL_PATH" in message
    with pytest.raises(ModelNotInstalled, match="no model file at .*other.gguf"):
        get_provider("local", cache=False, model_path=str(tmp_path / "other.gguf"))


def test_cli_ask_uses_the_cache_unless_told_not_to(model_path: Path) -> None:
    runner = CliRunner()
    question = ["ask", "Which Python keyword defines a function? One word.", "--max-tokens", "4"]
    first = runner.invoke(app, question)
    second = runner.invoke(app, question)
    third = runner.invoke(app, [*question, "--no-cache"])
    for result in (first, second, third):
        assert result.exit_code == 0, result.output
        assert "def" in result.stdout
    assert "(cache)" not in first.stderr
    assert "(cache)" in second.stderr
    assert "(cache)" not in third.stderr


def test_auto_threads_yields_a_core_to_a_busy_neighbour(model_path: Path) -> None:
    import subprocess
    import sys
    import time

    provider = LocalProvider(model_path=model_path, threads=0)  # auto
    busy = subprocess.Popen([sys.executable, "-c", "while True: pass"])
    try:
        time.sleep(1.0)
        reply = provider.send(Request.build([user("Say ok.")], max_tokens=2))
    finally:
        busy.kill()
        busy.wait()
    assert reply.details["threads"] == 1


def test_auto_threads_rule() -> None:
    assert local.auto_threads(0.0, cores=2) == 2
    assert local.auto_threads(0.3, cores=2) == 2
    assert local.auto_threads(0.9, cores=2) == 1
    assert local.auto_threads(1.9, cores=2) == 1
    assert local.auto_threads(0.0, cores=1) == 1
