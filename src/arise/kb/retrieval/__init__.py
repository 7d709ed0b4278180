"""Retrieval of knowledge-base entries: top-k per component for a query.

BM25 is the default and needs nothing else. When a local embedding model folder is
available (see `embedding.find_model`), "auto" fuses BM25 with the embedding backend, which
measured best (docs/benchmarks.md).
"""

from __future__ import annotations

import os

from arise.kb.loader import KnowledgeBase
from arise.kb.retrieval.base import Hit, Retriever, RetrieverError
from arise.kb.retrieval.bm25 import BM25Retriever
from arise.kb.retrieval.embedding import EmbeddingRetriever, EmbeddingUnavailable, find_model
from arise.kb.retrieval.hybrid import HybridRetriever

BACKENDS = ("auto", "bm25", "embedding", "hybrid")
HYBRID_LEXICAL_WEIGHT = 1.5


def make_retriever(
    kb: KnowledgeBase, backend: str = "auto", model: str | os.PathLike[str] | None = None
) -> Retriever:
    """A retriever over `kb`.

    backend: "bm25"; "embedding" or "hybrid" (BM25 + embeddings; both raise
    EmbeddingUnavailable without a model); or "auto": hybrid when a model folder is given
    or found and loads, else BM25.
    """
    if backend not in BACKENDS:
        raise RetrieverError(f"unknown retrieval backend {backend!r}; choose from {BACKENDS}")
    if backend == "bm25":
        return BM25Retriever(kb)
    if backend == "embedding":
        return EmbeddingRetriever(kb, model)
    if backend == "hybrid":
        return HybridRetriever(
            BM25Retriever(kb), EmbeddingRetriever(kb, model), HYBRID_LEXICAL_WEIGHT
        )
    if find_model(model) is not None:
        try:
            return HybridRetriever(
                BM25Retriever(kb), EmbeddingRetriever(kb, model), HYBRID_LEXICAL_WEIGHT
            )
        except EmbeddingUnavailable:
            pass
    return BM25Retriever(kb)


__all__ = [
    "BACKENDS",
    "HYBRID_LEXICAL_WEIGHT",
    "BM25Retriever",
    "EmbeddingRetriever",
    "EmbeddingUnavailable",
    "Hit",
    "HybridRetriever",
    "Retriever",
    "RetrieverError",
    "find_model",
    "make_retriever",
]
