"""The SQLite response cache, with the real llama.cpp server behind it."""

from __future__ import annotations

from pathlib import Path

import pytest

from arise.llm import get_provider
from arise.llm.cache import ResponseCache, cache_key
from arise.llm.types import Request, user

pytestmark = pytest.mark.slow

PROMPT = [user("Name one colour of a traffic light. One word.")]


def test_miss_then_hit_is_identical_and_free(llama_server: str, tmp_path: Path) -> None:
    db = tmp_path / "responses.sqlite3"
    first = get_provider("llamacpp", base_url=llama_server, cache=True, cache_path=db)
    miss = first.complete(PROMPT, max_tokens=6)
    assert not miss.cached and miss.usage.calls == 1
    first.close()

    # a new process-like stack on the same file: the re-run costs nothing
    again = get_provider("llamacpp", base_url=llama_server, cache=True, cache_path=db)
    hit = again.complete(PROMPT, max_tokens=6)
    assert hit.cached and hit.text == miss.text
    assert hit.usage.calls == 0 and hit.usage.cached_calls == 1 and hit.usage.total_tokens == 0
    assert hit.details["original_usage"]["prompt_tokens"] == miss.usage.prompt_tokens
    assert hit.latency < miss.latency / 10
    assert again.total.cached_calls == 1 and again.total.calls == 0
    again.close()

    # any parameter change is a different entry
    changed = get_provider("llamacpp", base_url=llama_server, cache=True, cache_path=db)
    other = changed.complete(PROMPT, max_tokens=7)
    assert not other.cached
    changed.close()
    store = ResponseCache(db)
    assert store.stats()["entries"] == 2
    store.close()


def test_no_cache_always_calls(llama_server: str, tmp_path: Path) -> None:
    db = tmp_path / "responses.sqlite3"
    llm = get_provider("llamacpp", base_url=llama_server, cache=False, cache_path=db)
    a = llm.complete(PROMPT, max_tokens=4)
    b = llm.complete(PROMPT, max_tokens=4)
    assert not a.cached and not b.cached and llm.total.calls == 2
    assert not db.exists()
    llm.close()


def test_sampled_calls_are_keyed_by_run_index_or_seed(llama_server: str, tmp_path: Path) -> None:
    db = tmp_path / "responses.sqlite3"
    run0 = get_provider("llamacpp", base_url=llama_server, cache_path=db, run_index=0)
    run1 = get_provider("llamacpp", base_url=llama_server, cache_path=db, run_index=1)
    warm = run0.complete(PROMPT, max_tokens=4, temperature=0.8)
    assert not warm.cached
    assert run0.complete(PROMPT, max_tokens=4, temperature=0.8).cached  # same run: replayed
    assert not run1.complete(PROMPT, max_tokens=4, temperature=0.8).cached  # new run: sampled
    # greedy calls do not depend on the run index
    run0.complete(PROMPT, max_tokens=4, temperature=0.0)
    assert run1.complete(PROMPT, max_tokens=4, temperature=0.0).cached
    run0.close()
    run1.close()


def test_key_rules() -> None:
    greedy = Request.build(PROMPT, temperature=0.0)
    sampled = Request.build(PROMPT, temperature=0.7)
    seeded = Request.build(PROMPT, temperature=0.7, seed=3)
    assert cache_key("p", "m", greedy, 0) == cache_key("p", "m", greedy, 5)
    assert cache_key("p", "m", sampled, 0) != cache_key("p", "m", sampled, 1)
    assert cache_key("p", "m", seeded, 0) == cache_key("p", "m", seeded, 1)
    assert cache_key("p", "m", greedy) != cache_key("p", "other-model", greedy)
    assert cache_key("p", "m", greedy) != cache_key("q", "m", greedy)
