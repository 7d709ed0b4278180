"""The prefix store with the real embedded model, each step in a new process as a user
runs it: the answers are the same tokens with the store off, while it is built and when it
is loaded; a damaged entry is rebuilt by `arise llm warm`."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from arise.cli import app
from arise.llm import local
from arise.llm.prefix_store import PrefixStore

pytestmark = pytest.mark.slow

DESCRIPTION = "The ego car goes straight while a cyclist on the right front swerves into its lane."

# One process: the extraction call greedy, then sampled with a seed; prints what came back.
_CALLS = """
import json, sys
from arise.generate.extract import extraction_messages
from arise.llm.registry import get_provider
from arise.llm.types import Request
provider = get_provider("local", cache=False)  # settings and ARISE_* as a user gets them
out = []
for temperature, seed in ((0.0, None), (0.8, 7)):
    request = Request.build(
        extraction_messages(sys.argv[1]), temperature=temperature, max_tokens=48, seed=seed
    )
    reply = provider.send(request)
    out.append({"text": reply.text, "prefix": reply.details["prefix"],
                "evaluated": reply.usage.prompt_tokens_evaluated,
                "prompt": reply.usage.prompt_tokens})
print(json.dumps(out))
"""


def _run(env: dict[str, str]) -> list[dict[str, object]]:
    done = subprocess.run(
        [sys.executable, "-c", _CALLS, DESCRIPTION],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
        check=True,
    )
    result: list[dict[str, object]] = json.loads(done.stdout.strip().splitlines()[-1])
    return result


def test_the_store_never_changes_an_answer(model_path: Path, tmp_path: Path) -> None:
    env = {**os.environ, "ARISE_CACHE_DIR": str(tmp_path / "cache")}
    off = _run({**env, "ARISE_PREFIX_STORE": "off"})
    assert PrefixStore(tmp_path / "cache" / "prefix-store").entries() == [], "off writes nothing"
    built = _run(env)
    loaded = _run(env)
    for calls in (off, built, loaded):
        assert [c["text"] for c in calls] == [c["text"] for c in off]
    assert all(str(c["text"]).startswith("{") for c in off), "real answers, JSON specs"
    assert [c["prefix"] for c in off] == ["evaluated", "in_context"]
    assert [c["prefix"] for c in built] == ["built", "in_context"]
    assert [c["prefix"] for c in loaded] == ["loaded", "in_context"]
    prompt = int(str(loaded[0]["prompt"]))
    evaluated = int(str(loaded[0]["evaluated"]))
    assert prompt > 800 and evaluated < 120, "a loaded prefix is not read again"
    assert int(str(off[0]["evaluated"])) >= prompt - 1


def test_warm_builds_and_rebuilds_a_damaged_entry(model_path: Path) -> None:
    local.unload()  # states other tests left in memory belong to their own stores
    runner = CliRunner()
    first = runner.invoke(app, ["llm", "warm"])
    assert first.exit_code == 0, first.output
    assert first.output.count("built and stored") == 3, first.output
    store = PrefixStore()
    entries = store.entries()
    assert len(entries) == 3
    doctor = runner.invoke(app, ["doctor"])
    assert "prefix store: 3 entries" in doctor.output, doctor.output
    victim = entries[0]
    blob = bytearray(victim.read_bytes())
    blob[len(blob) // 2] ^= 0x55
    victim.write_bytes(bytes(blob))
    local.unload()  # a new process would not hold the states in memory either
    second = runner.invoke(app, ["llm", "warm"])
    assert second.exit_code == 0, second.output
    assert second.output.count("already stored") == 2
    assert second.output.count("built and stored") == 1
    assert "checksum mismatch" in second.output
    cleared = runner.invoke(app, ["llm", "warm", "--clear"])
    assert "removed 3 stored prefix(es)" in cleared.output


def test_generate_builds_the_store_once_and_writes_the_same_script(
    model_path: Path, tmp_path: Path
) -> None:
    # "2 seconds": a time the rules leave to the model, so the script's numbers are tuned
    # (a second prefix).
    description = (
        "The ego drives along a straight road when a pedestrian steps off the right "
        "sidewalk 2 seconds before it arrives and stops in its lane."
    )
    env = {**os.environ, "ARISE_CACHE_DIR": str(tmp_path / "cache"), "ARISE_LLM_CACHE": "off"}
    outputs = []
    for name in ("first", "second"):
        done = subprocess.run(
            # The rules read this description whole: --ask-model always makes the model read
            # it too, so that the extraction prefix is built, then loaded, like the tuning's.
            [
                *[sys.executable, "-m", "arise", "generate", description],
                *["--ask-model", "always", "-o", str(tmp_path / name)],
            ],
            env=env,
            capture_output=True,
            text=True,
            timeout=900,
        )
        assert done.returncode == 0, done.stdout + done.stderr
        outputs.append(done.stdout)
    assert outputs[0].count("prefix store: first run") == 1
    assert "prefix store" not in outputs[1]
    first, second = (
        json.loads((tmp_path / name / "report.json").read_text()) for name in ("first", "second")
    )
    script = (tmp_path / "first" / "scenario.scenic").read_text()
    assert script == (tmp_path / "second" / "scenario.scenic").read_text()
    assert first["llm"]["prefixes_built"] >= 2 and second["llm"]["prefixes_loaded"] >= 2
    assert second["llm"]["prompt_tokens"] == first["llm"]["prompt_tokens"]
    assert second["llm"]["prompt_tokens_evaluated"] < first["llm"]["prompt_tokens_evaluated"] / 2
    assert [c["label"] for c in second["llm_calls"]][:2] == ["extract", "adapt"]
