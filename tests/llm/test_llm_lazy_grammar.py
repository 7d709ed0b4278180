"""Lazy grammar checks with the real embedded model: greedy JSON answers are the same tokens
with and without them, over the prompts the generator sends, and the full grammar pass
still happens when the best token is not allowed."""

from __future__ import annotations

from pathlib import Path

import pytest

from arise.generate.assemble import adapt_messages
from arise.generate.extract import extraction_messages
from arise.generate.spec import ExtractionAnswer
from arise.llm.local import LocalProvider
from arise.llm.types import Request

pytestmark = pytest.mark.slow

DESCRIPTIONS = (
    "A car runs a red light and crosses in front of the ego at an intersection.",
    "On a rainy night the ego follows a truck on the highway; the truck brakes hard.",
)


def _answer(provider: LocalProvider, request: Request) -> tuple[str, int | None]:
    reply = provider.send(request)
    passes = reply.details.get("grammar_full_passes")
    return reply.text, passes


def test_lazy_grammar_gives_the_same_tokens(model_path: Path, tmp_path: Path) -> None:
    schema = ExtractionAnswer.model_json_schema()
    requests = [
        Request.build(
            extraction_messages(text),
            temperature=0.0,
            max_tokens=160,
            json_schema=schema,
            schema_name="ExtractionAnswer",
        )
        for text in DESCRIPTIONS
    ]
    # no grammar, and a sampled answer: both keep llama-cpp-python's own chain
    requests.append(
        Request.build(adapt_messages(DESCRIPTIONS[0], "- (none)"), temperature=0.0, max_tokens=20)
    )
    sampled = Request.build(
        extraction_messages(DESCRIPTIONS[1]),
        temperature=0.8,
        seed=7,
        max_tokens=30,
        json_schema=schema,
        schema_name="ExtractionAnswer",
    )
    requests.append(sampled)
    full = LocalProvider(model_path=model_path, prefix_store=False, lazy_grammar=False)
    lazy = LocalProvider(model_path=model_path, prefix_store=False, lazy_grammar=True)
    for request in requests:
        expected, none = _answer(full, request)
        got, passes = _answer(lazy, request)
        assert got == expected
        assert none is None, "with lazy checks off, the chain is llama-cpp-python's own"
        if request.json_schema is not None and request.temperature == 0.0:
            assert expected.startswith("{") and len(expected) > 40, "a real JSON answer"
            assert passes is not None, "greedy with a grammar takes the lazy path"
        else:
            assert passes is None, "no grammar, or sampled: nothing to check lazily"
